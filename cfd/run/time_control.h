// Time control of a run (the `time:` section, docs/formulation.md section 9):
// the time step and its ramp, the end time, the rigid-lid start of a
// free-surface run, the uniform initial field, and the one steady criterion
// (cfd/run/steady_criterion.h) that ends a pseudo-transient run early.
//
//   time:
//     dt: 2.5                  # s
//     end: 750                 # s (a harmonic motion with `periods` sets it instead)
//     ramp_steps: 10           # dt ramps from dt / ramp_steps to dt, at the start and after the lid release
//     rigid_lid_windows: 1     # the free surface passes no flux for this many steady windows, then is released
//     initial_velocity: false  # start from the reference velocity (reference.speed along reference.direction)
//     steady:
//       quantities: [drag, eta]  # drag: R_T, R_P, R_F along reference.direction, by |R_T|;
//                                # force: the force vector, by |F|; eta: the free-surface elevation;
//                                # ship_loads: X, Y and N / reference.length in ship axes about
//                                # the motion's centre, by |(X, Y)| (captive static drift)
//       tolerance: 1.0e-3
//       window: 0              # s of pseudo-time; omitted: one flow-through (needs reference.speed)
//       window_steps: 20       # the window spans at least this many steps
//       min_windows: 2         # no stop before this many windows (after the lid release)
//       min_steps: 0           # nor before this many steps
//
// The ramp counts steps of the present phase: the run, then the released
// free surface. A checkpoint keeps the lid release time and the phase (its
// start and steps, the lid's end, the criterion's window: RestorePhase), so
// a restarted run ramps and settles as the uninterrupted one.
#pragma once

#include <map>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "cfd/mesh/mesh.h"
#include "cfd/run/steady_criterion.h"

namespace kelvin::cfd {

class LinearizedFreeSurface;
class PimpleSolver;

enum class SteadyQuantity { kDrag, kForce, kEta, kShipLoads };

struct SteadyOptions {
  std::vector<SteadyQuantity> quantities;
  SteadyCriterionOptions criterion;  // window: resolved (seconds) by the loader
  bool window_is_flow_through = false;  // the window was left to default to one flow-through
  double min_windows = 2.0;
  int min_steps = 0;
  double ship_load_arm = 0.0;  // m, scales N in ship_loads; 0: reference.length (a campaign sets Lpp)
  void Validate() const;
};

struct TimeControlOptions {
  double dt = 0.0;   // s
  double end = 0.0;  // s
  int ramp_steps = 0;
  double rigid_lid_windows = 0.0;
  bool initial_velocity = false;
  std::optional<SteadyOptions> steady;
  void Validate() const;
};

// What the run reached, for monitors and reports.
struct SteadyStatus {
  bool enabled = false;
  bool settled = false;
  int settled_step = -1;
  double force_change = 0.0;  // NaN until a full window of the present phase
  double eta_change = 0.0;
  double window = 0.0;        // s
  bool rigid_lid = false;     // the surface is still held
  double release_time = 0.0;  // NaN: not released (or never held)
};

class TimeControl {
 public:
  // free_surface: the case's linearized free surface (null: none).
  TimeControl(TimeControlOptions options, LinearizedFreeSurface* free_surface);

  // Before the first step: the phase starts, the lid is set (not on a
  // restart), the initial velocity (not on a restart); `scalars` are those
  // of the checkpoint restarted from.
  void Start(PimpleSolver& solver, bool restarted, const std::map<std::string, double>& scalars,
             const Vector3& initial_velocity);
  // After Start on a restart: the phase (its start, its steps, the
  // criterion's window) as the checkpoint kept it (CheckpointArrays), so the
  // ramp and the criterion go on as if the run had not stopped. Checkpoints
  // without them leave the phase restarting at the restart time.
  void RestorePhase(const std::map<std::string, double>& scalars,
                    const std::map<std::string, std::vector<double>>& arrays);
  double NextTimeStep() const;
  // Steps left to time.end at the nominal dt.
  int StepsToEnd(double time) const;
  // After each step: the monitored groups (drag or force) and eta.
  void Record(const PimpleSolver& solver, std::span<const SteadyGroup> groups, std::span<const double> eta);
  bool settled() const { return status_.settled; }
  const SteadyStatus& status() const { return status_; }
  const TimeControlOptions& options() const { return options_; }
  // Run scalars a checkpoint keeps (the lid release time).
  std::map<std::string, double> CheckpointScalars() const;
  std::map<std::string, std::vector<double>> CheckpointArrays() const;

 private:
  void StartPhase(double time);

  TimeControlOptions options_;
  LinearizedFreeSurface* free_surface_;
  std::optional<SteadyCriterion> criterion_;
  SteadyStatus status_;
  double phase_start_ = 0.0;
  int phase_steps_ = 0;
  double rigid_until_ = 0.0;
};

}  // namespace kelvin::cfd
