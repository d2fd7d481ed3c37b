// OpenFOAM polyMesh/points, ASCII or binary (the FoamFile header says which).
#include "cfd/mesh/poly_mesh_reader.h"
#include "tests/fuzz/fuzz_input.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  kelvin::fuzz::ExpectInputError(
      [&] { kelvin::cfd::ParsePolyMeshPoints(kelvin::fuzz::Text(data, size), "polyMesh/points"); });
  return 0;
}
