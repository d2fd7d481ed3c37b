// A campaign of free-running CFD maneuvers: `kelvin run case.yaml
// -m turning:35:stbd -m zigzag:10/10:port --jobs N` flies the case once per
// maneuver (its maneuver.kind replaced), each in <output>/<run>/ where <run>
// is the definition with ':' and '/' as '_' (turning_35_stbd). The runs are
// resumable jobs, as in the captive campaign (cfd_campaign.h):
//   maneuver.h5    the finished run (the pilot writes it at the end, atomically;
//                  its presence marks the run done, and a rerun skips it)
//   checkpoint.h5  the last checkpoint (output.checkpoint_interval); a run
//                  without maneuver.h5 continues from it, so a killed campaign
//                  ends on the same results as an uninterrupted one, bit for bit
//   log.txt        a worker's output (jobs > 1)
// With jobs > 1 the runs execute as separate `kelvin run -m <one>` processes,
// at most `jobs` at a time. A diverging run does not stop the others: the
// campaign finishes them and reports the failed ones (each keeps its last
// good checkpoint). A stop request (SIGINT / SIGTERM) stops every run in
// progress with a checkpoint.
#pragma once

#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "cfd/run/run_case.h"

namespace kelvin::cfd {

struct ManeuverCampaignOptions {
  std::vector<std::string> maneuvers;   // kelvin simulate's definitions: turning:35:stbd, zigzag:10/10:port, ...
  int jobs = 1;                         // runs at a time; > 1 runs worker processes
  std::filesystem::path executable;     // the kelvin program (jobs > 1)
  std::filesystem::path output;         // empty: the case's output.directory
  RunOptions run;                       // progress, poly_mesh_override, stop_requested (jobs 1; restart,
                                        // output_override and maneuver are set per run)
  std::FILE* stream = stdout;           // the campaign's table
};

struct ManeuverRun {
  enum class State { kLeft, kRunning, kDone, kFinishedBefore, kFailed, kInterrupted };
  std::string maneuver;  // canonical definition (ManeuverSpec::ToString)
  std::string name;      // directory name
  std::filesystem::path directory;
  State state = State::kLeft;
  std::string message;  // why it failed or stopped
  pid_t pid = -1;
  int starts = 0;  // worker processes started (DiedStartingMpi)
};

struct ManeuverCampaignSummary {
  std::vector<ManeuverRun> runs;
  bool complete = false;     // every run has its maneuver.h5
  bool interrupted = false;  // a stop was requested
  int failed = 0;
  std::string table;  // the final table
};

// Runs or resumes the campaign. Throws ArgumentError for a bad maneuver
// definition (naming it), one given twice, jobs < 1 or a case without a
// maneuver: section, and ConfigError for a bad case; a run that diverges or
// fails is reported in the summary, not thrown.
ManeuverCampaignSummary RunManeuverCampaign(const std::filesystem::path& case_file,
                                            const ManeuverCampaignOptions& options);

}  // namespace kelvin::cfd
