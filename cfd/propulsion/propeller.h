// Body-force propeller: an actuator disk loaded from the open-water curve
// at the effective advance ratio (docs/formulation.md 6.2).
//
// Effective inflow. The velocity the CFD gives at the disk, U_disk (the
// thrust-weighted axial velocity relative to the disk, ActuatorDisk::
// DiskVelocity), contains the disk's own induced velocity u_a. Open-water
// curves are tabulated against the inflow without it, U_A. Actuator-disk
// momentum theory (Rankine-Froude) for thrust T on area A: the far wake
// moves at U_A + 2 u_a, so T = rho A (U_A + u_a) 2 u_a; with
// C_Th = T / (0.5 rho A U_A^2) that is u_a = (1/2) U_A (sqrt(1 + C_Th) - 1).
// Written with U_disk = U_A + u_a it is linear in u_a:
//   T = 2 rho A U_disk u_a   =>   U_A = U_disk - T / (2 rho A U_disk),
// closed form (kDiskMomentum, A = pi D^2 / 4 times the share of the disk
// the mesh holds, against the thrust the mesh holds).
// For a disk that is not uniformly loaded the same balance holds annulus by
// annulus (kAnnularMomentum, the default): an annulus of loading
// L(r) = dT/dA has U_A + u_a(r) = (U_A + sqrt(U_A^2 + 2 L / rho)) / 2, and
// U_A is the root of
//   sum_c w_c (U_A + sqrt(U_A^2 + 2 L_c / rho)) / 2 = U_disk
// over the disk cells with the thrust weights w_c of DiskVelocity, which is
// increasing in U_A (solved by safeguarded Newton). For uniform loading
// (L = T / A) it reduces to the closed form above. With the Hough-Ordway
// loading the two differ: the thrust-weighted mean of u_a(r) ~ L(r) is
// T / (2 rho U_disk A_eff) with A_eff = (int L dA)^2 / int L^2 dA < A, so the
// closed form under-corrects.
//
// Coupling: each Update (after an outer iteration) takes U_disk from the
// present flow and the thrust of the previous Update for the correction,
// gives J = U_A / (n D), K_T(J), K_Q(J), T = rho n^2 D^4 K_T and
// Q = rho n^2 D^5 K_Q, and writes the body force of the new (relaxed) T, Q:
// a fixed point over the outer iterations and time steps.
#pragma once

#include <Eigen/Core>

#include <functional>
#include <string>
#include <vector>

#include "cfd/propulsion/actuator_disk.h"
#include "cfd/solver/pimple_solver.h"
#include "simulator/mmg/open_water.h"

namespace kelvin::cfd {

struct PropellerOptions {
  enum class InflowCorrection { kAnnularMomentum, kDiskMomentum };
  InflowCorrection correction = InflowCorrection::kAnnularMomentum;
  // T <- T_prev + relaxation (T_new - T_prev), and Q likewise, from the
  // second Update on (the first takes T_new). 1 = none. The open-water runs
  // of actuator_disk_test use 0.5 and settle (3 CPU s on the coarse grid); 1 has not
  // been tried since a root-finder fix that made the coupling settle.
  double thrust_relaxation = 1.0;
  // Apply the torque (swirl). Off only on a domain cut by symmetry planes
  // through the axis, which cannot carry swirl; K_Q and Q are still reported.
  bool apply_torque = true;
  // The share of the propeller the mesh holds: 1, or 1/2 and 1/4 for a disk
  // cut by one or two symmetry planes through its axis. The mesh carries
  // mesh_share T and mesh_share Q; T, Q, K_T, K_Q are the whole propeller's.
  // Checked against the disk's sampled share (ActuatorDisk::mesh_share)
  // within 5%.
  double mesh_share = 1.0;
  void Validate() const;  // throws ConfigError naming the disk's name
  std::string name = "propeller";
};

// One Update: what a history row needs.
struct PropellerState {
  double n = 0.0;       // rate of revolution (1/s)
  double U_disk = 0.0;  // thrust-weighted axial velocity through the disk (m/s)
  double U_A = 0.0;     // effective inflow, induced velocity removed (m/s)
  double J = 0.0;       // U_A / (n D)
  double K_T = 0.0;
  double K_Q = 0.0;
  double T = 0.0;       // thrust on the propeller, along the axis (N)
  double Q = 0.0;       // torque on the water, about sense x axis (N m)
  bool clamped = false; // start-up only: J was outside the table and was held at its end
};

class Propeller {
 public:
  using BodyVelocity = std::function<Vector3(int cell)>;
  Propeller(ActuatorDisk disk, sim::OpenWaterCurve curve, PropellerOptions options = {});

  // Open-water mode at n > 0 (1/s). Adds the body force to cell_source (an
  // empty vector is sized first) for the placement rotation R. Throws
  // ConfigError naming <name>.open_water, the J and the table's range when
  // J leaves the table (or when the flow through the disk is reversed).
  // With start_up, a J outside the table is held at the table's end instead
  // (J_min when the flow through the disk is reversed, or when the quasi-
  // steady inflow correction removes more than the flow through the disk:
  // the flow has not yet taken up the disk's induced velocity, so the
  // propeller works as at bollard pull), and the state says clamped.
  PropellerState Update(const PimpleSolver& solver, const BodyVelocity& body_velocity, const Eigen::Matrix3d& R,
                        double n, double rho, std::vector<Vector3>& cell_source, bool start_up = false);
  // Fixed load: the prescribed T and Q (J, K_T, K_Q are reported as 0; n
  // is kept), with the same U_disk and U_A diagnostics.
  PropellerState UpdateFixedLoad(const PimpleSolver& solver, const BodyVelocity& body_velocity,
                                 const Eigen::Matrix3d& R, double thrust, double torque, double rho,
                                 std::vector<Vector3>& cell_source);
  // U_A from U_disk for the thrust T of the whole propeller (see above).
  double EffectiveInflow(double U_disk, double thrust, double rho) const;

  // What a checkpoint needs for a bit-for-bit restart: the last load and
  // rate (the relaxation and the correction start from them).
  struct State {
    double thrust = 0.0;
    double torque = 0.0;
    double n = 0.0;
  };
  State GetState() const { return state_; }
  // Adds the body force of the state's load (a restart restores the cell
  // source the solver had).
  void ApplyState(double rho, const Eigen::Matrix3d& R, std::vector<Vector3>& cell_source) const {
    Apply(state_.thrust, state_.torque, rho, R, cell_source);
  }
  void SetState(const State& state) { state_ = state; }

  const ActuatorDisk& disk() const { return disk_; }
  const sim::OpenWaterCurve& curve() const { return curve_; }
  const PropellerOptions& options() const { return options_; }

 private:
  double AnnularInflow(double U_disk, double thrust, double rho) const;
  void Apply(double thrust, double torque, double rho, const Eigen::Matrix3d& R,
             std::vector<Vector3>& cell_source) const;

  ActuatorDisk disk_;
  sim::OpenWaterCurve curve_;
  PropellerOptions options_;
  State state_;
};

}  // namespace kelvin::cfd
