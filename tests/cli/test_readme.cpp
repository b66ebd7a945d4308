// The docs' examples are true: every `sylva ...` line in the ```sh blocks of README.md (its
// quick start) and then of docs/*.md runs, in order, in one fresh folder, and exits 0; a ```toml
// block whose first line is "# NAME.toml" is written there as NAME.toml first. Their generated
// tables document the program: every long option of every command's --help and every key
// `sylva styles NAME` lists for a built-in style is in one of them. And the docs.tables test
// (sylva_docs --check) fails when one of docs/'s tables is stale.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <regex>
#include <set>
#include <sstream>

#include "tests/test_support.h"

namespace sylva::test {
namespace {

// README.md, then docs/*.md in name order.
std::vector<std::string> doc_files() {
  std::vector<std::string> files;
  for (const auto& entry : std::filesystem::directory_iterator(source_dir() + "/docs"))
    if (entry.path().extension() == ".md") files.push_back(entry.path().string());
  std::sort(files.begin(), files.end());
  files.insert(files.begin(), source_dir() + "/README.md");
  return files;
}

// Runs the examples of `path` in `dir`; returns how many ran.
int run_examples(const std::string& path, const std::string& dir) {
  std::istringstream doc(read_file(path));
  bool in_sh = false, in_toml = false;
  std::string toml;
  int ran = 0, number = 0;
  for (std::string line; std::getline(doc, line);) {
    ++number;
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
    EXPECT_EQ(r.status, 0) << path << ":" << number << ": " << line << "\n" << r.output;
    ++ran;
  }
  return ran;
}

TEST(Readme, ExampleCommandsRun) {
  const std::string dir = temp_dir("readme");
  const std::vector<std::string> files = doc_files();
  // The quick start's five commands and the two of "CPU or GPU".
  EXPECT_EQ(run_examples(files[0], dir), 7) << "the README has seven example commands";
  int ran = 0;
  for (size_t i = 1; i < files.size(); ++i)
    ran += run_examples(files[i], dir);
  EXPECT_GE(ran, 30);
}

// The text of the generated blocks (cli/docs.h) of README.md and docs/*.md, joined.
std::string generated_tables() {
  std::string text;
  for (const std::string& path : doc_files()) {
    std::istringstream doc(read_file(path));
    bool in = false;
    for (std::string line; std::getline(doc, line);) {
      if (line.starts_with("<!-- generated: ")) in = true;
      if (line == "<!-- end generated -->") in = false;
      if (in) text += line + "\n";
    }
  }
  return text;
}

std::string docs_binary() {
  return (std::filesystem::path(sylva_binary()).parent_path() / "sylva_docs").string();
}

// A copy of README.md and docs/ in a fresh folder; returns the folder.
std::string copy_docs() {
  const std::string dir = temp_dir("docs-copy");
  std::filesystem::copy_file(source_dir() + "/README.md", dir + "/README.md");
  std::filesystem::copy(source_dir() + "/docs", dir + "/docs");
  return dir;
}

TEST(Docs, StaleTableInDocsFailsTheCheck) {
  const std::string dir = copy_docs();
  const std::string check = docs_binary() + " --check " + dir + "/README.md " + dir + "/docs";
  RunResult fresh = run_command(check);
  ASSERT_EQ(fresh.status, 0) << fresh.output;
  // One cell of a generated table in docs/styles.md goes stale: a default that changed.
  const std::string styles = dir + "/docs/styles.md";
  std::string text = read_file(styles);
  const std::string row = "| `toon.bands` | [2, 8] bands | `3` |";
  const size_t at = text.find(row);
  ASSERT_NE(at, std::string::npos);
  text.replace(at, row.size(), "| `toon.bands` | [2, 8] bands | `4` |");
  write_file(styles, text);
  RunResult stale = run_command(check);
  EXPECT_EQ(stale.status, 1) << stale.output;
  EXPECT_NE(stale.output.find("styles.md: the generated tables are stale"), std::string::npos)
      << stale.output;
  // `make docs` puts it right, touching nothing else.
  RunResult fix = run_command(docs_binary() + " " + dir + "/README.md " + dir + "/docs");
  EXPECT_EQ(fix.status, 0) << fix.output;
  EXPECT_EQ(read_file(styles), read_file(source_dir() + "/docs/styles.md"));
  EXPECT_EQ(run_command(check).status, 0);
}

TEST(Docs, OptionListedNowhereIsAnError) {
  const std::string dir = copy_docs();
  const std::string scenes = dir + "/docs/scenes.md";
  std::string text = read_file(scenes);
  const size_t begin = text.find("<!-- generated: group view -->");
  ASSERT_NE(begin, std::string::npos);
  const size_t end = text.find("<!-- end generated -->", begin);
  text.erase(begin, end + std::string("<!-- end generated -->").size() - begin);
  write_file(scenes, text);
  RunResult r = run_command(docs_binary() + " --check " + dir + "/README.md " + dir + "/docs");
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_EQ(count_lines(r.output), 1) << r.output;
  EXPECT_NE(r.output.find("no generated table lists"), std::string::npos) << r.output;
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
