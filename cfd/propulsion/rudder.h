// Body-force rudder: a lifting surface driven by the inflow the CFD gives
// at the rudder, plus the deflection (docs/formulation.md 6.3).
//
// Geometry (body-fixed grid axes: x forward, y to port, z up). A
// rectangular blade of span H_R and chord c = A_R / H_R (the ship file's
// area and span), its mid-chord point on the stock at (x_R, y_R) and its
// span from z_top - H_R to z_top. Positive delta turns the trailing edge to
// starboard, which turns the ship to starboard (the simulator's convention,
// simulator/mmg/mmg_model.h). The normal force F_N acts on the blade along
// n = (-sin delta, cos delta, 0) in grid axes: in ship axes (y to
// starboard) the rudder's load is X = -F_N sin delta, Y = -F_N cos delta,
// as MMG writes it before its interaction factors (1 - t_R), (1 + a_H), x_H:
// in the CFD those come out of the flow around the hull.
//
// Lift model. With the effective inflow (u_R from ahead, v_R towards
// starboard, both relative to the moving blade, the blade's own induced
// velocity removed; see below),
//   alpha_R = delta - atan2(v_R, u_R),   U_R^2 = u_R^2 + v_R^2,
//   F_N = 1/2 rho A_R U_R^2 C_N(alpha_R),
//   C_N = f_alpha sin(alpha_R) for |alpha_R| <= alpha_stall, held at
//         f_alpha sin(alpha_stall) beyond (a plateau: no post-stall drop),
//   f_alpha = 6.13 Lambda / (Lambda + 2.25),  Lambda = H_R^2 / A_R,
// the lift slope of Fujii & Tsuda (1961), "Experimental researches on rudder
// performance (2)", J. Zosen Kiokai 110:31-42 (the form MMG uses: Yasukawa &
// Yoshimura 2015, J. Mar. Sci. Technol. 20:37-52), unless the case gives
// its own.
//
// Body force. F_N is spread uniformly over the blade's box (span x chord x
// thickness, turned about the stock to delta), each cell weighted by the
// part of its volume inside (cfd/propulsion/cell_overlap.h): the water gets
// -F_N n in total, exactly. The box is sampled at construction every 5 deg
// up to max_angle and the two positions around delta are blended linearly
// (so the distribution moves smoothly with the blade, and a restart needs
// nothing but delta). An undeflected box at large angles carries the
// streamwise part F_N sin delta on a frontal area of only the thickness:
// in a uniform stream at 30 deg it blocked the flow ahead and F_N came out
// 10% low (tests/cfd/propulsion/rudder_test.cc).
//
// Inflow. The relative velocity U - u_body is averaged (volume weights)
// over a sample box ahead of the leading edge: the blade's span and
// thickness, sample_length chords long, centred sample_distance chords
// ahead. There it holds the hull's wake and flow straightening and the
// propeller's race, and also the blade's own induced velocity (the upwash
// of its bound vorticity and the blockage of its drag), which the lift
// curve already accounts for and must not see twice. That part is removed
// with the linearized inviscid response to the blade's body force: for a
// point force F on the water at the origin in a stream of speed U along the
// unit vector e, U de/dx = -grad p / rho + F delta(x) and div u = 0 give
// p = F . x / (4 pi |x|^3), and upstream of the force (outside its wake)
//   u(x) = -grad G(x) / (rho U),
//   G = (1 / 4 pi) [ -F_e / r + (F_perp . b) / (r (r - a)) ],
// with a = x . e, b = x - a e, r = |x|, F_e = F . e, F_perp = F - F_e e:
// the horseshoe vortex of the lateral force (bound vortex and trailing
// legs) and the source of the streamwise force. It is summed over the
// blade's cells (and their images in the waterline z = 0 with
// waterline_image, the low-Froude limit of the free surface) at the sample
// cells, with the force of the previous Update (the one the flow holds) and
// e = -x (the stream from ahead).
#pragma once

#include <Eigen/Core>

#include <functional>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "cfd/motion/ship_forces.h"
#include "cfd/solver/pimple_solver.h"

namespace kelvin::cfd {

struct RudderOptions {
  std::string name = "rudder";  // key in error messages
  double area = 0.0;            // A_R (m^2)
  double span = 0.0;            // H_R (m)
  Vector3 stock = Vector3::Zero();  // mid-chord at the blade's top: (x_R, y_R, z_top), grid axes (m)
  double thickness = 0.2;           // blade box thickness / chord
  double sample_distance = 1.0;     // chords from the leading edge to the sample box centre
  double sample_length = 0.25;      // chords, streamwise extent of the sample box
  double lift_slope = 0.0;          // f_alpha (1/rad); 0: Fujii's from the aspect ratio
  double stall_angle = 35.0 * 3.14159265358979323846 / 180.0;  // rad
  double max_angle = 35.0 * 3.14159265358979323846 / 180.0;    // rad, the largest blade angle (the ship's limit)
  bool waterline_image = false;     // image of the blade in z = 0 for the induced velocity
  double force_relaxation = 0.7;    // F_N <- F_N + relaxation (F_N,new - F_N) from the second Update
  // Fewer blade cells across the chord than this gives a warning.
  double min_cells_across = 4.0;
  double chord() const { return area / span; }
  double aspect_ratio() const { return span * span / area; }
  void Validate() const;  // throws ConfigError naming name.<key>
};

// Fujii & Tsuda's lift slope f_alpha (1/rad) for the aspect ratio Lambda.
double FujiiLiftSlope(double aspect_ratio);

// One Update: what a history row needs.
struct RudderState {
  double delta = 0.0;     // rad, the blade angle
  double u_R = 0.0;       // m/s, effective inflow from ahead
  double v_R = 0.0;       // m/s, effective inflow towards starboard
  double alpha_R = 0.0;   // rad, effective angle of attack
  double F_N = 0.0;       // N, normal force on the blade (relaxed: the one applied)
  double u_sample = 0.0;  // m/s, sampled inflow from ahead before the induced velocity is removed
  double v_sample = 0.0;  // m/s, the same towards starboard
};

class Rudder {
 public:
  using BodyVelocity = std::function<Vector3(int cell)>;
  // The angle of attack up to which the body-force blade's normal force is
  // validated: within 1% of the lift curve in a uniform stream on two grids
  // (5 and 10 cells across the chord). Beyond it the blade's own blockage
  // outgrows the linearized induced velocity removed from the sample: -3.0%
  // at 25 deg and -7.2% at 30 deg with 10 cells across, -2.3% at 30 deg with
  // 5 (BENCHMARKS.md rudder_stream); runs that go beyond it are told so.
  static constexpr double kValidatedAngle = 20.0 * 3.14159265358979323846 / 180.0;  // rad
  // `mesh` must hold its body-fixed geometry. Throws ConfigError when the
  // blade or the sample box holds no cell (outside the mesh), when a blade
  // cell owns a wall face (the blade inside or against the hull), or for a
  // bad option. Warns when the chord spans fewer than min_cells_across cells.
  Rudder(const Mesh& mesh, RudderOptions options);

  // On MPI ranks: a rudder built on the undecomposed mesh (the same on every
  // rank) samples and loads the rank's own cells of it; `n_cells` is the
  // rank's local mesh size. The sampled inflow is then the sum over the
  // ranks (collective). Nothing changes serially.
  void Localize(std::shared_ptr<const DomainPart> part, int n_cells);

  // The model's normal-force coefficient C_N(alpha) (the lift curve).
  double NormalForceCoefficient(double alpha) const;
  // Samples the inflow, computes F_N at blade angle delta (rad) and adds the
  // body force to cell_source (an empty vector is sized first) for the
  // placement rotation R.
  RudderState Update(const PimpleSolver& solver, const BodyVelocity& body_velocity, const Eigen::Matrix3d& R,
                     double delta, double rho, std::vector<Vector3>& cell_source);
  // The blade's load on the body, ship axes about `centre` (grid axes).
  PlanarLoad BodyLoad(const RudderState& state, const Vector3& centre) const;

  // What a checkpoint needs for a bit-for-bit restart: the applied load.
  struct State {
    double F_N = 0.0;
    double delta = 0.0;
    bool started = false;
  };
  State GetState() const { return state_; }
  void SetState(const State& state) { state_ = state; }
  // Adds the body force of the state's load (a restart restores the cell
  // source the solver had).
  void ApplyState(double rho, const Eigen::Matrix3d& R, std::vector<Vector3>& cell_source) const;

  const RudderOptions& options() const { return options_; }
  double lift_slope() const { return lift_slope_; }
  const std::vector<int>& sample_cells() const { return sample_cells_; }
  // The blade's volume the cells carry over the box's, amidships (1 when
  // the mesh holds the whole blade).
  double blade_share() const { return blade_share_; }
  // Chord over the typical blade cell size.
  double cells_across_chord() const { return cells_across_; }
  // Blade centroid, grid axes.
  Vector3 centroid() const;

 private:
  // The blade's cells at one tabulated angle.
  struct BladePosition {
    double angle = 0.0;
    std::vector<int> cells;
    std::vector<double> weights;  // share of the force per cell (sum 1)
    std::vector<double> volumes;
    // Sample-mean induced velocity per unit force on the water (columns:
    // unit force along grid x, y, z), times rho U: u = M F / (rho U).
    Eigen::Matrix3d induced = Eigen::Matrix3d::Zero();
    OwnedEntries own;  // the cells this rank holds, and their cells in its mesh
  };
  // The tabulated positions k, k + 1 around delta and the blend s in [0, 1].
  std::pair<std::size_t, double> Bracket(double delta) const;
  Eigen::Matrix3d Induced(double delta) const;
  void Apply(double F_N, double delta, double rho, const Eigen::Matrix3d& R, std::vector<Vector3>& cell_source) const;
  void CheckWalls(const Mesh& mesh, const BladePosition& pos) const;

  RudderOptions options_;
  double lift_slope_ = 0.0;
  int n_cells_ = 0;
  std::vector<BladePosition> positions_;  // -max_angle ... max_angle by 5 deg
  std::vector<int> sample_cells_;
  std::vector<double> sample_weight_;  // volume weights (sum 1)
  OwnedEntries sample_own_;
  std::shared_ptr<const DomainPart> part_;  // null serially
  double blade_share_ = 0.0;
  double cells_across_ = 0.0;
  State state_;
};

}  // namespace kelvin::cfd
