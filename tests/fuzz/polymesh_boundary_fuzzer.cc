// OpenFOAM polyMesh/boundary.
#include "cfd/mesh/poly_mesh_reader.h"
#include "tests/fuzz/fuzz_input.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  kelvin::fuzz::ExpectInputError(
      [&] { kelvin::cfd::ParsePolyMeshBoundary(kelvin::fuzz::Text(data, size), "polyMesh/boundary"); });
  return 0;
}
