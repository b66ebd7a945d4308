#include "styles/frame_folder.h"

#include <cstdio>
#include <filesystem>
#include <string_view>

#include "core/error.h"
#include "core/io/atomic_file.h"
#include "core/io/codecs_png.h"

namespace fs = std::filesystem;

namespace sylva {

const char* frame_format_name(FrameFormat format) {
  switch (format) {
    case FrameFormat::Png:
      return "png";
    case FrameFormat::Exr:
      return "exr";
    case FrameFormat::Svg:
      return "svg";
    case FrameFormat::Pdf:
      return "pdf";
  }
  return "png";
}

FrameFormat parse_frame_format(const std::string& name, const std::string& where) {
  for (FrameFormat f : {FrameFormat::Png, FrameFormat::Exr, FrameFormat::Svg, FrameFormat::Pdf})
    if (name == frame_format_name(f)) return f;
  throw InputError(where, "must be png, exr, svg or pdf, not '" + name + "'");
}

std::string frame_file_name(int frame, FrameFormat format) {
  char name[32];
  std::snprintf(name, sizeof name, "frame-%05d.", frame);
  return std::string(name) + frame_format_name(format);
}

int frame_index_of(const std::string& name, FrameFormat format) {
  const std::string prefix = "frame-";
  std::string suffix = ".";
  suffix += frame_format_name(format);
  if (name.size() != prefix.size() + 5 + suffix.size() || !name.starts_with(prefix) ||
      !name.ends_with(suffix))
    return -1;
  int index = 0;
  for (size_t i = prefix.size(); i < prefix.size() + 5; ++i) {
    if (name[i] < '0' || name[i] > '9') return -1;
    index = index * 10 + (name[i] - '0');
  }
  return index;
}

std::string frame_problem(const std::string& path, FrameFormat format) {
  std::error_code ec;
  if (!fs::is_regular_file(path, ec)) return "no such file";
  std::string bytes;
  try {
    bytes = read_file_bytes(path);
  } catch (const InputError& e) {
    return e.what();
  }
  const auto* data = reinterpret_cast<const unsigned char*>(bytes.data());
  if (format == FrameFormat::Png) {
    DecodeReport report;
    if (!decode_png(data, bytes.size(), &report).empty()) return "";
    return "cannot decode the image" + (report.error.empty() ? "" : ": " + report.error);
  }
  const auto ends_with = [&](std::string_view tail) {
    const size_t end = bytes.find_last_not_of(" \r\n");
    return end != std::string::npos && std::string_view(bytes.data(), end + 1).ends_with(tail);
  };
  if (format == FrameFormat::Svg) return ends_with("</svg>") ? "" : "truncated (no closing </svg>)";
  if (format == FrameFormat::Pdf) return ends_with("%%EOF") ? "" : "truncated (no %%EOF)";
  const bool exr =
      bytes.size() > 4 && data[0] == 0x76 && data[1] == 0x2f && data[2] == 0x31 && data[3] == 0x01;
  return exr ? "" : "not an OpenEXR file";
}

int remove_stale_frame_temporaries(const std::string& dir, int begin, int end, FrameFormat format) {
  std::error_code ec;
  int removed = 0;
  for (const auto& entry : fs::directory_iterator(dir, ec)) {
    const std::string name = entry.path().filename().string();
    const size_t tmp = name.rfind(".tmp");
    if (name.size() < 2 || name[0] != '.' || tmp == std::string::npos) continue;
    const int index = frame_index_of(name.substr(1, tmp - 1), format);
    if (index < begin || index >= end) continue;
    std::error_code rm;
    if (fs::remove(entry.path(), rm)) ++removed;
  }
  return removed;
}

}  // namespace sylva
