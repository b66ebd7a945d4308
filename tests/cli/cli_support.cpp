#include "tests/cli/cli_support.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <functional>
#include <map>
#include <sstream>
#include <vector>

#include "tests/test_support.h"

namespace sylva::test {

void expect_input_error(const std::string& args, const std::string& needle) {
  RunResult r = run_sylva(args);
  EXPECT_EQ(r.status, 2) << args << "\n" << r.output;
  EXPECT_EQ(count_lines(r.output), 1) << args << "\n" << r.output;
  EXPECT_EQ(r.output.rfind("sylva: error: ", 0), 0u) << r.output;
  EXPECT_NE(r.output.find(needle), std::string::npos)
      << "expected '" << needle << "' in " << r.output;
}

std::vector<std::string> listing(const std::string& dir) {
  std::vector<std::string> names;
  for (const auto& e : std::filesystem::directory_iterator(dir))
    names.push_back(e.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

std::string decoded_frames(const std::string& video) {
  const RunResult r =
      run_command("ffmpeg -v error -i " + video + " -map 0:v -f framemd5 - | grep -v '^#'");
  EXPECT_EQ(r.status, 0) << r.output;
  return r.output;
}

namespace {

// Where the sampled scenes of every test program are kept: beside the build's sylva, one file
// per (arguments, sylva's size and time), so a rebuilt sylva samples afresh.
std::string shared_scene_path(const std::string& tag, const std::string& args) {
  namespace fs = std::filesystem;
  const fs::path sylva(SYLVA_BINARY);
  std::error_code ec;
  const auto size = fs::file_size(sylva, ec);
  const auto time = fs::last_write_time(sylva, ec).time_since_epoch().count();
  const size_t key =
      std::hash<std::string>{}(args + "|" + std::to_string(size) + "|" + std::to_string(time));
  const fs::path dir = sylva.parent_path().parent_path() / "test-scenes";
  fs::create_directories(dir, ec);
  return (dir / (tag + "-" + std::to_string(key) + ".glb")).string();
}

}  // namespace

const std::string& sampled_scene(const std::string& tag, const std::string& args) {
  static std::map<std::string, std::string> paths;  // tag -> .glb; map references stay valid
  auto it = paths.find(tag);
  if (it != paths.end()) return it->second;
  // Each ctest entry is a process of its own: the scene is sampled once for all of them, into a
  // file of this process's, then renamed into place (atomic: a reader never sees half a file).
  const std::string p = shared_scene_path(tag, args);
  if (!std::filesystem::exists(p)) {
    const std::string mine = temp_dir(tag) + "/" + tag + ".glb";
    RunResult r = run_sylva("sample " + args + " -o " + mine);
    EXPECT_EQ(r.status, 0) << r.output;
    std::error_code ec;
    std::filesystem::rename(mine, p, ec);
    if (ec) std::filesystem::copy_file(mine, p, std::filesystem::copy_options::overwrite_existing);
  }
  return paths.emplace(tag, p).first->second;
}

const std::string& small_tree() {
  return sampled_scene("tree", "tree --leaves 2000 --seed 3");
}

cv::Mat oiio_channels(const std::string& image, const std::string& names, const std::string& dir) {
  static int n = 0;
  const std::string out = dir + "/oiio-" + std::to_string(n++);
  std::filesystem::create_directories(out);
  std::string list = names;
  std::replace(list.begin(), list.end(), ',', ' ');
  const RunResult r =
      run_command("/usr/bin/python3 " + source_dir() + "/tests/tools/read_channels.py " + image +
                  " " + out + " " + list);
  EXPECT_EQ(r.status, 0) << r.output;
  if (r.status != 0) return {};
  std::vector<cv::Mat> planes;
  std::istringstream lines(r.output);
  std::string name, kind;
  for (int w = 0, h = 0; lines >> name >> kind >> w >> h;) {
    const std::string bytes = read_file(out + "/" + name + ".raw");
    if (bytes.size() != size_t(w) * size_t(h) * 4) return {};
    cv::Mat m(h, w, kind == "uint" ? CV_32SC1 : CV_32FC1);
    std::memcpy(m.data, bytes.data(), bytes.size());
    planes.push_back(m);
  }
  cv::Mat merged;
  cv::merge(planes, merged);
  return merged;
}

std::vector<std::map<std::string, std::string>> parse_csv(const std::string& text) {
  std::vector<std::vector<std::string>> lines;
  std::vector<std::string> fields(1);
  bool quoted = false;
  for (size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (quoted) {
      if (c == '"' && i + 1 < text.size() && text[i + 1] == '"') {
        fields.back() += '"';
        ++i;
      } else if (c == '"') {
        quoted = false;
      } else {
        fields.back() += c;
      }
    } else if (c == '"') {
      quoted = true;
    } else if (c == ',') {
      fields.emplace_back();
    } else if (c == '\n') {
      lines.push_back(fields);
      fields.assign(1, "");
    } else {
      fields.back() += c;
    }
  }
  std::vector<std::map<std::string, std::string>> rows;
  for (size_t l = 1; l < lines.size(); ++l) {
    EXPECT_EQ(lines[l].size(), lines[0].size()) << "line " << l;
    std::map<std::string, std::string>& row = rows.emplace_back();
    for (size_t f = 0; f < lines[0].size() && f < lines[l].size(); ++f)
      row[lines[0][f]] = lines[l][f];
  }
  return rows;
}

double number(const std::map<std::string, std::string>& row, const std::string& column) {
  const auto it = row.find(column);
  EXPECT_TRUE(it != row.end() && !it->second.empty()) << column;
  return it == row.end() || it->second.empty() ? 0.0 : std::stod(it->second);
}

}  // namespace sylva::test
