// The docs' generated tables (`make docs`; the docs.tables test fails when one is stale): each
// block between "<!-- generated: KIND NAME -->" and "<!-- end generated -->" in README.md or
// docs/*.md is a table made from the declarations themselves, so the docs list what the program
// accepts:
//   options sylva      the program's own options (--help, --version, --verbose)
//   options COMMAND    a command's options outside the shared groups ("options farm slurm")
//   group NAME         a group of options several commands share (scene, view, foliage, style,
//                      turntable: cli/common_options.h), with the commands that have it
//   params SECTION     the style keys of a section (style, foliage, ao, ...): what is allowed,
//                      the default, the built-in styles that change it, the meaning
// Every option and style key must be in some file's block.
#pragma once

#include <CLI/CLI.hpp>
#include <string>
#include <vector>

namespace sylva::cli {

struct DocFile {
  std::string path;  // as given, for messages
  std::string text;
};

// `files` with every generated block rewritten from `app` (every command registered) and the
// built-in styles, in the same order. Throws InputError(path, ...) for a block it does not know
// or an unclosed one, and InputError("docs", ...) for an option or style key that no block of
// any file lists.
std::vector<DocFile> generate_docs(const std::vector<DocFile>& files, const CLI::App& app);

}  // namespace sylva::cli
