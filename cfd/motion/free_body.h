// 3DoF rigid-body motion of a free-running hull (docs/formulation.md
// section 12): surge, sway and yaw in ship axes (x forward, y starboard, z
// down) about the reference point (midship), with G at x_G forward of it:
//
//   m (du/dt - v r - x_G r^2)                = X
//   m (dv/dt + u r + x_G dr/dt)              = Y
//   (I_zG + m x_G^2) dr/dt + m x_G (dv/dt + u r) = N
//
// X, Y, N are everything that acts on the body: the water on the hull
// patches (pressure and viscous, with the free surface), the propeller's
// thrust (and its yaw moment for a shaft off the centreline; the torque is a
// roll moment, outside these three degrees of freedom), external loads (a
// tow force, the skin-friction correction F_D). The added masses of the water are in the water's force,
// not in these equations; they only enter the coupling below.
//
// Time discretization: the solver's scheme, Euler or BDF2 (constant
// coefficients, as cfd/fv AddDdt), for the velocities and the pose (the
// explicit scheme below steps the velocities by forward Euler):
//   D(q) = (a q_{n+1} - b q_n + c q_{n-1}) / dt,  (a, b, c) = (1, 1, 0) or (3/2, 2, 1/2).
//
// Coupling inside the PIMPLE outer loop (kStabilised): the residual of the
// body equations with the water's force F^k after outer iteration k,
//   R^k = F^k + C(nu^k) - M D(nu^k),   C = (m (v r + x_G r^2), -m u r, -m x_G u r),
// is removed by a quasi-Newton step whose Jacobian is the body's inertia plus
// an estimate M_a of the water's added masses:
//   nu^{k+1} = nu^k + omega (a / dt)^{-1} (M + M_a)^{-1} R^k.
// The water's force responds to an acceleration like -M_a,true a / dt, so the
// iteration contracts with the factor |M_a - M_a,true| / (M + M_a) (without
// relaxation; < 1 for any M_a > (M_a,true - M) / 2); with M_a = 0 it is the
// plain fixed point,
// whose factor M_a,true / M exceeds 1 for a hull lighter than its added mass
// (sway and yaw of fine hulls). kExplicit is the naive staggered scheme:
// nu_{n+1} from the force of the previous step, no correction; it amplifies
// by about M_a,true / M per step and fails on the same hulls
// (tests/cfd/motion/free_body_test.cc and free_running_test.cc show both).
//
// The mesh is placed once per step at the predicted pose (the outer
// iterations update the mesh velocity, the wall velocity and the free
// surface's advection, not the placement): a rigid mesh obeys the space
// conservation law for any rigid velocity, and the placement lags the
// converged pose by O(dt^2 dnu/dt), corrected at the next step.
#pragma once

#include <array>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "cfd/motion/body_kinematics.h"
#include "cfd/motion/ship_forces.h"

namespace kelvin::cfd {

enum class BodyCoupling { kStabilised, kExplicit };

struct FreeBodyOptions {
  double mass = 0.0;  // kg
  double x_G = 0.0;   // m, G forward of the reference point
  double I_zG = 0.0;  // kg m^2, yaw inertia about G
  // Which degrees of freedom move under the loads: surge, sway, yaw. A held
  // one keeps its initial velocity (times the start-up factor).
  std::array<bool, 3> free = {true, true, true};
  // Initial velocities in ship axes (u m/s, v m/s, r rad/s), reached through
  // the start-up factor of cfd/motion/rigid_motion.h over ramp_time; until
  // release_time every degree of freedom is held (towed), then the free ones
  // are released.
  std::array<double, 3> initial = {0.0, 0.0, 0.0};
  double ramp_time = 0.0;     // s
  double release_time = 0.0;  // s, >= ramp_time
  double initial_heading = 0.0;  // rad
  // Constant external load in ship axes (a tow force, F_D), N and N m.
  PlanarLoad external;
  BodyCoupling coupling = BodyCoupling::kStabilised;
  // Added-mass estimate of the stabilised coupling: m_x, m_y (kg), J_z (kg m^2).
  std::array<double, 3> added_mass = {0.0, 0.0, 0.0};
  double relaxation = 1.0;  // omega in (0, 1]
  bool bdf2 = true;         // the solver's backward scheme (false: Euler)
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();  // reference point, grid axes (m)
  // A body speed beyond this many times the initial speed scale stops the run.
  double divergence_factor = 10.0;
  // Throws ConfigError naming `where`.key, the value and what is expected.
  void Validate(const std::string& where) const;
};

// The body state a checkpoint keeps (doubles, so a restart is bit for bit).
struct FreeBodyState {
  double time = 0.0;
  int steps = 0;
  std::array<double, 3> nu{}, nu_old{};        // (u, v, r) at t_n and t_{n-1}
  std::array<double, 3> pos{}, pos_old{};      // (x0, y0, psi) at t_n and t_{n-1}
  // Where the mesh is placed at t_n: the step's prediction, which lags pos by
  // O(dt^2); a restart places the mesh there again (bit for bit).
  std::array<double, 3> placed{};
  PlanarLoad load;                             // the last load on the body (explicit scheme)
  std::vector<double> Pack() const;
  static FreeBodyState Unpack(const std::vector<double>& packed);
};

class FreeBody : public BodyKinematics {
 public:
  explicit FreeBody(FreeBodyOptions options);  // validates

  // BodyKinematics: the placed mesh's position and heading with the
  // velocities of the iterate of the step in progress (what the flow sees).
  Pose At(double t) const override;
  const Eigen::Vector3d& centre() const override { return options_.centre; }
  double nominal_speed() const override;

  // Starts the step to t_new: accepts the present iterate as t_n and
  // predicts t_{n+1} (extrapolated, or explicit from the last load).
  void BeginStep(double t_new, double dt);
  // One coupling correction with the load of the latest outer iteration;
  // returns the velocity change |d nu| (u, v in m/s, r times half the ship
  // length `length`) over the speed scale (the initial speed, or 1 m/s when
  // the body starts from rest; the same scale as Diverged).
  double Correct(const PlanarLoad& load, double length);
  // The pose the mesh is placed at during this step (the prediction).
  const Pose& placed() const { return placed_; }
  // The integrated pose of the iterate (the trajectory), and its velocities.
  Pose Trajectory() const { return MakePose(pos_); }
  const std::array<double, 3>& velocities() const { return nu_; }
  double time() const { return t_; }
  // The force held degrees of freedom need (the carriage's), ship axes.
  const PlanarLoad& constraint_load() const { return constraint_; }
  bool released() const;
  // True if the state is not finite or a speed exceeds divergence_factor
  // times the speed scale; `why` then says which.
  bool Diverged(std::string* why) const;

  FreeBodyState state() const;
  void SetState(const FreeBodyState& s);
  const FreeBodyOptions& options() const { return options_; }

 private:
  struct Coefficients {
    double a, b, c;
  };
  Coefficients Bdf() const;
  // Held velocity of degree of freedom i at time t (start-up law) and its rate.
  double HeldVelocity(int i, double t) const;
  double HeldAcceleration(int i, double t) const;
  bool IsFree(int i) const;
  // D(nu) of the iterate (free), the start-up law's rate (held).
  std::array<double, 3> Rates() const;
  // Solves A x = rhs on the free degrees of freedom (0 on the held ones).
  std::array<double, 3> SolveFree(const Eigen::Matrix3d& A, const std::array<double, 3>& rhs) const;
  // The pose at positions `pos` with the iterate's velocities, and the
  // update of the iterate's positions from its velocities.
  Pose MakePose(const std::array<double, 3>& pos) const;
  void IntegratePose();
  // The body's mass matrix M in (u, v, r) about the reference point.
  Eigen::Matrix3d MassMatrix() const;
  // M D(nu) - C(nu): what the load must equal, per degree of freedom.
  std::array<double, 3> Inertia(const std::array<double, 3>& nu, const std::array<double, 3>& rate) const;

  FreeBodyOptions options_;
  FreeBodyState accepted_;       // t_n (and t_{n-1})
  bool in_step_ = false;         // the iterate is a step in progress (t_{n+1})
  std::array<double, 3> nu_{};   // iterate (u, v, r)
  std::array<double, 3> pos_{};  // iterate (x0, y0, psi)
  double t_ = 0.0, dt_ = 0.0;
  PlanarLoad last_load_;
  Pose pose_, placed_;
  PlanarLoad constraint_;
};

}  // namespace kelvin::cfd
