#include "cfd/io/vtu_writer.h"

#include <fmt/format.h>

#include <algorithm>
#include <cstdint>
#include <functional>
#include <numeric>
#include <span>
#include <utility>

#include "data/schema/atomic_file.h"
#include "data/schema/errors.h"

namespace kelvin::cfd {

namespace {

// A VTK XML file with its arrays in one raw appended block, each a UInt64
// byte count and the little-endian values: exact doubles, and about a third
// of the size of the same file in ASCII. Each array is declared with its
// size and a function that appends its bytes, so the file's text is the only
// copy of the data built while it is written.
class AppendedFile {
 public:
  using Fill = std::function<void(std::string&)>;
  // Opens the file's XML: `kind` ("UnstructuredGrid" or "PolyData") and the
  // Piece's attributes.
  AppendedFile(const std::string& kind, const std::string& piece) : kind_(kind) {
    xml_ = fmt::format(
        "<?xml version=\"1.0\"?>\n<VTKFile type=\"{0}\" version=\"1.0\" byte_order=\"LittleEndian\" "
        "header_type=\"UInt64\">\n<{0}>\n<Piece {1}>\n",
        kind, piece);
  }
  void Tag(const std::string& text) { xml_ += text; }
  void Array(const char* type, const std::string& name, int components, std::uint64_t bytes, Fill fill) {
    xml_ += fmt::format("<DataArray type=\"{}\" Name=\"{}\" NumberOfComponents=\"{}\" format=\"appended\" "
                        "offset=\"{}\"/>\n",
                        type, name, components, appended_);
    appended_ += sizeof bytes + bytes;
    arrays_.push_back({bytes, std::move(fill)});
  }
  void Write(const std::filesystem::path& path) {
    xml_ += fmt::format("</Piece>\n</{}>\n<AppendedData encoding=\"raw\">\n_", kind_);
    const std::string tail = "\n</AppendedData>\n</VTKFile>\n";
    std::string out = std::move(xml_);
    out.reserve(out.size() + appended_ + tail.size());
    for (const auto& [bytes, fill] : arrays_) {
      Raw(out, &bytes, 1);
      const std::size_t before = out.size();
      fill(out);
      KELVIN_CHECK(out.size() - before == bytes, "an array fills the bytes it declared");
    }
    out += tail;
    data::WriteFileAtomically(path, out);
  }
  template <typename T>
  static void Raw(std::string& out, const T* values, std::size_t n) {
    out.append(reinterpret_cast<const char*>(values), n * sizeof(T));
  }

 private:
  std::string kind_, xml_;
  std::uint64_t appended_ = 0;
  std::vector<std::pair<std::uint64_t, Fill>> arrays_;
};

// The coordinates of `points` (x, y, z each), as the file's Points.
void Points(AppendedFile& file, const Mesh& mesh, std::span<const int> points) {
  file.Tag("<Points>\n");
  file.Array("Float64", "Points", 3, 24 * points.size(), [&mesh, points](std::string& out) {
    for (int p : points) AppendedFile::Raw(out, mesh.points()[p].data(), 3);
  });
  file.Tag("</Points>\n");
}

template <typename T>
void Values(AppendedFile& file, const char* type, const char* name, const std::vector<T>& values) {
  file.Array(type, name, 1, values.size() * sizeof(T),
             [&values](std::string& out) { AppendedFile::Raw(out, values.data(), values.size()); });
}

// The first n * components values of each array, as cell (or face) data.
void CellData(AppendedFile& file, const std::vector<VtuCellData>& data, int n) {
  file.Tag("<CellData>\n");
  for (const VtuCellData& d : data) {
    const auto count = static_cast<std::size_t>(n) * d.components;
    KELVIN_CHECK(d.values.size() >= count, "a value per cell or face written");
    file.Array("Float64", d.name, d.components, count * sizeof(double),
               [&d, count](std::string& out) { AppendedFile::Raw(out, d.values.data(), count); });
  }
  file.Tag("</CellData>\n");
}

// The distinct points of cell c, ascending.
void CellPoints(const Mesh& mesh, int c, std::vector<int>& pts) {
  const auto off = mesh.cell_face_offsets();
  const auto cf = mesh.cell_faces();
  pts.clear();
  for (int k = off[c]; k < off[c + 1]; ++k) {
    const std::span<const int> fp = mesh.face(cf[k]);
    pts.insert(pts.end(), fp.begin(), fp.end());
  }
  std::sort(pts.begin(), pts.end());
  pts.erase(std::unique(pts.begin(), pts.end()), pts.end());
}

}  // namespace

void WriteVtu(const std::filesystem::path& path, const Mesh& mesh, const std::vector<VtuCellData>& data,
              int n_cells) {
  const int nc = n_cells < 0 ? mesh.n_cells() : n_cells;
  KELVIN_CHECK(nc <= mesh.n_cells(), "a piece holds cells of its mesh");
  // Polyhedral cells: the distinct points of each cell (connectivity), and
  // per cell [n_faces, (n_points, ids...)...] with the faces oriented
  // outwards (faces). Their ends are counted first; the lists themselves are
  // written straight into the file.
  const auto off = mesh.cell_face_offsets();
  const auto cf = mesh.cell_faces();
  std::vector<std::int64_t> offsets(nc), face_offsets(nc);
  std::vector<int> pts;
  std::int64_t n_connectivity = 0, n_faces = 0;
  for (int c = 0; c < nc; ++c) {
    CellPoints(mesh, c, pts);
    n_connectivity += static_cast<std::int64_t>(pts.size());
    offsets[c] = n_connectivity;
    n_faces += 1;
    for (int k = off[c]; k < off[c + 1]; ++k) n_faces += 1 + static_cast<std::int64_t>(mesh.face(cf[k]).size());
    face_offsets[c] = n_faces;
  }
  std::vector<int> all(mesh.n_points());
  std::iota(all.begin(), all.end(), 0);
  const std::vector<std::uint8_t> types(static_cast<std::size_t>(nc), 42);  // VTK_POLYHEDRON
  AppendedFile file("UnstructuredGrid", fmt::format("NumberOfPoints=\"{}\" NumberOfCells=\"{}\"", mesh.n_points(), nc));
  Points(file, mesh, all);
  file.Tag("<Cells>\n");
  file.Array("Int64", "connectivity", 1, 8 * n_connectivity, [&](std::string& out) {
    std::vector<int> cell;
    for (int c = 0; c < nc; ++c) {
      CellPoints(mesh, c, cell);
      for (int p : cell) {
        const std::int64_t v = p;
        AppendedFile::Raw(out, &v, 1);
      }
    }
  });
  Values(file, "Int64", "offsets", offsets);
  Values(file, "UInt8", "types", types);
  file.Array("Int64", "faces", 1, 8 * n_faces, [&](std::string& out) {
    auto put = [&out](std::int64_t v) { AppendedFile::Raw(out, &v, 1); };
    for (int c = 0; c < nc; ++c) {
      put(off[c + 1] - off[c]);
      for (int k = off[c]; k < off[c + 1]; ++k) {
        const int f = cf[k];
        const std::span<const int> fp = mesh.face(f);
        put(static_cast<std::int64_t>(fp.size()));
        const bool flip = mesh.owner()[f] != c;
        for (std::size_t i = 0; i < fp.size(); ++i) put(flip ? fp[fp.size() - 1 - i] : fp[i]);
      }
    }
  });
  Values(file, "Int64", "faceoffsets", face_offsets);
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
  Points(file, mesh, used);
  file.Tag("<Polys>\n");
  Values(file, "Int64", "connectivity", connectivity);
  Values(file, "Int64", "offsets", offsets);
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
