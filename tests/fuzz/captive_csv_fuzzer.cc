// Captive runs as CSV (towing-tank data, data/schema/captive_schema.md).
#include <sstream>

#include "data/schema/captive_io.h"
#include "tests/fuzz/fuzz_input.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::istringstream in(kelvin::fuzz::Text(data, size));
  kelvin::fuzz::ExpectInputError([&] { kelvin::data::ReadRunCsv(in, "run.csv"); });
  return 0;
}
