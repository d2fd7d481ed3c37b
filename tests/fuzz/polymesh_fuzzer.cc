// A whole OpenFOAM polyMesh, checked across its files and built into a Mesh.
// The input is the five files points, faces, owner, neighbour, boundary, in
// that order, each ended by a line "@@@@" (tests/fuzz/polymesh_input.h).
#include "cfd/mesh/poly_mesh_reader.h"
#include "tests/fuzz/fuzz_input.h"
#include "tests/fuzz/polymesh_input.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const kelvin::cfd::PolyMeshText text = kelvin::fuzz::SplitPolyMesh(kelvin::fuzz::Text(data, size));
  kelvin::fuzz::ExpectInputError([&] { kelvin::cfd::ParsePolyMesh(text, "polyMesh"); });
  return 0;
}
