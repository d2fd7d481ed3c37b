#include "cfd/io/vtu_writer.h"

#include <fmt/format.h>

#include <algorithm>
#include <cstdint>
#include <numeric>
#include <span>

#include "data/schema/atomic_file.h"
#include "data/schema/errors.h"

namespace kelvin::cfd {

namespace {

// A VTK XML file with its arrays in one raw appended block, each a UInt64
// byte count and the little-endian values: exact doubles, and about a third
// of the size (and of the memory while written) of the same file in ASCII.
class AppendedFile {
 public:
  // Opens the file's XML: `kind` ("UnstructuredGrid" or "PolyData") and the
  // Piece's attributes.
  AppendedFile(const std::string& kind, const std::string& piece) : kind_(kind) {
    xml_ = fmt::format(
        "<?xml version=\"1.0\"?>\n<VTKFile type=\"{0}\" version=\"1.0\" byte_order=\"LittleEndian\" "
        "header_type=\"UInt64\">\n<{0}>\n<Piece {1}>\n",
        kind, piece);
  }
  void Tag(const std::string& text) { xml_ += text; }
  template <typename T>
  void Array(const char* type, const std::string& name, int components, const std::vector<T>& values) {
    xml_ += fmt::format("<DataArray type=\"{}\" Name=\"{}\" NumberOfComponents=\"{}\" format=\"appended\" "
                        "offset=\"{}\"/>\n",
                        type, name, components, blob_.size());
    const std::uint64_t bytes = values.size() * sizeof(T);
    blob_.append(reinterpret_cast<const char*>(&bytes), sizeof bytes);
    blob_.append(reinterpret_cast<const char*>(values.data()), bytes);
  }
  void Write(const std::filesystem::path& path) {
    xml_ += fmt::format("</Piece>\n</{}>\n<AppendedData encoding=\"raw\">\n_", kind_);
    xml_ += blob_;
    std::string().swap(blob_);
    xml_ += "\n</AppendedData>\n</VTKFile>\n";
    data::WriteFileAtomically(path, xml_);
  }

 private:
  std::string kind_, xml_, blob_;
};

std::vector<double> Coordinates(const Mesh& mesh, std::span<const int> points) {
  std::vector<double> out;
  out.reserve(3 * points.size());
  for (int p : points) {
    const Vector3& x = mesh.points()[p];
    out.insert(out.end(), {x.x(), x.y(), x.z()});
  }
  return out;
}

// The first n * components values of each array, as cell (or face) data.
void CellData(AppendedFile& file, const std::vector<VtuCellData>& data, int n) {
  file.Tag("<CellData>\n");
  for (const VtuCellData& d : data) {
    const auto count = static_cast<std::size_t>(n) * d.components;
    KELVIN_CHECK(d.values.size() >= count, "a value per cell or face written");
    file.Array("Float64", d.name, d.components, std::vector<double>(d.values.begin(), d.values.begin() + count));
  }
  file.Tag("</CellData>\n");
}

}  // namespace

void WriteVtu(const std::filesystem::path& path, const Mesh& mesh, const std::vector<VtuCellData>& data,
              int n_cells) {
  const int nc = n_cells < 0 ? mesh.n_cells() : n_cells;
  KELVIN_CHECK(nc <= mesh.n_cells(), "a piece holds cells of its mesh");
  // Polyhedral cells: the distinct points of each cell, and per cell
  // [n_faces, (n_points, ids...)...] with the faces oriented outwards.
  std::vector<std::int64_t> connectivity, offsets, faces, face_offsets;
  const std::vector<std::uint8_t> types(static_cast<std::size_t>(nc), 42);  // VTK_POLYHEDRON
  const auto off = mesh.cell_face_offsets();
  const auto cf = mesh.cell_faces();
  std::vector<int> pts;
  for (int c = 0; c < nc; ++c) {
    pts.clear();
    faces.push_back(off[c + 1] - off[c]);
    for (int k = off[c]; k < off[c + 1]; ++k) {
      const int f = cf[k];
      const std::span<const int> fp = mesh.face(f);
      faces.push_back(static_cast<std::int64_t>(fp.size()));
      const bool flip = mesh.owner()[f] != c;
      for (std::size_t i = 0; i < fp.size(); ++i) faces.push_back(flip ? fp[fp.size() - 1 - i] : fp[i]);
      pts.insert(pts.end(), fp.begin(), fp.end());
    }
    std::sort(pts.begin(), pts.end());
    pts.erase(std::unique(pts.begin(), pts.end()), pts.end());
    connectivity.insert(connectivity.end(), pts.begin(), pts.end());
    offsets.push_back(static_cast<std::int64_t>(connectivity.size()));
    face_offsets.push_back(static_cast<std::int64_t>(faces.size()));
  }
  std::vector<int> all(mesh.n_points());
  std::iota(all.begin(), all.end(), 0);
  AppendedFile file("UnstructuredGrid", fmt::format("NumberOfPoints=\"{}\" NumberOfCells=\"{}\"", mesh.n_points(), nc));
  file.Tag("<Points>\n");
  file.Array("Float64", "Points", 3, Coordinates(mesh, all));
  file.Tag("</Points>\n<Cells>\n");
  file.Array("Int64", "connectivity", 1, connectivity);
  file.Array("Int64", "offsets", 1, offsets);
  file.Array("UInt8", "types", 1, types);
  file.Array("Int64", "faces", 1, faces);
  file.Array("Int64", "faceoffsets", 1, face_offsets);
  file.Tag("</Cells>\n");
  CellData(file, data, nc);
  file.Write(path);
}

void WritePatchVtp(const std::filesystem::path& path, const Mesh& mesh, const Patch& patch,
                   const std::vector<VtuCellData>& face_data) {
  // The patch's own points, numbered in order of first use.
  std::vector<int> local(mesh.n_points(), -1);
  std::vector<int> used;
  std::vector<std::int64_t> connectivity, offsets;
  for (int f = patch.start; f < patch.start + patch.size; ++f) {
    for (int p : mesh.face(f)) {
      if (local[p] < 0) {
        local[p] = static_cast<int>(used.size());
        used.push_back(p);
      }
      connectivity.push_back(local[p]);
    }
    offsets.push_back(static_cast<std::int64_t>(connectivity.size()));
  }
  for (const VtuCellData& d : face_data) {
    KELVIN_CHECK(d.values.size() == static_cast<std::size_t>(patch.size) * d.components, "one value per patch face");
  }
  AppendedFile file("PolyData", fmt::format("NumberOfPoints=\"{}\" NumberOfVerts=\"0\" NumberOfLines=\"0\" "
                                            "NumberOfStrips=\"0\" NumberOfPolys=\"{}\"",
                                            used.size(), patch.size));
  file.Tag("<Points>\n");
  file.Array("Float64", "Points", 3, Coordinates(mesh, used));
  file.Tag("</Points>\n<Polys>\n");
  file.Array("Int64", "connectivity", 1, connectivity);
  file.Array("Int64", "offsets", 1, offsets);
  file.Tag("</Polys>\n");
  CellData(file, face_data, patch.size);
  file.Write(path);
}

namespace {

// The index of a dataset in pieces: `kind` is "UnstructuredGrid" or "PolyData".
void WriteParallelIndex(const std::filesystem::path& path, const std::string& kind,
                        const std::vector<std::string>& pieces, const std::vector<VtuCellData>& data) {
  std::string out = fmt::format(
      "<?xml version=\"1.0\"?>\n<VTKFile type=\"P{0}\" version=\"1.0\" byte_order=\"LittleEndian\">\n"
      "<P{0} GhostLevel=\"0\">\n<PPoints>\n<PDataArray type=\"Float64\" NumberOfComponents=\"3\"/>\n</PPoints>\n"
      "<PCellData>\n",
      kind);
  for (const VtuCellData& d : data) {
    out += fmt::format("<PDataArray type=\"Float64\" Name=\"{}\" NumberOfComponents=\"{}\"/>\n", d.name, d.components);
  }
  out += "</PCellData>\n";
  for (const std::string& piece : pieces) out += fmt::format("<Piece Source=\"{}\"/>\n", piece);
  out += fmt::format("</P{}>\n</VTKFile>\n", kind);
  data::WriteFileAtomically(path, out);
}

}  // namespace

void WritePvtu(const std::filesystem::path& path, const std::vector<std::string>& pieces,
               const std::vector<VtuCellData>& data) {
  WriteParallelIndex(path, "UnstructuredGrid", pieces, data);
}

void WritePvtp(const std::filesystem::path& path, const std::vector<std::string>& pieces,
               const std::vector<VtuCellData>& face_data) {
  WriteParallelIndex(path, "PolyData", pieces, face_data);
}

void PvdSeries::Add(double time, const std::filesystem::path& vtu_file) {
  entries_.emplace_back(time, vtu_file.filename().string());
  std::string out = "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\">\n<Collection>\n";
  for (const auto& [t, file] : entries_) {
    out += fmt::format("  <DataSet timestep=\"{:.12g}\" group=\"\" part=\"0\" file=\"{}\"/>\n", t, file);
  }
  out += "</Collection>\n</VTKFile>\n";
  data::WriteFileAtomically(path_, out);
}

}  // namespace kelvin::cfd
