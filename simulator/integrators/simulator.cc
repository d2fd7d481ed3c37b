#include "simulator/integrators/simulator.h"

#include <arkode/arkode_erkstep.h>
#include <cvode/cvode.h>
#include <fmt/format.h>
#include <nvector/nvector_serial.h>
#include <sundials/sundials_context.h>
#include <sunlinsol/sunlinsol_dense.h>
#include <sunmatrix/sunmatrix_dense.h>
#include <sunnonlinsol/sunnonlinsol_fixedpoint.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "data/schema/errors.h"

namespace kelvin::sim {

namespace {

int RhsCallback(sunrealtype t, N_Vector y, N_Vector ydot, void* user) {
  const auto* sim = static_cast<const Simulator*>(user);
  sim->Rhs(t, N_VGetArrayPointer(y), N_VGetArrayPointer(ydot));
  for (int i = 0; i < kStateSize; ++i) {
    if (!std::isfinite(N_VGetArrayPointer(ydot)[i])) return 1;  // recoverable: the step is retried smaller
  }
  return 0;
}

int HeadingRoot(sunrealtype, N_Vector y, sunrealtype* g, void* user) {
  const auto* sim = static_cast<const Simulator*>(user);
  g[0] = N_VGetArrayPointer(y)[kPsi] - sim->heading_target();
  return 0;
}

void CheckFlag(int flag, const char* what) {
  if (flag < 0) throw std::runtime_error(fmt::format("SUNDIALS {} failed with flag {}", what, flag));
}

}  // namespace

struct Simulator::Sundials {
  SUNContext ctx = nullptr;
  N_Vector y = nullptr;
  N_Vector abstol = nullptr;
  void* cvode = nullptr;
  void* erk = nullptr;
  SUNNonlinearSolver nls = nullptr;
  bool root_active = false;

  ~Sundials() {
    if (cvode) CVodeFree(&cvode);
    if (erk) ERKStepFree(&erk);
    if (nls) SUNNonlinSolFree(nls);
    if (abstol) N_VDestroy(abstol);
    if (y) N_VDestroy(y);
    if (ctx) SUNContext_Free(&ctx);
  }
};

void SimulatorOptions::Validate() const {
  if (!(rtol > 0 && rtol < 1)) throw ArgumentError(fmt::format("integrator rtol = {}: expected 0 < rtol < 1", rtol));
  if (!(atol > 0)) throw ArgumentError(fmt::format("integrator atol = {}: expected a positive tolerance", atol));
  if (!(fixed_step > 0 && std::isfinite(fixed_step))) {
    throw ArgumentError(fmt::format("integrator step = {} s: expected a positive step", fixed_step));
  }
  if (max_steps <= 0) throw ArgumentError(fmt::format("integrator max_steps = {}: expected > 0", max_steps));
}

Simulator::Simulator(const MmgModel<double>& model, const SimulatorOptions& options)
    : Simulator(std::make_unique<MmgPlant>(model), options) {}

Simulator::Simulator(std::unique_ptr<const Plant> plant, const SimulatorOptions& options)
    : plant_(std::move(plant)), options_(options), sun_(std::make_unique<Sundials>()) {
  options_.Validate();
  rudder_.set_rate(plant_->ship().limits.rudder_rate);
  rps_.set_rate(plant_->ship().limits.rps_rate);
  CheckFlag(SUNContext_Create(nullptr, &sun_->ctx), "SUNContext_Create");
  sun_->y = N_VNew_Serial(kStateSize, sun_->ctx);
  sun_->abstol = N_VNew_Serial(kStateSize, sun_->ctx);
}

Simulator::~Simulator() = default;

long Simulator::steps_taken() const {
  long n = 0;
  if (sun_->cvode) CVodeGetNumSteps(sun_->cvode, &n);
  if (sun_->erk) ERKStepGetNumSteps(sun_->erk, &n);
  return n;
}

void Simulator::Rhs(double t, const double* y, double* ydot) const {
  plant_->Derivative(y, rudder_.PositionAt(t), rps_.PositionAt(t), ydot);
}

void Simulator::Reset(double t0, const StateVector& state, double delta, double n) {
  t_ = t0;
  y_ = state;
  rudder_.Reset(t0, ClampRudderAngle(delta, plant_->ship().limits.rudder_max));
  rps_.Reset(t0, n);
  double* yd = N_VGetArrayPointer(sun_->y);
  for (int i = 0; i < kStateSize; ++i) yd[i] = y_[i];
  if (options_.method == SimulatorOptions::Method::kAdaptive) {
    const double L = plant_->ship().principal.Lpp;
    const double U = std::max(std::hypot(state[kU], state[kV]), 1e-3);
    double* at = N_VGetArrayPointer(sun_->abstol);
    at[kX] = at[kY] = options_.atol * L;
    at[kPsi] = options_.atol;
    at[kU] = at[kV] = options_.atol * U;
    at[kR] = options_.atol * U / L;
    if (!sun_->cvode) {
      sun_->cvode = CVodeCreate(options_.use_bdf ? CV_BDF : CV_ADAMS, sun_->ctx);
      CheckFlag(CVodeInit(sun_->cvode, RhsCallback, t0, sun_->y), "CVodeInit");
      CheckFlag(CVodeSetUserData(sun_->cvode, this), "CVodeSetUserData");
      // Adams with fixed-point iteration: no Jacobian needed for this
      // non-stiff 6-state system.
      sun_->nls = SUNNonlinSol_FixedPoint(sun_->y, 0, sun_->ctx);
      CheckFlag(CVodeSetNonlinearSolver(sun_->cvode, sun_->nls), "CVodeSetNonlinearSolver");
      CheckFlag(CVodeSetMaxNumSteps(sun_->cvode, options_.max_steps), "CVodeSetMaxNumSteps");
      CheckFlag(CVodeSetMaxStep(sun_->cvode, 0.5 * L / U), "CVodeSetMaxStep");
    } else {
      CheckFlag(CVodeReInit(sun_->cvode, t0, sun_->y), "CVodeReInit");
    }
    CheckFlag(CVodeSStolerances(sun_->cvode, options_.rtol, 0.0), "CVodeSStolerances");
    CheckFlag(CVodeSVtolerances(sun_->cvode, options_.rtol, sun_->abstol), "CVodeSVtolerances");
    CVodeSetNoInactiveRootWarn(sun_->cvode);
  } else {
    if (!sun_->erk) {
      sun_->erk = ERKStepCreate(RhsCallback, t0, sun_->y, sun_->ctx);
      if (!sun_->erk) throw std::runtime_error("ERKStepCreate failed");
      CheckFlag(ERKStepSetUserData(sun_->erk, this), "ERKStepSetUserData");
      CheckFlag(ERKStepSetTableNum(sun_->erk, ARKODE_ZONNEVELD_5_3_4), "ERKStepSetTableNum");
      CheckFlag(ERKStepSetFixedStep(sun_->erk, options_.fixed_step), "ERKStepSetFixedStep");
      CheckFlag(ERKStepSetMaxNumSteps(sun_->erk, options_.max_steps), "ERKStepSetMaxNumSteps");
    } else {
      CheckFlag(ERKStepReset(sun_->erk, t0, sun_->y), "ERKStepReset");
    }
  }
}

void Simulator::Restart() {
  // The right-hand side changes its derivative when an order is given: restart
  // the multistep method there instead of stepping across the kink.
  double* yd = N_VGetArrayPointer(sun_->y);
  for (int i = 0; i < kStateSize; ++i) yd[i] = y_[i];
  if (sun_->cvode) CheckFlag(CVodeReInit(sun_->cvode, t_, sun_->y), "CVodeReInit");
  if (sun_->erk) CheckFlag(ERKStepReset(sun_->erk, t_, sun_->y), "ERKStepReset");
}

void Simulator::SetRudderOrder(double delta_order) {
  const double order = ClampRudderAngle(delta_order, plant_->ship().limits.rudder_max);
  if (order == rudder_.order() && rudder_.PositionAt(t_) == order) return;
  rudder_.SetOrder(t_, order);
  Restart();
}

void Simulator::SetRpsOrder(double n_order) {
  const auto& ship = plant_->ship();
  const double hi = ship.limits.rps_max.value_or(std::numeric_limits<double>::infinity());
  const double lo = ship.propeller.reverse_kt ? -hi : 0.0;
  const double order = std::clamp(n_order, lo, hi);
  if (order == rps_.order() && rps_.PositionAt(t_) == order) return;
  rps_.SetOrder(t_, order);
  Restart();
}

bool Simulator::Advance(double t_end, std::optional<double> heading_event) {
  if (t_end <= t_) return false;
  if (options_.method == SimulatorOptions::Method::kFixedStep) {
    const double h = options_.fixed_step;
    const double steps_real = (t_end - t_) / h;
    const long steps = std::lround(steps_real);
    if (std::abs(steps_real - static_cast<double>(steps)) * h > 1e-9) {
      throw ArgumentError(fmt::format("fixed-step run to t = {} s from t = {} s is not a whole number of {} s steps",
                                      t_end, t_, h));
    }
    for (long i = 0; i < steps; ++i) {
      const double psi_before = y_[kPsi];
      Step();
      if (heading_event && (psi_before - *heading_event) * (y_[kPsi] - *heading_event) <= 0 &&
          psi_before != *heading_event) {
        return true;
      }
    }
    return false;
  }
  // Adaptive: integrate in segments that end at every actuator kink.
  heading_target_ = heading_event.value_or(0.0);
  if (heading_event.has_value() != sun_->root_active) {
    if (heading_event) {
      CheckFlag(CVodeRootInit(sun_->cvode, 1, HeadingRoot), "CVodeRootInit");
    } else {
      CheckFlag(CVodeRootInit(sun_->cvode, 0, nullptr), "CVodeRootInit");
    }
    sun_->root_active = heading_event.has_value();
  }
  while (t_ < t_end) {
    const double kink = std::min(rudder_.RampEnd(), rps_.RampEnd());
    const bool stop_at_kink = kink > t_ && kink < t_end;
    const double target = stop_at_kink ? kink : t_end;
    CheckFlag(CVodeSetStopTime(sun_->cvode, target), "CVodeSetStopTime");
    double t_reached = t_;
    const int flag = CVode(sun_->cvode, target, sun_->y, &t_reached, CV_NORMAL);
    if (flag < 0) {
      throw std::runtime_error(fmt::format("CVODE failed at t = {} s with flag {} ({})", t_reached, flag,
                                           CVodeGetReturnFlagName(flag)));
    }
    t_ = t_reached;
    const double* yd = N_VGetArrayPointer(sun_->y);
    for (int i = 0; i < kStateSize; ++i) y_[i] = yd[i];
    if (flag == CV_ROOT_RETURN) return true;
    if (stop_at_kink && t_ >= kink) Restart();
  }
  return false;
}

void Simulator::Step() {
  KELVIN_CHECK(sun_->erk != nullptr, "Simulator::Step needs the fixed-step method");
  const double t_next = t_ + options_.fixed_step;
  ERKStepSetStopTime(sun_->erk, t_next);
  double t_reached = t_;
  const int flag = ERKStepEvolve(sun_->erk, t_next, sun_->y, &t_reached, ARK_NORMAL);
  KELVIN_CHECK(flag >= 0, "ERKStep fixed step failed");
  t_ = t_reached;
  const double* yd = N_VGetArrayPointer(sun_->y);
  for (int i = 0; i < kStateSize; ++i) y_[i] = yd[i];
}

}  // namespace kelvin::sim
