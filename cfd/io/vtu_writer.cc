#include "cfd/io/vtu_writer.h"

#include <fmt/format.h>

#include <algorithm>

#include "data/schema/atomic_file.h"
#include "data/schema/errors.h"

namespace kelvin::cfd {

void WriteVtu(const std::filesystem::path& path, const Mesh& mesh, const std::vector<VtuCellData>& data,
              int n_cells) {
  const int nc = n_cells < 0 ? mesh.n_cells() : n_cells;
  KELVIN_CHECK(nc <= mesh.n_cells(), "a piece holds cells of its mesh");
  for (const VtuCellData& d : data) {
    KELVIN_CHECK(d.values.size() >= static_cast<std::size_t>(nc) * d.components, "a value per cell written");
  }
  std::string out;
  out.reserve(static_cast<std::size_t>(nc) * 400);
  auto append = [&out](const std::string& s) { out += s; };
  append("<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\">\n");
  append(fmt::format("<UnstructuredGrid>\n<Piece NumberOfPoints=\"{}\" NumberOfCells=\"{}\">\n", mesh.n_points(),
                     nc));
  append("<Points>\n<DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\">\n");
  for (const Vector3& p : mesh.points()) append(fmt::format("{:.9g} {:.9g} {:.9g}\n", p.x(), p.y(), p.z()));
  append("</DataArray>\n</Points>\n<Cells>\n");
  // Connectivity: the distinct points of each cell; faces: per cell
  // [n_faces, (n_points, ids...)...] with outward orientation.
  std::string connectivity, offsets, types, faces, face_offsets;
  long long conn_count = 0, face_count = 0;
  const auto off = mesh.cell_face_offsets();
  const auto cf = mesh.cell_faces();
  std::vector<int> pts;
  for (int c = 0; c < nc; ++c) {
    pts.clear();
    std::string cell_faces = fmt::format("{}", off[c + 1] - off[c]);
    long long n_face_entries = 1;
    for (int k = off[c]; k < off[c + 1]; ++k) {
      const int f = cf[k];
      const std::span<const int> fp = mesh.face(f);
      cell_faces += fmt::format(" {}", fp.size());
      const bool flip = mesh.owner()[f] != c;
      for (std::size_t i = 0; i < fp.size(); ++i) {
        const int p = flip ? fp[fp.size() - 1 - i] : fp[i];
        cell_faces += fmt::format(" {}", p);
        pts.push_back(p);
      }
      n_face_entries += 1 + static_cast<long long>(fp.size());
    }
    std::sort(pts.begin(), pts.end());
    pts.erase(std::unique(pts.begin(), pts.end()), pts.end());
    for (int p : pts) connectivity += fmt::format("{} ", p);
    connectivity += "\n";
    conn_count += static_cast<long long>(pts.size());
    offsets += fmt::format("{}\n", conn_count);
    types += "42\n";
    faces += cell_faces + "\n";
    face_count += n_face_entries;
    face_offsets += fmt::format("{}\n", face_count);
  }
  append("<DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">\n" + connectivity + "</DataArray>\n");
  append("<DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">\n" + offsets + "</DataArray>\n");
  append("<DataArray type=\"UInt8\" Name=\"types\" format=\"ascii\">\n" + types + "</DataArray>\n");
  append("<DataArray type=\"Int64\" Name=\"faces\" format=\"ascii\">\n" + faces + "</DataArray>\n");
  append("<DataArray type=\"Int64\" Name=\"faceoffsets\" format=\"ascii\">\n" + face_offsets + "</DataArray>\n");
  append("</Cells>\n<CellData>\n");
  for (const VtuCellData& d : data) {
    append(fmt::format("<DataArray type=\"Float64\" Name=\"{}\" NumberOfComponents=\"{}\" format=\"ascii\">\n",
                       d.name, d.components));
    for (int c = 0; c < nc; ++c) {
      for (int k = 0; k < d.components; ++k) {
        append(fmt::format("{:.9g}{}", d.values[static_cast<std::size_t>(c) * d.components + k],
                           k + 1 == d.components ? "\n" : " "));
      }
    }
    append("</DataArray>\n");
  }
  append("</CellData>\n</Piece>\n</UnstructuredGrid>\n</VTKFile>\n");
  data::WriteFileAtomically(path, out);
}

void WritePatchVtp(const std::filesystem::path& path, const Mesh& mesh, const Patch& patch,
                   const std::vector<VtuCellData>& face_data) {
  // The patch's own points, numbered in order of first use.
  std::vector<int> local(mesh.n_points(), -1);
  std::vector<int> used;
  std::string connectivity, offsets;
  long long count = 0;
  for (int f = patch.start; f < patch.start + patch.size; ++f) {
    for (int p : mesh.face(f)) {
      if (local[p] < 0) {
        local[p] = static_cast<int>(used.size());
        used.push_back(p);
      }
      connectivity += fmt::format("{} ", local[p]);
    }
    connectivity += "\n";
    count += static_cast<long long>(mesh.face(f).size());
    offsets += fmt::format("{}\n", count);
  }
  std::string out = "<?xml version=\"1.0\"?>\n<VTKFile type=\"PolyData\" version=\"1.0\" byte_order=\"LittleEndian\">\n";
  out += fmt::format(
      "<PolyData>\n<Piece NumberOfPoints=\"{}\" NumberOfVerts=\"0\" NumberOfLines=\"0\" NumberOfStrips=\"0\" "
      "NumberOfPolys=\"{}\">\n",
      used.size(), patch.size);
  out += "<Points>\n<DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\">\n";
  for (int p : used) {
    const Vector3& x = mesh.points()[p];
    out += fmt::format("{:.9g} {:.9g} {:.9g}\n", x.x(), x.y(), x.z());
  }
  out += "</DataArray>\n</Points>\n<Polys>\n";
  out += "<DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">\n" + connectivity + "</DataArray>\n";
  out += "<DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">\n" + offsets + "</DataArray>\n";
  out += "</Polys>\n<CellData>\n";
  for (const VtuCellData& d : face_data) {
    KELVIN_CHECK(d.values.size() == static_cast<std::size_t>(patch.size) * d.components, "one value per patch face");
    out += fmt::format("<DataArray type=\"Float64\" Name=\"{}\" NumberOfComponents=\"{}\" format=\"ascii\">\n",
                       d.name, d.components);
    for (int i = 0; i < patch.size; ++i) {
      for (int k = 0; k < d.components; ++k) {
        out += fmt::format("{:.9g}{}", d.values[static_cast<std::size_t>(i) * d.components + k],
                           k + 1 == d.components ? "\n" : " ");
      }
    }
    out += "</DataArray>\n";
  }
  out += "</CellData>\n</Piece>\n</PolyData>\n</VTKFile>\n";
  data::WriteFileAtomically(path, out);
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
