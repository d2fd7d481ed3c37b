// Ship files (data/ships/*.yaml).
#include "data/schema/config.h"
#include "simulator/mmg/ship_parameters.h"
#include "tests/fuzz/fuzz_input.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  kelvin::fuzz::ExpectInputError([&] {
    const auto root = kelvin::data::ConfigNode::LoadString(kelvin::fuzz::Text(data, size), "ship.yaml");
    kelvin::sim::LoadShip(root, "/nonexistent/ship.yaml");
  });
  return 0;
}
