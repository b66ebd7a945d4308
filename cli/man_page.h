// The man page sylva(1), in man(7) troff, from the same declarations as the docs' tables
// (cli/option_rows.h): every command with its own options, the shared option groups once, the
// program's options, exit status, environment and files. Built by `sylva_docs --man` and
// installed with the program (CMakeLists.txt).
#pragma once

#include <CLI/CLI.hpp>
#include <string>

namespace sylva::cli {

// `version` goes in the page's footer ("sylva 0.1.0 (commit ...)"). No date, so the same
// sources give the same bytes.
std::string man_page(const CLI::App& app, const std::string& version);

}  // namespace sylva::cli
