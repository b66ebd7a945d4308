// The README's examples are true: every `sylva ...` line in its ```sh blocks runs, in order,
// in a fresh folder, and exits 0.
#include <gtest/gtest.h>

#include <sstream>

#include "tests/test_support.h"

namespace sylva::test {
namespace {

TEST(Readme, ExampleCommandsRun) {
  std::istringstream readme(read_file(source_dir() + "/README.md"));
  std::string dir = temp_dir("readme");
  bool in_sh = false;
  int ran = 0;
  for (std::string line; std::getline(readme, line);) {
    if (line.rfind("```", 0) == 0) {
      in_sh = line == "```sh";
      continue;
    }
    if (!in_sh || line.rfind("sylva ", 0) != 0) continue;
    std::string cmd = line.substr(6);
    size_t hash = cmd.find("  #");
    if (hash != std::string::npos) cmd = cmd.substr(0, hash);
    RunResult r =
        run_sylva("--version >/dev/null && cd " + dir + " && " + sylva_binary() + " " + cmd);
    EXPECT_EQ(r.status, 0) << line << "\n" << r.output;
    ++ran;
  }
  EXPECT_GE(ran, 4);
}

}  // namespace
}  // namespace sylva::test
