#include "cfd/grid/mesh_writer.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <numbers>
#include <random>
#include <string>

#include "cfd/io/vtu_writer.h"
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
  const std::vector<double> angle = FaceNonOrthogonality(mesh);
  std::vector<double> cell_angle(mesh.n_cells(), 0.0);
  for (int f = 0; f < mesh.n_internal_faces(); ++f) {
    cell_angle[mesh.owner()[f]] = std::max(cell_angle[mesh.owner()[f]], angle[f]);
    cell_angle[mesh.neighbour()[f]] = std::max(cell_angle[mesh.neighbour()[f]], angle[f]);
  }
  const std::vector<double> volume(mesh.cell_volumes().begin(), mesh.cell_volumes().end());
  WriteVtu(path, mesh, {{"volume", 1, volume}, {"non_orthogonality", 1, std::move(cell_angle)}});
}

}  // namespace kelvin::cfd
