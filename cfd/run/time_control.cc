#include "cfd/run/time_control.h"

#include <fmt/format.h>

#include <cmath>
#include <limits>

#include "cfd/freesurface/linearized_free_surface.h"
#include "cfd/solver/pimple_solver.h"
#include "data/schema/errors.h"

namespace kelvin::cfd {
namespace {
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr const char* kReleaseScalar = "rigid_lid_release_time";
constexpr const char* kOldReleaseScalar = "resistance_release_time";  // checkpoints of the older layout
constexpr const char* kPhaseStart = "phase_start";
constexpr const char* kPhaseSteps = "phase_steps";
constexpr const char* kRigidUntil = "rigid_lid_until";
constexpr const char* kWindowArray = "steady_window";
}  // namespace

void SteadyOptions::Validate() const {
  criterion.Validate();
  if (quantities.empty()) throw ConfigError("quantities: expected at least one of drag, force, eta, ship_loads");
  if (!(min_windows >= 1.0) || !std::isfinite(min_windows)) {
    throw ConfigError(fmt::format("min_windows = {}; expected >= 1", min_windows));
  }
  if (min_steps < 0) throw ConfigError(fmt::format("min_steps = {}; expected >= 0", min_steps));
}

void TimeControlOptions::Validate() const {
  if (!(dt > 0.0) || !std::isfinite(dt)) throw ConfigError(fmt::format("dt = {} s; expected > 0", dt));
  if (!(end > 0.0) || !std::isfinite(end)) throw ConfigError(fmt::format("end = {} s; expected > 0", end));
  if (ramp_steps < 0) throw ConfigError(fmt::format("ramp_steps = {}; expected >= 0", ramp_steps));
  if (!(rigid_lid_windows >= 0.0) || !std::isfinite(rigid_lid_windows)) {
    throw ConfigError(fmt::format("rigid_lid_windows = {}; expected >= 0 windows", rigid_lid_windows));
  }
  if (rigid_lid_windows > 0.0 && !steady) {
    throw ConfigError(fmt::format(
        "rigid_lid_windows = {}; expected a steady: section too (the lid is held for windows of its criterion)",
        rigid_lid_windows));
  }
  if (steady) steady->Validate();
}

TimeControl::TimeControl(TimeControlOptions options, LinearizedFreeSurface* free_surface)
    : options_(std::move(options)), free_surface_(free_surface) {
  options_.Validate();
  if (options_.rigid_lid_windows > 0.0 && !free_surface_) {
    throw ConfigError(fmt::format(
        "rigid_lid_windows = {}; expected a linearizedFreeSurface patch (a double body has no lid to release)",
        options_.rigid_lid_windows));
  }
  status_.enabled = options_.steady.has_value();
  status_.release_time = kNaN;
  if (status_.enabled) status_.window = options_.steady->criterion.window;
}

void TimeControl::StartPhase(double time) {
  phase_start_ = time;
  phase_steps_ = 0;
  if (options_.steady) criterion_.emplace(options_.steady->criterion);
  status_.force_change = status_.eta_change = kNaN;
}

void TimeControl::Start(PimpleSolver& solver, bool restarted, const std::map<std::string, double>& scalars,
                        const Vector3& initial_velocity) {
  StartPhase(solver.time());
  if (restarted) {
    for (const char* name : {kReleaseScalar, kOldReleaseScalar}) {
      if (const auto it = scalars.find(name); it != scalars.end()) status_.release_time = it->second;
    }
  }
  if (free_surface_ && options_.rigid_lid_windows > 0.0) {
    if (!restarted) free_surface_->SetRigidLid(true);
    status_.rigid_lid = free_surface_->rigid_lid();
    rigid_until_ = solver.time() + options_.rigid_lid_windows * status_.window;
  }
  if (restarted || !options_.initial_velocity) return;
  VectorField& U = solver.U();
  for (int i = 0; i < solver.mesh().n_cells(); ++i) U[i] = initial_velocity;
}

double TimeControl::NextTimeStep() const {
  const int ramp = options_.ramp_steps;
  if (ramp <= 1 || phase_steps_ >= ramp) return options_.dt;
  return options_.dt * (phase_steps_ + 1) / ramp;
}

int TimeControl::StepsToEnd(double time) const {
  return static_cast<int>(std::ceil((options_.end - time) / options_.dt - 1e-9));
}

void TimeControl::Record(const PimpleSolver& solver, std::span<const SteadyGroup> groups,
                         std::span<const double> eta) {
  ++phase_steps_;
  if (status_.rigid_lid) {
    // Rigid-lid phase: no steady test; the surface is released when its time is up.
    if (solver.time() >= rigid_until_ * (1 - 1e-12)) {
      free_surface_->SetRigidLid(false);
      status_.rigid_lid = false;
      status_.release_time = solver.time();
      StartPhase(solver.time());
    }
    return;
  }
  if (!criterion_) return;
  criterion_->Add(solver.time(), groups, eta);
  status_.force_change = criterion_->force_change();
  status_.eta_change = criterion_->eta_change();
  const SteadyOptions& st = *options_.steady;
  const bool long_enough = solver.time() - phase_start_ >= st.min_windows * status_.window * (1 - 1e-9) &&
                           phase_steps_ >= st.min_steps;
  if (!status_.settled && long_enough && criterion_->Settled()) {
    status_.settled = true;
    status_.settled_step = solver.step();
  }
}

std::map<std::string, double> TimeControl::CheckpointScalars() const {
  std::map<std::string, double> scalars{{kPhaseStart, phase_start_},
                                        {kPhaseSteps, static_cast<double>(phase_steps_)}};
  if (status_.rigid_lid) scalars[kRigidUntil] = rigid_until_;
  if (!std::isnan(status_.release_time)) scalars[kReleaseScalar] = status_.release_time;
  return scalars;
}

std::map<std::string, std::vector<double>> TimeControl::CheckpointArrays() const {
  if (!criterion_) return {};
  return {{kWindowArray, criterion_->Save()}};
}

void TimeControl::RestorePhase(const std::map<std::string, double>& scalars,
                               const std::map<std::string, std::vector<double>>& arrays) {
  const auto start = scalars.find(kPhaseStart), steps = scalars.find(kPhaseSteps);
  if (start == scalars.end() || steps == scalars.end()) return;  // an older checkpoint
  phase_start_ = start->second;
  phase_steps_ = static_cast<int>(steps->second);
  if (const auto until = scalars.find(kRigidUntil); until != scalars.end() && status_.rigid_lid) {
    rigid_until_ = until->second;
  }
  if (const auto window = arrays.find(kWindowArray); window != arrays.end() && criterion_) {
    criterion_->Load(window->second);
    status_.force_change = criterion_->force_change();
    status_.eta_change = criterion_->eta_change();
  }
}

}  // namespace kelvin::cfd
