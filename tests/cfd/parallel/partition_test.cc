// The partitioner (cfd/parallel/partition.h) on one rank: the prism columns
// of thin cells are found and never cut, the parts are balanced, and a mesh
// with fewer columns than ranks is refused by name.
#include <gtest/gtest.h>

#include <mpi.h>

#include <string>

#include "cfd/mesh/box_mesh.h"
#include "cfd/parallel/partition.h"
#include "data/schema/errors.h"

namespace kelvin::cfd {
namespace {

// 8 x 2 x 40 cells on 4 x 1 x 1 m, graded 10:1 in z: every cell is thin
// across its z faces (dz <= 0.065 m against dx = 0.5 m), so the cells form
// 16 columns of 40. Cut without the columns, the cheapest bisection of this
// graph is horizontal (16 faces, against 80 for a vertical one).
Mesh LayeredSlab() {
  BoxMeshOptions o;
  o.max = Vector3(4.0, 1.0, 1.0);
  o.cells = {8, 2, 40};
  o.grading = {1.0, 1.0, 10.0};
  return MakeBoxMesh(o);
}

// Cells thin across face f by the partitioner's own measure, both sides.
bool ThinFace(const Mesh& mesh, int f, double aspect) {
  const double a = mesh.face_area_magnitudes()[f];
  const double v = std::min(mesh.cell_volumes()[mesh.owner()[f]], mesh.cell_volumes()[mesh.neighbour()[f]]);
  return a * std::sqrt(a) >= aspect * v;
}

TEST(PrismColumns, ThinCellsFormColumnsAndIsotropicCellsStandAlone) {
  const Mesh slab = LayeredSlab();
  std::vector<int> column;
  EXPECT_EQ(PrismColumns(slab, 5.0, column), 16);
  BoxMeshOptions cube;
  cube.cells = {6, 6, 6};
  const Mesh uniform = MakeBoxMesh(cube);
  EXPECT_EQ(PrismColumns(uniform, 5.0, column), uniform.n_cells());
}

// The test meshes are small: no minimum of cells per rank.
PartitionOptions SmallMeshes() {
  PartitionOptions o;
  o.min_cells_per_rank = 1;
  return o;
}

TEST(PartitionCells, KeepsColumnsWholeAndBalancesTheParts) {
  const Mesh slab = LayeredSlab();
  const PartitionOptions options = SmallMeshes();
  for (int parts : {2, 4}) {
    PartitionSummary summary;
    const std::vector<int> part = PartitionCells(slab, parts, MPI_COMM_SELF, options, &summary);
    ASSERT_EQ(static_cast<int>(part.size()), slab.n_cells());
    EXPECT_EQ(summary.n_columns, 16);
    EXPECT_EQ(summary.largest_column, 40);
    for (int f = 0; f < slab.n_internal_faces(); ++f) {
      if (ThinFace(slab, f, options.column_aspect)) {
        EXPECT_EQ(part[slab.owner()[f]], part[slab.neighbour()[f]]) << "column cut at face " << f;
      }
    }
    // 16 columns of 40 cells split evenly over 2 or 4 parts.
    for (int n : summary.part_cells) EXPECT_EQ(n, slab.n_cells() / parts) << parts << " parts";
    EXPECT_EQ(summary.imbalance, 0.0);
    // A vertical cut: 40 faces per column pair split; never the 16-face horizontal one.
    EXPECT_GE(summary.cut_faces, 40);
  }
}

// The same graph gives the same parts every time (threaded PT-Scotch did
// not: runs on ranks were not reproducible, nor their restarts bit for bit).
TEST(PartitionCells, IsReproducible) {
  BoxMeshOptions o;
  o.cells = {24, 24, 24};
  o.perturbation = 0.1;
  const Mesh cube = MakeBoxMesh(o);
  const std::vector<int> first = PartitionCells(cube, 4, MPI_COMM_SELF, SmallMeshes());
  for (int k = 0; k < 8; ++k) {
    EXPECT_EQ(PartitionCells(cube, 4, MPI_COMM_SELF, SmallMeshes()), first) << "partition " << k + 2;
  }
}

TEST(PartitionCells, OnePartNeedsNoPartitioner) {
  const Mesh slab = LayeredSlab();
  const std::vector<int> part = PartitionCells(slab, 1, MPI_COMM_SELF);
  for (int p : part) EXPECT_EQ(p, 0);
}

TEST(PartitionCells, MorePartsThanColumnsIsRefusedByName) {
  const Mesh slab = LayeredSlab();
  try {
    PartitionCells(slab, 17, MPI_COMM_SELF, SmallMeshes());
    FAIL() << "expected a ConfigError";
  } catch (const ConfigError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("640 cells in 16 prism columns"), std::string::npos) << what;
    EXPECT_NE(what.find("17 ranks"), std::string::npos) << what;
  }
}

TEST(PartitionCells, TooFewCellsPerRankIsRefusedWithTheRankCountThatFits) {
  const Mesh slab = LayeredSlab();  // 640 cells
  PartitionOptions o;
  o.min_cells_per_rank = 200;
  EXPECT_NO_THROW(PartitionCells(slab, 3, MPI_COMM_SELF, o));
  try {
    PartitionCells(slab, 4, MPI_COMM_SELF, o);
    FAIL() << "expected a ConfigError";
  } catch (const ConfigError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("640 cells over 4 ranks is 160 per rank; expected at least 200"), std::string::npos) << what;
    EXPECT_NE(what.find("run on at most 3 rank(s)"), std::string::npos) << what;
  }
}

TEST(PartitionOptions, BadValuesAreRefusedByName) {
  PartitionOptions o;
  o.column_aspect = 0.5;
  EXPECT_THROW(o.Validate(), ConfigError);
  o = {};
  o.imbalance = 0.0;
  EXPECT_THROW(o.Validate(), ConfigError);
  o = {};
  o.min_cells_per_rank = 0;
  EXPECT_THROW(o.Validate(), ConfigError);
}

}  // namespace
}  // namespace kelvin::cfd
