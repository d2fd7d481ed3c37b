#include "cfd/campaign/campaign_jobs.h"

#include <fmt/format.h>

#include <cstdio>
#include <fstream>

#include "data/report/progress.h"
#include "data/schema/atomic_file.h"
#include "data/schema/captive_plan.h"

namespace kelvin::cfd {
namespace {

namespace fs = std::filesystem;

PrescribedMotion ToPrescribed(data::MotionKind kind) {
  switch (kind) {
    case data::MotionKind::kStaticDrift:
      return PrescribedMotion::kStaticDrift;
    case data::MotionKind::kPureSway:
      return PrescribedMotion::kPureSway;
    case data::MotionKind::kPureYaw:
      return PrescribedMotion::kPureYaw;
    case data::MotionKind::kYawDrift:
      return PrescribedMotion::kYawDrift;
    case data::MotionKind::kCircularMotion:
      return PrescribedMotion::kCircularMotion;
  }
  return PrescribedMotion::kStaticDrift;
}

// The steady criterion of a steady run: X, Y, N / Lpp in ship axes over the
// campaign's settle window, tested from the end of the ramp plus one window.
SteadyOptions SettleCriterion(const data::CampaignFile& f, const data::CaptiveShip& ship,
                              const data::MotionParameters& m) {
  SteadyOptions o;
  o.quantities = {SteadyQuantity::kShipLoads};
  const double window =
      f.cfd.settle_window > 0 ? f.cfd.settle_window : std::min(2.0 * ship.Lpp / m.U, f.cfd.steady_duration);
  o.criterion.window = window;
  o.criterion.window_steps = 5;
  o.criterion.tolerance = f.cfd.settle_tolerance;
  o.min_windows = (m.t_ramp + window) / window;
  o.ship_load_arm = ship.Lpp;
  return o;
}

std::string StateName(CampaignJob::State s) {
  switch (s) {
    case CampaignJob::State::kLeft:
      return "left";
    case CampaignJob::State::kRunning:
      return "running";
    case CampaignJob::State::kDone:
      return "done";
    case CampaignJob::State::kFailed:
      return "failed";
  }
  return "";
}

}  // namespace

std::vector<CampaignJob> PlanCampaignJobs(const data::CampaignFile& f, const data::CaptiveShip& ship,
                          double case_dt) {
  data::CampaignDesign design = f.design;
  design.U = f.speed;
  std::vector<CampaignJob> jobs;
  for (const data::PlannedRun& run : data::PlanRuns(design, ship.Lpp, f.sampling)) {
    CampaignJob job;
    job.name = run.name;
    job.motion = run.motion;
    const data::MotionParameters& m = run.motion;
    MotionOptions& o = job.cfd_motion;
    o.kind = ToPrescribed(m.kind);
    o.speed = m.U;
    o.drift_angle = m.beta;
    o.sway_amplitude = m.y_a;
    o.yaw_amplitude = m.psi_a;
    o.period = data::IsHarmonic(m.kind) ? m.Period() : 0.0;
    o.yaw_rate = m.r_prime * m.U / ship.Lpp;
    // Harmonic runs ramp the motion up over motion_ramp_periods periods; the
    // captive schema's t_ramp (what the analysis discards) stays
    // ramp_periods periods. Both laws agree for t >= t_ramp.
    o.ramp_time = data::IsHarmonic(m.kind) ? f.cfd.motion_ramp_periods * m.Period() : m.t_ramp;
    o.centre = Vector3(f.cfd.centre[0], f.cfd.centre[1], f.cfd.centre[2]);
    if (data::IsHarmonic(m.kind)) {
      job.dt = o.period / f.cfd.steps_per_period;
      job.steps = (f.sampling.ramp_periods + f.sampling.periods) * f.cfd.steps_per_period;
    } else {
      job.dt = case_dt;
      job.steps =
          static_cast<int>(std::llround((f.cfd.steady_ramp + f.cfd.steady_duration) / case_dt));
      if (f.cfd.settle) job.settle = SettleCriterion(f, ship, m);
    }
    job.dir = f.cfd.directory / run.name;
    jobs.push_back(std::move(job));
  }
  if (f.appendages) {
    for (const data::AppendageTest& t : data::PlanAppendageTests(*f.appendages, f.speed, ship.Lpp)) {
      CampaignJob job;
      job.name = t.name;
      job.appendage = t;
      job.dt = case_dt;
      job.steps = static_cast<int>(std::llround((f.cfd.steady_ramp + f.cfd.steady_duration) / case_dt));
      job.dir = f.cfd.directory / t.name;
      jobs.push_back(std::move(job));
    }
  }
  return jobs;
}

void WriteProgressFile(const CampaignJob& job, double seconds) {
  data::WriteFileAtomically(job.dir / "progress.txt",
                            fmt::format("{} {} {:.3f}\n", job.step, job.steps, seconds));
}

std::string ProgressTableText(const std::vector<CampaignJob>& jobs, double elapsed, long computed) {
  std::string out =
      fmt::format("  {:<30} {:<16} {:<8} {:>13}\n", "run", "motion", "status", "steps");
  int done = 0, running = 0, left = 0;
  long remaining = 0;
  for (const CampaignJob& j : jobs) {
    out += fmt::format("  {:<30} {:<16} {:<8} {:>6}/{:<6}\n", j.name,
                       j.appendage ? std::string_view("prop+rudder") : data::MotionKindName(j.motion.kind),
                       StateName(j.state), j.step, j.steps);
    done += j.state == CampaignJob::State::kDone;
    running += j.state == CampaignJob::State::kRunning;
    left += j.state == CampaignJob::State::kLeft;
    if (j.state != CampaignJob::State::kDone) remaining += j.steps - j.step;
  }
  const std::string eta =
      computed > 0 && elapsed > 0
          ? FormatDuration(static_cast<double>(remaining) * elapsed / static_cast<double>(computed))
          : std::string("unknown");
  out += fmt::format("  {} done, {} running, {} left; {} steps to go, ETA {} (elapsed {})\n", done,
                     running, left, remaining, eta, FormatDuration(elapsed));
  return out;
}

void ReadProgressFile(CampaignJob& job) {
  std::ifstream in(job.dir / "progress.txt");
  int step = 0, steps = 0;
  if (in >> step >> steps) job.step = step;
}

// The state of every job from its directory: done when result.h5 exists,
// otherwise at the step of its progress file.
void ReadJobStates(std::vector<CampaignJob>& jobs) {
  for (CampaignJob& j : jobs) {
    if (fs::exists(j.dir / "result.h5")) {
      j.state = CampaignJob::State::kDone;
      j.step = j.steps;
    } else {
      ReadProgressFile(j);
    }
  }
}


}  // namespace kelvin::cfd
