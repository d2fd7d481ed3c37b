// `kelvin mesh` case files.
#include "cfd/grid/mesh_case.h"
#include "tests/fuzz/fuzz_input.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  kelvin::fuzz::ExpectInputError(
      [&] { kelvin::cfd::ParseMeshCase(kelvin::fuzz::Text(data, size), "mesh.yaml", "/nonexistent"); });
  return 0;
}
