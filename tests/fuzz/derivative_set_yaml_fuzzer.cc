// Derivative sets (the hull derivatives `kelvin identify` writes).
#include "data/schema/config.h"
#include "simulator/mmg/derivative_set.h"
#include "tests/fuzz/fuzz_input.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  kelvin::fuzz::ExpectInputError([&] {
    const auto root = kelvin::data::ConfigNode::LoadString(kelvin::fuzz::Text(data, size), "derivatives.yaml");
    kelvin::sim::LoadDerivativeSet(root, "/nonexistent/derivatives.yaml");
  });
  return 0;
}
