// The snappyHexMesh path: the dictionaries for the double-body domain, a
// CI-sized DTC grid from Debian's OpenFOAM with its quality report, and the
// errors when OpenFOAM is missing. KELVIN_SNAPPY_FULL=1 runs the benchmark
// grid of data/cases/mesh/dtc_snappy.yaml instead (ctest label slow).
#include "cfd/grid/snappy_mesher.h"

#include <fmt/format.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>
#include <sstream>
#include <vector>

#include "cfd/geometry/hydrostatics.h"
#include "cfd/grid/hull_grid.h"
#include "cfd/grid/mesh_case.h"
#include "cfd/grid/mesh_writer.h"
#include "cfd/grid/spacing.h"
#include "data/schema/errors.h"
#include "tests/test_utilities/test_utilities.h"

namespace kelvin::cfd {
namespace {

using kelvin::testing::ScopedTempDir;
using kelvin::testing::SourceDir;
using ::testing::HasSubstr;

std::string Slurp(const std::filesystem::path& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

TEST(SnappyMesherTest, DictionariesDescribeTheDoubleBodyDomain) {
  ScopedTempDir dir;
  const TriangleSurface hull = WigleySurface(2.0, 0.2, 0.125, 0.05, 40, 10);
  SnappyOptions o;
  o.reynolds = 4e6;
  o.y_plus = 30;
  o.layers = 5;
  WriteSnappyCase(hull, o, dir.path());
  const std::string block = Slurp(dir / "system/blockMeshDict");
  // Domain: 1 L ahead, 2 L behind, +-1 L wide, 1 L deep, top on z = 0.
  EXPECT_THAT(block, HasSubstr("(-4 -2 -2)"));
  EXPECT_THAT(block, HasSubstr("(4 2 0)"));
  for (const char* patch : {"freeSurface", "inlet", "outlet", "side", "bottom"})
    EXPECT_THAT(block, HasSubstr(patch));
  const std::string snappy = Slurp(dir / "system/snappyHexMeshDict");
  // Layers relative to the hull cells (L / 10 / 2^3 = 25 mm): five layers
  // at expansion 1.2 whose first is the height for y+ 30.
  const double first = FirstCellHeight(30, 4e6, 2.0);
  EXPECT_THAT(snappy, HasSubstr("relativeSizes true;"));
  EXPECT_THAT(snappy, HasSubstr(fmt::format("finalLayerThickness {:.6g};",
                                            first * std::pow(1.2, 4) / 0.025)));
  EXPECT_NEAR(SnappyFirstLayer(o, 2.0), first, 1e-12);
  EXPECT_THAT(snappy, HasSubstr("expansionRatio 1.2;"));
  EXPECT_THAT(snappy, HasSubstr("nSurfaceLayers 5;"));
  EXPECT_THAT(snappy, HasSubstr("kelvinWake"));
  // Hull level 3, wake level 1: the near-hull box gets level 2 unless set.
  EXPECT_THAT(snappy, HasSubstr("nearHull { mode inside; levels ((1e15 2)); }"));
  EXPECT_TRUE(std::filesystem::exists(dir / "constant/triSurface/hull.stl"));
  o.near_level = 3;
  WriteSnappyCase(hull, o, dir.path());
  EXPECT_THAT(Slurp(dir / "system/snappyHexMeshDict"),
              HasSubstr("nearHull { mode inside; levels ((1e15 3)); }"));
  // A given outermost layer (a coarser grid of a family keeps grid 1's):
  // half a cell, so the first is 12.5 mm / 1.2^4.
  o.final_layer_ratio = 0.5;
  EXPECT_NEAR(SnappyFirstLayer(o, 2.0), 0.0125 / std::pow(1.2, 4), 1e-12);
  o.final_layer_ratio = 0;
  // Auto layers: the fewest whose outermost reaches half a hull cell
  // (12.5 mm) from the first layer for the target y+.
  o.layers = SnappyOptions::kAutoLayers;
  const int n = SnappyLayerCount(o, 2.0);
  EXPECT_GE(first * std::pow(1.2, n - 1), 0.0125);
  EXPECT_LT(first * std::pow(1.2, n - 2), 0.0125);
  EXPECT_NEAR(SnappyFirstLayer(o, 2.0), first, 1e-12);
  o.near_level = 4;  // above hull_level
  EXPECT_THROW(o.Validate(), ConfigError);
}

// A user's refinement box becomes a searchable box refined inside to its
// level; a box without volume is refused, naming it.
TEST(SnappyMesherTest, RefinementBoxesReachTheDictionary) {
  ScopedTempDir dir;
  const TriangleSurface hull = WigleySurface(2.0, 0.2, 0.125, 0.05, 40, 10);
  SnappyOptions o;
  o.boxes = {{{1.9, -0.05, -0.1}, {2.05, 0.05, 0}, 5}};
  WriteSnappyCase(hull, o, dir.path());
  const std::string snappy = Slurp(dir / "system/snappyHexMeshDict");
  EXPECT_THAT(snappy, HasSubstr("userBox0 { type searchableBox; min (1.9 -0.05 -0.1); max (2.05 0.05 0); }"));
  EXPECT_THAT(snappy, HasSubstr("userBox0 { mode inside; levels ((1e15 5)); }"));
  o.boxes.push_back({{0, 0, -0.1}, {0.1, 0, 0}, 4});
  try {
    o.Validate();
    ADD_FAILURE() << "a flat box was accepted";
  } catch (const ConfigError& e) {
    EXPECT_THAT(e.what(), HasSubstr("'boxes[1]' min = (0 0 -0.1), max = (0.1 0 0): expected finite corners "
                                    "with min < max"));
  }
}

// The layer table at the end of a snappyHexMesh log (OpenFOAM v1912 format):
// the table before layer addition ("avg thickness") is not the result.
TEST(SnappyMesherTest, ReadsTheLayersSnappyKept) {
  ScopedTempDir dir;
  std::ofstream(dir / "log.snappyHexMesh")
      << "patch faces    layers avg thickness[m]\n"
         "                     near-wall overall\n"
         "----- -----    ------ --------- -------\n"
         "hull 4068     6      0.00776   0.0767\n"
         "Layer addition iteration 0\n"
         "patch faces    layers   overall thickness\n"
         "                       [m]       [%]\n"
         "----- -----    ------   ---       ---\n"
         "hull 4068     5.05     0.0665    86.6\n"
         "\n"
         "Layer mesh : cells:69986  faces:223574  points:84155\n";
  double layers = 0, percent = 0;
  ASSERT_TRUE(ReadSnappyLayerTable(dir / "log.snappyHexMesh", "hull", &layers, &percent));
  EXPECT_DOUBLE_EQ(layers, 5.05);
  EXPECT_DOUBLE_EQ(percent, 86.6);
  EXPECT_FALSE(ReadSnappyLayerTable(dir / "log.snappyHexMesh", "rudder", &layers, &percent));
  EXPECT_FALSE(ReadSnappyLayerTable(dir / "missing.log", "hull", &layers, &percent));
}

// The per-face counts of 0/nSurfaceLayers (writeFlags (layerFields)), in
// the layout snappyHexMesh 1912 writes them; a patch whose name is the tail
// of another's (hull, skeg_hull) is found by its whole name.
TEST(SnappyMesherTest, ReadsTheLayersOfEachHullFace) {
  ScopedTempDir dir;
  std::ofstream(dir / "nSurfaceLayers")
      << "FoamFile\n{\n    class       volScalarField;\n    object      nSurfaceLayers;\n}\n"
         "dimensions      [0 0 0 0 0 0 0];\ninternalField   uniform 0;\nboundaryField\n{\n"
         "    skeg_hull\n    {\n        type            fixedValue;\n        value           uniform 2;\n    }\n"
         "    hull\n    {\n        type            fixedValue;\n"
         "        value           nonuniform List<scalar> \n4\n(\n7\n7\n3\n0\n)\n;\n    }\n}\n";
  EXPECT_EQ(ReadSnappyFaceLayers(dir / "nSurfaceLayers", "hull", 4), (std::vector<double>{7, 7, 3, 0}));
  EXPECT_EQ(ReadSnappyFaceLayers(dir / "nSurfaceLayers", "skeg_hull", 3), (std::vector<double>{2, 2, 2}));
  EXPECT_TRUE(ReadSnappyFaceLayers(dir / "missing", "hull", 4).empty());
  try {
    ReadSnappyFaceLayers(dir / "nSurfaceLayers", "hull", 5);
    FAIL() << "no error";
  } catch (const DataFileError& e) {
    EXPECT_THAT(e.what(), HasSubstr("nSurfaceLayers: 4 values, expected one per face"));
    EXPECT_THAT(e.what(), HasSubstr("patch 'hull', 5 faces"));
  }
  try {
    ReadSnappyFaceLayers(dir / "nSurfaceLayers", "rudder", 5);
    FAIL() << "no error";
  } catch (const DataFileError& e) {
    EXPECT_THAT(e.what(), HasSubstr("no entry for the patch"));
  }
}

TEST(SnappyMesherTest, MissingOpenFoamIsOneClearError) {
  ScopedTempDir dir;
  SnappyOptions o;
  o.openfoam_bashrc = "/nonexistent/openfoam/bashrc";
  const TriangleSurface hull = WigleySurface(2.0, 0.2, 0.125, 0.05, 20, 6);
  try {
    RunSnappy(hull, o, dir.path());
    FAIL() << "no error";
  } catch (const DataFileError& e) {
    EXPECT_THAT(e.what(),
                HasSubstr("/nonexistent/openfoam/bashrc: OpenFOAM environment not found"));
  }
}

// OpenFOAM's checkMesh reads the polyMesh kelvin writes for a Wigley grid and
// finds the same cells, volume and non-orthogonality, and no failed check
// other than the aspect ratio of the y+ ~ 1 wall cells.
TEST(SnappyMesherTest, CheckMeshAgreesWithKelvinsQualityOfTheWigleyGrid) {
  if (!std::filesystem::exists("/usr/share/openfoam/etc/bashrc"))
    GTEST_SKIP() << "Debian openfoam not installed";
  ScopedTempDir dir;
  const WigleySections wigley(2.5, 0.25, 0.15625);
  HullGridOptions o;
  o.cells_hull = 24;
  o.cells_upstream = 6;
  o.cells_downstream = 8;
  o.cells_girth = 12;
  o.cells_below_keel = 8;
  o.cells_normal = 16;
  const Mesh mesh = MakeHullGrid(wigley, o);
  WritePolyMesh(mesh, dir.path());
  std::filesystem::create_directories(dir / "system");
  std::ofstream(dir / "system/controlDict")
      << "FoamFile { version 2.0; format ascii; class dictionary; object controlDict; }\n"
         "application checkMesh; startFrom startTime; startTime 0; stopAt endTime; endTime 1; "
         "deltaT 1;\n"
         "writeControl timeStep; writeInterval 1;\n";
  std::ofstream(dir / "system/fvSchemes")
      << "FoamFile { version 2.0; format ascii; class dictionary; object fvSchemes; }\n"
         "ddtSchemes { default steadyState; } gradSchemes { default Gauss linear; } divSchemes { "
         "default none; }\n"
         "laplacianSchemes { default Gauss linear corrected; } interpolationSchemes { default "
         "linear; }\n"
         "snGradSchemes { default corrected; }\n";
  std::ofstream(dir / "system/fvSolution")
      << "FoamFile { version 2.0; format ascii; class dictionary; object fvSolution; }\n";
  const auto r = kelvin::testing::RunCommand(
      "bash -c 'source /usr/share/openfoam/etc/bashrc >/dev/null 2>&1; "
      "checkMesh -case \"" +
      dir.path().string() + "\"'");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  auto number_after = [&](const std::string& key) {
    const auto pos = r.output.find(key);
    EXPECT_NE(pos, std::string::npos) << key << "\n" << r.output;
    return pos == std::string::npos ? -1.0 : std::stod(r.output.substr(pos + key.size()));
  };
  const MeshQuality q = mesh.Quality();
  EXPECT_EQ(static_cast<int>(number_after("    cells:")), q.n_cells);
  // The boundary faces on the hull are slightly warped quads; the two codes
  // integrate a warped face's pyramid differently (OpenFOAM with the face's
  // total area vector at its centroid), which moves the total by about the
  // warp volume of the hull faces: ~1e-6 of the domain here.
  EXPECT_NEAR(number_after("Total volume = ") / q.total_volume, 1.0, 1e-5);
  EXPECT_NEAR(number_after("Mesh non-orthogonality Max: "), q.max_non_orthogonality, 1e-3);
  EXPECT_THAT(r.output, HasSubstr("Face pyramids OK."));
  EXPECT_THAT(r.output, HasSubstr("Cell volumes OK."));
  EXPECT_THAT(r.output, HasSubstr("Non-orthogonality check OK."));
  EXPECT_THAT(r.output, HasSubstr("Failed 1 mesh checks."));  // the aspect ratio only
  EXPECT_THAT(r.output, HasSubstr("High aspect ratio cells found"));
}

TEST(SnappyMesherTest, DtcGridQualityReport) {
  if (!std::filesystem::exists("/usr/share/openfoam/etc/bashrc"))
    GTEST_SKIP() << "Debian openfoam not installed";
  const bool full = std::getenv("KELVIN_SNAPPY_FULL") != nullptr;
  MeshCase c = LoadMeshCase(SourceDir() / "data/cases/mesh/dtc_snappy.yaml");
  if (!full) {
    // CI size: coarser background and one level less on the hull.
    c.snappy.base_cells_per_length = 8;
    c.snappy.hull_level = 3;
    c.snappy.near_level = 2;
    c.snappy.wake_level = 1;
  }
  c.write_vtu = false;
  ScopedTempDir dir;
  // A relative output directory, as `kelvin mesh -o grids/dtc` gives it: the
  // OpenFOAM tools run inside it, so their logs must not be looked up
  // relative to it a second time (the run used to fail with "cannot find
  // log.blockMesh").
  const std::filesystem::path cwd = std::filesystem::current_path();
  std::filesystem::current_path(dir.path());
  std::vector<GridSummary> grids;
  try {
    grids = RunMeshCase(c, 1, "grids/dtc");
  } catch (...) {
    std::filesystem::current_path(cwd);
    throw;
  }
  std::filesystem::current_path(cwd);
  ASSERT_EQ(grids.size(), 1u);
  EXPECT_TRUE(std::filesystem::exists(dir / "grids/dtc/log.snappyHexMesh"));
  const GridSummary& g = grids[0];
  fmt::print("{}", g.report);
  EXPECT_GT(g.quality.min_volume, 0.0);
  // snappyHexMesh's own limit (meshQualityControls maxNonOrtho 65).
  EXPECT_LT(g.quality.max_non_orthogonality, 65.0);
  EXPECT_LT(g.quality.boundary_openness, 1e-10);
  // Snapping puts the hull patch points on the STL surface; the faces
  // between them cut the chords of curved parts and round the features, so
  // on average the patch lies within a small fraction of a hull cell of the
  // surface. An unsnapped (castellated) hull would sit about a quarter of a
  // cell off. Mean offset = |V_grid - V_stl| / S_wet, required below 5% of
  // the hull surface cell size L / base / 2^level.
  const HullPlacement placement = LoadHullPlacement(c.ship_file);
  const TriangleSurface hull = LoadHull(placement);
  const double stl = UnderwaterVolume(hull);
  const Hydrostatics hs = ComputeHydrostatics(hull, placement.Lpp, placement.B, placement.T);
  const double cell =
      placement.Lpp / c.snappy.base_cells_per_length / std::pow(2.0, c.snappy.hull_level);
  const double offset = std::abs(g.hull_volume - stl) / hs.wetted_area;
  fmt::print(
      "hull patch volume / STL volume = {:.5f}; mean offset {:.3g} mm = {:.3g} of the {:.3g} mm "
      "hull cells\n",
      g.hull_volume / stl, 1e3 * offset, offset / cell, 1e3 * cell);
  EXPECT_LT(offset, 0.05 * cell);
  // The report carries the figures the issue asks for.
  EXPECT_THAT(g.report, HasSubstr("non-orthogonality max"));
  EXPECT_THAT(g.report, HasSubstr("skewness max"));
  EXPECT_THAT(g.report, HasSubstr("y+ estimate"));
  EXPECT_GT(g.y_plus.min, 0.0);
  // The layer table of the log is read back into the report.
  EXPECT_GT(g.snappy.layers_kept, 0.0);
  EXPECT_LE(g.snappy.layers_kept, g.snappy.layers);
  EXPECT_THAT(g.report, HasSubstr("layers kept by snappyHexMesh"));
  // And the per-face counts, weighted by area: a share of the request no
  // larger than the share of the area that has layers at all.
  EXPECT_GT(g.snappy.layers_area_percent, 0.0);
  EXPECT_LE(g.snappy.layers_area_percent, 100.0);
  EXPECT_GE(g.snappy.area_without_layers_percent, 0.0);
  EXPECT_LE(g.snappy.layers_area_percent, 100.0 - g.snappy.area_without_layers_percent + 1e-9);
  EXPECT_THAT(g.report, HasSubstr("layers kept over the hull area"));
  if (full) {
    // Issue #25 acceptance 2 on the default grid: at least 90% of the
    // requested layers over the hull area (97.6% measured on 2026-12-02;
    // 84.1% while the tet-quality test shrank the layers at the bow and
    // stern), and the first-cell y+ estimate within a factor 1.5 of the
    // target.
    EXPECT_GE(g.snappy.layers_area_percent, 90.0);
    EXPECT_LT(g.snappy.area_without_layers_percent, 2.0);
    EXPECT_GT(g.y_plus.mean, c.y_plus / 1.5);
    EXPECT_LT(g.y_plus.mean, c.y_plus * 1.5);
  }
}

}  // namespace
}  // namespace kelvin::cfd
