// The linearized free surface on a rigidly moving mesh (issue 7: "the
// free-surface kinematic condition uses the mesh velocity"). A block
// submerged under the free surface is towed through still water on the
// moving mesh (earth frame; the kinematic condition advects eta with the
// motion's point velocity) and, separately, held fixed in a uniform inflow
// with the equal and opposite constant mesh velocity in the free-surface
// condition (the ship-fixed formulation the resistance cases use). The two
// are the same flow seen from two frames, so after the same number of steps
// the drag and the wave elevation on the free-surface patch must agree
// (Galilean consistency, issue 7 acceptance 2, here with waves).
//
// The block (0.5 m x 0.25 m x 0.125 m, top 0.125 m below z = 0) moves at
// U = 1.25 m/s: transverse wavelength 2 pi U^2 / g = 1.0 m, depth Froude
// number U / sqrt(g d) = 1.13, so the surface carries a real wave pattern
// (checked below against the pattern's size).
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "cfd/freesurface/linearized_free_surface.h"
#include "cfd/run/run_case.h"
#include "cfd/motion/ship_forces.h"
#include "data/schema/config.h"

namespace kelvin::cfd {
namespace {

constexpr double kSpeed = 1.25;
constexpr double kRho = 1000.0;
constexpr double kNu = 0.01;

// Box from x = -3 to 2 (the block near x = 0), y in [-1.5, 1.5], depth 1 m;
// cells of 0.125 m in x and y and 0.0625 m in z.
const char* kMesh = R"(mesh:
  box: {min: [-3, -1.5, -1], max: [2, 1.5, 0], cells: [40, 24, 16],
        obstacle: {min: [22, 11, 12], max: [26, 13, 14]}}
physics: {nu: 0.01, rho: 1000}
schemes: {time: euler, convection: linear_upwind, gradient: least_squares}
solution:
  n_outer: 2
  n_correctors: 2
  momentum: {solver: bicgstab, relative_tolerance: 1.0e-10, absolute_tolerance: 1.0e-14}
  pressure: {solver: pcg_amg, relative_tolerance: 1.0e-9, final_relative_tolerance: 1.0e-10}
time: {dt: 0.05, end: 2.5}
output: {directory: out, vtu_interval: -1, checkpoint_interval: -1, forces: [obstacle]}
)";

struct Result {
  double X = 0.0;             // force on the block along x (N)
  std::vector<double> eta;    // on the free-surface patch faces
};

Result RunText(const std::string& yaml, const Vector3& initial_velocity) {
  const auto root = data::ConfigNode::LoadString(yaml, "free_surface_motion_test.yaml");
  Case c = LoadCase(root, ".");
  for (Vector3& u : c.solver->U().values()) u = initial_velocity;
  const int steps = static_cast<int>(std::lround(c.settings.time.end / c.settings.time.dt));
  for (int i = 0; i < steps; ++i) {
    const StepSummary s = c.solver->Step(c.settings.time.dt);
    EXPECT_TRUE(s.finite);
    if (!s.finite) break;
  }
  const Mesh& mesh = *c.mesh;
  const int top = mesh.FindPatch("zmax");
  const auto* lfs = dynamic_cast<const LinearizedFreeSurface*>(&c.solver->p().bc(top));
  EXPECT_NE(lfs, nullptr);
  const Pose pose = c.motion ? c.motion->body().At(c.solver->time()) : Pose{};
  const Vector3 centre = c.motion ? c.motion->body().centre() : Vector3::Zero();
  Result r;
  const std::vector<int> body = {mesh.FindPatch("obstacle")};
  r.X = ComputeHullLoads(*c.solver, body, kRho, kNu, pose, centre).Total().X;
  if (lfs) r.eta = lfs->eta();
  return r;
}

TEST(FreeSurfaceMotion, TowedBlockUnderTheSurfaceEqualsTheShipFixedRun) {
  // Earth frame: the grid moves along +x at U from rest in still water.
  const Result moving = RunText(std::string(kMesh) + R"(motion: {kind: static_drift, speed: 1.25, ramp_time: 0}
boundary:
  xmin: {U: {type: farField, inflow: [0, 0, 0], band: 0.3}, p: {type: farField, value: 0, band: 0.3}}
  xmax: {U: {type: farField, inflow: [0, 0, 0], band: 0.3}, p: {type: farField, value: 0, band: 0.3}}
  ymin: {U: {type: slip}, p: {type: zeroGradient}}
  ymax: {U: {type: slip}, p: {type: zeroGradient}}
  zmin: {U: {type: slip}, p: {type: zeroGradient}}
  obstacle: {U: {type: movingWallVelocity}, p: {type: zeroGradient}}
  zmax:
    U: {type: zeroGradient}
    p: {type: linearizedFreeSurface, advection: linear_upwind}
)",
                            Vector3::Zero());
  // Ship frame: the water comes at -U from xmax; the free surface moves
  // relative to it at +U.
  const Result fixed = RunText(std::string(kMesh) + R"(boundary:
  xmax: {U: {type: fixedValue, value: [-1.25, 0, 0]}, p: {type: zeroGradient}}
  xmin: {U: {type: zeroGradient}, p: {type: fixedValue, value: 0}}
  ymin: {U: {type: slip}, p: {type: zeroGradient}}
  ymax: {U: {type: slip}, p: {type: zeroGradient}}
  zmin: {U: {type: slip}, p: {type: zeroGradient}}
  obstacle: {U: {type: noSlip}, p: {type: zeroGradient}}
  zmax:
    U: {type: zeroGradient}
    p: {type: linearizedFreeSurface, advection: linear_upwind, mesh_velocity: [1.25, 0, 0]}
)",
                           Vector3(-kSpeed, 0, 0));
  ASSERT_EQ(moving.eta.size(), fixed.eta.size());
  ASSERT_FALSE(fixed.eta.empty());
  double diff = 0.0, norm = 0.0, peak = 0.0;
  for (std::size_t i = 0; i < fixed.eta.size(); ++i) {
    diff += (moving.eta[i] - fixed.eta[i]) * (moving.eta[i] - fixed.eta[i]);
    norm += fixed.eta[i] * fixed.eta[i];
    peak = std::max(peak, std::abs(fixed.eta[i]));
  }
  const double eta_rel = std::sqrt(diff / norm);
  const double x_rel = std::abs(moving.X - fixed.X) / std::abs(fixed.X);
  std::printf("drag: moving %.8g N, fixed %.8g N (relative difference %.3g); eta: peak %.3g m, "
              "relative L2 difference %.3g\n",
              moving.X, fixed.X, x_rel, peak, eta_rel);
  // The body makes waves: a peak elevation of at least 0.1 mm (about 5% of
  // the dynamic head U^2 / 2g = 0.08 m scaled by (block height / depth)^2).
  EXPECT_GT(peak, 1e-4);
  EXPECT_LT(fixed.X, 0.0);  // resistance points aft
  // The two frames differ only in round-off of the relative flux and in how
  // the (different) boundary conditions at the open ends act: within 0.2 %
  // in drag as for the double-body case, and 1 % in eta.
  EXPECT_LT(x_rel, 0.002);
  EXPECT_LT(eta_rel, 0.01);
}

}  // namespace
}  // namespace kelvin::cfd
