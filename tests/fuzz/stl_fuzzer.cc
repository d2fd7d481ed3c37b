// STL hulls, ASCII, binary or gzip-compressed (the reader tells them apart
// from the content).
#include "cfd/geometry/triangle_surface.h"
#include "tests/fuzz/fuzz_input.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  kelvin::fuzz::ExpectInputError([&] { kelvin::cfd::ParseStl(kelvin::fuzz::Text(data, size), "fuzz.stl"); });
  return 0;
}
