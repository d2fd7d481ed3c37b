#include "cfd/run/run_case.h"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <cmath>
#include <memory>
#include <vector>

#include "cfd/freesurface/linearized_free_surface.h"
#include "data/schema/atomic_file.h"
#include "cfd/run/captive_sampler.h"
#include "cfd/run/free_running.h"
#include "cfd/run/resistance_monitor.h"
#include "cfd/run/maneuver_pilot.h"
#include "cfd/run/standard_monitors.h"

namespace kelvin::cfd {

namespace fs = std::filesystem;

namespace {

// The monitors the case's sections ask for, in the order they run.
std::vector<std::unique_ptr<Monitor>> MakeMonitors(const Case& c) {
  const CaseSettings& s = c.settings;
  std::vector<std::unique_ptr<Monitor>> m;
  if (c.free_body) m.push_back(std::make_unique<FreeRunningCoupler>(c));
  if (c.maneuver) m.push_back(std::make_unique<ManeuverPilot>(c, *c.maneuver));
  m.push_back(std::make_unique<FieldOutput>(s.output.directory, s.output.vtu_interval));
  m.push_back(std::make_unique<TurbulenceReport>());
  if (s.reference.speed > 0.0 && !c.force_patches.empty()) m.push_back(std::make_unique<ForceCoefficients>(c));
  if (s.resistance) m.push_back(std::make_unique<ResistanceMonitor>(c));
  if (s.output.captive) {
    const PrimeScales scales{s.rho, s.reference.length, s.reference.draft, c.motion->body().nominal_speed()};
    m.push_back(std::make_unique<CaptiveSampler>(c, c.force_patches, scales));
  }
  return m;
}

// A change over the criterion's window; NaN until the run has filled one.
std::string ChangeText(double change) {
  return std::isfinite(change) ? fmt::format("{:.3g}", change) : std::string("unknown (no full window yet)");
}

std::string SteadyLine(const SteadyStatus& st, const SteadyOptions& o) {
  const std::string changes = fmt::format("force change {}, eta change {} over {:.4g} s / >= {} steps",
                                          ChangeText(st.force_change), ChangeText(st.eta_change), st.window,
                                          o.criterion.window_steps);
  return st.settled ? fmt::format("steady: settled at step {} ({})", st.settled_step, changes)
                    : fmt::format("steady: NOT settled by time.end ({}, tolerance {:.3g})", changes,
                                  o.criterion.tolerance);
}

}  // namespace

RunSummary RunCase(const fs::path& case_file, const RunOptions& options) {
  CaseOverrides overrides;
  overrides.poly_mesh = options.poly_mesh_override;
  overrides.output = options.output_override;
  overrides.maneuver = options.maneuver;
  overrides.ranks = options.ranks;
  Case c = LoadCaseFile(case_file, overrides);
  const DomainPart* part = c.part.get();
  if (part) {
    spdlog::info("decomposed over {} MPI ranks: {} cells, rank {} owns {} and holds {} ghost cells", part->size,
                 part->n_global_cells, part->rank, part->n_owned, part->cells.size() - part->n_owned);
  }
  if (!part || part->rank == 0) {
    spdlog::info("mesh quality:\n{}", part ? c.whole_mesh_quality : c.mesh->Quality().Report());
  }
  OnFirstRank(part, [&] {
    fs::create_directories(c.settings.output.directory);
    // What a killed earlier run left half-written beside its files.
    if (const int n = data::RemoveStaleTemporaries(c.settings.output.directory)) {
      spdlog::info("removed {} temporary file(s) a stopped run left in {}", n, c.settings.output.directory.string());
    }
  });
  if (c.free_surface && options.restart.empty() && c.settings.time.rigid_lid_windows == 0.0 &&
      c.free_surface->options().linearization == LinearizedFreeSurfaceOptions::Linearization::kLocalFlow &&
      (!part || part->rank == 0)) {
    spdlog::warn("{}: linearization local_flow without time.rigid_lid_windows: the kinematic condition is linearized "
                 "about the flow of the first step, not about a double body; start from a rigid lid, or restart from "
                 "a converged double body's checkpoint (docs/formulation.md section 3.1)",
                 case_file.string());
  }
  std::vector<std::unique_ptr<Monitor>> owned = MakeMonitors(c);
  std::vector<Monitor*> monitors;
  for (auto& m : owned) monitors.push_back(m.get());
  RunDriverOptions o;
  o.restart = options.restart;
  o.checkpoint = c.settings.output.directory / "checkpoint.h5";
  o.checkpoint_interval = c.settings.output.checkpoint_interval;
  o.history = c.settings.output.directory / "history.h5";
  o.progress = options.progress;
  o.stop_requested = options.stop_requested;
  const RunDriverSummary d = RunDriver(c, monitors, o);

  RunSummary summary;
  summary.steps = d.steps;
  summary.time = d.time;
  summary.output_directory = c.settings.output.directory;
  summary.last_checkpoint = d.last_checkpoint;
  summary.wall_seconds = d.wall_seconds;
  summary.outer_iterations = d.outer_iterations;
  summary.steady_converged = d.steady.settled;
  summary.steady_change = d.steady.force_change;
  if (d.status == RunDriverSummary::Status::kDiverged || d.status == RunDriverSummary::Status::kInterrupted) {
    summary.status = d.status == RunDriverSummary::Status::kDiverged ? RunSummary::Status::kDiverged
                                                                     : RunSummary::Status::kInterrupted;
    summary.message = d.message;
    return summary;
  }
  summary.message = fmt::format("completed {} steps to t = {:.6g} s; results in {}", summary.steps, summary.time,
                                summary.output_directory.string());
  if (c.settings.time.steady) summary.message += "\n  " + SteadyLine(d.steady, *c.settings.time.steady);
  for (const std::string& line : d.report) summary.message += "\n  " + line;
  if (c.settings.time.steady && !d.steady.settled) {
    if (std::isfinite(d.steady.force_change)) {
      spdlog::warn("{}: the steady criterion was NOT met by time.end; the forces still change by {:.3g} of their size",
                   case_file.string(), d.steady.force_change);
    } else {
      spdlog::warn("{}: the steady criterion was NOT met by time.end; the run ended before its first full window",
                   case_file.string());
    }
  }
  return summary;
}

}  // namespace kelvin::cfd
