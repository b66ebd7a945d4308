// Helpers of the end-to-end CLI tests (tests/cli).
#pragma once

#include <string>

namespace sylva::test {

// `sylva <args>` exits 2 with a single "sylva: error:" line that mentions `needle`.
void expect_input_error(const std::string& args, const std::string& needle);

// A scene written once per test program by `sylva sample ARGS -o <temp>/<tag>.glb`.
const std::string& sampled_scene(const std::string& tag, const std::string& args);

// A small sample tree (2000 leaves, seed 3), generated once per test program.
const std::string& small_tree();

}  // namespace sylva::test
