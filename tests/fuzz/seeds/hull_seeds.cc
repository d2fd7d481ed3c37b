// Hull seeds: a closed box (8 vertices, 12 outward triangles) as ASCII STL,
// binary STL (the project's WriteStl), both gzip-compressed, and OBJ.
#include <fmt/format.h>
#include <zlib.h>

#include "cfd/geometry/triangle_surface.h"
#include "tests/fuzz/seeds/seeds.h"

namespace kelvin::fuzz {
namespace {

namespace fs = std::filesystem;

cfd::TriangleSurface Box() {
  cfd::TriangleSurface s;
  for (int i = 0; i < 8; ++i) s.vertices.emplace_back(4.0 * (i & 1), 1.0 * ((i >> 1) & 1), ((i >> 2) & 1) - 0.5);
  s.triangles = {{0, 2, 1}, {1, 2, 3}, {4, 5, 6}, {5, 7, 6}, {0, 1, 4}, {1, 5, 4},
                 {2, 6, 3}, {3, 6, 7}, {0, 4, 2}, {2, 4, 6}, {1, 3, 5}, {3, 7, 5}};
  return s;
}

std::string AsciiStl(const cfd::TriangleSurface& s) {
  std::string out = "solid box\n";
  for (std::size_t t = 0; t < s.triangles.size(); ++t) {
    const Eigen::Vector3d n = s.Normal(t).normalized();
    out += fmt::format("  facet normal {} {} {}\n    outer loop\n", n.x(), n.y(), n.z());
    for (int v : s.triangles[t]) {
      out += fmt::format("      vertex {} {} {}\n", s.vertices[v].x(), s.vertices[v].y(), s.vertices[v].z());
    }
    out += "    endloop\n  endfacet\n";
  }
  return out + "endsolid box\n";
}

std::string Obj(const cfd::TriangleSurface& s) {
  std::string out = "# box\no box\n";
  for (const auto& v : s.vertices) out += fmt::format("v {} {} {}\n", v.x(), v.y(), v.z());
  out += "vn 0 0 1\nvt 0 0\n";
  for (std::size_t t = 0; t < s.triangles.size(); ++t) {
    const auto& tr = s.triangles[t];
    if (t % 3 == 0) {
      out += fmt::format("f {}/1/1 {}//1 {}\n", tr[0] + 1, tr[1] + 1, tr[2] + 1);
    } else {
      out += fmt::format("f {} {} {}\n", tr[0] - 8, tr[1] - 8, tr[2] - 8);  // relative to the end
    }
  }
  return out;
}

std::string Gzip(const std::string& bytes, const fs::path& scratch) {
  gzFile gz = gzopen(scratch.c_str(), "wb9");
  gzwrite(gz, bytes.data(), static_cast<unsigned>(bytes.size()));
  gzclose(gz);
  const std::string out = ReadBytes(scratch);
  fs::remove(scratch);
  return out;
}

}  // namespace

void WriteHullSeeds(const fs::path& out) {
  const cfd::TriangleSurface box = Box();
  const fs::path dir = out / "stl";
  cfd::WriteStl(box, dir / "box_binary.stl");
  const std::string binary = ReadBytes(dir / "box_binary.stl");
  WriteSeed(dir, "box_ascii.stl", AsciiStl(box));
  WriteSeed(dir, "box_binary.stl.gz", Gzip(binary, dir / "scratch.gz"));
  WriteSeed(dir, "box_ascii.stl.gz", Gzip(AsciiStl(box), dir / "scratch.gz"));
  WriteSeed(out / "obj", "box.obj", Obj(box));
  WriteSeed(out / "obj", "box.obj.gz", Gzip(Obj(box), out / "obj" / "scratch.gz"));
}

}  // namespace kelvin::fuzz
