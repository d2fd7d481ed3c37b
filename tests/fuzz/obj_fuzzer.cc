// Wavefront OBJ hulls (plain or gzip-compressed).
#include "cfd/geometry/triangle_surface.h"
#include "tests/fuzz/fuzz_input.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  kelvin::fuzz::ExpectInputError([&] { kelvin::cfd::ParseObj(kelvin::fuzz::Text(data, size), "fuzz.obj"); });
  return 0;
}
