// The README's examples are true: every `sylva ...` line in its ```sh blocks runs, in order,
// in a fresh folder, and exits 0; a ```toml block whose first line is "# NAME.toml" is written
// there as NAME.toml first. And its generated tables document the program: every long option
// of every command's --help and every key `sylva styles NAME` lists for a built-in style is in
// one of them.
#include <gtest/gtest.h>

#include <regex>
#include <set>
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

// The text of the README's generated blocks (cli/docs.h), joined.
std::string generated_tables() {
  std::istringstream readme(read_file(source_dir() + "/README.md"));
  std::string text;
  bool in = false;
  for (std::string line; std::getline(readme, line);) {
    if (line.starts_with("<!-- generated: ")) in = true;
    if (line == "<!-- end generated -->") in = false;
    if (in) text += line + "\n";
  }
  return text;
}

// The long options on the option lines of `sylva ARGS --help` ("  -o,--output TEXT ...").
std::set<std::string> long_options(const std::string& args) {
  const RunResult r = run_sylva(args + " --help");
  EXPECT_EQ(r.status, 0) << args << "\n" << r.output;
  std::set<std::string> options;
  std::istringstream lines(r.output);
  static const std::regex option(R"(--[a-z][a-z0-9-]*)");
  for (std::string line; std::getline(lines, line);) {
    const size_t first = line.find_first_not_of(' ');
    if (first == std::string::npos || first == 0 || line[first] != '-') continue;
    const std::string names = line.substr(first, line.find(' ', first) - first);
    for (std::sregex_iterator m(names.begin(), names.end(), option), end; m != end; ++m)
      options.insert(m->str());
  }
  return options;
}

TEST(Readme, EveryOptionAndStyleKeyIsInAGeneratedTable) {
  const std::string tables = generated_tables();
  ASSERT_GT(tables.size(), 1000u);
  size_t options = 0;
  for (const char* command : {"sample", "info", "render", "buffers", "styles", "compare",
                              "turntable", "encode", "farm slurm", "bake", "tradeoff"})
    for (const std::string& o : long_options(command)) {
      EXPECT_NE(tables.find("`" + o + "`"), std::string::npos) << command << " " << o;
      ++options;
    }
  EXPECT_GT(options, 150u);
  size_t keys = 0;
  for (const char* style :
       {"standard", "expressive", "ink", "pen", "toon", "watercolor", "blobs"}) {
    const RunResult r = run_sylva(std::string("styles ") + style);
    ASSERT_EQ(r.status, 0) << r.output;
    std::istringstream lines(r.output);
    bool table = false;
    for (std::string line; std::getline(lines, line);) {
      const std::string key = line.substr(0, line.find(' '));
      if (table && key.find('.') != std::string::npos) {
        EXPECT_NE(tables.find("`" + key + "`"), std::string::npos) << style << " " << key;
        ++keys;
      }
      table = table || key == "key";
    }
  }
  EXPECT_GT(keys, 7u * 100u);
}

}  // namespace
}  // namespace sylva::test
