#include "core/gl/downsample.h"

#include <array>
#include <cmath>
#include <opencv2/core/utility.hpp>

#include "core/color.h"
#include "core/error.h"

namespace sylva {

namespace {

constexpr int kLinearSteps = 4096;  // resolution of the linear -> sRGB table

struct SrgbTables {
  std::array<float, 256> to_linear{};
  std::array<uint8_t, kLinearSteps + 1> to_srgb{};
  SrgbTables() {
    for (int i = 0; i < 256; ++i)
      to_linear[i] = srgb_to_linear(i / 255.0f);
    for (int i = 0; i <= kLinearSteps; ++i) {
      to_srgb[i] = cv::saturate_cast<uint8_t>(
          std::lround(255.0f * linear_to_srgb(static_cast<float>(i) / kLinearSteps)));
    }
  }
};

const SrgbTables& srgb_tables() {
  static const SrgbTables tables;
  return tables;
}

void check_input(const cv::Mat& m, int factor, int type) {
  SYLVA_CHECK(factor >= 1 && factor <= 4, "SSAA factor must be in [1, 4]");
  SYLVA_CHECK(m.type() == type, "unexpected image type for down-sampling");
  SYLVA_CHECK(m.rows % factor == 0 && m.cols % factor == 0, "size not a multiple of factor");
}

}  // namespace

cv::Mat downsample_color(const cv::Mat& bgra_srgb, int factor) {
  check_input(bgra_srgb, factor, CV_8UC4);
  if (factor == 1) return bgra_srgb;
  const SrgbTables& t = srgb_tables();
  cv::Mat out(bgra_srgb.rows / factor, bgra_srgb.cols / factor, CV_8UC4);
  const float inv = 1.0f / static_cast<float>(factor * factor);
  cv::parallel_for_(cv::Range(0, out.rows), [&](const cv::Range& rows) {
    for (int y = rows.start; y < rows.end; ++y) {
      auto* dst = out.ptr<cv::Vec4b>(y);
      for (int x = 0; x < out.cols; ++x) {
        float sum[4] = {0, 0, 0, 0};
        for (int sy = 0; sy < factor; ++sy) {
          const auto* src = bgra_srgb.ptr<cv::Vec4b>(y * factor + sy) + x * factor;
          for (int sx = 0; sx < factor; ++sx) {
            for (int c = 0; c < 3; ++c)
              sum[c] += t.to_linear[src[sx][c]];
            sum[3] += src[sx][3];
          }
        }
        for (int c = 0; c < 3; ++c) {
          dst[x][c] = t.to_srgb[std::lround(sum[c] * inv * kLinearSteps)];
        }
        dst[x][3] = cv::saturate_cast<uint8_t>(std::lround(sum[3] * inv));
      }
    }
  });
  return out;
}

cv::Mat downsample_covered(const cv::Mat& values, const cv::Mat& coverage, int factor,
                           bool renormalize) {
  SYLVA_CHECK(values.depth() == CV_32F && values.channels() <= 4, "float image expected");
  check_input(values, factor, values.type());
  SYLVA_CHECK(coverage.type() == CV_8UC1 && coverage.size() == values.size(), "coverage size");
  if (factor == 1) return values;
  const int channels = values.channels();
  cv::Mat out(values.rows / factor, values.cols / factor, values.type());
  cv::parallel_for_(cv::Range(0, out.rows), [&](const cv::Range& rows) {
    for (int y = rows.start; y < rows.end; ++y) {
      auto* dst = out.ptr<float>(y);
      for (int x = 0; x < out.cols; ++x) {
        double sum[4] = {0, 0, 0, 0};
        int covered = 0;
        for (int sy = 0; sy < factor; ++sy) {
          const auto* src = values.ptr<float>(y * factor + sy) + x * factor * channels;
          const auto* cov = coverage.ptr<uint8_t>(y * factor + sy) + x * factor;
          for (int sx = 0; sx < factor; ++sx) {
            if (!cov[sx]) continue;
            ++covered;
            for (int c = 0; c < channels; ++c)
              sum[c] += src[sx * channels + c];
          }
        }
        float* px = dst + x * channels;
        double norm = 0.0;
        for (int c = 0; c < channels; ++c) {
          px[c] = covered ? static_cast<float>(sum[c] / covered) : 0.0f;
          norm += static_cast<double>(px[c]) * px[c];
        }
        // Opposite normals can cancel (a leaf edge-on); keep the zero rather than divide by it.
        if (renormalize && norm > 1e-12) {
          const float inv = static_cast<float>(1.0 / std::sqrt(norm));
          for (int c = 0; c < channels; ++c)
            px[c] *= inv;
        }
      }
    }
  });
  return out;
}

cv::Mat downsample_id(const cv::Mat& ids, int factor) {
  check_input(ids, factor, CV_32SC1);
  if (factor == 1) return ids;
  cv::Mat out(ids.rows / factor, ids.cols / factor, CV_32SC1);
  cv::parallel_for_(cv::Range(0, out.rows), [&](const cv::Range& rows) {
    for (int y = rows.start; y < rows.end; ++y) {
      auto* dst = out.ptr<int32_t>(y);
      for (int x = 0; x < out.cols; ++x) {
        int32_t block[16];
        int n = 0;
        for (int sy = 0; sy < factor; ++sy) {
          const auto* src = ids.ptr<int32_t>(y * factor + sy) + x * factor;
          for (int sx = 0; sx < factor; ++sx)
            block[n++] = src[sx];
        }
        int32_t best = 0;
        int best_count = 0;
        for (int i = 0; i < n; ++i) {
          if (block[i] == 0 || block[i] == best) continue;
          int count = 0;
          for (int j = i; j < n; ++j)
            count += block[j] == block[i];
          if (count > best_count) {
            best = block[i];
            best_count = count;
          }
        }
        dst[x] = best;
      }
    }
  });
  return out;
}

}  // namespace sylva
