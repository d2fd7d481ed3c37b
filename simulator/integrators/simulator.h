// Time integration of the MMG model with SUNDIALS 6: CVODE (adaptive BDF/Adams,
// for fast time; it stops exactly at actuator kinks and locates heading
// events by root finding) or ARKODE ERKStep with a fixed step (deterministic,
// allocation-free stepping for real time). Both sit behind this one class.
#pragma once

#include <array>
#include <memory>
#include <optional>

#include "simulator/integrators/actuators.h"
#include "simulator/integrators/plant.h"
#include "simulator/maneuvers/maneuver_plant.h"
#include "simulator/mmg/mmg_model.h"

namespace kelvin::sim {

using StateVector = std::array<double, kStateSize>;  // [x, y, psi, u, v_m, r]

struct SimulatorOptions {
  enum class Method { kAdaptive, kFixedStep };
  Method method = Method::kAdaptive;
  // Adaptive (CVODE, Adams): relative tolerance and absolute tolerances
  // scaled by Lpp for positions, 1 rad for heading, U0 for velocities.
  double rtol = 1e-10;
  double atol = 1e-10;
  bool use_bdf = false;  // Adams suits this non-stiff system; BDF is available
  long max_steps = 1000000;
  // Fixed-step (ERKStep, 4th-order Zonneveld 5-3-4 table): step in seconds.
  double fixed_step = 0.05;

  void Validate() const;  // throws kelvin::ArgumentError with the bad option
};

class Simulator final : public ManeuverPlant {
 public:
  // Integrates the MMG model (the usual case). Refers to `model`, which must
  // outlive the simulator.
  Simulator(const MmgModel<double>& model, const SimulatorOptions& options);
  Simulator(const MmgModel<double>&& model, const SimulatorOptions& options) = delete;  // would dangle
  // Integrates any plant (e.g. a LinearPlant in tests).
  Simulator(std::unique_ptr<const Plant> plant, const SimulatorOptions& options);
  ~Simulator() override;
  Simulator(const Simulator&) = delete;
  Simulator& operator=(const Simulator&) = delete;

  // Starts at time t0 in `state`, rudder at delta (rad) and propeller at n (1/s).
  void Reset(double t0, const StateVector& state, double delta, double n);

  // Orders take effect from the current time; the rudder order is clamped to
  // the ship's maximum angle and the rps order to [0, rps_max], or [-rps_max,
  // rps_max] with reverse thrust (rps_max = infinity when the ship gives none).
  void SetRudderOrder(double delta_order) override;
  void SetRpsOrder(double n_order) override;

  // Integrates to t_end (adaptive: exactly, stopping at every actuator kink;
  // fixed step: by whole steps, t_end - time() must be a multiple of the step
  // within 1e-9 s). If `heading_event` is set, stops early where psi crosses
  // that value (adaptive: located by root finding to the integrator
  // tolerance; fixed step: at the end of the step that crosses) and returns
  // true.
  bool Advance(double t_end, std::optional<double> heading_event = std::nullopt);

  // One fixed step (fixed-step method only). Never allocates.
  void Step();

  double time() const override { return t_; }
  double heading() const override { return y_[kPsi]; }
  double surge_speed() const override { return y_[kU]; }
  const StateVector& state() const { return y_; }
  double rudder() const { return rudder_.PositionAt(t_); }
  double rudder_order() const { return rudder_.order(); }
  double rps() const { return rps_.PositionAt(t_); }
  double rps_order() const { return rps_.order(); }
  const ShipParameters& ship() const { return plant_->ship(); }
  const Plant& plant() const { return *plant_; }
  const SimulatorOptions& options() const { return options_; }
  long steps_taken() const;

  // Right-hand side for the integrators (public so the C callbacks reach it).
  void Rhs(double t, const double* y, double* ydot) const;
  double heading_target() const { return heading_target_; }

 private:
  struct Sundials;
  void Restart();

  std::unique_ptr<const Plant> plant_;
  SimulatorOptions options_;
  RateLimitedActuator rudder_;
  RateLimitedActuator rps_;
  double t_ = 0.0;
  StateVector y_{};
  double heading_target_ = 0.0;
  std::unique_ptr<Sundials> sun_;
};

}  // namespace kelvin::sim
