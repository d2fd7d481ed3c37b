// Pressure at a curved slip wall (docs/formulation.md section 4.6).
//
// A zero normal gradient at a slip wall puts the wall cell's pressure on the
// wall. Where the wall is curved that is wrong at first order in the cell
// size: the flow that follows the wall turns, and the normal momentum balance
// at an impermeable wall (u . n = 0 along the wall, inviscid) asks for
//
//   dp/dn = u_t . (grad_s n) . u_t
//
// (kinematic pressure; n the outward normal of the fluid, grad_s n the
// surface gradient of that normal, u_t the tangential velocity): the pressure
// falls toward a convex wall by u_t^2 / R. This is the curvature-corrected
// symmetry condition of Dadone and Grossman (AIAA J. 32, 1994), carried to
// unstructured grids with a mesh-estimated curvature by Wang and Sun (AIAA
// 2002-0966), here for an incompressible, cell-centred scheme. With the zero
// gradient the wall cell feels about half the normal pressure gradient the
// turning flow needs, and the scheme loses total pressure along a curved body (the
// d'Alembert test, BENCHMARKS.md `dalembert`).
//
// The condition is Neumann with that gradient, explicit in the velocity:
//   p_b = p_P + g d,   snGrad(p)_b = g,   g = u_t . S . u_t,
// with d the normal distance from the cell centre to the face. u_t is the
// tangential part of the owner cell's velocity, reconstructed from the face
// fluxes of the cell (u_P = sum_f F_f (x_f - x_P) / V_P, exact for a uniform
// flow), so the condition needs nothing but the flux the solver hands every
// condition. S = grad_s n comes from cfd/bc/wall_curvature.h (zero at sharp
// edges: no finite curvature to correct with). |g| d is capped at half the
// tangential dynamic head u_t^2 / 2, past which the cell is too coarse for the wall's
// radius (kappa d > 1/2) and the Taylor step would overshoot; the first
// update that caps a face warns (the wall is under-resolved there).
//
// g is explicit in the velocity, and the wall cell's velocity answers a
// change of its wall pressure within a step: at large time steps the loop
// gains about dt |u_t| kappa per step (300 at the DTC's stem at Courant 25,
// where the run diverged in two steps). Each step therefore moves g from the
// last step's value g^n toward the new one g* by
//   beta = 1 / (1 + dt |u_t| kappa),   kappa = |g*| / |u_t|^2,
// which keeps the loop gain below 1 and leaves g = g* in a steady state;
// with a small step (time-accurate runs) beta is 1. g^n is checkpointed.
//
// The wall is impermeable: the solver's predicted flux on a face whose
// velocity condition fixes the flux carries this gradient, so the corrected
// flux stays the prescribed zero (PimpleSolver::FluxHbyA).
#pragma once

#include <Eigen/Dense>
#include <limits>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "cfd/bc/boundary_condition.h"
#include "cfd/freesurface/linearized_free_surface.h"

namespace kelvin::cfd {

class CurvedWallPressure : public BoundaryCondition<double> {
 public:
  // Fits the wall's curvature on patch `patch_index` of `mesh` as placed now,
  // kept in the body frame (the mesh moves rigidly). On MPI ranks `mesh` is
  // the rank's local mesh and `ranks` names the whole one: the fit is made on
  // the whole patch, so a face at a partition edge has every neighbour and
  // the answers do not depend on the partition.
  CurvedWallPressure(const Mesh& mesh, int patch_index, const FreeSurfaceOnRanks& ranks = {});
  void Update(const BcContext& ctx, std::span<const double> cell_values) override;
  std::string type() const override { return "curvedSlipWall"; }
  PatchRole role() const override { return PatchRole::kSymmetry; }

  // [time of g, time of g^n, g per face, g^n per face] for checkpoints, the
  // faces those of the whole patch on every MPI rank (collective there).
  std::vector<double> State() const override;
  void SetState(std::span<const double> state) override;
  // Faces of this mesh whose gradient the last update capped (kappa d > 1/2).
  int capped_faces() const { return capped_; }

 private:
  std::vector<Eigen::Matrix3d> body_shape_;  // S of each face in the body frame (S_E = R S R^T)
  std::shared_ptr<const DomainPart> part_;  // set on ranks only
  std::vector<int> whole_index_;            // on ranks: each face's index in the whole patch
  std::vector<int> owner_;                  // on ranks: each face's local owner cell
  int whole_size_ = 0;
  std::vector<double> g_, g_step_;  // g as last computed, and as it was at the end of the last step
  double time_ = std::numeric_limits<double>::quiet_NaN();       // ctx.time of g_
  double step_time_ = std::numeric_limits<double>::quiet_NaN();  // time of g_step_
  bool restored_ = false;  // g_ comes from a checkpoint: use it as it is at its own time
  int capped_ = 0;
  bool warned_ = false;
};

}  // namespace kelvin::cfd
