// Runs a YAML case file (`kelvin run case.yaml`): sections mesh / physics /
// schemes / solution / time / boundary / output. A bad key, an unknown patch
// or a patch without a condition is one ConfigError naming the file, line
// and key. Writes VTU/PVD fields, an HDF5 history (residuals, Courant number,
// continuity, forces on named patches with pressure and viscous parts) and
// HDF5 checkpoints; a diverging run stops with a clear status and keeps its
// last good checkpoint.
#pragma once

#include <filesystem>
#include <memory>
#include <optional>
#include <string>

#include "cfd/mesh/mesh.h"
#include "cfd/io/steady_control.h"
#include "cfd/motion/mesh_motion.h"
#include "cfd/solver/pimple_solver.h"
#include "data/schema/config.h"

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
  // time.steady: the force settled before time.end (steady_change is the
  // relative force range over the window at the last step).
  bool steady_converged = false;
  double steady_change = 0.0;
};

// Everything a case file defines, built and validated (the mesh is owned).
struct Case {
  std::unique_ptr<Mesh> mesh;
  // Prescribed rigid motion of the whole mesh (the `motion:` section), or null.
  std::unique_ptr<RigidMeshMotion> motion;
  std::unique_ptr<PimpleSolver> solver;
  double dt = 0.0;
  double end_time = 0.0;
  double rho = 1000.0;
  std::filesystem::path output_directory;
  int vtu_interval = 0;         // steps; 0 = only the last step, < 0 = never
  int checkpoint_interval = 0;  // steps; 0 = only the last step, < 0 = never
  std::vector<std::string> force_patches;
  // output.captive {length, draft}: ship-axis loads on the force patches in
  // the history (with a motion); length 0 = not requested.
  double captive_length = 0.0;
  double captive_draft = 0.0;
  SteadyControl steady;             // time.steady
  ResistanceReference resistance;   // output.resistance (area filled in)
};

// What a captive campaign sets for each run on top of a case file.
struct CaseOverrides {
  std::optional<MotionOptions> motion;  // the case file must then have no motion: section
  double dt = 0.0;                      // > 0: replaces time.dt (s)
  double end_time = 0.0;                // > 0: replaces time.end (s)
  std::filesystem::path poly_mesh;      // non-empty: replaces mesh.poly_mesh
};

Case LoadCase(const data::ConfigNode& root, const std::filesystem::path& case_dir,
              const CaseOverrides& overrides = {});
RunSummary RunCase(const std::filesystem::path& case_file, const RunOptions& options);

}  // namespace kelvin::cfd
