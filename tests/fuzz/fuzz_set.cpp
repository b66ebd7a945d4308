// `--set section.key=value` assignments (one per input line) through apply_assignment onto
// every parameter of the built-in styles; values that are refused must leave the set valid.
#include <sstream>

#include "styles/presets.h"
#include "styles/style_params.h"
#include "tests/fuzz/fuzz_check_params.h"
#include "tests/fuzz/fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  std::istringstream lines(std::string(reinterpret_cast<const char*>(data), size));
  sylva::StyleParams params;
  sylva::ParamSet set;
  sylva::bind_style_params(set, params);
  std::string line;
  while (std::getline(lines, line))
    sylva::fuzz::expect_input_error([&] { sylva::apply_assignment(line, set, "--set"); });
  sylva::fuzz::check_params_read_back(set);
  return 0;
}
