// The runs of a CFD captive campaign as jobs (cfd/campaign/cfd_campaign.h):
// the plan of the test matrix (and of the appendage tests) with each run's
// prescribed motion, time step and steady criterion; each job's state from
// its directory (result.h5 done, progress.txt the step reached); and the
// progress table the campaign prints.
#pragma once

#include <sys/types.h>

#include <chrono>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "cfd/campaign/cfd_campaign.h"
#include "cfd/motion/rigid_motion.h"
#include "cfd/run/time_control.h"
#include "data/schema/appendage_runs.h"
#include "data/schema/campaign_file.h"
#include "data/schema/captive_run.h"

namespace kelvin::cfd {

struct CampaignJob {
  enum class State { kLeft, kRunning, kDone, kFailed };
  std::string name;
  data::MotionParameters motion;  // as the captive schema records it
  MotionOptions cfd_motion;
  double dt = 0.0;
  int steps = 0;
  std::filesystem::path dir;
  // Steady runs: the criterion that ends them (none: a fixed duration).
  std::optional<SteadyOptions> settle;
  // A run with the propeller and rudder (tests.appendages): fixed duration.
  std::optional<data::AppendageTest> appendage;
  State state = State::kLeft;
  int step = 0;
  std::string message;
  pid_t pid = -1;
  int starts = 0;  // worker processes started (DiedStartingMpi)
};

// The campaign's runs in order (the test matrix, then the appendage tests),
// each in <cfd.directory>/<run name>; steady runs step at the case's dt.
std::vector<CampaignJob> PlanCampaignJobs(const data::CampaignFile& f, const data::CaptiveShip& ship, double case_dt);

// progress.txt of a job: "<step> <steps> <wall seconds>", written atomically.
void WriteProgressFile(const CampaignJob& job, double seconds);
// The step of a job's progress.txt, when it has one.
void ReadProgressFile(CampaignJob& job);
// The state of every job from its directory: done when result.h5 exists,
// otherwise at the step of its progress file.
void ReadJobStates(std::vector<CampaignJob>& jobs);

// The table of runs, their motion, state and steps, with the totals and the
// remaining time estimated from `computed` steps in `elapsed` seconds.
std::string ProgressTableText(const std::vector<CampaignJob>& jobs, double elapsed, long computed);

// The progress table of a campaign: kept in the summary at every update and
// printed (when the options ask for it) at most every 10 s unless forced.
class ProgressTable {
 public:
  ProgressTable(const data::CampaignFile& f, const CampaignRunOptions& options,
                const std::vector<CampaignJob>& jobs, CampaignRunSummary& summary)
      : file_(f), options_(options), jobs_(jobs), summary_(summary) {}
  double elapsed() const { return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count(); }
  void Print(bool force) {
    summary_.table = ProgressTableText(jobs_, elapsed(), summary_.steps_computed);
    if (!options_.progress) return;
    if (!force && std::chrono::steady_clock::now() - last_print_ < std::chrono::seconds(10)) return;
    last_print_ = std::chrono::steady_clock::now();
    std::fprintf(options_.stream, "captive campaign '%s' (cfd):\n%s", file_.name.c_str(),
                 summary_.table.c_str());
    std::fflush(options_.stream);
  }

 private:
  const data::CampaignFile& file_;
  const CampaignRunOptions& options_;
  const std::vector<CampaignJob>& jobs_;
  CampaignRunSummary& summary_;
  std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
  std::chrono::steady_clock::time_point last_print_ = std::chrono::steady_clock::now() - std::chrono::hours(1);
};

}  // namespace kelvin::cfd
