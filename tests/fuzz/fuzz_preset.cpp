// A user's TOML preset (`--style my.toml`) through apply_preset onto every parameter of the
// built-in styles. After a preset is taken, every parameter's value must read back through
// set_from_string (the ranges held), so nothing out of range reaches a pass.
#include "styles/presets.h"
#include "styles/style_params.h"
#include "tests/fuzz/fuzz_check_params.h"
#include "tests/fuzz/fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string path = sylva::fuzz::write_input(data, size, "in.toml");
  sylva::StyleParams params;
  sylva::ParamSet set;
  sylva::bind_style_params(set, params);
  sylva::fuzz::expect_input_error([&] {
    sylva::apply_preset(path, set);
    sylva::fuzz::check_params_read_back(set);
  });
  return 0;
}
