// look_images DIR [edges|ink|toon|watercolor]...: writes images of single passes on synthetic
// G-buffers into DIR for judging them by eye (scripts/look.sh builds and runs it). Not a
// check: nothing here fails on what the images look like. The scenes are the pass tests'
// (tests/passes/*_scenes.h). Bad input (a folder that cannot be made, an unknown set): one line,
// exit 2.
#include <cstdio>
#include <filesystem>
#include <map>
#include <opencv2/imgcodecs.hpp>
#include <stdexcept>
#include <string>
#include <vector>

#include "tests/look/look.h"

namespace sylva::test {
namespace {

const std::map<std::string, void (*)(const Save&)>& looks() {
  static const std::map<std::string, void (*)(const Save&)> l = {{"edges", &edges_look},
                                                                 {"ink", &ink_look},
                                                                 {"toon", &toon_look},
                                                                 {"watercolor", &watercolor_look}};
  return l;
}

}  // namespace
}  // namespace sylva::test

int main(int argc, char** argv) {
  using namespace sylva::test;
  if (argc < 2) {
    std::fprintf(stderr, "usage: look_images DIR [edges|ink|toon|watercolor]...\n");
    return 2;
  }
  const std::string dir = argv[1];
  std::vector<std::string> names(argv + 2, argv + argc);
  if (names.empty())
    for (const auto& [name, look] : looks())
      names.push_back(name);
  for (const std::string& name : names)
    if (!looks().contains(name)) {
      std::fprintf(stderr, "look_images: error: unknown set '%s' (edges, ink, toon, watercolor)\n",
                   name.c_str());
      return 2;
    }
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec) {
    std::fprintf(stderr, "look_images: error: %s: %s\n", dir.c_str(), ec.message().c_str());
    return 2;
  }
  const Save save = [&dir](const std::string& file, const cv::Mat& image) {
    const std::string path = dir + "/" + file;
    if (!cv::imwrite(path, image)) throw std::runtime_error("cannot write " + path);
    std::printf("wrote %s\n", path.c_str());
  };
  try {
    for (const std::string& name : names)
      looks().at(name)(save);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "look_images: error: %s\n", e.what());
    return 2;
  }
  return 0;
}
