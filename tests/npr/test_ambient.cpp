#include "npr/ambient.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "core/error.h"

namespace sylva {
namespace {

constexpr float kInf = std::numeric_limits<float>::infinity();
constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();

AmbientParams params(float ka_min, float d_min, float exponent) {
  AmbientParams p;
  p.ka_min = ka_min;
  p.d_min = d_min;
  p.exponent = exponent;
  return p;
}

// The `where()` of the InputError thrown by validate_ambient, or "" when it accepts.
std::string rejected_by(const AmbientParams& p) {
  try {
    validate_ambient(p);
  } catch (const InputError& e) {
    return e.where();
  }
  return "";
}

TEST(AmbientValidate, AcceptsDefaultsAndRangeEnds) {
  EXPECT_NO_THROW(validate_ambient(AmbientParams{}));
  EXPECT_NO_THROW(validate_ambient(params(0.0f, 1.0f, 1.0f)));
  EXPECT_NO_THROW(validate_ambient(params(1.0f, 1.0f, 1.0f)));
  EXPECT_NO_THROW(validate_ambient(params(0.5f, 1e-30f, 1.0f)));
  EXPECT_NO_THROW(validate_ambient(params(0.5f, 1e30f, 1.0f)));
  EXPECT_NO_THROW(validate_ambient(params(0.5f, 1.0f, 1e-3f)));
  EXPECT_NO_THROW(validate_ambient(params(0.5f, 1.0f, 100.0f)));
  EXPECT_NO_THROW(validate_ambient(params(0.5f, std::numeric_limits<float>::denorm_min(), 1.0f)));
}

TEST(AmbientValidate, RejectsKaMinOutsideRange) {
  EXPECT_EQ(rejected_by(params(-0.01f, 1.0f, 1.0f)), "ka-min");
  EXPECT_EQ(rejected_by(params(1.01f, 1.0f, 1.0f)), "ka-min");
  EXPECT_EQ(rejected_by(params(kNaN, 1.0f, 1.0f)), "ka-min");
  EXPECT_EQ(rejected_by(params(kInf, 1.0f, 1.0f)), "ka-min");
}

TEST(AmbientValidate, RejectsDMinOutsideRange) {
  EXPECT_EQ(rejected_by(params(0.2f, 0.0f, 1.0f)), "d-min");
  EXPECT_EQ(rejected_by(params(0.2f, -0.0f, 1.0f)), "d-min");
  EXPECT_EQ(rejected_by(params(0.2f, -1.0f, 1.0f)), "d-min");
  EXPECT_EQ(rejected_by(params(0.2f, kNaN, 1.0f)), "d-min");
  EXPECT_EQ(rejected_by(params(0.2f, kInf, 1.0f)), "d-min");
}

TEST(AmbientValidate, RejectsExponentOutsideRange) {
  EXPECT_EQ(rejected_by(params(0.2f, 1.0f, 0.0f)), "exponent");
  EXPECT_EQ(rejected_by(params(0.2f, 1.0f, -1.0f)), "exponent");
  EXPECT_EQ(rejected_by(params(0.2f, 1.0f, 100.5f)), "exponent");
  EXPECT_EQ(rejected_by(params(0.2f, 1.0f, kNaN)), "exponent");
  EXPECT_EQ(rejected_by(params(0.2f, 1.0f, kInf)), "exponent");
}

TEST(AmbientValidate, MessageNamesRangeAndValue) {
  try {
    validate_ambient(params(1.01f, 1.0f, 1.0f));
    FAIL() << "no throw";
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("[0, 1]"), std::string::npos) << what;
    EXPECT_NE(what.find("1.00999999"), std::string::npos) << what;
  }
  try {
    validate_ambient(params(0.2f, 1.0f, 100.5f));
    FAIL() << "no throw";
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("(0, 100]"), std::string::npos) << what;
    EXPECT_NE(what.find("100.5"), std::string::npos) << what;
  }
}

// Luft et al. Eq. 4, values worked out by hand.
TEST(AmbientTransfer, HandValues) {
  const AmbientParams lin = params(0.2f, 2.0f, 1.0f);
  EXPECT_EQ(ambient_transfer(0.0f, lin), 1.0f);
  EXPECT_EQ(ambient_transfer(-0.0f, lin), 1.0f);
  EXPECT_EQ(ambient_transfer(-5.0f, lin), 1.0f);
  EXPECT_FLOAT_EQ(ambient_transfer(1.0f, lin), 0.2f + 0.8f / 2.0f);  // d = d_min / 2, n = 1
  EXPECT_FLOAT_EQ(ambient_transfer(0.5f, lin), 0.2f + 0.8f * 0.75f);
  EXPECT_EQ(ambient_transfer(2.0f, lin), 0.2f);
  EXPECT_EQ(ambient_transfer(3.0f, lin), 0.2f);
  EXPECT_EQ(ambient_transfer(1e30f, lin), 0.2f);

  const AmbientParams quad = params(0.2f, 2.0f, 2.0f);
  EXPECT_FLOAT_EQ(ambient_transfer(1.0f, quad), 0.2f + 0.8f / 4.0f);  // (1/2)^2
  const AmbientParams cube_root = params(0.0f, 1.0f, 1.0f / 3.0f);
  EXPECT_NEAR(ambient_transfer(0.875f, cube_root), 0.5f, 1e-6f);  // (1/8)^(1/3)
}

TEST(AmbientTransfer, NonFiniteDensity) {
  const AmbientParams p = params(0.3f, 1.0f, 2.0f);
  EXPECT_EQ(ambient_transfer(kNaN, p), 1.0f);  // NaN counts as 0
  EXPECT_EQ(ambient_transfer(-kNaN, p), 1.0f);
  EXPECT_EQ(ambient_transfer(kInf, p), 0.3f);
  EXPECT_EQ(ambient_transfer(-kInf, p), 1.0f);
}

TEST(AmbientTransfer, ContinuousAtBothEnds) {
  for (float n : {1e-3f, 0.5f, 1.0f, 3.0f, 100.0f}) {
    const AmbientParams p = params(0.25f, 1.0f, n);
    // Just above 0 the curve starts at 1 ...
    EXPECT_NEAR(ambient_transfer(1e-9f, p), 1.0f, 1e-5f) << "n=" << n;
    // ... and just below d_min it arrives at ka_min. A tiny n makes the approach steep, so
    // the distance to d_min is chosen for each n: (1 - d)^n <= 1e-4 needs 1 - d <= 1e-4^(1/n).
    const double gap = std::pow(1e-4, 1.0 / n);
    if (gap > 1e-7) {
      const float d = static_cast<float>(1.0 - gap);
      EXPECT_NEAR(ambient_transfer(d, p), 0.25f, 1e-4f) << "n=" << n;
    }
    // The last float below d_min: 1 - d = 6e-8, so only n >= 0.5 can come this close.
    if (n >= 0.5f) {
      EXPECT_LE(ambient_transfer(std::nextafter(1.0f, 0.0f), p), 0.25f + 1e-3f) << "n=" << n;
    }
  }
}

TEST(AmbientTransfer, MonotoneAndInRangeOverExtremes) {
  for (float ka_min : {0.0f, 0.2f, 1.0f}) {
    for (float n : {1e-3f, 1.0f, 100.0f}) {
      for (float d_min : {1e-30f, 1.0f, 1e30f}) {
        const AmbientParams p = params(ka_min, d_min, n);
        ASSERT_NO_THROW(validate_ambient(p));
        float prev = 1.0f;
        // A sweep from well below 0 to well above d_min, relative to d_min.
        for (int i = -100; i <= 2100; ++i) {
          const float d = d_min * (static_cast<float>(i) / 1000.0f);
          const float ka = ambient_transfer(d, p);
          ASSERT_TRUE(std::isfinite(ka)) << d;
          ASSERT_GE(ka, ka_min) << "d=" << d << " n=" << n << " d_min=" << d_min;
          ASSERT_LE(ka, 1.0f) << "d=" << d << " n=" << n << " d_min=" << d_min;
          ASSERT_LE(ka, prev) << "not monotone at d=" << d << " n=" << n << " d_min=" << d_min;
          prev = ka;
        }
        EXPECT_EQ(ambient_transfer(2.0f * d_min, p), ka_min);
        // ka_min = 1 is a constant transfer.
        if (ka_min == 1.0f) {
          EXPECT_EQ(ambient_transfer(0.5f * d_min, p), 1.0f);
        }
      }
    }
  }
}

TEST(AmbientTransfer, TinyExponentIsAlmostAStep) {
  const AmbientParams p = params(0.1f, 1.0f, 1e-3f);
  EXPECT_GT(ambient_transfer(0.5f, p), 0.99f);
  EXPECT_GT(ambient_transfer(0.99f, p), 0.99f * 0.9f + 0.1f);
  EXPECT_EQ(ambient_transfer(1.0f, p), 0.1f);
}

TEST(AmbientTransfer, HugeExponentDarkensAtOnce) {
  const AmbientParams p = params(0.1f, 1.0f, 100.0f);
  EXPECT_LT(ambient_transfer(0.1f, p), 0.1f + 0.9f * 3e-5f);  // 0.9^100 ~ 2.66e-5
  EXPECT_GT(ambient_transfer(0.001f, p), 0.1f + 0.9f * 0.9f);
}

TEST(AmbientTransfer, TinyAndHugeDMinStayFinite) {
  const AmbientParams tiny = params(0.2f, 1e-30f, 1.0f);
  EXPECT_NEAR(ambient_transfer(0.5e-30f, tiny), 0.6f, 1e-6f);
  EXPECT_EQ(ambient_transfer(1e-20f, tiny), 0.2f);
  const float denorm = std::numeric_limits<float>::denorm_min();
  EXPECT_NEAR(ambient_transfer(denorm, tiny), 1.0f, 1e-6f);
  const AmbientParams huge = params(0.2f, 1e30f, 1.0f);
  EXPECT_NEAR(ambient_transfer(0.5e30f, huge), 0.6f, 1e-6f);
  EXPECT_NEAR(ambient_transfer(1.0f, huge), 1.0f, 1e-6f);
  const AmbientParams smallest = params(0.2f, denorm, 1.0f);
  EXPECT_EQ(ambient_transfer(denorm, smallest), 0.2f);
  EXPECT_EQ(ambient_transfer(0.0f, smallest), 1.0f);
}

TEST(AmbientEncode, LengthIsKaAndDirectionKept) {
  const glm::vec3 n = glm::normalize(glm::vec3(1.0f, -2.0f, 0.5f));
  for (float ka : {kKaFloor, 0.01f, 0.2f, 0.5f, 0.999f, 1.0f}) {
    const glm::vec3 e = encode_ka(n, ka);
    EXPECT_NEAR(glm::length(e), ka, 1e-6f) << ka;
    EXPECT_NEAR(glm::dot(glm::normalize(e), n), 1.0f, 1e-6f) << ka;
  }
}

TEST(AmbientEncode, ClampsAndFloors) {
  const glm::vec3 n(0.0f, 1.0f, 0.0f);
  EXPECT_EQ(encode_ka(n, 0.0f), n * kKaFloor);  // ka 0 keeps the direction
  EXPECT_EQ(encode_ka(n, -3.0f), n * kKaFloor);
  EXPECT_EQ(encode_ka(n, kKaFloor / 2.0f), n * kKaFloor);
  EXPECT_EQ(encode_ka(n, 1.5f), n);
  EXPECT_EQ(encode_ka(n, kInf), n);
  EXPECT_EQ(encode_ka(n, -kInf), n * kKaFloor);
  EXPECT_EQ(encode_ka(n, kNaN), n * kKaFloor);  // NaN: the floor, by definition
  EXPECT_EQ(encode_ka(n, 0.5f), n * 0.5f);
}

TEST(AmbientEncode, SlightlyNonUnitNormalStillGetsLengthKa) {
  const glm::vec3 n(0.0f, 0.0f, 1.01f);
  EXPECT_NEAR(glm::length(encode_ka(n, 0.3f)), 0.3f, 1e-7f);
}

TEST(AmbientEncodeDeathTest, ZeroNormalIsAProgrammingError) {
  GTEST_FLAG_SET(death_test_style, "threadsafe");
  EXPECT_DEATH_IF_SUPPORTED((void)encode_ka(glm::vec3(0.0f), 0.5f), "non-zero normal");
}

// One triangle whose three vertices have the given normals and ka values.
EncodingBias one_triangle_bias(const std::vector<glm::vec3>& normals, const std::vector<float>& ka,
                               int samples) {
  return normal_length_interpolation_bias(normals, ka, {0, 1, 2}, samples);
}

TEST(AmbientBias, ZeroWhenNormalsAgree) {
  const glm::vec3 n = glm::normalize(glm::vec3(0.3f, 0.4f, 0.5f));
  const EncodingBias b = one_triangle_bias({n, n, n}, {0.1f, 0.6f, 1.0f}, 64);
  EXPECT_EQ(b.sample_count, 64u);
  EXPECT_NEAR(b.mean_error, 0.0, 1e-12);
  EXPECT_NEAR(b.mean_abs_error, 0.0, 1e-12);
  EXPECT_NEAR(b.max_abs_error, 0.0, 1e-12);
}

TEST(AmbientBias, PositiveAndGrowingWithAngle) {
  double prev_mean = 0.0;
  double prev_max = 0.0;
  for (float deg : {10.0f, 30.0f, 60.0f, 90.0f, 150.0f}) {
    const float a = glm::radians(deg);
    // Three normals spread by `deg` around +z.
    const glm::vec3 n0(0.0f, 0.0f, 1.0f);
    const glm::vec3 n1(std::sin(a), 0.0f, std::cos(a));
    const glm::vec3 n2(0.0f, std::sin(a), std::cos(a));
    const EncodingBias b = one_triangle_bias({n0, n1, n2}, {0.8f, 0.8f, 0.8f}, 64);
    EXPECT_GT(b.mean_error, 0.0) << deg;                      // decoded < interpolated
    EXPECT_DOUBLE_EQ(b.mean_error, b.mean_abs_error) << deg;  // never the other way
    EXPECT_GT(b.mean_error, prev_mean) << deg;
    EXPECT_GT(b.max_abs_error, prev_max) << deg;
    EXPECT_LE(b.max_abs_error, 0.8 + 1e-9) << deg;
    prev_mean = b.mean_error;
    prev_max = b.max_abs_error;
  }
}

TEST(AmbientBias, KnownValueAtEdgeMidpoint) {
  // Two perpendicular unit normals with ka 1, the third equal to the first: on the edge
  // between 0 and 1 at its midpoint the decoded length is |(n0 + n1) / 2| = 1/sqrt(2). With
  // one sample the pattern's first point is barycentric (0, 0.5, 0.5).
  const glm::vec3 a(1.0f, 0.0f, 0.0f);
  const glm::vec3 b(0.0f, 1.0f, 0.0f);
  const EncodingBias bias = one_triangle_bias({a, a, b}, {1.0f, 1.0f, 1.0f}, 1);
  EXPECT_NEAR(bias.max_abs_error, 1.0 - std::sqrt(0.5), 1e-6);
}

TEST(AmbientBias, DeterministicAndAveragedOverTriangles) {
  const std::vector<glm::vec3> normals = {
      {0, 0, 1}, glm::normalize(glm::vec3(1, 0, 1)), glm::normalize(glm::vec3(0, 1, 1)), {0, 0, 1}};
  const std::vector<float> ka = {0.3f, 0.9f, 0.5f, 1.0f};
  const std::vector<uint32_t> tris = {0, 1, 2, 0, 2, 3, 1, 3, 0};
  const EncodingBias a = normal_length_interpolation_bias(normals, ka, tris, 37);
  const EncodingBias b = normal_length_interpolation_bias(normals, ka, tris, 37);
  EXPECT_EQ(a.sample_count, 3u * 37u);
  EXPECT_EQ(a.mean_error, b.mean_error);
  EXPECT_EQ(a.mean_abs_error, b.mean_abs_error);
  EXPECT_EQ(a.max_abs_error, b.max_abs_error);
  // The mean over all triangles is the mean of the per-triangle means (same sample count).
  double sum = 0.0;
  for (int t = 0; t < 3; ++t) {
    const std::vector<uint32_t> one(tris.begin() + 3 * t, tris.begin() + 3 * t + 3);
    sum += normal_length_interpolation_bias(normals, ka, one, 37).mean_error;
  }
  EXPECT_NEAR(a.mean_error, sum / 3.0, 1e-12);
}

TEST(AmbientBias, EmptyTriangleList) {
  const EncodingBias b = normal_length_interpolation_bias({}, {}, {}, 8);
  EXPECT_EQ(b.sample_count, 0u);
  EXPECT_EQ(b.mean_error, 0.0);
  EXPECT_EQ(b.max_abs_error, 0.0);
}

}  // namespace
}  // namespace sylva
