// Reader for OpenFOAM's constant/polyMesh (points, faces, owner, neighbour,
// boundary), ASCII or binary, faceList or faceCompactList, as written by
// blockMesh and snappyHexMesh. Every malformed input is one DataFileError that
// names the file, the entry and what was expected.
#pragma once

#include <filesystem>

#include "cfd/mesh/mesh.h"

namespace kelvin::cfd {

Mesh ReadPolyMesh(const std::filesystem::path& poly_mesh_dir);

}  // namespace kelvin::cfd
