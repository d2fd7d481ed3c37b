// VTK XML unstructured-grid output (.vtu, every cell as a VTK polyhedron),
// patch surfaces as polygon data (.vtp), both with their arrays in raw
// binary appended data (exact doubles), their parallel index files (.pvtu,
// .pvtp: one piece per MPI rank), and the .pvd collection that ties the time
// steps together for ParaView.
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

// Writes one .vtu file atomically: the mesh's first `n_cells` cells (all
// when negative; a rank's piece holds its owned cells, which come before its
// ghost cells), with the first n_cells * components values of each array.
void WriteVtu(const std::filesystem::path& path, const Mesh& mesh, const std::vector<VtuCellData>& data,
              int n_cells = -1);

// Writes the faces of one boundary patch as VTK XML polygon data (.vtp),
// atomically, with per-face data (n_faces * components values each): the
// wave elevation on the free surface, for instance.
void WritePatchVtp(const std::filesystem::path& path, const Mesh& mesh, const Patch& patch,
                   const std::vector<VtuCellData>& face_data);

// The index of a dataset written in pieces (one per rank): a .pvtu (or, for
// polygon data, a .pvtp) naming the piece files, relative to the index's
// directory, and the arrays each piece holds (names and components), atomically.
void WritePvtu(const std::filesystem::path& path, const std::vector<std::string>& pieces,
               const std::vector<VtuCellData>& data);
void WritePvtp(const std::filesystem::path& path, const std::vector<std::string>& pieces,
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
