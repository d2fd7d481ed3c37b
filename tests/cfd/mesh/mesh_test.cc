#include "cfd/mesh/mesh.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "cfd/mesh/box_mesh.h"
#include "cfd/mesh/dual_mesh.h"
#include "data/schema/errors.h"

namespace kelvin::cfd {
namespace {

// Sum of the outward area vectors of every cell: zero for closed cells.
double MaxCellOpenness(const Mesh& mesh) {
  std::vector<Vector3> sum(mesh.n_cells(), Vector3::Zero());
  for (int f = 0; f < mesh.n_faces(); ++f) {
    sum[mesh.owner()[f]] += mesh.face_areas()[f];
    if (f < mesh.n_internal_faces()) sum[mesh.neighbour()[f]] -= mesh.face_areas()[f];
  }
  double worst = 0.0;
  for (int c = 0; c < mesh.n_cells(); ++c) {
    worst = std::max(worst, sum[c].norm() / std::pow(mesh.cell_volumes()[c], 2.0 / 3.0));
  }
  return worst;
}

TEST(BoxMesh, UniformGeometry) {
  BoxMeshOptions opt;
  opt.max = Vector3(2.0, 1.0, 0.5);
  opt.cells = {8, 4, 2};
  const Mesh mesh = MakeBoxMesh(opt);
  EXPECT_EQ(mesh.n_cells(), 64);
  EXPECT_EQ(mesh.n_internal_faces(), 7 * 4 * 2 + 8 * 3 * 2 + 8 * 4 * 1);
  EXPECT_NEAR(mesh.total_volume(), 1.0, 1e-14);
  for (double v : mesh.cell_volumes()) EXPECT_NEAR(v, 1.0 / 64, 1e-15);
  for (int f = 0; f < mesh.n_internal_faces(); ++f) EXPECT_NEAR(mesh.weights()[f], 0.5, 1e-14);
  const MeshQuality q = mesh.Quality();
  EXPECT_NEAR(q.max_non_orthogonality, 0.0, 1e-6);
  EXPECT_NEAR(q.max_skewness, 0.0, 1e-12);
  EXPECT_LT(q.boundary_openness, 1e-15);
  EXPECT_LT(MaxCellOpenness(mesh), 1e-14);
  // Patch areas.
  const Patch& xmax = mesh.patches()[mesh.FindPatch("xmax")];
  double area = 0.0;
  for (int f = xmax.start; f < xmax.start + xmax.size; ++f) {
    area += mesh.face_areas()[f].x();
    EXPECT_GT(mesh.face_areas()[f].x(), 0.0);  // outward
  }
  EXPECT_NEAR(area, 0.5, 1e-14);
}

TEST(BoxMesh, GradingGivesTheRequestedSizeRatio) {
  BoxMeshOptions opt;
  opt.cells = {10, 1, 1};
  opt.grading = {4.0, 1.0, 1.0};
  const Mesh mesh = MakeBoxMesh(opt);
  const auto v = mesh.cell_volumes();
  const double first = *std::min_element(v.begin(), v.end());
  const double last = *std::max_element(v.begin(), v.end());
  EXPECT_NEAR(last / first, 4.0, 1e-10);
  EXPECT_NEAR(mesh.total_volume(), 1.0, 1e-14);
}

TEST(BoxMesh, PerturbedMeshIsSkewedButClosed) {
  BoxMeshOptions opt;
  opt.cells = {6, 6, 6};
  opt.perturbation = 0.2;
  const Mesh mesh = MakeBoxMesh(opt);
  EXPECT_NEAR(mesh.total_volume(), 1.0, 1e-13);
  const MeshQuality q = mesh.Quality();
  EXPECT_GT(q.max_non_orthogonality, 5.0);
  EXPECT_GT(q.max_skewness, 0.01);
  EXPECT_LT(MaxCellOpenness(mesh), 1e-13);
}

TEST(BoxMesh, PolyhedralVariantHasSplitFaceCells) {
  BoxMeshOptions opt;
  opt.cells = {4, 4, 4};
  opt.polyhedral = true;
  const Mesh mesh = MakeBoxMesh(opt);
  EXPECT_EQ(mesh.n_cells(), 32 * 8 + 32);
  int max_faces = 0;
  for (int c = 0; c < mesh.n_cells(); ++c) {
    max_faces = std::max(max_faces, mesh.cell_face_offsets()[c + 1] - mesh.cell_face_offsets()[c]);
  }
  EXPECT_EQ(max_faces, 24);
  EXPECT_NEAR(mesh.total_volume(), 1.0, 1e-13);
  EXPECT_LT(MaxCellOpenness(mesh), 1e-13);
  EXPECT_GT(mesh.Quality().max_skewness, 0.1);
}

TEST(DualMesh, PolygonalPrismsTileTheBox) {
  DualMeshOptions opt;
  opt.divisions = {6, 5, 3};
  opt.max = Vector3(2.0, 1.0, 0.6);
  opt.perturbation = 0.2;
  const Mesh mesh = MakeDualMesh(opt);
  EXPECT_EQ(mesh.n_cells(), 7 * 6 * 3);
  EXPECT_NEAR(mesh.total_volume(), 1.2, 1e-13);
  EXPECT_LT(MaxCellOpenness(mesh), 1e-13);
  EXPECT_LT(mesh.Quality().boundary_openness, 1e-15);
  int max_faces = 0;
  for (int c = 0; c < mesh.n_cells(); ++c) {
    max_faces = std::max(max_faces, mesh.cell_face_offsets()[c + 1] - mesh.cell_face_offsets()[c]);
  }
  EXPECT_GE(max_faces, 10);  // 8 kinked sides + top + bottom around an 8-triangle vertex
  // Patch areas: xmax is 1 x 0.6, zmax is 2 x 1.
  auto patch_area = [&](const char* name) {
    const Patch& p = mesh.patches()[mesh.FindPatch(name)];
    Vector3 a = Vector3::Zero();
    for (int f = p.start; f < p.start + p.size; ++f) a += mesh.face_areas()[f];
    return a;
  };
  EXPECT_TRUE(patch_area("xmax").isApprox(Vector3(0.6, 0, 0)));
  EXPECT_TRUE(patch_area("zmin").isApprox(Vector3(0, 0, -2.0)));
}

TEST(Mesh, RenumberingKeepsGeometryAndDoesNotWidenBandwidth) {
  BoxMeshOptions opt;
  opt.cells = {5, 7, 3};
  opt.polyhedral = true;
  Mesh mesh = MakeBoxMesh(opt);
  std::vector<double> volumes(mesh.cell_volumes().begin(), mesh.cell_volumes().end());
  const auto [before, after] = mesh.RenumberCells();
  EXPECT_LE(after, before);
  EXPECT_EQ(after, mesh.Bandwidth());
  std::vector<double> renumbered(mesh.cell_volumes().begin(), mesh.cell_volumes().end());
  std::sort(volumes.begin(), volumes.end());
  std::sort(renumbered.begin(), renumbered.end());
  for (std::size_t i = 0; i < volumes.size(); ++i) EXPECT_NEAR(volumes[i], renumbered[i], 1e-15);
  for (int f = 0; f < mesh.n_internal_faces(); ++f) {
    ASSERT_LT(mesh.owner()[f], mesh.neighbour()[f]);
    // Normal still points from owner to neighbour.
    EXPECT_GT(mesh.face_areas()[f].dot(mesh.deltas()[f]), 0.0);
    if (f > 0) {
      ASSERT_TRUE(mesh.owner()[f - 1] < mesh.owner()[f] ||
                  (mesh.owner()[f - 1] == mesh.owner()[f] && mesh.neighbour()[f - 1] < mesh.neighbour()[f]));
    }
  }
  EXPECT_LT(MaxCellOpenness(mesh), 1e-13);
}

TEST(BoxMesh, BadOptionsAreConfigErrors) {
  BoxMeshOptions opt;
  opt.cells = {0, 1, 1};
  EXPECT_THROW(MakeBoxMesh(opt), ConfigError);
  opt.cells = {1, 1, 1};
  opt.max = Vector3(0, 1, 1);
  EXPECT_THROW(MakeBoxMesh(opt), ConfigError);
}

}  // namespace
}  // namespace kelvin::cfd
