// Loads a YAML case file into a ready solver (`kelvin run`, captive runs):
// sections mesh / physics / schemes / solution / time / turbulence /
// boundary / motion / output / resistance. A bad key, an unknown patch or a
// patch without a condition is one ConfigError naming the file, line and key.
#pragma once

#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "cfd/io/steady_control.h"
#include "cfd/mesh/mesh.h"
#include "cfd/motion/mesh_motion.h"
#include "cfd/solver/pimple_solver.h"
#include "data/schema/config.h"

namespace kelvin::cfd {

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

}  // namespace kelvin::cfd
