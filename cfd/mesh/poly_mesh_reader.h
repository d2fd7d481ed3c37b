// Reader for OpenFOAM's constant/polyMesh (points, faces, owner, neighbour,
// boundary), ASCII or binary, faceList or faceCompactList, as written by
// blockMesh and snappyHexMesh. Every malformed input is one DataFileError that
// names the file, the entry and what was expected.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "cfd/mesh/mesh.h"

namespace kelvin::cfd {

Mesh ReadPolyMesh(const std::filesystem::path& poly_mesh_dir);

// The same from the files' text already in memory; `poly_mesh_dir` names the
// files in messages.
struct PolyMeshText {
  std::string points, faces, owner, neighbour, boundary;
};
Mesh ParsePolyMesh(const PolyMeshText& text, const std::filesystem::path& poly_mesh_dir);

// Each file on its own (`file` names it in messages); `what` names the
// labels of owner ("owners") or neighbour ("neighbours").
std::vector<Vector3> ParsePolyMeshPoints(const std::string& text, const std::filesystem::path& file);
std::vector<std::vector<int>> ParsePolyMeshFaces(const std::string& text, const std::filesystem::path& file);
std::vector<int> ParsePolyMeshLabels(const std::string& text, const std::filesystem::path& file,
                                     const std::string& what);
std::vector<Patch> ParsePolyMeshBoundary(const std::string& text, const std::filesystem::path& file);

}  // namespace kelvin::cfd
