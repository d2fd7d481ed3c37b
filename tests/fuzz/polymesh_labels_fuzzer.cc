// OpenFOAM polyMesh/owner and polyMesh/neighbour (label lists, ASCII or binary).
#include "cfd/mesh/poly_mesh_reader.h"
#include "tests/fuzz/fuzz_input.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  kelvin::fuzz::ExpectInputError(
      [&] { kelvin::cfd::ParsePolyMeshLabels(kelvin::fuzz::Text(data, size), "polyMesh/owner", "owners"); });
  return 0;
}
