// `kelvin run` case files: the settings that need no mesh (physics,
// reference, time, output, resistance).
#include "cfd/run/case_loader.h"
#include "data/schema/config.h"
#include "tests/fuzz/fuzz_input.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  kelvin::fuzz::ExpectInputError([&] {
    const auto root = kelvin::data::ConfigNode::LoadString(kelvin::fuzz::Text(data, size), "case.yaml");
    kelvin::cfd::ReadCaseSettings(root, "/nonexistent");
  });
  return 0;
}
