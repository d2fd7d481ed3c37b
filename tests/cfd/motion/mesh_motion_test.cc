// Rigid mesh motion: placement from the body-fixed geometry, exact mesh
// fluxes (space conservation law to round-off) and free-stream preservation
// (acceptance 1 of issue 7): still water, and a uniform current, stay exactly
// as they are under a prescribed surge + sway + yaw motion of a hull-less box.
#include "cfd/motion/mesh_motion.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "cfd/bc/outlet_inlet.h"
#include "cfd/mesh/box_mesh.h"
#include "tests/cfd/cfd_test_support.h"

namespace kelvin::cfd {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

Mesh Box(bool polyhedral, double perturbation) {
  BoxMeshOptions o;
  o.min = Vector3(-1.0, -0.8, -0.5);
  o.max = Vector3(1.2, 0.9, 0.0);
  o.cells = {9, 8, 5};
  o.perturbation = perturbation;
  o.polyhedral = polyhedral;
  o.seed = 3;
  o.kinds = {PatchKind::kPatch, PatchKind::kPatch, PatchKind::kPatch,
             PatchKind::kPatch, PatchKind::kPatch, PatchKind::kPatch};
  Mesh mesh = MakeBoxMesh(o);
  mesh.RenumberCells();
  return mesh;
}

// Surge, sway and yaw at once: yaw with drift at a carriage speed.
MotionOptions SurgeSwayYaw() {
  MotionOptions o;
  o.kind = PrescribedMotion::kYawDrift;
  o.speed = 1.5;
  o.drift_angle = 12.0 * kDeg;
  o.yaw_amplitude = 20.0 * kDeg;
  o.period = 0.8;
  o.ramp_time = 0.2;
  o.centre = Vector3(0.3, 0.05, -0.1);
  return o;
}

TEST(MeshPlacement, FollowsThePoseFromTheBodyFixedGeometry) {
  Mesh mesh = Box(true, 0.2);
  const std::vector<Vector3> xi(mesh.cell_centres().begin(), mesh.cell_centres().end());
  const std::vector<Vector3> sf(mesh.face_areas().begin(), mesh.face_areas().end());
  const std::vector<double> vol(mesh.cell_volumes().begin(), mesh.cell_volumes().end());
  const double non_orth = mesh.Quality().max_non_orthogonality;
  const RigidMotion motion(SurgeSwayYaw());
  for (double t : {0.37, 1.91, 0.37}) {
    const Pose p = motion.At(t);
    const Eigen::Matrix3d R = p.Rotation();
    const Vector3 tr = p.Translation(motion.options().centre);
    mesh.SetPlacement(R, tr);
    for (int c = 0; c < mesh.n_cells(); ++c) {
      ASSERT_LT((mesh.cell_centres()[c] - (R * xi[c] + tr)).norm(), 1e-15);
      ASSERT_EQ(mesh.cell_volumes()[c], vol[c]);
    }
    for (int f = 0; f < mesh.n_faces(); ++f)
      ASSERT_LT((mesh.face_areas()[f] - R * sf[f]).norm(), 1e-16);
    EXPECT_NEAR(mesh.Quality().max_non_orthogonality, non_orth, 1e-9);
  }
  mesh.SetPlacement(Eigen::Matrix3d::Identity(), Vector3::Zero());
  for (int c = 0; c < mesh.n_cells(); ++c) ASSERT_EQ(mesh.cell_centres()[c], xi[c]);
}

TEST(MeshFlux, SatisfiesTheSpaceConservationLawToRoundOff) {
  for (bool polyhedral : {false, true}) {
    Mesh mesh = Box(polyhedral, 0.25);  // non-planar faces
    const RigidMeshMotion motion(mesh, RigidMotion(SurgeSwayYaw()));
    std::vector<double> flux;
    double worst = 0.0;
    for (double t : {0.05, 0.33, 0.61, 1.4}) {
      motion.Apply(t, flux);
      std::vector<double> sum(mesh.n_cells(), 0.0), abs_sum(mesh.n_cells(), 0.0);
      for (int f = 0; f < mesh.n_faces(); ++f) {
        sum[mesh.owner()[f]] += flux[f];
        abs_sum[mesh.owner()[f]] += std::abs(flux[f]);
        if (f < mesh.n_internal_faces()) {
          sum[mesh.neighbour()[f]] -= flux[f];
          abs_sum[mesh.neighbour()[f]] += std::abs(flux[f]);
        }
      }
      for (int c = 0; c < mesh.n_cells(); ++c)
        worst = std::max(worst, std::abs(sum[c]) / abs_sum[c]);
    }
    EXPECT_LT(worst, 1e-14) << (polyhedral ? "polyhedral" : "hexahedral");
  }
}

TEST(MeshFlux, IsTheRigidBodyVelocityThroughPlanarFaces) {
  Mesh mesh = Box(false, 0.0);
  const RigidMeshMotion motion(mesh, RigidMotion(SurgeSwayYaw()));
  std::vector<double> flux;
  const double t = 0.71;
  motion.Apply(t, flux);
  const MovingWall::Motion wall = motion.WallMotion(t);
  for (int f = 0; f < mesh.n_faces(); ++f) {
    const Vector3 ub =
        wall.velocity + wall.angular_velocity.cross(mesh.face_centres()[f] - wall.centre);
    ASSERT_NEAR(flux[f], ub.dot(mesh.face_areas()[f]), 1e-15) << "face " << f;
  }
}

// max |u - current| after `steps` steps of the moving box with far-field
// conditions decided by the relative flux.
double FreeStreamError(Mesh& mesh, const Vector3& current, int steps) {
  const RigidMeshMotion motion(mesh, RigidMotion(SurgeSwayYaw()));
  auto U = testing::MakeField<Vector3>(
      "U", mesh, [&](const Patch&) { return std::make_unique<InletOutlet<Vector3>>(current); });
  auto p = testing::MakeField<double>(
      "p", mesh, [](const Patch&) { return std::make_unique<OutletInlet<double>>(0.0); });
  for (Vector3& u : U->values()) u = current;
  SchemeOptions schemes;
  schemes.gradient.scheme = GradientScheme::kLeastSquares;
  schemes.time = TimeScheme::kBackward;
  schemes.skew_correction = true;
  PimpleOptions pimple;
  pimple.n_outer = 2;
  pimple.n_non_orthogonal = 1;
  PimpleSolver solver(mesh, PhysicsOptions{1e-3, {}}, schemes, pimple, std::move(U), std::move(p));
  motion.Attach(solver);
  double worst = 0.0;
  for (int i = 0; i < steps; ++i) {
    const StepSummary s = solver.Step(0.02);
    EXPECT_TRUE(s.finite);
    for (const Vector3& u : solver.U().values()) worst = std::max(worst, (u - current).norm());
  }
  // The mesh did move: surge 1.5 m/s for 2 s, yaw up to 32 degrees.
  EXPECT_GT(mesh.placement_translation().norm(), 1.0);
  return worst;
}

TEST(FreeStream, StillWaterStaysAtRestUnderSurgeSwayYaw) {
  for (const auto& [polyhedral, perturbation] :
       {std::pair{false, 0.0}, std::pair{false, 0.25}, std::pair{true, 0.2}}) {
    Mesh mesh = Box(polyhedral, perturbation);
    const double err = FreeStreamError(mesh, Vector3::Zero(), 100);
    std::printf("still water, polyhedral %d perturbation %.2f: max |u| = %.3g m/s\n", polyhedral,
                perturbation, err);
    EXPECT_LT(err, 1e-10) << "polyhedral " << polyhedral << " perturbation " << perturbation;
  }
}

TEST(FreeStream, UniformCurrentStaysUniformUnderSurgeSwayYaw) {
  for (const auto& [polyhedral, perturbation] :
       {std::pair{false, 0.0}, std::pair{false, 0.25}, std::pair{true, 0.2}}) {
    Mesh mesh = Box(polyhedral, perturbation);
    const double err = FreeStreamError(mesh, Vector3(0.4, -0.3, 0.0), 100);
    std::printf("uniform current, polyhedral %d perturbation %.2f: max |u - U_c| = %.3g m/s\n",
                polyhedral, perturbation, err);
    EXPECT_LT(err, 1e-10) << "polyhedral " << polyhedral << " perturbation " << perturbation;
  }
}

}  // namespace
}  // namespace kelvin::cfd
