// OpenFOAM polyMesh/faces: faceList (ASCII) or faceCompactList (ASCII or binary).
#include "cfd/mesh/poly_mesh_reader.h"
#include "tests/fuzz/fuzz_input.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  kelvin::fuzz::ExpectInputError(
      [&] { kelvin::cfd::ParsePolyMeshFaces(kelvin::fuzz::Text(data, size), "polyMesh/faces"); });
  return 0;
}
