#include "core/io/image_io.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <opencv2/imgcodecs.hpp>  // the enums only: the functions are in the plugin
#include <vector>

#include "core/error.h"
#include "core/io/atomic_file.h"
#include "core/io/codecs.h"
#include "core/io/codecs_png.h"

namespace sylva {

namespace {

// PNG through libpng rather than cv::imencode: OpenCV gives no say over the row filters, and
// its adaptive filtering at zlib level 6 took 57 ms of a 1024² ink render's 0.76 s. Level 3
// without filters takes a seventh of that; line drawings (flat paper, runs of ink) come out
// smaller, shaded renders about 15% larger.
constexpr PngEncodeOptions kPngOptions = {3, false, false, 0.0};

std::string lower_extension(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return std::tolower(c); });
  return ext;
}
}  // namespace

bool all_finite(const cv::Mat& image) {
  if (image.depth() != CV_32F && image.depth() != CV_64F) return true;
  return cv::checkRange(image);
}

void write_image(const std::string& path, const cv::Mat& image) {
  write_image(path, image, 0.0);
}

void write_image(const std::string& path, const cv::Mat& image, double dpi) {
  SYLVA_CHECK(!image.empty(), "write_image: empty image for " + path);
  SYLVA_CHECK(all_finite(image), "write_image: non-finite values in " + path);
  std::string ext = lower_extension(path);
  if (ext == ".png") {
    SYLVA_CHECK(image.depth() == CV_8U || image.depth() == CV_16U, "PNG needs 8/16-bit");
    SYLVA_CHECK(image.channels() >= 1 && image.channels() <= 4, "PNG needs 1 to 4 channels");
    std::string png;
    png.reserve(image.total() * image.elemSize() / 8);
    PngEncodeOptions options = kPngOptions;
    options.dpi = dpi;
    if (!encode_png(image, options, png)) throw InputError(path, "cannot encode image as .png");
    write_file_atomic(path, png);
    return;
  }
  std::vector<int> params;
  if (ext == ".tif" || ext == ".tiff") {
    params = {cv::IMWRITE_TIFF_COMPRESSION, 1};  // uncompressed: exact and fast
    if (dpi > 0.0) {
      const int d = int(std::lround(dpi));
      params.insert(params.end(), {cv::IMWRITE_TIFF_RESUNIT, 2, cv::IMWRITE_TIFF_XDPI, d,
                                   cv::IMWRITE_TIFF_YDPI, d});  // 2: inch
    }
  } else if (ext == ".exr") {
    SYLVA_CHECK(image.depth() == CV_32F, "EXR needs float32");
  } else if (ext == ".jpg" || ext == ".jpeg") {
    params = {cv::IMWRITE_JPEG_QUALITY, 95};
  } else {
    throw InputError(
        path, "unsupported image extension '" + ext + "' (allowed: .png, .tiff, .tif, .exr, .jpg)");
  }
  std::vector<uchar> bytes;
  bool ok = false;
  try {
    ok = codecs().encode(ext, image, bytes, params);
  } catch (const cv::Exception& e) {
    throw InputError(path, std::string("cannot encode image: ") + e.err);
  }
  if (!ok) throw InputError(path, "cannot encode image as " + ext);
  write_file_atomic(path, std::string(bytes.begin(), bytes.end()));
}

cv::Mat read_image(const std::string& path) {
  std::string bytes = read_file_bytes(path);
  cv::Mat img;
  try {
    img = decode_image(reinterpret_cast<const unsigned char*>(bytes.data()), bytes.size());
  } catch (const cv::Exception&) {
    img.release();
  }
  if (img.empty())
    throw InputError(path,
                     "not a readable image (PNG, JPEG, TIFF, BMP, WebP, PNM, OpenEXR or Radiance "
                     "HDR expected)");
  return img;
}

cv::Mat preview_normal(const cv::Mat& normal) {
  cv::Mat out(normal.size(), CV_8UC3, cv::Scalar::all(0));
  for (int y = 0; y < normal.rows; ++y)
    for (int x = 0; x < normal.cols; ++x) {
      cv::Vec3f n = normal.at<cv::Vec3f>(y, x);
      if (n == cv::Vec3f(0, 0, 0)) continue;
      // BGR order: blue = z, green = y, red = x (the usual normal-map look).
      out.at<cv::Vec3b>(y, x) = cv::Vec3b(cv::saturate_cast<uchar>((n[2] + 1) * 127.5f),
                                          cv::saturate_cast<uchar>((n[1] + 1) * 127.5f),
                                          cv::saturate_cast<uchar>((n[0] + 1) * 127.5f));
    }
  return out;
}

cv::Mat preview_depth(const cv::Mat& depth) {
  cv::Mat out(depth.size(), CV_8UC3, cv::Scalar::all(0));
  float lo = 1e30f, hi = 0;
  for (int y = 0; y < depth.rows; ++y)
    for (int x = 0; x < depth.cols; ++x) {
      float d = depth.at<float>(y, x);
      if (d <= 0) continue;
      lo = std::min(lo, d);
      hi = std::max(hi, d);
    }
  float range = std::max(hi - lo, 1e-6f);
  for (int y = 0; y < depth.rows; ++y)
    for (int x = 0; x < depth.cols; ++x) {
      float d = depth.at<float>(y, x);
      if (d <= 0) continue;
      uchar v = cv::saturate_cast<uchar>(255.0f - 200.0f * (d - lo) / range);
      out.at<cv::Vec3b>(y, x) = cv::Vec3b(v, v, v);
    }
  return out;
}

cv::Mat preview_position(const cv::Mat& position) {
  cv::Vec3f lo(1e30f, 1e30f, 1e30f), hi(-1e30f, -1e30f, -1e30f);
  auto covered = [](const cv::Vec3f& p) { return p != cv::Vec3f(0, 0, 0); };
  for (int y = 0; y < position.rows; ++y)
    for (int x = 0; x < position.cols; ++x) {
      cv::Vec3f p = position.at<cv::Vec3f>(y, x);
      if (!covered(p)) continue;
      for (int c = 0; c < 3; ++c) {
        lo[c] = std::min(lo[c], p[c]);
        hi[c] = std::max(hi[c], p[c]);
      }
    }
  cv::Mat out(position.size(), CV_8UC3, cv::Scalar::all(0));
  for (int y = 0; y < position.rows; ++y)
    for (int x = 0; x < position.cols; ++x) {
      cv::Vec3f p = position.at<cv::Vec3f>(y, x);
      if (!covered(p)) continue;
      cv::Vec3b& o = out.at<cv::Vec3b>(y, x);
      for (int c = 0; c < 3; ++c)
        o[2 - c] = cv::saturate_cast<uchar>(40.0f + 215.0f * (p[c] - lo[c]) /
                                                        std::max(hi[c] - lo[c], 1e-6f));
    }
  return out;
}

cv::Mat preview_ids(const cv::Mat& ids) {
  cv::Mat out(ids.size(), CV_8UC3, cv::Scalar::all(0));
  for (int y = 0; y < ids.rows; ++y)
    for (int x = 0; x < ids.cols; ++x) {
      uint32_t id = static_cast<uint32_t>(ids.at<int32_t>(y, x));
      if (id == 0) continue;
      uint32_t h = id * 2654435761u;  // Knuth's multiplicative hash spreads neighbours apart
      h ^= h >> 15;
      out.at<cv::Vec3b>(y, x) =
          cv::Vec3b(64 + (h & 0xBF), 64 + ((h >> 8) & 0xBF), 64 + ((h >> 16) & 0xBF));
    }
  return out;
}

cv::Mat preview_scalar(const cv::Mat& values) {
  cv::Mat out;
  values.convertTo(out, CV_8U, 255.0);
  cv::Mat bgr;
  cv::merge(std::vector<cv::Mat>{out, out, out}, bgr);
  return bgr;
}

}  // namespace sylva
