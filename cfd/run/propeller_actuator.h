// The body-force propeller of a free-running run (cfd/propulsion/propeller.h)
// as an actuator of the free-running coupler (cfd/run/free_running.h), with
// its rate: fixed (ramped from 0), or controlled to the self-propulsion point.
//
//   propeller:
//     thickness: 0.25            # disk thickness / D
//     distribution: hough_ordway # hough_ordway | uniform
//     correction: annular        # annular | disk (momentum theory of the induced velocity)
//     thrust_relaxation: 0.7     # T <- T + 0.7 (T_new - T) per outer iteration
//     swirl: true                # apply the torque (false: thrust only, a symmetric wake)
//     rate: {n: 10.0, ramp_time: 1.0}            # 1/s
//     self_propulsion:           # instead of a fixed rate: n is controlled
//       start_time: 2.0          # s
//       response_time: 1.0       # s, integral controller time constant
//       average_time: 2.0        # s, the reported point averages the last 2 s
//       towed_resistance: 31.8   # N, R_T of the towed hull without propeller (thrust deduction)
//
// The disk sits where the ship file puts it (propeller.D_p, x_P_prime,
// y_P, z_P, hub_ratio, blades) and is loaded from its open-water curve
// (sim::CfdOpenWater): the same ship file as motion.ship.
//
// Self-propulsion (surge held, the CFD form of a towed self-propulsion
// test): the carriage force X_c on the held surge is -(X_hull + T + F_D) at
// constant speed, with F_D = motion.external_load.X (0 at the model point,
// the skin-friction correction at the ship point). Each step
//   n <- n + (dt / tau) X_c / (dT/dn),   dT/dn = 2 T / n  (T ~ n^2 at fixed J),
// so n rises while the carriage still pushes. Reported over the last
// average_time (however the run ends: time.end or the steady criterion):
// n, T, Q, K_T, K_Q, J (the disk's effective advance ratio),
// the thrust deduction t = 1 - (R_T - F_D) / T and the Taylor wake fraction
// from thrust identity w_T = 1 - J_T n D / U, J_T = K_T^-1(T / (rho n^2 D^4)).
#pragma once

#include <deque>
#include <memory>
#include <optional>
#include <string>

#include "cfd/propulsion/propeller.h"
#include "cfd/run/free_running.h"

namespace kelvin::cfd {

struct SelfPropulsionOptions {
  double start_time = 0.0;
  double response_time = 1.0;
  double average_time = 2.0;
  double towed_resistance = 0.0;  // N; 0: t is not reported
};

struct PropellerRunOptions {
  double n = 0.0;          // 1/s: the fixed rate, or the controller's start
  double ramp_time = 0.0;  // s
  std::optional<SelfPropulsionOptions> self_propulsion;
  double speed = 0.0;      // m/s, the towed speed (wake fraction)
  double external_x = 0.0;  // N, F_D
};

// Reads the case's `propeller:` section for the free body of `c`; null
// without one.
std::unique_ptr<BodyActuator> LoadPropellerActuator(const Case& c, const data::ConfigNode& root);

class PropellerActuator final : public BodyActuator {
 public:
  PropellerActuator(Propeller propeller, PropellerRunOptions options, double rho, double y_P);

  void Update(const PimpleSolver& solver, const FreeBody& body, int outer, std::vector<Vector3>& cell_source,
              PlanarLoad& load) override;
  void BeforeStep(double t_new, double dt) override;
  void Start(History& history) override;
  void AfterStep(const FreeBody& body, History& history) override;
  void AddCheckpointScalars(CheckpointScalars& scalars) const override;
  void RestoreScalars(const CheckpointScalars& scalars) override;
  void ApplyRestored(const PimpleSolver& solver, std::vector<Vector3>& cell_source) const override;
  void WriteHistory(data::H5Writer& writer) const override;
  std::vector<std::string> Finish() override;

  const PropellerState& last() const { return last_; }
  const Propeller& propeller() const { return propeller_; }
  const PropellerRunOptions& options() const { return options_; }

 private:
  // One step of the averaging window (the last average_time of the run).
  struct Sample {
    double dt = 0, n = 0, T = 0, Q = 0, J = 0, X_c = 0;
  };
  static constexpr int kSampleFields = 6;
  struct Point {
    double n, T, Q, K_T, K_Q, J, X_c, t_deduction, w_T, J_T;
  };
  Point SelfPropulsionPoint() const;

  Propeller propeller_;
  PropellerRunOptions options_;
  double rho_, y_P_;
  double n_ = 0.0;      // the rate of the step in progress
  double n_set_ = 0.0;  // the controller's rate
  double t_ = 0.0, dt_ = 0.0;
  double last_constraint_x_ = 0.0;
  bool warned_ = false;
  bool applied_ = false;  // the last Update applied a body force
  PropellerState last_;
  std::deque<Sample> window_;
  double window_length_ = 0.0;
  History::Column state_col_ = -1, effective_col_ = -1;
};

}  // namespace kelvin::cfd
