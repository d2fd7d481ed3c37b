// The one time loop of kelvin (`kelvin run`, CFD captive runs, `kelvin gci`):
//
//   restart? -> monitors.Start -> loop {
//       dt = time control (ramp) -> solver.Step (monitors.AfterOuterIteration inside)
//       -> diverged? stop, keep the last good checkpoint
//       -> patch face forces (once per patch) -> history row
//       -> time control (lid release, steady criterion) -> monitors.AfterStep
//       -> checkpoint (monitors.BeforeCheckpoint first) and history.h5
//   } until time.end, the steady criterion, or the step budget
//   -> monitors.Finish (report lines)
//
// The driver owns the time control, divergence handling, checkpoints,
// restarts and the named history; everything else is a monitor
// (cfd/run/monitor.h).
#pragma once

#include <filesystem>
#include <functional>
#include <span>
#include <string>

#include "cfd/run/case_loader.h"
#include "cfd/run/monitor.h"

namespace kelvin::cfd {

struct RunDriverOptions {
  std::filesystem::path restart;     // checkpoint to continue from (empty: none)
  std::filesystem::path checkpoint;  // where checkpoints go (empty: none)
  int checkpoint_interval = 0;       // steps; 0: at the end only; < 0: never
  bool checkpoint_at_end = true;     // also on the last step
  std::filesystem::path history;     // history.h5 (empty: none), written with each checkpoint and at the end
  long step_budget = 0;              // > 0: stop after this many steps, as if killed (tests)
  // Polled after each step: a signal number (SIGTERM, SIGINT) asks for a
  // clean stop: a checkpoint (when `checkpoint` is set) and the history,
  // then kInterrupted. Null or 0: run on.
  std::function<int()> stop_requested;
  bool progress = true;
  std::string label = "kelvin run";
};

struct RunDriverSummary {
  // kStopped: the step budget ran out; kInterrupted: stop_requested said so.
  enum class Status { kCompleted, kDiverged, kStopped, kInterrupted };
  Status status = Status::kCompleted;
  std::string message;  // on divergence: where and what, with the last good checkpoint
  int steps = 0;        // steps computed in this call
  int outer_iterations = 0;
  double time = 0.0;
  double wall_seconds = 0.0;
  std::filesystem::path last_checkpoint;
  SteadyStatus steady;
  std::vector<std::string> report;  // the monitors' report lines of a completed run
};

RunDriverSummary RunDriver(Case& c, std::span<Monitor* const> monitors, const RunDriverOptions& options);

// The ship_loads group of the steady criterion: X, Y and N / arm of the hull
// loads in ship axes, scaled by |(X, Y)|.
SteadyGroup ShipLoadGroup(const PlanarLoad& load, double arm);

// Where a diverging run began to blow up, from its per-step largest Courant
// numbers (oldest first): the first of the last run of steps above twice the
// median (grew), or the last step when the last step is not above it.
struct CourantOnset {
  std::size_t step = 0;  // index into the history
  bool grew = false;
  double median = 0.0;
};
CourantOnset CourantGrowthOnset(std::span<const double> courant);

}  // namespace kelvin::cfd
