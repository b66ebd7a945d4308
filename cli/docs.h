// The README's generated tables (`make docs`; the docs.readme test fails when they are stale):
// each block between "<!-- generated: KIND NAME -->" and "<!-- end generated -->" is a table
// made from the declarations themselves, so the README lists what the program accepts:
//   options sylva      the program's own options (--help, --version)
//   options COMMAND    a command's options outside the shared groups ("options farm slurm")
//   group NAME         a group of options several commands share (scene, view, foliage, style,
//                      turntable: cli/common_options.h), with the commands that have it
//   params SECTION     the style keys of a section (style, foliage, ao, ...): what is allowed,
//                      the default, the built-in styles that change it, the meaning
#pragma once

#include <CLI/CLI.hpp>
#include <string>

namespace sylva::cli {

// `readme` with every generated block rewritten from `app` (every command registered) and
// the built-in styles. Throws InputError("README", ...) for a block it does not know, an
// unclosed block, or an option or style key that no block lists.
std::string generate_readme(const std::string& readme, const CLI::App& app);

}  // namespace sylva::cli
