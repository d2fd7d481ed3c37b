// The body-force rudder of a free-running run (cfd/propulsion/rudder.h) as
// an actuator of the free-running coupler (cfd/run/free_running.h), with
// its steering gear: the blade turns towards the order at the ship's rate
// limit (actuators.rudder_rate_deg_s), clamped to rudder_max_deg.
//
//   rudder:
//     angle_deg: 0.0            # the order from the start (a maneuver pilot changes it)
//     thickness: 0.2            # blade box thickness / chord
//     sample_distance: 1.0      # chords from the leading edge to the inflow sample
//     sample_length: 0.25       # chords
//     stall_angle_deg: 35
//     lift_slope: 0             # f_alpha (1/rad); 0: Fujii's from H_R^2 / A_R
//     waterline_image: true     # the blade's image in z = 0 for its induced velocity
//     force_relaxation: 0.7
//
// The blade is the ship file's rudder (A_R, H_R, x_R_prime, z_top): its
// mid-chord on the centreline at x_R = centre.x + x_R_prime Lpp, its top
// z_top below the calm waterline. Its load on the body is X = -F_N sin
// delta, Y = -F_N cos delta and their moment about the reference point;
// history columns rudder/state (delta, order, F_N) and rudder/inflow (u_R,
// v_R, alpha_R, and the sampled u, v before the induced part is removed)
// every step. The run's end reports a WARNING when |alpha_R| went beyond
// the range where the blade's force is validated (Rudder::kValidatedAngle).
#pragma once

#include <memory>
#include <string>

#include "cfd/propulsion/rudder.h"
#include "cfd/run/free_running.h"

namespace kelvin::cfd {

// Reads the case's `rudder:` section for the free body of `c`; null without
// one. Throws ConfigError for a ship file without a rudder, a rudder outside
// the mesh or against the hull, or a bad key.
std::unique_ptr<BodyActuator> LoadRudderActuator(const Case& c, const data::ConfigNode& root);

struct SteeringGear {
  double max_angle = 0.0;  // rad
  double rate = 0.0;       // rad/s
};

class RudderActuator final : public BodyActuator {
 public:
  RudderActuator(Rudder rudder, SteeringGear gear, double initial_order, double rho);

  // The helm order (rad), clamped to the gear's maximum; the blade follows
  // at the rate limit from the next step.
  void SetOrder(double order);
  double order() const { return order_; }
  double angle() const { return delta_; }

  void Update(const PimpleSolver& solver, const FreeBody& body, int outer, std::vector<Vector3>& cell_source,
              PlanarLoad& load) override;
  void BeforeStep(double t_new, double dt) override;
  void Start(History& history) override;
  void AfterStep(const FreeBody& body, History& history) override;
  void AddCheckpointScalars(CheckpointScalars& scalars) const override;
  void RestoreScalars(const CheckpointScalars& scalars) override;
  void ApplyRestored(const PimpleSolver& solver, std::vector<Vector3>& cell_source) const override;
  std::vector<std::string> Finish() override;

  const RudderState& last() const { return last_; }
  const Rudder& rudder() const { return rudder_; }

 private:
  Rudder rudder_;
  SteeringGear gear_;
  double rho_;
  double order_ = 0.0;
  double delta_ = 0.0;  // the blade angle of the step in progress
  double t_ = 0.0;
  RudderState last_;
  double dt_ = 0.0;           // the step in progress (s)
  double max_alpha_ = 0.0;    // largest |alpha_R| of the run (rad)
  double time_beyond_ = 0.0;  // time with |alpha_R| beyond Rudder::kValidatedAngle (s)
  History::Column state_col_ = -1, inflow_col_ = -1;
};

}  // namespace kelvin::cfd
