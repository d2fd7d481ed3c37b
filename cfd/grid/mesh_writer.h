// Writers for kelvin meshes: OpenFOAM polyMesh (ASCII, read back by
// ReadPolyMesh and opened by ParaView and OpenFOAM) and VTK XML unstructured
// grid (.vtu, polyhedral cells, for ParaView) with cell volume and
// non-orthogonality. Both write into a temporary location and rename, so an
// error never leaves a half-written mesh behind.
#pragma once

#include <filesystem>

#include "cfd/mesh/mesh.h"

namespace kelvin::cfd {

// Writes <case_dir>/constant/polyMesh/{points,faces,owner,neighbour,boundary}.
// The polyMesh directory is replaced as a whole.
void WritePolyMesh(const Mesh& mesh, const std::filesystem::path& case_dir);

// Writes a .vtu file (binary appended data).
void WriteVtu(const Mesh& mesh, const std::filesystem::path& path);

// Non-orthogonality (degrees) of each face: angle between the face area
// vector and the owner-to-neighbour vector (owner-to-face-centre on the
// boundary).
std::vector<double> FaceNonOrthogonality(const Mesh& mesh);

}  // namespace kelvin::cfd
