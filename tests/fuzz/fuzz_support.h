// Shared pieces of the fuzz harnesses (tests/fuzz/README.md): every harness defines
// LLVMFuzzerTestOneInput, which feeds the bytes to one of Sylva's parsers the way a user's file
// or option would reach it. The contract checked: the parser returns a valid result or throws
// sylva::InputError; anything else (another exception, a sanitizer report, a broken
// invariant, a hang, an allocation over the limit) is a finding. The same sources are built
// as libFuzzer programs (cmake -DSYLVA_FUZZ=ON, `make fuzz`) and, in the normal builds, as
// replay programs that run the committed regression inputs and the generated seeds once
// (tests/fuzz/replay_main.cpp).
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "core/error.h"

namespace sylva::fuzz {

// A private folder for this process (created once under $TMPDIR or /tmp, removed at exit).
const std::string& scratch_dir();

// Writes the input to scratch_dir()/name, replacing it, and returns the path: the loaders
// take paths, and the extension chooses the format.
std::string write_input(const uint8_t* data, size_t size, const std::string& name);

// A broken invariant: prints what and aborts, which libFuzzer reports as a crash.
[[noreturn]] void fail(const std::string& what);

// Runs f; an InputError is the expected answer to bad input and is swallowed.
template <class F>
void expect_input_error(F&& f) {
  try {
    f();
  } catch (const InputError&) {
  }
}

}  // namespace sylva::fuzz
