// Body-force propeller: an actuator disk of given thrust T and torque Q
// spread over the cells of an annular cylinder (docs/formulation.md 6.2).
//
// Conventions (grid axes, body-fixed, as the mesh is built):
//  - `axis` is the direction of the thrust ON THE PROPELLER (for a ship
//    going ahead with x forward: (1, 0, 0)). The force the disk applies to
//    the water is the reaction, -T axis: the water is pushed aft.
//  - `sense` = +1 is a propeller turning right-handed about +axis (angular
//    velocity along +axis; with axis forward that is a right-handed ship
//    propeller, clockwise seen from astern). The blades drag the water
//    round with them: the torque the disk applies to the water is
//    +sense Q axis (the shaft torque the engine delivers).
//  So, summed over the disk cells c, with rho f_c V_c the force on cell c:
//    sum_c rho f_c V_c . axis = -T,
//    sum_c ((x_c - centre) x rho f_c V_c) . axis = +sense Q,
//  exactly (to round-off) on any mesh: the loads are normalized by their
//  discrete sums.
//
// Radial distribution. With r' = r / R, r'_h = r_h / R and
// r* = (r' - r'_h) / (1 - r'_h), the force per unit volume is
//   Hough-Ordway:  f_x ~ r* sqrt(1 - r*),
//                  f_theta ~ r* sqrt(1 - r*) / ((1 - r'_h) r* + r'_h)
//                          = f_x / r'
// (Hough & Ordway 1965, "The generalized actuator disk", Developments in
// Theoretical and Applied Mechanics 2:317-336; the form used by Stern, Kim,
// Patel & Chen 1988, J. Ship Research 32(4):246-262), and
//   uniform:       f_x = const, f_theta ~ 1 / r'
// (constant thrust and torque per unit disk area: the loading of actuator-
// disk momentum theory). Both are uniform through the thickness. The
// tangential force on a cell acts along e_theta = axis x r_hat at its centre.
//
// Cells. A cell belongs to the disk in proportion to the part of its volume
// inside the cylinder r_h <= r <= R, |axial| <= thickness / 2
// (cfd/propulsion/cell_overlap.h, refined to a quarter of the thickness and
// of the annulus width). The cell's axial and tangential loads are the
// sampled integrals of f_x and f_theta over its inside part, so the disk's
// area and the radial distribution do not jump by whole
// cells at its edge. The ratio of the discrete sum to the analytic integral
// over the cylinder (discrete_to_analytic_*) is the discretization's own
// error.
#pragma once

#include <Eigen/Core>

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "cfd/field/field.h"
#include "cfd/mesh/mesh.h"
#include "cfd/parallel/domain_part.h"

namespace kelvin::cfd {

struct ActuatorDiskOptions {
  enum class Distribution { kHoughOrdway, kUniform };
  // Key of the disk in error messages (e.g. "case.yaml: propulsion.propeller").
  std::string name = "propeller";
  Vector3 centre = Vector3::Zero();   // disk centre, body-fixed grid axes (m)
  Vector3 axis = Vector3::UnitX();    // unit thrust direction on the propeller, grid axes
  double diameter = 1.0;              // D = 2R (m)
  double hub_ratio = 0.2;             // r_h / R, in [0, 0.5)
  double thickness = 0.1;             // axial extent of the disk (m), > 0
  Distribution distribution = Distribution::kHoughOrdway;
  int sense = +1;                     // +1 right-handed about +axis, -1 left-handed
  // Fewer disk cells across the diameter than this gives a warning (not an
  // error: coarse grids of a grid study are legitimate).
  double min_cells_across = 10.0;
  // Throws ConfigError naming name.<key> and the value.
  void Validate() const;
};

class ActuatorDisk {
 public:
  // `mesh` must hold its body-fixed geometry (no placement yet); the disk
  // keeps its cells and body-axis directions forever. Throws ConfigError
  // when the disk has no cells (outside the mesh), touches a wall (a disk
  // cell owns a wall face, or a wall face centre lies within the annulus
  // grown by half the adjacent cell's size: the disk overlaps the hull;
  // wall faces within the hub radius grown by half a cell are the shaft
  // boss and allowed) or
  // an option is bad. Warns (spdlog) when fewer than min_cells_across cells
  // span the diameter.
  ActuatorDisk(const Mesh& mesh, ActuatorDiskOptions options);

  // On MPI ranks: a disk built on the undecomposed mesh (the same on every
  // rank) acts on the rank's own cells of it; `n_cells` is the rank's local
  // mesh size, the size of the cell sources. The disk's velocity is then the
  // sum over the ranks (collective). Nothing changes serially.
  void Localize(std::shared_ptr<const DomainPart> part, int n_cells);

  // Adds the body force of thrust T (N) and torque Q (N m) per unit mass
  // (m/s^2, earth axes) to cell_source (sized n_cells; an empty vector is
  // sized first), for the placement rotation R (x_E = R x_B + t).
  void AddBodyForce(double thrust, double torque, double rho, const Eigen::Matrix3d& R,
                    std::vector<Vector3>& cell_source) const;
  // Velocity through the disk relative to it: the component of U - u_body
  // along -axis (positive for a propeller going ahead), averaged over the
  // disk cells with the axial load as weight. body_velocity(cell) is the
  // rigid-body velocity at the cell centre in earth axes (null: at rest).
  double DiskVelocity(const VectorField& U, const std::function<Vector3(int cell)>& body_velocity,
                      const Eigen::Matrix3d& R) const;

  const ActuatorDiskOptions& options() const { return options_; }
  // Disk cells and, per disk cell, the fraction of its volume inside the
  // cylinder and the axial load weight (sum 1).
  const std::vector<int>& cells() const { return cells_; }
  const std::vector<double>& volume_fractions() const { return fraction_; }
  const std::vector<double>& axial_weights() const { return axial_weight_; }
  // Per disk cell: the thrust per unit disk area at the cell for a unit
  // disk thrust (1/m^2): thickness x the cell's axial force density,
  // weight / (fraction V). About 1/A everywhere for a uniform disk without
  // hub (the local loading of annular momentum theory).
  const std::vector<double>& loading_per_unit_thrust() const { return loading_; }
  // The fraction of the cylinder's volume the mesh holds (1, or 1/4 for a
  // disk cut by two symmetry planes through its axis).
  double mesh_share() const;
  // pi D^2 / 4, the area of momentum theory.
  double area() const;
  // The volume of the disk the cells carry (sum of fraction * V).
  double discrete_volume() const { return discrete_volume_; }
  // Discrete sum / analytic integral over the cylinder of f_x and of
  // r f_theta (1 on a perfect discretization; 1/4 for a quarter disk cut
  // by symmetry planes).
  double discrete_to_analytic_thrust() const { return ratio_thrust_; }
  double discrete_to_analytic_torque() const { return ratio_torque_; }
  // D over the typical disk cell size (the cube root of the median volume).
  double cells_across_diameter() const { return cells_across_; }

 private:
  struct CellLoad {
    int cell;
    double fraction;  // of the cell's volume inside the disk
    double axial;     // integral of the unnormalized f_x over the inside part
    double tangential;  // same for f_theta
  };
  std::vector<CellLoad> SampleCells(const Mesh& mesh) const;
  void Normalize(const Mesh& mesh, const std::vector<CellLoad>& loads);
  void CheckWalls(const Mesh& mesh) const;
  void CheckResolution();

  ActuatorDiskOptions options_;
  int n_cells_ = 0;
  std::vector<int> cells_;
  std::shared_ptr<const DomainPart> part_;  // null serially
  OwnedEntries own_;                        // the disk cells this rank holds, and their cells in its mesh
  std::vector<double> fraction_;
  std::vector<double> axial_weight_;      // sum 1
  std::vector<double> tangential_weight_; // sum of weight * r_c is 1 (1/m)
  std::vector<Vector3> e_theta_;          // body axes, unit (zero on the axis)
  std::vector<double> volume_;            // cell volumes V_c
  std::vector<double> loading_;           // thrust per unit disk area per unit thrust (1/m^2)
  double discrete_volume_ = 0.0;
  double ratio_thrust_ = 0.0;
  double ratio_torque_ = 0.0;
  double cells_across_ = 0.0;
};

}  // namespace kelvin::cfd
