#include "npr/bspline.h"

#include <algorithm>
#include <cmath>

#include "core/error.h"

namespace sylva {

namespace {

// Uniform cubic B-spline basis at u in [0, 1].
void bspline_basis(double u, double b[4]) {
  const double u2 = u * u, u3 = u2 * u, v = 1.0 - u;
  b[0] = v * v * v / 6.0;
  b[1] = (3.0 * u3 - 6.0 * u2 + 4.0) / 6.0;
  b[2] = (-3.0 * u3 + 3.0 * u2 + 3.0 * u + 1.0) / 6.0;
  b[3] = u3 / 6.0;
}

// Catmull-Rom through p1 (u = 0) and p2 (u = 1).
template <class T>
T catmull_rom_segment(const T& p0, const T& p1, const T& p2, const T& p3, double u) {
  const double u2 = u * u, u3 = u2 * u;
  const double c0 = -0.5 * u3 + u2 - 0.5 * u;
  const double c1 = 1.5 * u3 - 2.5 * u2 + 1.0;
  const double c2 = -1.5 * u3 + 2.0 * u2 + 0.5 * u;
  const double c3 = 0.5 * u3 - 0.5 * u2;
  return p0 * static_cast<float>(c0) + p1 * static_cast<float>(c1) + p2 * static_cast<float>(c2) +
         p3 * static_cast<float>(c3);
}

template <class T>
T catmull_rom_any(const std::vector<T>& keys, double t) {
  SYLVA_CHECK(!keys.empty(), "catmull_rom: no keys");
  const int n = static_cast<int>(keys.size());
  if (n == 1 || !(t > 0.0)) return keys.front();
  if (t >= n - 1) return keys.back();
  const int i = std::min(static_cast<int>(std::floor(t)), n - 2);
  const double u = t - i;
  auto key = [&](int k) -> T {
    if (k < 0) return keys[0] * 2.0f - keys[1];
    if (k >= n) return keys[static_cast<size_t>(n - 1)] * 2.0f - keys[static_cast<size_t>(n - 2)];
    return keys[static_cast<size_t>(k)];
  };
  return catmull_rom_segment(key(i - 1), key(i), key(i + 1), key(i + 2), u);
}

}  // namespace

glm::vec2 closed_bspline_point(const std::vector<glm::vec2>& p, double t) {
  SYLVA_CHECK(!p.empty(), "closed_bspline_point: no control points");
  const int n = static_cast<int>(p.size());
  t = std::fmod(t, static_cast<double>(n));
  if (t < 0) t += n;
  int i = static_cast<int>(std::floor(t));
  if (i >= n) i = n - 1;
  double b[4];
  bspline_basis(t - i, b);
  glm::dvec2 sum(0.0);
  for (int k = 0; k < 4; ++k)
    sum += b[k] * glm::dvec2(p[static_cast<size_t>(((i - 1 + k) % n + n) % n)]);
  return glm::vec2(sum);
}

std::vector<glm::vec2> sample_closed_bspline(const std::vector<glm::vec2>& p,
                                             int samples_per_segment) {
  SYLVA_CHECK(samples_per_segment >= 1, "sample_closed_bspline: samples_per_segment < 1");
  std::vector<glm::vec2> out;
  out.reserve(p.size() * static_cast<size_t>(samples_per_segment));
  for (size_t i = 0; i < p.size(); ++i)
    for (int s = 0; s < samples_per_segment; ++s)
      out.push_back(closed_bspline_point(
          p, static_cast<double>(i) + static_cast<double>(s) / samples_per_segment));
  return out;
}

glm::vec2 catmull_rom(const std::vector<glm::vec2>& keys, double t) {
  return catmull_rom_any(keys, t);
}

float catmull_rom(const std::vector<float>& keys, double t) {
  return catmull_rom_any(keys, t);
}

}  // namespace sylva
