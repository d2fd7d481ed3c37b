// Unit tests of the 2D face mesh of a planar patch in z = 0 (PatchSurface):
// its edges, normals and rim, the exact least-squares gradient of a linear
// field, the geometry after a rigid in-plane motion, and a row of faces.
#include "cfd/freesurface/patch_surface.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <vector>

#include "tests/cfd/freesurface/free_surface_test_support.h"

namespace kelvin::cfd {
namespace {

using testing::Box;

TEST(PatchSurface, EdgesNormalsRimAndExactLinearGradient) {
  for (bool polyhedral : {false, true}) {
    const Mesh mesh = Box({6, 4, 2}, polyhedral);
    const int top = mesh.FindPatch("zmax");
    const PatchSurface s(mesh, top);
    EXPECT_EQ(s.size(), mesh.patches()[top].size);
    // Each face is closed: its outward edge normals sum to zero, and their
    // lengths add up to the perimeter.
    for (int i = 0; i < s.size(); ++i) {
      Vector3 sum = Vector3::Zero();
      for (int e : s.face_edges(i))
        sum += s.edges()[e].face == i ? s.edges()[e].normal : -s.edges()[e].normal;
      EXPECT_LT(sum.norm(), 1e-12) << "face " << i;
    }
    // Rim edges lie on the box sides and know the patch across them.
    int rim = 0;
    for (const auto& e : s.edges()) {
      if (e.neighbour >= 0) {
        EXPECT_GT(e.normal.dot(s.centres()[e.neighbour] - s.centres()[e.face]), 0.0);
        continue;
      }
      ++rim;
      ASSERT_GE(e.rim_patch, 0);
      const std::string& name = mesh.patches()[e.rim_patch].name;
      const Vector3 n = e.normal.normalized();
      if (name == "xmin") {
        EXPECT_NEAR(n.x(), -1.0, 1e-12);
      }
      if (name == "xmax") {
        EXPECT_NEAR(n.x(), 1.0, 1e-12);
      }
      if (name == "ymin") {
        EXPECT_NEAR(n.y(), -1.0, 1e-12);
      }
      if (name == "ymax") {
        EXPECT_NEAR(n.y(), 1.0, 1e-12);
      }
      EXPECT_TRUE(name != "zmin" && name != "zmax") << name;
    }
    EXPECT_GE(rim, 2 * (6 + 4));
    // Least squares is exact for a linear field.
    std::vector<double> f(s.size());
    for (int i = 0; i < s.size(); ++i)
      f[i] = 2.0 * s.centres()[i].x() - 3.0 * s.centres()[i].y() + 1.0;
    std::vector<Vector3> g;
    s.Gradient(f, g);
    for (int i = 0; i < s.size(); ++i) {
      ASSERT_TRUE(s.valid_gradient(i));
      EXPECT_NEAR(g[i].x(), 2.0, 1e-10);
      EXPECT_NEAR(g[i].y(), -3.0, 1e-10);
    }
  }
}

// The mesh placed rigidly (rotated about z and translated in the plane,
// Mesh::SetPlacement): updating the geometry of a surface built on it before
// the placement gives the surface built on a mesh made from the moved points.
TEST(PatchSurface, UpdateGeometryFollowsARigidInPlaneMotion) {
  const Mesh a = Box({5, 3, 2}, true);
  const Eigen::AngleAxisd rot(0.3, Vector3::UnitZ());
  std::vector<Vector3> points;
  for (const Vector3& x : a.points()) points.push_back(rot * x + Vector3(1.5, -0.7, 0.0));
  std::vector<std::vector<int>> faces;
  for (int f = 0; f < a.n_faces(); ++f) faces.emplace_back(a.face(f).begin(), a.face(f).end());
  const Mesh b(points, faces, std::vector<int>(a.owner().begin(), a.owner().end()),
               std::vector<int>(a.neighbour().begin(), a.neighbour().end()), a.patches());
  const int top = a.FindPatch("zmax");
  PatchSurface moved(a, top);
  Mesh placed = a;
  placed.SetPlacement(rot.toRotationMatrix(), Vector3(1.5, -0.7, 0.0));
  moved.UpdateGeometry(placed);
  const PatchSurface fresh(b, top);
  ASSERT_EQ(moved.edges().size(), fresh.edges().size());
  for (int i = 0; i < moved.size(); ++i)
    EXPECT_LT((moved.centres()[i] - fresh.centres()[i]).norm(), 1e-12);
  for (std::size_t e = 0; e < moved.edges().size(); ++e) {
    EXPECT_LT((moved.edges()[e].normal - fresh.edges()[e].normal).norm(), 1e-12);
    EXPECT_LT((moved.edges()[e].normal - rot * PatchSurface(a, top).edges()[e].normal).norm(),
              1e-12);
  }
  std::vector<double> f(moved.size());
  for (int i = 0; i < moved.size(); ++i)
    f[i] = moved.centres()[i].x() + 2.0 * moved.centres()[i].y();
  std::vector<Vector3> g;
  moved.Gradient(f, g);
  for (int i = 0; i < moved.size(); ++i) EXPECT_LT((g[i] - Vector3(1.0, 2.0, 0.0)).norm(), 1e-9);
}

TEST(PatchSurface, RowOfFacesGetsItsInLineGradient) {
  // The surface of a 2D mesh (one cell across) is a row of faces.
  const Mesh mesh = Box({8, 1, 2});
  const PatchSurface s(mesh, mesh.FindPatch("zmax"));
  std::vector<double> f(s.size());
  for (int i = 0; i < s.size(); ++i) f[i] = 0.5 * s.centres()[i].x();
  std::vector<Vector3> g;
  s.Gradient(f, g);
  for (int i = 0; i < s.size(); ++i) {
    EXPECT_TRUE(s.valid_gradient(i));
    EXPECT_NEAR(g[i].x(), 0.5, 1e-12);
    EXPECT_NEAR(g[i].y(), 0.0, 1e-12);
  }
}

}  // namespace
}  // namespace kelvin::cfd
