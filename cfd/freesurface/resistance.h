// Steady hull resistance on the linearized free surface
// (docs/lfs-formulation.md sections 3 and 5): pseudo-transient marching to a
// converged state, the resistance split, and the free-surface outputs.
//
// - SteadyConvergence: stops a pseudo-transient run once, over the last
//   window of pseudo-time (one flow-through by default), every monitored
//   force changed by less than `tolerance` times the total resistance and
//   the elevation field eta by less than `tolerance` in the relative L2 norm.
// - Resistance split along the inflow direction d (R = F . d, F the force of
//   the water on the hull): friction R_F (wall shear), pressure R_P, total
//   R_T = R_F + R_P, coefficients by 0.5 rho S U^2 with S the wetted area at
//   rest. The wave-making part is C_W = C_P - C_P(double body), the pressure
//   resistance coefficient of this run minus that of a double-body run on
//   the same grid (its resistance.h5), and R_W = C_W 0.5 rho S U^2. The waterline correction
//   R_WL = d . sum_e 0.5 rho g eta_e^2 n_e over the patch edges on the hull
//   (n_e the in-plane edge normal times the edge length, pointing from the
//   water into the hull: the hydrostatic pressure rho g (eta - z) of the
//   wave crest between z = 0 and z = eta) is reported separately and never
//   added to R_T.
// - Wave cuts: eta along lines y = const, sampled in the patch face that
//   contains each point and reconstructed linearly with the face gradient.
// - Hull wave profile: eta extrapolated to the waterline edges on the hull.
#pragma once

#include <array>
#include <cstddef>
#include <deque>
#include <filesystem>
#include <memory>
#include <limits>
#include <map>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "cfd/freesurface/linearized_free_surface.h"
#include "cfd/freesurface/patch_surface.h"
#include "cfd/solver/pimple_solver.h"
#include "data/schema/config.h"

namespace kelvin::cfd {

class SteadyConvergence {
 public:
  // window: pseudo-time (s) over which the change is measured; tolerance:
  // relative change (e.g. 1e-3); min_steps: the window also spans at least
  // this many steps (at Courant 100 one flow-through is only a few steps).
  // Throws ConfigError on bad values.
  SteadyConvergence(double window, double tolerance, int min_steps = 1);

  // Adds the state at pseudo-time `time`: the monitored forces (N; the first
  // is the total resistance, the scale of all force changes) and the field
  // eta (empty for a double-body run).
  void Add(double time, std::span<const double> forces, std::span<const double> eta);

  // True once the history spans a full window and the largest change within
  // it is below the tolerance for the forces and for eta.
  bool Converged() const;
  // Largest relative change over the current window (forces by |R_T|, eta in
  // the L2 norm by |eta|); NaN until a full window is available.
  double force_change() const { return force_change_; }
  double eta_change() const { return eta_change_; }
  double window() const { return window_; }
  double tolerance() const { return tolerance_; }

 private:
  struct Sample {
    double time;
    std::vector<double> forces;
    std::vector<double> eta;
  };
  double window_;
  double tolerance_;
  int min_steps_;
  std::deque<Sample> samples_;
  double force_change_;
  double eta_change_;
};

// Elevation along the line y = y0 at the given x stations; NaN where the
// point lies outside the patch (e.g. inside the hull's waterplane).
std::vector<double> WaveCut(const PatchSurface& surface, std::span<const double> eta, double y0,
                            std::span<const double> x);

struct WaveProfile {
  std::vector<double> x, y, eta;  // per waterline edge on the hull, sorted by (side, x)
};
// eta at the edges of the patch that lie on mesh patch `hull_patch`,
// extrapolated from the face with its least-squares gradient.
WaveProfile HullWaveProfile(const PatchSurface& surface, std::span<const double> eta, int hull_patch);

// Waterline-integral force (N, mesh axes) on the hull: sum over the hull rim
// edges of 0.5 rho g eta_e^2 n_e (see above); eta_e as in HullWaveProfile.
Vector3 WaterlineForce(const PatchSurface& surface, std::span<const double> eta, int hull_patch, double rho,
                       double g);

// What the `resistance:` section of a case file asks for.
struct ResistanceOptions {
  std::string hull_patch = "hull";
  std::string free_surface_patch;  // empty: double body (no eta)
  Vector3 inflow = Vector3::Zero();  // m/s; speed |inflow|, direction d = inflow / |inflow|
  double rho = 1000.0;
  double g = 9.81;
  double wetted_area = 0.0;  // m^2; 0: area of the hull patch (wetted surface at rest)
  double length = 0.0;       // m; > 0: Froude and Reynolds numbers in the report
  double nu = 0.0;           // m^2/s (for the Reynolds number)
  std::vector<double> wave_cut_y;  // m
  int wave_cut_points = 400;
  std::filesystem::path double_body;  // resistance.h5 of a double-body run on the same grid (optional)
  // Pseudo-transient marching.
  double tolerance = 1e-3;
  double window = 0.0;       // s; 0: one flow-through (domain length along d / speed)
  double min_windows = 2.0;  // no stop before this many windows of pseudo-time
  int window_steps = 20;     // the window spans at least this many steps
  // Start from the uniform inflow (not on restart). Off by default: on the
  // Wigley wall-function grid the uniform start diverged within 4 steps at
  // Courant 30 where the start from rest with the time-step ramp did not.
  bool initial_velocity = false;
  // Time step ramps linearly from dt / ramp_steps to dt, at the start and
  // again when the rigid lid is released.
  int ramp_steps = 0;
  // Pseudo-time (in windows) of the rigid-lid start: the free surface passes
  // no flux (double-body flow) until then and is released with eta = 0. An
  // impulsive start with the surface free raised a 1.5 m bow wave on the 6 m
  // Wigley at Fn 0.316 (stagnation head 0.3 m) and diverged; released from
  // the double-body flow it converged. 0: free from the first step. Skipped
  // on a restart unless the checkpoint was written during the rigid phase.
  double rigid_lid_windows = 0.0;
};

class ResistanceMonitor {
 public:
  // Resolves the patches and the scales; throws ConfigError naming the
  // option on a bad value.
  ResistanceMonitor(const PimpleSolver& solver, ResistanceOptions options);

  // Before the time loop: the uniform initial field (unless restarted).
  // `checkpoint`: the run scalars of the checkpoint restarted from (see
  // CheckpointScalars()).
  void Start(PimpleSolver& solver, bool restarted, const std::map<std::string, double>& checkpoint = {});
  // What a checkpoint must keep for a restarted run to report as the
  // uninterrupted one: the lid release time, once released.
  std::map<std::string, double> CheckpointScalars() const;
  // Time step of the next step for the case's dt (the ramp).
  double TimeStep(double dt) const;
  // After each step: pressure and viscous force on the hull (N, mesh axes).
  // Returns true once the run has converged.
  bool Record(const PimpleSolver& solver, const Vector3& pressure, const Vector3& viscous);
  // Writes resistance.h5 (coefficients, split, history, wave cuts and hull
  // profile) and returns a one-paragraph summary for the run report.
  std::string Write(const std::filesystem::path& file, const PimpleSolver& solver) const;

  bool converged() const { return converged_; }
  // Pseudo-time at which the rigid lid was released (NaN: not yet, or never held).
  double release_time() const { return release_time_; }
  int hull_patch() const { return hull_; }
  double speed() const { return speed_; }
  double wetted_area() const { return area_; }
  // Unit inflow direction: the resistance is the hull force along it.
  const Vector3& direction() const { return direction_; }

 private:
  const LinearizedFreeSurface* FreeSurface(const PimpleSolver& solver) const;
  // Starts a phase (the run, or the free surface after the rigid lid):
  // convergence window, minimum duration and time-step ramp count from here.
  void StartPhase(double time);

  ResistanceOptions options_;
  int hull_ = -1;
  int free_surface_ = -1;
  Vector3 direction_ = Vector3::Zero();
  double speed_ = 0.0;
  double area_ = 0.0;
  double flow_through_ = 0.0;
  double start_time_ = 0.0;
  int phase_steps_ = 0;
  bool started_ = false;
  LinearizedFreeSurface* lid_ = nullptr;  // the surface while it is held rigid
  double rigid_until_ = 0.0;
  double release_time_ = std::numeric_limits<double>::quiet_NaN();
  std::optional<SteadyConvergence> convergence_;
  bool converged_ = false;
  int converged_step_ = -1;
  // History per recorded step: time, R_T, R_F, R_P, R_WL, force change, eta change.
  std::vector<std::array<double, 7>> history_;
};

// The `resistance:` section of a case file (see cfd/README.md):
//   resistance:
//     hull: hull                  # wall patch whose force is the resistance
//     free_surface: freeSurface   # linearizedFreeSurface patch (omit: double body)
//     inflow: [-2.42, 0, 0]       # m/s: speed and direction of the resistance
//     wetted_area: 5.9            # m^2 (default: area of the hull patch)
//     length: 6                   # m (Fn and Re in the report)
//     wave_cuts: [0.6, 1.2]       # y of the wave cuts (m)
//     wave_cut_points: 400
//     double_body: ../db/resistance.h5   # for the wave-making part
//     steady: {tolerance: 1.0e-3, window: 0, window_steps: 20, min_windows: 2, initial_velocity: false,
//              ramp_steps: 10, rigid_lid_windows: 1}
// rho and nu come from `physics`, g from the free surface. Throws
// ConfigError naming the key.
std::unique_ptr<ResistanceMonitor> LoadResistance(const data::ConfigNode& node, const PimpleSolver& solver,
                                                  const data::ConfigNode& physics,
                                                  const std::filesystem::path& case_dir);

}  // namespace kelvin::cfd
