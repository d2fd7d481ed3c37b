// The one reader of a YAML case file (`kelvin run`, captive runs, `kelvin
// gci`); cfd/README.md lists its sections and keys:
//   mesh / physics / reference / schemes / solution / time / turbulence /
//   boundary / motion / output / resistance / partition
// Each section is read once into its component's Options (defaults live in
// those structs). ReadCaseSettings reads what needs no mesh; LoadCase builds
// the mesh, the conditions and the solver on top. A bad key, an unknown
// patch, a patch without a condition or a key of an older layout is one
// ConfigError naming the file, line and key and what is expected.
#pragma once

#include <filesystem>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "cfd/motion/free_body.h"
#include "cfd/motion/mesh_motion.h"
#include "cfd/parallel/domain_part.h"
#include "cfd/parallel/partition.h"
#include "cfd/run/body_actuator.h"
#include "cfd/run/free_running_loader.h"
#include "cfd/run/maneuver_settings.h"
#include "cfd/run/time_control.h"
#include "cfd/solver/pimple_solver.h"
#include "data/schema/config.h"

namespace kelvin::cfd {

class LinearizedFreeSurface;

// `reference:` the scales of coefficients, prime loads and flow-throughs.
struct CaseReference {
  double speed = 0.0;                    // m/s; 0: none
  Vector3 direction = Vector3(1, 0, 0);  // unit drag direction: that of the flow past the hull
  double area = 0.0;                     // m^2; 0: the area of output.forces patches
  double length = 0.0;                   // m; 0: none (Fn, Re, prime system)
  double draft = 0.0;                    // m; 0: none (prime system)
  Vector3 velocity() const { return speed * direction; }
};

// `output:`.
struct OutputOptions {
  std::filesystem::path directory = "results";
  int vtu_interval = 0;         // steps; 0 = only the last step, < 0 = never
  int checkpoint_interval = 0;  // steps; 0 = only the last step, < 0 = never
  std::vector<std::string> force_patches;
  bool captive = false;         // ship-axis loads of the force patches (output.captive)
};

// `resistance:` the steady resistance report (cfd/run/resistance_monitor.h).
struct ResistanceOptions {
  std::string hull_patch = "hull";
  std::string free_surface_patch;  // empty: double body (no eta)
  std::vector<double> wave_cut_y;  // m
  int wave_cut_points = 400;
  std::filesystem::path double_body;  // resistance.h5 of a double-body run on the same grid (optional)
  void Validate() const;
};

// What a case file sets that needs no mesh.
struct CaseSettings {
  std::filesystem::path file;
  double nu = 0.0;     // m^2/s
  double rho = 1000.0;  // kg/m^3
  std::optional<Vector3> body_force;  // m/s^2, uniform momentum source
  CaseReference reference;
  TimeControlOptions time;  // end may be 0 until the motion or a campaign sets it
  OutputOptions output;
  std::optional<ResistanceOptions> resistance;
  bool free_surface = false;  // some patch has a linearizedFreeSurface pressure
  PartitionOptions partition;  // `partition:` how a run on MPI ranks cuts the mesh
};

// Reads `physics`, `reference`, `time`, `output` and `resistance` (and
// refuses the keys of older layouts).
CaseSettings ReadCaseSettings(const data::ConfigNode& root, const std::filesystem::path& case_dir);

// Everything a case file defines, built and validated (the mesh is owned).
// On MPI ranks (CaseOverrides::ranks) `mesh` is the rank's local mesh
// (cfd/parallel/decompose.h), `part` the rank's part, and `whole_mesh` the
// undecomposed mesh while the case is set up (the actuators find their cells
// on it), released by every rank once loaded; `whole_mesh_quality` is its
// quality report on rank 0. Serially they are null and empty.
struct Case {
  CaseSettings settings;
  std::unique_ptr<Mesh> mesh;
  std::unique_ptr<Mesh> whole_mesh;
  std::string whole_mesh_quality;
  std::shared_ptr<const DomainPart> part;
  // Rigid motion of the whole mesh (the `motion:` section): prescribed, or
  // of the free body; null without a motion.
  std::unique_ptr<RigidMeshMotion> motion;
  // A free-running run (`motion: {kind: free}`): the body the mesh follows,
  // its settings and the mesh indices of its hull patches.
  std::shared_ptr<FreeBody> free_body;
  std::optional<FreeRunningSettings> free_running;
  std::vector<int> hull_patches;
  // What acts on the free body through the flow (`propeller:`).
  std::vector<std::unique_ptr<BodyActuator>> actuators;
  std::optional<ManeuverPilotSettings> maneuver;  // flown by cfd/run/maneuver_pilot.h
  std::unique_ptr<PimpleSolver> solver;
  LinearizedFreeSurface* free_surface = nullptr;  // the pressure condition that owns eta, or null
  std::vector<int> force_patches;                 // mesh indices of output.forces
};

// What a captive campaign sets for each run on top of a case file.
struct CaseOverrides {
  std::optional<MotionOptions> motion;  // the case file must then have no motion: section
  double dt = 0.0;                      // > 0: replaces time.dt (s)
  double end_time = 0.0;                // > 0: replaces time.end (s)
  std::filesystem::path poly_mesh;      // non-empty: replaces mesh.poly_mesh
  std::filesystem::path output;         // non-empty: replaces output.directory
  std::optional<SteadyOptions> steady;  // replaces time.steady (window in seconds)
  std::string maneuver;                 // non-empty: replaces maneuver.kind (kelvin run -m)
  // The ranks the run is decomposed over: MPI_COMM_NULL or a communicator of
  // one rank runs serially. Collective over it.
  MPI_Comm ranks = MPI_COMM_NULL;
};

Case LoadCase(const data::ConfigNode& root, const std::filesystem::path& case_dir,
              const CaseOverrides& overrides = {});
Case LoadCaseFile(const std::filesystem::path& case_file, const CaseOverrides& overrides = {});

// Total face area of the patches (m^2).
double PatchArea(const Mesh& mesh, std::span<const int> patches);
// One flow-through (s): the mesh extent along reference.direction / reference.speed.
// On MPI ranks (`part`) the extent of the whole mesh (collective).
double FlowThroughTime(const Mesh& mesh, const CaseReference& reference, const DomainPart* part = nullptr);

}  // namespace kelvin::cfd
