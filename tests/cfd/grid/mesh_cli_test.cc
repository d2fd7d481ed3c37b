// `kelvin mesh` end to end: a Wigley family from a case file, and the exit
// code and single message of a bad case file and a bad --family.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>

#include "cfd/geometry/hydrostatics.h"
#include "cfd/grid/hull_grid.h"
#include "cfd/mesh/poly_mesh_reader.h"
#include "tests/test_utilities/test_utilities.h"

namespace kelvin {
namespace {

using kelvin::testing::RunCommand;
using kelvin::testing::ScopedTempDir;
using ::testing::HasSubstr;

std::string Kelvin() { return (kelvin::testing::ToolsDir() / "kelvin").string(); }

void Write(const std::filesystem::path& p, const std::string& text) { std::ofstream(p) << text; }

const char* kCase = R"(mesh:
  hull:
    wigley: {length: 2.5, beam: 0.25, draft: 0.15625}
  flow: {speed: 2.0, viscosity: 1.0e-6}
  structured: {cells_hull: 24, cells_upstream: 6, cells_downstream: 8, cells_girth: 12, cells_below_keel: 8, cells_normal: 16}
output:
  directory: grids
  vtu: false
)";

TEST(MeshCliTest, WritesAFamilyOfThreeGrids) {
  ScopedTempDir dir;
  Write(dir / "case.yaml", kCase);
  const auto r = RunCommand(Kelvin() + " mesh " + (dir / "case.yaml").string() + " --family 3");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  for (const char* g : {"grid1", "grid2", "grid3"}) {
    EXPECT_TRUE(std::filesystem::exists(dir / "grids" / g / "constant/polyMesh/faces")) << g;
    EXPECT_TRUE(std::filesystem::exists(dir / "grids" / g / "quality.txt")) << g;
    EXPECT_FALSE(std::filesystem::exists(dir / "grids" / g / "mesh.vtu")) << g;
  }
  EXPECT_TRUE(std::filesystem::exists(dir / "grids/family.txt"));
  // Re = U L / nu = 2 * 2.5 / 1e-6.
  EXPECT_THAT(r.output, HasSubstr("Re = 5e+06"));
  EXPECT_THAT(r.output, HasSubstr("family: 3 grids, ratio 1.41421"));
}

// The STL path of the built-in generator: a Wigley hull written as binary
// STL in its own units and placement (mm, keel at z = 0, waterline at
// z = T), described by a ship file, meshed by slicing its sections.
TEST(MeshCliTest, StructuredGridOfAnStlHullFromAShipFile) {
  ScopedTempDir dir;
  cfd::TriangleSurface hull = cfd::WigleySurface(2.5, 0.25, 0.15625, 0.05, 240, 48);
  for (auto& v : hull.vertices) {
    v.z() += 0.15625;
    v *= 1000.0;
  }
  cfd::WriteStl(hull, dir / "wigley.stl");
  Write(dir / "wigley_ship.yaml", R"(ship: {name: Wigley}
principal: {Lpp: 2.5, B: 0.25, d: 0.15625, nu: 1.0e-6}
geometry: {file: wigley.stl, length_unit: 0.001, x_ap: 0.0, waterline_z: 0.15625, bow_direction: "+x"}
)");
  std::string text = kCase;
  text.replace(text.find("    wigley: {length: 2.5, beam: 0.25, draft: 0.15625}"),
               std::string("    wigley: {length: 2.5, beam: 0.25, draft: 0.15625}").size(),
               "    ship: wigley_ship.yaml");
  text.replace(text.find("flow: {speed: 2.0, viscosity: 1.0e-6}"),
               std::string("flow: {speed: 2.0, viscosity: 1.0e-6}").size(), "flow: {speed: 2.0}");
  Write(dir / "stl_case.yaml", text);
  const auto r = RunCommand(Kelvin() + " mesh " + (dir / "stl_case.yaml").string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  // Re from the ship file's Lpp and nu; the sliced hull encloses the Wigley
  // volume 4/9 L B T = 0.0434028 m^3 to the faceting of 24 x 12 hull faces
  // (about 0.5%, the product trapezoid rule, see hull_grid_test).
  EXPECT_THAT(r.output, HasSubstr("Re = 5e+06"));
  const cfd::Mesh mesh = cfd::ReadPolyMesh(dir / "grids/constant/polyMesh");
  const double exact = 4.0 / 9.0 * 2.5 * 0.25 * 0.15625;
  std::printf("sliced STL hull volume / (4/9 L B T) - 1 = %.3e\n",
              cfd::HullPatchVolume(mesh) / exact - 1.0);
  EXPECT_NEAR(cfd::HullPatchVolume(mesh) / exact, 1.0, 0.01);
  EXPECT_LT(mesh.Quality().max_non_orthogonality, 60.0);
}

// --hull: a hull the project cannot ship (the KCS) comes from the user and
// replaces the ship file's geometry.file; without it the missing file is
// one clear error, and a Wigley-formula case has no hull file to replace.
TEST(MeshCliTest, HullOptionReplacesTheShipFilesSurface) {
  ScopedTempDir dir;
  cfd::WriteStl(cfd::WigleySurface(2.5, 0.25, 0.15625, 0.05, 240, 48), dir / "user_hull.stl");
  Write(dir / "ship.yaml", R"(ship: {name: Wigley}
principal: {Lpp: 2.5, B: 0.25, d: 0.15625, nu: 1.0e-6}
geometry: {file: not-shipped.stl, length_unit: 1.0, x_ap: 0.0, waterline_z: 0.0, bow_direction: "+x"}
)");
  std::string text = kCase;
  text.replace(text.find("    wigley: {length: 2.5, beam: 0.25, draft: 0.15625}"),
               std::string("    wigley: {length: 2.5, beam: 0.25, draft: 0.15625}").size(), "    ship: ship.yaml");
  text.replace(text.find("flow: {speed: 2.0, viscosity: 1.0e-6}"),
               std::string("flow: {speed: 2.0, viscosity: 1.0e-6}").size(), "flow: {speed: 2.0}");
  Write(dir / "case.yaml", text);
  const auto missing = RunCommand(Kelvin() + " mesh " + (dir / "case.yaml").string());
  EXPECT_EQ(missing.exit_code, 1) << missing.output;
  EXPECT_THAT(missing.output, HasSubstr("not-shipped.stl"));
  const auto r = RunCommand(Kelvin() + " mesh " + (dir / "case.yaml").string() + " --hull " +
                            (dir / "user_hull.stl").string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const cfd::Mesh mesh = cfd::ReadPolyMesh(dir / "grids/constant/polyMesh");
  EXPECT_NEAR(cfd::HullPatchVolume(mesh) / (4.0 / 9.0 * 2.5 * 0.25 * 0.15625), 1.0, 0.01);
  Write(dir / "wigley.yaml", kCase);
  const auto w = RunCommand(Kelvin() + " mesh " + (dir / "wigley.yaml").string() + " --hull " +
                            (dir / "user_hull.stl").string());
  EXPECT_NE(w.exit_code, 0) << w.output;
  EXPECT_THAT(w.output, HasSubstr("uses the Wigley formula"));
}

TEST(MeshCliTest, BadCaseFileExitsWithOneMessage) {
  ScopedTempDir dir;
  std::string text = kCase;
  text.replace(text.find("vtu: false"), 10, "vtk: false");
  Write(dir / "bad.yaml", text);
  const auto r = RunCommand(Kelvin() + " mesh " + (dir / "bad.yaml").string());
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_THAT(r.output,
              HasSubstr("bad.yaml:8: unknown key 'output.vtk'; valid keys: directory, vtu"));
  EXPECT_FALSE(std::filesystem::exists(dir / "grids"));
  const auto f = RunCommand(Kelvin() + " mesh " + (dir / "bad.yaml").string() + " --family 9");
  EXPECT_EQ(f.exit_code, 2) << f.output;
  EXPECT_THAT(f.output, HasSubstr("--family"));
}

}  // namespace
}  // namespace kelvin
