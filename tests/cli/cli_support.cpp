#include "tests/cli/cli_support.h"

#include <gtest/gtest.h>

#include <map>

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

const std::string& sampled_scene(const std::string& tag, const std::string& args) {
  static std::map<std::string, std::string> paths;  // tag -> .glb; map references stay valid
  auto it = paths.find(tag);
  if (it != paths.end()) return it->second;
  std::string p = temp_dir(tag) + "/" + tag + ".glb";
  RunResult r = run_sylva("sample " + args + " -o " + p);
  EXPECT_EQ(r.status, 0) << r.output;
  return paths.emplace(tag, p).first->second;
}

const std::string& small_tree() {
  return sampled_scene("tree", "tree --leaves 2000 --seed 3");
}

}  // namespace sylva::test
