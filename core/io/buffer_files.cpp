#include "core/io/buffer_files.h"

#include <nlohmann/json.hpp>
#include <opencv2/imgproc.hpp>

#include "core/error.h"
#include "core/io/atomic_file.h"
#include "core/io/exr_writer.h"
#include "core/io/image_io.h"

namespace sylva {

void check_buffer_files(const BufferFiles& files) {
  if (files.format != "tiff" && files.format != "exr")
    throw InputError("--format", "unknown format '" + files.format + "' (allowed: tiff, exr)");
  parse_exr_compression(files.compression, "--compression");
}

std::string camera_json(const Camera& c) {
  auto mat = [](const glm::mat4& m) {
    nlohmann::json rows = nlohmann::json::array();  // row-major: rows[i][j] = m[j][i]
    for (int i = 0; i < 4; ++i)
      rows.push_back({m[0][i], m[1][i], m[2][i], m[3][i]});
    return rows;
  };
  nlohmann::json j = {{"width", c.width},
                      {"height", c.height},
                      {"near", c.near_plane},
                      {"far", c.far_plane},
                      {"orthographic", c.ortho},
                      {"eye", {c.eye.x, c.eye.y, c.eye.z}},
                      {"view", mat(c.view)},
                      {"projection", mat(c.proj)},
                      {"matrix_layout", "row-major, column vectors: p_view = view * p_world"}};
  return j.dump(2) + "\n";
}

namespace {

// A buffer as its TIFF holds it: ids as float32 (exact below 2^24), and 3-channel (x, y, z)
// buffers in the file's R, G, B for every reader (OpenCV writes a Mat's channel 0 as blue).
cv::Mat tiff_of(Target t, const cv::Mat& m) {
  cv::Mat file = m;
  if (t == Target::Id) m.convertTo(file, CV_32F);
  if (m.channels() == 3) cv::cvtColor(m, file, cv::COLOR_RGB2BGR);
  return file;
}

cv::Mat preview_of(Target t, const cv::Mat& m) {
  switch (t) {
    case Target::Id:
      return preview_ids(m);
    case Target::Normal:
      return preview_normal(m);
    case Target::Position:
      return preview_position(m);
    case Target::Depth:
      return preview_depth(m);
    default:
      return preview_scalar(m);
  }
}

void write_tiff_set(const std::filesystem::path& dir, const BufferImages& buffers) {
  for (const auto& [t, m] : buffers) {
    const std::string name = target_name(t);
    if (t == Target::Color || t == Target::Albedo) {
      write_image((dir / (name + ".png")).string(), m);
      continue;
    }
    write_image((dir / (name + ".tiff")).string(), tiff_of(t, m));
    write_image((dir / (name + ".preview.png")).string(), preview_of(t, m));
  }
}

// Compositors' names: R G B A, albedo.R/G/B, N.X/Y/Z, Z, P.X/Y/Z, id (uint), ka, ao.
void add_buffer_channels(ExrImage& exr, Target t, const cv::Mat& m) {
  switch (t) {
    case Target::Color:
      add_exr_colour(exr, m, "");
      return;
    case Target::Albedo: {
      add_exr_colour(exr, m, "albedo.");
      exr.channels.pop_back();  // albedo.A repeats A
      return;
    }
    case Target::Normal:
      add_exr_channels(exr, m, {"N.X", "N.Y", "N.Z"}, ExrType::Float);
      return;
    case Target::Position:
      add_exr_channels(exr, m, {"P.X", "P.Y", "P.Z"}, ExrType::Float);
      return;
    case Target::Depth:
      add_exr_channels(exr, m, {"Z"}, ExrType::Float);
      return;
    case Target::Id:
      add_exr_channels(exr, m, {"id"}, ExrType::Uint);
      return;
    default:
      add_exr_channels(exr, m, {target_name(t)}, ExrType::Float);
  }
}

void write_exr_file(const std::filesystem::path& path, const BufferImages& buffers,
                    const Camera& camera, const BufferFiles& files,
                    const std::vector<CryptomatteImage>& mattes) {
  ExrImage exr;
  exr.compression = parse_exr_compression(files.compression, "--compression");
  for (const auto& [t, m] : buffers)
    add_buffer_channels(exr, t, m);
  for (const CryptomatteImage& m : mattes)
    add_cryptomatte(exr, m.layer, m.samples, m.factor, cryptomatte_ranks(m.factor));
  exr.camera =
      ExrCamera{camera.view, camera.proj * camera.view, camera.near_plane, camera.far_plane};
  write_exr(path.string(), exr);
}

}  // namespace

void write_buffer_files(const std::filesystem::path& dir, const BufferImages& buffers,
                        const Camera& camera, const BufferFiles& files,
                        const std::vector<CryptomatteImage>& mattes) {
  if (files.format == "exr")
    write_exr_file(dir / "buffers.exr", buffers, camera, files, mattes);
  else
    write_tiff_set(dir, buffers);
  write_file_atomic((dir / "camera.json").string(), camera_json(camera));
}

}  // namespace sylva
