// The pose of the body the mesh moves with (docs/formulation.md section 2),
// whatever sets it: a prescribed captive motion (cfd/motion/rigid_motion.h)
// or the body equations of a free-running run (cfd/motion/free_body.h).
//
// Conventions are those of the captive schema: earth axes x0 forward, y0 to
// starboard, heading psi positive to starboard; the CFD grid has z up and y
// to port, so the placement of the body-fixed grid in the z-up earth frame is
//   x_E = c + (x0, -y0, 0) + Rz(-psi) (xi - c),   c = reference point (grid axes).
#pragma once

#include <Eigen/Core>

namespace kelvin::cfd {

// The state of the body at one time.
struct Pose {
  double x0 = 0.0, y0 = 0.0, psi = 0.0;  // earth position (m, starboard +) and heading (rad)
  double dx0 = 0.0, dy0 = 0.0, r = 0.0;  // earth velocity (m/s) and yaw rate (rad/s)
  // Body velocities of the reference point in ship axes (x forward, y
  // starboard): u = dx0 cos psi + dy0 sin psi, v = -dx0 sin psi + dy0 cos psi.
  double u() const;
  double v() const;
  // Placement of the grid in the z-up earth frame (see the file comment).
  Eigen::Matrix3d Rotation() const;                                  // Rz(-psi)
  Eigen::Vector3d Translation(const Eigen::Vector3d& centre) const;  // x_E = R xi + t
  Eigen::Vector3d Velocity() const;                                  // (dx0, -dy0, 0)
  Eigen::Vector3d AngularVelocity() const;                           // (0, 0, -r)
};

class BodyKinematics {
 public:
  virtual ~BodyKinematics() = default;
  // Pose and rates at time t (s). A free body answers for the time of the
  // step in progress (its latest coupling iterate).
  virtual Pose At(double t) const = 0;
  // The reference point (midship) in grid axes (m).
  virtual const Eigen::Vector3d& centre() const = 0;
  // The forward speed that scales the run (m/s): the carriage speed, or the
  // free body's initial speed.
  virtual double nominal_speed() const = 0;
};

}  // namespace kelvin::cfd
