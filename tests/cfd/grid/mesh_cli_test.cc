// `kelvin mesh` end to end: a Wigley family from a case file, and the exit
// code and single message of a bad case file and a bad --family.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fstream>

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
