// VTK XML unstructured-grid output (.vtu, every cell as a VTK polyhedron),
// patch surfaces as polygon data (.vtp), and the .pvd collection that ties
// the time steps together for ParaView.
#pragma once

#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "cfd/mesh/mesh.h"

namespace kelvin::cfd {

struct VtuCellData {
  std::string name;
  int components = 1;          // 1 or 3
  std::vector<double> values;  // n_cells * components
};

// Writes one .vtu file atomically.
void WriteVtu(const std::filesystem::path& path, const Mesh& mesh, const std::vector<VtuCellData>& data);

// Writes the faces of one boundary patch as VTK XML polygon data (.vtp),
// atomically, with per-face data (n_faces * components values each): the
// wave elevation on the free surface, for instance.
void WritePatchVtp(const std::filesystem::path& path, const Mesh& mesh, const Patch& patch,
                   const std::vector<VtuCellData>& face_data);

// A .pvd series: Add() records a file and rewrites the collection.
class PvdSeries {
 public:
  explicit PvdSeries(std::filesystem::path path) : path_(std::move(path)) {}
  void Add(double time, const std::filesystem::path& vtu_file);

 private:
  std::filesystem::path path_;
  std::vector<std::pair<double, std::string>> entries_;
};

}  // namespace kelvin::cfd
