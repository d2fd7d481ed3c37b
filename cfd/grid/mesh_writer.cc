#include "cfd/grid/mesh_writer.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <numbers>
#include <random>
#include <string>

#include "data/schema/atomic_file.h"
#include "data/schema/errors.h"

namespace kelvin::cfd {

namespace fs = std::filesystem;

namespace {

std::string Header(const char* cls, const char* object, const std::string& note = "") {
  std::string h = fmt::format(
      "/*--------------------------------*- C++ -*----------------------------------*\\\n"
      "  Written by kelvin\n"
      "\\*---------------------------------------------------------------------------*/\n"
      "FoamFile\n{{\n    version     2.0;\n    format      ascii;\n    class       {};\n",
      cls);
  if (!note.empty()) h += fmt::format("    note        \"{}\";\n", note);
  h += fmt::format("    location    \"constant/polyMesh\";\n    object      {};\n}}\n\n", object);
  return h;
}

void WriteText(const fs::path& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary);
  out << text;
  if (!out) throw DataFileError(fmt::format("{}: cannot write", path.string()));
}

// A sibling of `target` that does not exist yet.
fs::path TemporaryDirFor(const fs::path& target) {
  std::random_device rd;
  for (int attempt = 0; attempt < 100; ++attempt) {
    fs::path p = target;
    p += fmt::format(".tmp{:08x}", rd());
    if (!fs::exists(p)) return p;
  }
  throw DataFileError(fmt::format("{}: cannot find a free temporary name", target.string()));
}

}  // namespace

void WritePolyMesh(const Mesh& mesh, const fs::path& case_dir) {
  const fs::path target = case_dir / "constant" / "polyMesh";
  fs::create_directories(target.parent_path());
  const fs::path tmp = TemporaryDirFor(target);
  fs::create_directories(tmp);
  try {
    const std::string note =
        fmt::format("nPoints:{}  nCells:{}  nFaces:{}  nInternalFaces:{}", mesh.n_points(),
                    mesh.n_cells(), mesh.n_faces(), mesh.n_internal_faces());
    std::string s = Header("vectorField", "points");
    s += fmt::format("{}\n(\n", mesh.n_points());
    for (const Vector3& p : mesh.points())
      s += fmt::format("({:.15g} {:.15g} {:.15g})\n", p.x(), p.y(), p.z());
    s += ")\n";
    WriteText(tmp / "points", s);

    s = Header("faceList", "faces");
    s += fmt::format("{}\n(\n", mesh.n_faces());
    for (const auto& f : mesh.faces()) {
      s += fmt::format("{}(", f.size());
      for (std::size_t m = 0; m < f.size(); ++m) {
        if (m) s += ' ';
        s += std::to_string(f[m]);
      }
      s += ")\n";
    }
    s += ")\n";
    WriteText(tmp / "faces", s);

    auto labels = [&](const char* object, std::span<const int> v) {
      std::string t = Header("labelList", object, note);
      t += fmt::format("{}\n(\n", v.size());
      for (int c : v) t += fmt::format("{}\n", c);
      t += ")\n";
      WriteText(tmp / object, t);
    };
    labels("owner", mesh.owner());
    labels("neighbour", mesh.neighbour());

    s = Header("polyBoundaryMesh", "boundary");
    s += fmt::format("{}\n(\n", mesh.patches().size());
    for (const Patch& p : mesh.patches()) {
      const std::string type = PatchKindName(p.kind);
      s += fmt::format("    {}\n    {{\n        type            {};\n", p.name, type);
      if (p.kind == PatchKind::kWall) s += "        inGroups        List<word> 1(wall);\n";
      if (p.kind == PatchKind::kSymmetry || p.kind == PatchKind::kEmpty) {
        s += fmt::format("        inGroups        List<word> 1({});\n", type);
      }
      s += fmt::format("        nFaces          {};\n        startFace       {};\n    }}\n", p.size,
                       p.start);
    }
    s += ")\n";
    WriteText(tmp / "boundary", s);
    if (fs::exists(target)) fs::remove_all(target);
    fs::rename(tmp, target);
  } catch (...) {
    std::error_code ec;
    fs::remove_all(tmp, ec);
    throw;
  }
}

std::vector<double> FaceNonOrthogonality(const Mesh& mesh) {
  std::vector<double> angle(mesh.n_faces(), 0.0);
  for (int f = 0; f < mesh.n_faces(); ++f) {
    const Vector3& d = mesh.deltas()[f];
    const double c = d.dot(mesh.face_areas()[f]) / (d.norm() * mesh.face_area_magnitudes()[f]);
    angle[f] = std::acos(std::clamp(c, -1.0, 1.0)) * 180.0 / std::numbers::pi;
  }
  return angle;
}

void WriteVtu(const Mesh& mesh, const fs::path& path) {
  const int nc = mesh.n_cells();
  // Polyhedral cells: unique points, and faces oriented outwards.
  std::vector<std::int64_t> connectivity, offsets, faces, face_offsets;
  std::vector<std::uint8_t> types(nc, 42);  // VTK_POLYHEDRON
  const auto off = mesh.cell_face_offsets();
  const auto cf = mesh.cell_faces();
  std::vector<int> cell_points;
  for (int c = 0; c < nc; ++c) {
    cell_points.clear();
    faces.push_back(off[c + 1] - off[c]);
    for (int m = off[c]; m < off[c + 1]; ++m) {
      const int f = cf[m];
      const auto& pts = mesh.faces()[f];
      faces.push_back(static_cast<std::int64_t>(pts.size()));
      if (mesh.owner()[f] == c) {
        for (int p : pts) faces.push_back(p);
      } else {
        for (auto it = pts.rbegin(); it != pts.rend(); ++it) faces.push_back(*it);
      }
      cell_points.insert(cell_points.end(), pts.begin(), pts.end());
    }
    std::sort(cell_points.begin(), cell_points.end());
    cell_points.erase(std::unique(cell_points.begin(), cell_points.end()), cell_points.end());
    connectivity.insert(connectivity.end(), cell_points.begin(), cell_points.end());
    offsets.push_back(static_cast<std::int64_t>(connectivity.size()));
    face_offsets.push_back(static_cast<std::int64_t>(faces.size()));
  }
  std::vector<double> coords;
  coords.reserve(3 * mesh.n_points());
  for (const Vector3& p : mesh.points()) coords.insert(coords.end(), {p.x(), p.y(), p.z()});
  const std::vector<double> angle = FaceNonOrthogonality(mesh);
  std::vector<double> cell_angle(nc, 0.0);
  for (int f = 0; f < mesh.n_internal_faces(); ++f) {
    cell_angle[mesh.owner()[f]] = std::max(cell_angle[mesh.owner()[f]], angle[f]);
    cell_angle[mesh.neighbour()[f]] = std::max(cell_angle[mesh.neighbour()[f]], angle[f]);
  }
  const std::vector<double> volume(mesh.cell_volumes().begin(), mesh.cell_volumes().end());

  std::string xml;
  std::string blob;
  std::size_t offset = 0;
  auto array = [&](const char* type, const char* name, int components, const void* data,
                   std::size_t bytes) {
    xml += fmt::format(
        "        <DataArray type=\"{}\" Name=\"{}\"{} format=\"appended\" offset=\"{}\"/>\n", type,
        name, components > 1 ? fmt::format(" NumberOfComponents=\"{}\"", components) : "", offset);
    const std::uint64_t n = bytes;
    blob.append(reinterpret_cast<const char*>(&n), sizeof n);
    blob.append(static_cast<const char*>(data), bytes);
    offset += sizeof n + bytes;
  };
  xml +=
      "<?xml version=\"1.0\"?>\n"
      "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" "
      "header_type=\"UInt64\">\n"
      "  <UnstructuredGrid>\n";
  xml +=
      fmt::format("    <Piece NumberOfPoints=\"{}\" NumberOfCells=\"{}\">\n", mesh.n_points(), nc);
  xml += "      <Points>\n";
  array("Float64", "Points", 3, coords.data(), coords.size() * sizeof(double));
  xml += "      </Points>\n      <Cells>\n";
  array("Int64", "connectivity", 1, connectivity.data(), connectivity.size() * 8);
  array("Int64", "offsets", 1, offsets.data(), offsets.size() * 8);
  array("UInt8", "types", 1, types.data(), types.size());
  array("Int64", "faces", 1, faces.data(), faces.size() * 8);
  array("Int64", "faceoffsets", 1, face_offsets.data(), face_offsets.size() * 8);
  xml += "      </Cells>\n      <CellData Scalars=\"volume\">\n";
  array("Float64", "volume", 1, volume.data(), volume.size() * sizeof(double));
  array("Float64", "non_orthogonality", 1, cell_angle.data(), cell_angle.size() * sizeof(double));
  xml +=
      "      </CellData>\n    </Piece>\n  </UnstructuredGrid>\n  <AppendedData encoding=\"raw\">\n "
      "  _";
  std::string content = std::move(xml);
  content += blob;
  content += "\n  </AppendedData>\n</VTKFile>\n";
  data::WriteFileAtomically(path, content);
}

}  // namespace kelvin::cfd
