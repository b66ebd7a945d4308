#include "tests/cli/cli_support.h"

#include <gtest/gtest.h>

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

const std::string& small_tree() {
  static std::string path = [] {
    std::string p = temp_dir("tree") + "/tree.glb";
    RunResult r = run_sylva("sample tree --leaves 2000 --seed 3 -o " + p);
    EXPECT_EQ(r.status, 0) << r.output;
    return p;
  }();
  return path;
}

}  // namespace sylva::test
