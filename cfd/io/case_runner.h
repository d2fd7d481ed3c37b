// Runs a YAML case file (`kelvin run case.yaml`): sections mesh / physics /
// schemes / solution / time / boundary / output. A bad key, an unknown patch
// or a patch without a condition is one ConfigError naming the file, line
// and key. Writes VTU/PVD fields, an HDF5 history (residuals, Courant number,
// continuity, forces on named patches with pressure and viscous parts) and
// HDF5 checkpoints; a diverging run stops with a clear status and keeps its
// last good checkpoint.
#pragma once

#include <filesystem>
#include <span>
#include <string>

#include "cfd/io/case_loader.h"

namespace kelvin::cfd {

struct RunOptions {
  std::filesystem::path restart;  // checkpoint to continue from (empty: none)
  std::filesystem::path output_override;  // replaces output.directory when set
  std::filesystem::path poly_mesh_override;  // replaces mesh.poly_mesh when set (grid families)
  bool progress = true;
};

struct RunSummary {
  enum class Status { kCompleted, kDiverged };
  Status status = Status::kCompleted;
  std::string message;
  int steps = 0;
  double time = 0.0;
  std::filesystem::path output_directory;
  std::filesystem::path last_checkpoint;
  double wall_seconds = 0.0;
  int outer_iterations = 0;
  // The run reached its steady state before time.end: time.steady (the force
  // settled; steady_change is the relative force range over the window at
  // the last step) or the criterion of the resistance section.
  bool steady_converged = false;
  double steady_change = 0.0;
};

RunSummary RunCase(const std::filesystem::path& case_file, const RunOptions& options);

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
