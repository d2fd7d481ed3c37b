// Captive campaigns in CFD (`kelvin captive campaign.yaml` with solver: cfd):
// every run of the test matrix is the campaign's `kelvin run` case with the
// prescribed motion of the run (cfd/motion), and the hull loads in ship axes
// go straight into the captive HDF5 schema that `kelvin identify` reads
// (data/schema/captive_schema.md), with the pressure / viscous parts and the
// prime-system forces beside them.
//
// Runs are resumable jobs. Each run lives in <cfd.directory>/<run name>/:
//   samples.h5     the loads up to the last checkpoint (written first)
//   checkpoint.h5  the solver state at that step (cfd/io/checkpoint.h)
//   result.h5      the finished run (its presence marks the run done)
//   progress.txt   "<step> <steps> <wall seconds>" for the progress table
// A killed campaign resumes each run from its last checkpoint (a settling
// run gives the steady criterion the loads of the steps before it, from its
// samples) and skips the finished ones; the result equals that of an
// uninterrupted campaign bit for bit. With jobs > 1 the runs execute as separate `kelvin captive --run`
// processes, at most `jobs` at a time, and the parent prints the table. With ranks_per_run > 1 each of
// them is started under the MPI launcher (`mpiexec -n ranks_per_run kelvin captive --run ...`) and
// decomposes its case over its ranks, rank 0 writing the run's files.
#pragma once

#include <mpi.h>

#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "data/schema/campaign_file.h"

namespace kelvin::cfd {

struct CampaignRunOptions {
  int jobs = 0;                      // concurrent runs; 0 = the campaign file's cfd.jobs
  long stop_after_steps = 0;         // > 0: stop, as if killed, after this many steps in this call
  std::string only_run;              // run just this run and write its result (worker mode)
  std::filesystem::path executable;  // the kelvin program (for jobs > 1)
  // Ranks of each run: > 1 starts every run, even with jobs 1, as a worker
  // under `launcher` (mpiexec).
  int ranks_per_run = 1;
  std::filesystem::path launcher;
  // Worker mode under a launcher: the ranks only_run is decomposed over
  // (MPI_COMM_NULL: this process alone).
  MPI_Comm ranks = MPI_COMM_NULL;
  std::filesystem::path output;  // campaign HDF5 (default: <cfd.directory>/<name>.h5)
  bool progress = true;          // print the progress table
  std::FILE* stream = stdout;
};

struct CampaignRunSummary {
  bool complete = false;  // every run finished and the campaign file is written
  int runs_total = 0;
  int runs_done = 0;
  long steps_computed = 0;  // time steps computed in this call
  std::filesystem::path output;
  std::string table;  // the last progress table
};

// Runs or resumes the campaign. Throws ConfigError for a bad cfd: section or
// case (naming the file and key) and InputError when a run diverges (naming
// the run and its last checkpoint, which stays on disk).
CampaignRunSummary RunCfdCampaign(const data::CampaignFile& file,
                                  const CampaignRunOptions& options);

}  // namespace kelvin::cfd
