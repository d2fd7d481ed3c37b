// `kelvin run case.yaml` (and each grid of `kelvin gci`): loads the case
// (cfd/run/case_loader.h), makes the monitors its sections ask for, and runs
// it through the run driver (cfd/run/run_driver.h). Writes VTU/PVD fields,
// an HDF5 history (residuals, Courant number, continuity, forces on named
// patches with pressure and viscous parts, and what the monitors add) and
// HDF5 checkpoints; a diverging run stops with a clear status and keeps its
// last good checkpoint.
#pragma once

#include <filesystem>
#include <functional>
#include <string>

#include <mpi.h>

#include "cfd/run/run_driver.h"

namespace kelvin::cfd {

struct RunOptions {
  std::filesystem::path restart;             // checkpoint to continue from (empty: none)
  std::filesystem::path output_override;     // replaces output.directory when set
  std::filesystem::path poly_mesh_override;  // replaces mesh.poly_mesh when set (grid families)
  std::string maneuver;                      // non-empty: replaces maneuver.kind (kelvin run -m)
  bool progress = true;
  // Polled after each step (RunDriverOptions::stop_requested): `kelvin run`
  // passes the SIGTERM / SIGINT it caught.
  std::function<int()> stop_requested;
  // The MPI ranks to decompose the case over (cfd/parallel): a communicator
  // of more than one rank runs on them (collective; rank 0 writes every
  // file); MPI_COMM_NULL or one rank runs serially.
  MPI_Comm ranks = MPI_COMM_NULL;
};

struct RunSummary {
  // kInterrupted: a stop was requested; the message names the checkpoint.
  enum class Status { kCompleted, kDiverged, kInterrupted };
  Status status = Status::kCompleted;
  std::string message;
  int steps = 0;
  double time = 0.0;
  std::filesystem::path output_directory;
  std::filesystem::path last_checkpoint;
  double wall_seconds = 0.0;
  int outer_iterations = 0;
  // The run met time.steady before time.end; steady_change is the relative
  // change of the monitored forces over its window at the last step.
  bool steady_converged = false;
  double steady_change = 0.0;
};

RunSummary RunCase(const std::filesystem::path& case_file, const RunOptions& options);

}  // namespace kelvin::cfd
