// Mesh case files: the shipped examples parse, every bad input gives one
// clear message (file, line, key, value, expected), and a grid family is
// written as polyMesh + .vtu + quality report and read back by ReadPolyMesh.
#include "cfd/grid/mesh_case.h"

#include <fmt/format.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <sstream>

#include "cfd/mesh/poly_mesh_reader.h"
#include "data/schema/errors.h"
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
  EXPECT_EQ(d.snappy.hull_level, 4);
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
          "key 'mesh.hull' = (a map): expected exactly one of 'wigley' (the formula) or 'ship'"));
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
    std::ifstream vtu(gdir / "mesh.vtu");
    std::string first;
    std::getline(vtu, first);
    EXPECT_EQ(first, "<?xml version=\"1.0\"?>");
  }
  EXPECT_GT(grids[0].quality.n_cells, grids[1].quality.n_cells);
  EXPECT_GT(grids[1].quality.n_cells, grids[2].quality.n_cells);
  EXPECT_TRUE(std::filesystem::exists(dir / "family.txt"));
  EXPECT_THAT(ErrorOf([&] { RunMeshCase(c, 7, dir.path()); }),
              HasSubstr("--family 7: expected 1 to 6 grids"));
}

}  // namespace
}  // namespace kelvin::cfd
