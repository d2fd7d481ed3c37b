// Mesh case files: the shipped examples parse, every bad input gives one
// clear message (file, line, key, value, expected), and a grid family is
// written as polyMesh + .vtu + quality report and read back by ReadPolyMesh.
#include "cfd/grid/mesh_case.h"

#include <fmt/format.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <sstream>

#include "cfd/mesh/poly_mesh_reader.h"
#include "data/schema/config.h"
#include "data/schema/errors.h"
#include "tests/cfd/vtk_read.h"
#include "tests/test_utilities/test_utilities.h"

namespace kelvin::cfd {
namespace {

using kelvin::testing::ScopedTempDir;
using kelvin::testing::SourceDir;
using ::testing::AllOf;
using ::testing::HasSubstr;

template <typename F>
std::string ErrorOf(F&& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return "(no error)";
}

const char* kWigley = R"(mesh:
  method: structured
  hull:
    wigley: {length: 2.5, beam: 0.25, draft: 0.15625}
  flow:
    reynolds: 5.0e6
  y_plus: 1.0
  structured: {cells_hull: 24, cells_upstream: 6, cells_downstream: 8, cells_girth: 12, cells_below_keel: 8, cells_normal: 16}
  family: {ratio: 1.41421356}
output:
  directory: out
)";

MeshCase Parse(const std::string& text) {
  return ParseMeshCase(text, "case.yaml", SourceDir() / "data" / "cases" / "mesh");
}

// kWigley with the line containing `from` replaced by `to`.
std::string Edit(const std::string& from, const std::string& to) {
  std::string s = kWigley;
  const auto pos = s.find(from);
  EXPECT_NE(pos, std::string::npos) << from;
  return s.replace(pos, from.size(), to);
}

TEST(MeshCaseTest, ShippedCaseFilesParse) {
  const MeshCase w = LoadMeshCase(SourceDir() / "data" / "cases" / "mesh" / "wigley.yaml");
  EXPECT_TRUE(w.wigley);
  EXPECT_EQ(w.method, MeshMethod::kStructured);
  EXPECT_EQ(w.structured.cells_hull, 60);
  EXPECT_DOUBLE_EQ(w.structured.reynolds, 5e6);
  const MeshCase d = LoadMeshCase(SourceDir() / "data" / "cases" / "mesh" / "dtc_snappy.yaml");
  EXPECT_EQ(d.method, MeshMethod::kSnappy);
  EXPECT_EQ(d.ship_file.filename(), "dtc.yaml");
  EXPECT_EQ(d.snappy.layers, SnappyOptions::kAutoLayers);
  // Re = U Lpp / nu with the DTC ship file's Lpp and nu.
  EXPECT_NEAR(d.reynolds, 1.668 * 5.976 / 1.09e-6, 1e-6 * d.reynolds);
  EXPECT_EQ(d.snappy.hull_level, 5);
  EXPECT_EQ(d.snappy.near_level, 3);
  EXPECT_EQ(d.family_layers, FamilyLayers::kSimilar);
  // Its first-layer family: the same grid 1, layers sized from y_plus on every grid.
  const MeshCase fl = LoadMeshCase(SourceDir() / "data" / "cases" / "mesh" / "dtc_snappy_first_layer.yaml");
  EXPECT_EQ(fl.family_layers, FamilyLayers::kSameFirstLayer);
  EXPECT_EQ(fl.snappy.base_cells_per_length, d.snappy.base_cells_per_length);
  EXPECT_EQ(fl.snappy.layers, d.snappy.layers);
  EXPECT_DOUBLE_EQ(fl.y_plus, d.y_plus);
}

TEST(MeshCaseTest, BadInputGivesOneClearMessage) {
  EXPECT_THAT(ErrorOf([] { Parse(Edit("  y_plus: 1.0", "  y_pluss: 1.0")); }),
              AllOf(HasSubstr("case.yaml:7: unknown key 'mesh.y_pluss'"),
                    HasSubstr("valid keys: method, hull"), HasSubstr("(did you mean 'y_plus'?)")));
  EXPECT_THAT(
      ErrorOf([] { Parse(Edit("method: structured", "method: delaunay")); }),
      HasSubstr("case.yaml:2: key 'mesh.method' = 'delaunay': expected 'structured' or 'snappy'"));
  EXPECT_THAT(
      ErrorOf([] {
        Parse(Edit("    wigley: {length: 2.5, beam: 0.25, draft: 0.15625}",
                   "    wigley: {length: 2.5, beam: 0.25, draft: 0.15625}\n    ship: a.yaml"));
      }),
      HasSubstr(
          "key 'mesh.hull' = (a map): expected exactly one of 'wigley' (the formula), 'spheroid' (a submerged "
          "body) or 'ship'"));
  EXPECT_THAT(ErrorOf([] { Parse(Edit("draft: 0.15625", "draft: -0.1")); }),
              HasSubstr("key 'mesh.hull.wigley.draft' = '-0.1': expected a positive number"));
  EXPECT_THAT(
      ErrorOf([] { Parse(Edit("    reynolds: 5.0e6", "    reynolds: 5.0e6\n    speed: 2.0")); }),
      HasSubstr("key 'mesh.flow' = (a map): expected either 'reynolds' or 'speed'"));
  EXPECT_THAT(
      ErrorOf([] { Parse(Edit("    reynolds: 5.0e6", "    speed: 2.0")); }),
      HasSubstr(
          "key 'mesh.flow' = (a map): expected 'viscosity' (m^2/s): the hull has no ship file"));
  EXPECT_THAT(ErrorOf([] { Parse(Edit("    reynolds: 5.0e6", "    reynolds: 50")); }),
              HasSubstr("key 'mesh.flow.reynolds' = '50'"));
  EXPECT_THAT(ErrorOf([] { Parse(Edit("  y_plus: 1.0", "  y_plus: 0")); }),
              HasSubstr("key 'mesh.y_plus' = '0': expected a finite number > 0"));
  EXPECT_THAT(
      ErrorOf([] { Parse(Edit("cells_hull: 24", "cells_hull: 1")); }),
      HasSubstr("key 'mesh.structured.cells_hull' = '1': expected an integer in [2, 100000]"));
  EXPECT_THAT(ErrorOf([] { Parse(Edit("cells_hull: 24", "cells_hull: many")); }),
              HasSubstr("key 'mesh.structured.cells_hull' = 'many'"));
  EXPECT_THAT(ErrorOf([] { Parse(Edit("cells_hull: 24", "cels_hull: 24")); }),
              AllOf(HasSubstr("unknown key 'mesh.structured.cels_hull'"),
                    HasSubstr("did you mean 'cells_hull'")));
  EXPECT_THAT(
      ErrorOf([] { Parse(Edit("ratio: 1.41421356", "ratio: 1.05")); }),
      HasSubstr("key 'mesh.family.ratio' = '1.05': expected a refinement ratio in [1.1, 4]"));
  EXPECT_THAT(ErrorOf([] { Parse(Edit("ratio: 1.41421356", "ratio: 1.41421356, layers: same")); }),
              HasSubstr("key 'mesh.family.layers' = 'same': expected 'similar'"));
  EXPECT_THAT(ErrorOf([] { Parse(Edit("ratio: 1.41421356", "ratio: 1.41421356, layers: first_layer")); }),
              HasSubstr("key 'mesh.family.layers' = 'first_layer': expected no family.layers with mesh.method "
                        "'structured'"));
  EXPECT_EQ(Parse(kWigley).family_layers, FamilyLayers::kSimilar);
  EXPECT_THAT(ErrorOf([] { Parse(Edit("  y_plus: 1.0", "  y_plus: 1.0\n  waves: {froude: -0.3}")); }),
              HasSubstr("key 'mesh.waves.froude' = '-0.3': expected a positive number"));
  EXPECT_THAT(ErrorOf([] { Parse(Edit("  y_plus: 1.0", "  y_plus: 1.0\n  waves: {froude: 0.3, cells: 12}")); }),
              HasSubstr("unknown key 'mesh.waves.cells'"));
  EXPECT_THAT(ErrorOf([] { Parse(Edit("  directory: out", "  folder: out")); }),
              HasSubstr("unknown key 'output.folder'; valid keys: directory, vtu"));
  EXPECT_THAT(ErrorOf([] { Parse(Edit("method: structured", "method: snappy")); }),
              HasSubstr("expected 'structured' for the Wigley formula"));
  EXPECT_THAT(ErrorOf([] {
                Parse(Edit("    wigley: {length: 2.5, beam: 0.25, draft: 0.15625}",
                           "    ship: nowhere.yaml"));
              }),
              HasSubstr("key 'mesh.hull.ship' = 'nowhere.yaml': expected an existing ship file"));
  EXPECT_THAT(
      ErrorOf([] { Parse(Edit("  y_plus: 1.0", "  snappy: {hull_level: 2, wake_level: 3}")); }),
      HasSubstr("key 'mesh.snappy.wake_level' = '3': expected at most hull_level = 2"));
  EXPECT_THAT(ErrorOf([] {
                Parse(Edit("  y_plus: 1.0", "  snappy: {hull_level: 3, wake_level: 1, near_level: 5}"));
              }),
              HasSubstr("key 'mesh.snappy.near_level' = '5': expected an integer in [wake_level, "
                        "hull_level] = [1, 3]"));
  EXPECT_THAT(
      ErrorOf([] { Parse(Edit("  y_plus: 1.0", "  snappy: {layers: -3}")); }),
      HasSubstr("key 'mesh.snappy.layers' = '-3': expected 'auto' or an integer in [0, 50]"));
  EXPECT_THAT(ErrorOf([] { Parse(Edit("  y_plus: 1.0", "  domain: {depth: 0}")); }),
              HasSubstr("key 'mesh.domain.depth' = '0': expected a finite number > 0"));
  EXPECT_THAT(ErrorOf([] { Parse("mesh: [1, 2\n"); }), HasSubstr("case.yaml:2: YAML syntax error"));
  EXPECT_THAT(ErrorOf([] { Parse("output: {directory: x}\n"); }), HasSubstr("key 'mesh'"));
  EXPECT_THAT(ErrorOf([] { LoadMeshCase("/nonexistent/case.yaml"); }),
              HasSubstr("/nonexistent/case.yaml: file not found"));
}

// Reads the appended raw arrays of a .vtu written by WriteVtu and checks
// that they describe `mesh`: sizes of every array, the offsets' last
// entries, the cell types and the points.
void CheckVtu(const std::filesystem::path& path, const Mesh& mesh) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  const std::string text = ss.str();
  const auto data = text.find("<AppendedData encoding=\"raw\">");
  ASSERT_NE(data, std::string::npos);
  const std::size_t base = text.find('_', data) + 1;
  auto array = [&](const std::string& name) { return testing::VtkRaw(text, name); };
  auto int64s = [&](const std::string& name) { return testing::VtkInt64s(text, name); };
  const std::string points = array("Points");
  ASSERT_EQ(points.size(), 24u * mesh.n_points());
  double p0[3];
  std::memcpy(p0, points.data(), sizeof p0);
  EXPECT_NEAR(p0[0], mesh.points()[0].x(),
              1e-12 * (1 + std::abs(p0[0])));  // polyMesh has 15 digits
  EXPECT_NEAR(p0[2], mesh.points()[0].z(), 1e-12 * (1 + std::abs(p0[2])));
  const std::string types = array("types");
  ASSERT_EQ(types.size(), static_cast<std::size_t>(mesh.n_cells()));
  EXPECT_TRUE(
      std::all_of(types.begin(), types.end(), [](char t) { return t == 42; }));  // VTK_POLYHEDRON
  const auto connectivity = int64s("connectivity"), offsets = int64s("offsets");
  const auto faces = int64s("faces"), face_offsets = int64s("faceoffsets");
  ASSERT_EQ(offsets.size(), static_cast<std::size_t>(mesh.n_cells()));
  ASSERT_EQ(face_offsets.size(), static_cast<std::size_t>(mesh.n_cells()));
  EXPECT_EQ(offsets.back(), static_cast<std::int64_t>(connectivity.size()));
  EXPECT_EQ(face_offsets.back(), static_cast<std::int64_t>(faces.size()));
  // Hexahedra: 8 points and 6 quadrilaterals per cell.
  EXPECT_EQ(connectivity.size(), 8u * mesh.n_cells());
  EXPECT_EQ(faces.size(), static_cast<std::size_t>(mesh.n_cells()) * (1 + 6 * 5));
  EXPECT_EQ(array("volume").size(), 8u * mesh.n_cells());
  EXPECT_EQ(array("non_orthogonality").size(), 8u * mesh.n_cells());
  EXPECT_NE(text.find("</VTKFile>", base), std::string::npos);
}

// A path the file system cannot examine (a name longer than NAME_MAX, found by
// the mesh_case_yaml fuzzer) is a missing file with the key named, not a
// std::filesystem exception that ends the program.
// Each malformed refinement box is refused naming its element and value.
TEST(MeshCaseTest, BadRefinementBoxGivesOneClearMessage) {
  const std::pair<const char*, const char*> cases[] = {
      {"[{min: [0, 0, 0], max: [1, 1], level: 4}]",
       "key 'mesh.snappy.boxes[0].max' = (a list): expected [x, y, z] in metres, got 2 numbers"},
      {"[{min: [0, 0, 0], max: [1, 1, 1]}]", "missing required key 'mesh.snappy.boxes[0].level'"},
      {"[{min: [0, .nan, 0], max: [1, 1, 1], level: 4}]",
       "key 'mesh.snappy.boxes[0].min[1]' = '.nan': expected a finite number"},
      {"[{min: [0, 0, 0], max: [1, -1, 1], level: 4}]",
       "key 'mesh.snappy.boxes[0].max' = (a list): expected a corner above min = [0, 0, 0] in x, y and z, got "
       "[1, -1, 1]"},
      {"[{min: [0, 0, 0], max: [1, 1, 1], level: 9}]",
       "key 'mesh.snappy.boxes[0].level' = '9': expected an integer in [0, 8]"},
      {"{min: [0, 0, 0]}", "key 'mesh.snappy.boxes' = (a map): expected a list of boxes"},
  };
  for (const auto& [boxes, message] : cases) {
    const std::string snappy = std::string("  snappy: {boxes: ") + boxes + "}";
    EXPECT_THAT(ErrorOf([&] { Parse(Edit("  y_plus: 1.0", snappy)); }), HasSubstr(message)) << boxes;
  }
}

TEST(MeshCaseTest, ShipPathTheFileSystemCannotExamineIsAMissingFile) {
  const std::string name(300, 'x');
  const std::string text = Edit("    wigley: {length: 2.5, beam: 0.25, draft: 0.15625}", "    ship: /" + name + "/s.yaml");
  EXPECT_THAT(ErrorOf([&] { Parse(text); }),
              AllOf(HasSubstr("key 'mesh.hull.ship' = '/" + name), HasSubstr("expected an existing ship file")));
  EXPECT_THAT(ErrorOf([&] { data::ConfigNode::LoadFile("/" + name + ".yaml"); }),
              HasSubstr(name + ".yaml: file not found"));
}

TEST(MeshCaseTest, FamilyIsWrittenAndReadBack) {
  ScopedTempDir dir;
  const MeshCase c = Parse(kWigley);
  const auto grids = RunMeshCase(c, 3, dir.path());
  ASSERT_EQ(grids.size(), 3u);
  for (const auto& g : grids) {
    const auto gdir = dir / fmt::format("grid{}", g.level);
    ASSERT_TRUE(std::filesystem::exists(gdir / "quality.txt"));
    ASSERT_TRUE(std::filesystem::exists(gdir / "mesh.vtu"));
    const Mesh back = ReadPolyMesh(gdir / "constant" / "polyMesh");
    EXPECT_EQ(back.n_cells(), g.quality.n_cells);
    EXPECT_EQ(back.n_faces(), g.quality.n_faces);
    EXPECT_NEAR(back.total_volume() / g.quality.total_volume, 1.0, 1e-12);
    EXPECT_EQ(back.patches()[back.FindPatch("hull")].kind, PatchKind::kWall);
    EXPECT_LT(g.quality.max_non_orthogonality, 60.0);
    std::ifstream in(gdir / "quality.txt");
    std::stringstream text;
    text << in.rdbuf();
    EXPECT_THAT(text.str(),
                AllOf(HasSubstr("non-orthogonality max"), HasSubstr("y+ estimate"),
                      HasSubstr("negative or zero volumes: none"), HasSubstr("aspect ratio max")));
    CheckVtu(gdir / "mesh.vtu", back);
  }
  EXPECT_GT(grids[0].quality.n_cells, grids[1].quality.n_cells);
  EXPECT_GT(grids[1].quality.n_cells, grids[2].quality.n_cells);
  EXPECT_TRUE(std::filesystem::exists(dir / "family.txt"));
  EXPECT_THAT(ErrorOf([&] { RunMeshCase(c, 7, dir.path()); }),
              HasSubstr("--family 7: expected 1 to 6 grids"));
}

}  // namespace
}  // namespace kelvin::cfd
