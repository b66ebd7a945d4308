// sylva_docs README.md [--check]: rewrites the README's generated tables (cli/docs.h) from the
// program's option declarations and the style parameters' specs (`make docs`). With --check it
// writes nothing and exits 1, naming the first stale line, when the README differs from what
// it would write (the docs.readme test). Bad input: one line, exit 2.
#include <CLI/CLI.hpp>
#include <cstdio>
#include <sstream>

#include "cli/app.h"
#include "cli/docs.h"
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

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2 || argc > 3 || (argc == 3 && std::string(argv[2]) != "--check")) {
    std::fprintf(stderr, "usage: sylva_docs README.md [--check]\n");
    return 2;
  }
  const std::string path = argv[1];
  const bool check = argc == 3;
  try {
    CLI::App app;
    sylva::cli::add_commands(app);
    const std::string old = read_text(path);
    const std::string generated = sylva::cli::generate_readme(old, app);
    if (check) {
      const std::string diff = first_difference(old, generated);
      if (diff.empty()) return 0;
      std::fprintf(stderr, "%s: the generated tables are stale (run make docs); %s\n", path.c_str(),
                   diff.c_str());
      return 1;
    }
    if (generated != old) sylva::write_file_atomic(path, generated);
  } catch (const sylva::InputError& e) {
    std::fprintf(stderr, "sylva_docs: error: %s\n", e.what());
    return 2;
  }
  return 0;
}
