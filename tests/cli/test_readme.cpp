// The README's examples are true: every `sylva ...` line in its ```sh blocks runs, in order,
// in a fresh folder, and exits 0; a ```toml block whose first line is "# NAME.toml" is written
// there as NAME.toml first.
#include <gtest/gtest.h>

#include <sstream>

#include "tests/test_support.h"

namespace sylva::test {
namespace {

TEST(Readme, ExampleCommandsRun) {
  std::istringstream readme(read_file(source_dir() + "/README.md"));
  std::string dir = temp_dir("readme");
  bool in_sh = false, in_toml = false;
  std::string toml;
  int ran = 0;
  for (std::string line; std::getline(readme, line);) {
    if (line.rfind("```", 0) == 0) {
      if (in_toml && toml.rfind("# ", 0) == 0) {
        const std::string name = toml.substr(2, toml.find('\n') - 2);
        if (name.ends_with(".toml")) write_file(dir + "/" + name, toml);
      }
      in_sh = line == "```sh";
      in_toml = line == "```toml";
      toml.clear();
      continue;
    }
    if (in_toml) toml += line + "\n";
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
