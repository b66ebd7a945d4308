// sylva_docs [--check] PATH...: rewrites the generated tables (cli/docs.h) of the markdown files
// given, a folder standing for its *.md files, from the program's option declarations and the
// style parameters' specs (`make docs`: README.md docs). With --check it writes nothing and exits
// 1, naming the first stale file and line, when a file differs from what it would write (the
// docs.tables test). sylva_docs --man OUT writes the man page sylva(1) (cli/man_page.h).
// Bad input: one line, exit 2.
#include <CLI/CLI.hpp>
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <sstream>

#include "cli/app.h"
#include "cli/docs.h"
#include "cli/man_page.h"
#include "cli/version.h"
#include "core/error.h"
#include "core/io/atomic_file.h"

namespace {

std::string read_text(const std::string& path) {
  FILE* f = std::fopen(path.c_str(), "rb");
  if (f == nullptr) throw sylva::InputError(path, "cannot read it");
  std::string text;
  char buf[65536];
  for (size_t n; (n = std::fread(buf, 1, sizeof buf, f)) > 0;)
    text.append(buf, n);
  std::fclose(f);
  return text;
}

// The first line where `a` and `b` differ (1-based), with both versions.
std::string first_difference(const std::string& a, const std::string& b) {
  std::istringstream sa(a), sb(b);
  std::string la, lb;
  for (int line = 1;; ++line) {
    const bool ga = bool(std::getline(sa, la)), gb = bool(std::getline(sb, lb));
    if (!ga && !gb) return "";
    if (!ga || !gb || la != lb)
      return "line " + std::to_string(line) + ": has\n  " + (ga ? la : "(the end)") +
             "\ngenerated:\n  " + (gb ? lb : "(the end)");
  }
}

// The files of `paths`: a folder's *.md in name order, a file as it is.
std::vector<sylva::cli::DocFile> read_docs(const std::vector<std::string>& paths) {
  std::vector<sylva::cli::DocFile> files;
  for (const std::string& path : paths) {
    std::error_code ec;
    if (!std::filesystem::is_directory(path, ec)) {
      files.push_back({path, read_text(path)});
      continue;
    }
    std::vector<std::string> names;
    for (const auto& entry : std::filesystem::directory_iterator(path, ec))
      if (entry.path().extension() == ".md") names.push_back(entry.path().string());
    if (ec) throw sylva::InputError(path, "cannot list it: " + ec.message());
    std::sort(names.begin(), names.end());
    for (const std::string& name : names)
      files.push_back({name, read_text(name)});
  }
  return files;
}

int usage() {
  std::fprintf(stderr, "usage: sylva_docs [--check] FILE.md|FOLDER... | sylva_docs --man OUT\n");
  return 2;
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<std::string> args(argv + 1, argv + argc);
  try {
    CLI::App app;
    sylva::cli::add_commands(app);
    if (!args.empty() && args[0] == "--man") {
      if (args.size() != 2) return usage();
      sylva::write_file_atomic(args[1], sylva::cli::man_page(app, sylva::cli::version_line()));
      return 0;
    }
    const bool check = !args.empty() && args[0] == "--check";
    if (check) args.erase(args.begin());
    if (args.empty()) return usage();
    const std::vector<sylva::cli::DocFile> old = read_docs(args);
    const std::vector<sylva::cli::DocFile> generated = sylva::cli::generate_docs(old, app);
    for (size_t i = 0; i < old.size(); ++i) {
      if (generated[i].text == old[i].text) continue;
      if (check) {
        std::fprintf(stderr, "%s: the generated tables are stale (run make docs); %s\n",
                     old[i].path.c_str(), first_difference(old[i].text, generated[i].text).c_str());
        return 1;
      }
      sylva::write_file_atomic(old[i].path, generated[i].text);
    }
  } catch (const sylva::InputError& e) {
    std::fprintf(stderr, "sylva_docs: error: %s\n", e.what());
    return 2;
  }
  return 0;
}
