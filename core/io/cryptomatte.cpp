#include "core/io/cryptomatte.h"

#include <murmurhash.h>

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <nlohmann/json.hpp>
#include <utility>

#include "core/error.h"

namespace sylva {

uint32_t murmur3_32(std::string_view data) {
  uint32_t out[1] = {0};
  lmmh_x86_32(data.data(), unsigned(data.size()), 0, out);
  return out[0];
}

float cryptomatte_id(uint32_t hash) {
  const uint32_t exponent = std::clamp((hash >> 23) & 0xffu, 1u, 254u);
  const uint32_t bits = (hash & 0x807fffffu) | (exponent << 23);
  float f;
  std::memcpy(&f, &bits, 4);
  return f;
}

std::string cryptomatte_hex(float id) {
  uint32_t bits;
  std::memcpy(&bits, &id, 4);
  char hex[9];
  std::snprintf(hex, sizeof hex, "%08x", bits);
  return hex;
}

namespace {

using Ranked = std::vector<std::pair<float, int>>;  // (float id, samples), best first

// The ids of one pixel's block of samples, ranked by how many samples they cover.
void rank_block(const cv::Mat& samples, int x0, int y0, int factor, const std::vector<float>& ids,
                Ranked& ranked) {
  ranked.clear();
  for (int y = y0; y < y0 + factor; ++y)
    for (int x = x0; x < x0 + factor; ++x) {
      const int32_t id = samples.at<int32_t>(y, x);
      if (id == 0) continue;
      SYLVA_CHECK(id > 0 && size_t(id) < ids.size(), "add_cryptomatte: an id without a name");
      const float f = ids[size_t(id)];
      auto it = std::find_if(ranked.begin(), ranked.end(),
                             [f](const auto& r) { return std::memcmp(&r.first, &f, 4) == 0; });
      if (it == ranked.end())
        ranked.emplace_back(f, 1);
      else
        ++it->second;
    }
  std::sort(ranked.begin(), ranked.end(), [](const auto& a, const auto& b) {
    return a.second != b.second ? a.second > b.second : a.first < b.first;
  });
}

std::string manifest(const CryptomatteLayer& layer) {
  nlohmann::json m = nlohmann::json::object();
  for (const std::string& name : layer.names)
    m[name] = cryptomatte_hex(cryptomatte_id(murmur3_32(name)));
  return m.dump();
}

}  // namespace

void add_cryptomatte(ExrImage& exr, const CryptomatteLayer& layer, const cv::Mat& samples,
                     int factor, int ranks) {
  SYLVA_CHECK(samples.type() == CV_32SC1 && factor >= 1 && samples.cols % factor == 0 &&
                  samples.rows % factor == 0,
              "add_cryptomatte: int32 id samples, a whole factor of the image");
  SYLVA_CHECK(ranks >= 2 && ranks <= 16 && ranks % 2 == 0, "add_cryptomatte: 2 to 16 ranks");
  const int w = samples.cols / factor, h = samples.rows / factor;
  if (exr.channels.empty()) {
    exr.width = w;
    exr.height = h;
  }
  SYLVA_CHECK(exr.width == w && exr.height == h, "add_cryptomatte: samples of the image's size");
  std::vector<float> ids(layer.names.size() + 1, 0.0f);
  for (size_t k = 0; k < layer.names.size(); ++k)
    ids[k + 1] = cryptomatte_id(murmur3_32(layer.names[k]));
  const float per_sample = 1.0f / float(factor * factor);
  std::vector<cv::Mat> planes(size_t(ranks) * 2);
  for (cv::Mat& p : planes)
    p = cv::Mat::zeros(h, w, CV_32FC1);
  cv::parallel_for_(cv::Range(0, h), [&](const cv::Range& rows) {
    Ranked ranked;
    for (int y = rows.start; y < rows.end; ++y)
      for (int x = 0; x < w; ++x) {
        rank_block(samples, x * factor, y * factor, factor, ids, ranked);
        for (size_t r = 0; r < std::min(ranked.size(), size_t(ranks)); ++r) {
          planes[2 * r].at<float>(y, x) = ranked[r].first;
          planes[2 * r + 1].at<float>(y, x) = float(ranked[r].second) * per_sample;
        }
      }
  });
  for (int l = 0; l < ranks / 2; ++l) {
    const std::string prefix = layer.name + char('0' + l / 10) + char('0' + l % 10) + ".";
    for (int c = 0; c < 4; ++c)
      exr.channels.push_back({prefix + "RGBA"[c], ExrType::Float, planes[size_t(4 * l + c)]});
  }
  char hash[9];
  std::snprintf(hash, sizeof hash, "%08x", murmur3_32(layer.name));
  const std::string key = "cryptomatte/" + std::string(hash, 7) + "/";
  exr.strings.emplace_back(key + "name", layer.name);
  exr.strings.emplace_back(key + "hash", "MurmurHash3_32");
  exr.strings.emplace_back(key + "conversion", "uint32_to_float32");
  exr.strings.emplace_back(key + "manifest", manifest(layer));
}

}  // namespace sylva
