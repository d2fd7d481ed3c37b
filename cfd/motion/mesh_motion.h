// Rigid motion of the whole mesh with the hull (docs/formulation.md
// section 2): the earth-frame geometry follows from the pose each step and the
// mesh flux is exact for the rigid-body velocity u_b = U0 + omega x (x - x0).
//
// The mesh flux of face f is the integral of u_b . n over the face. u_b is
// affine, so on the triangles the mesh fans each face into (the same ones
// that define its area vector and centre) the integral is exact:
//   F_b,f = V_B . S_f^B + omega_B . M_f,   M_f = sum_tri (c_tri - c) x S_tri,
// with V_B and omega_B the velocity of the reference point c and the angular
// velocity in grid axes and S^B, M_f body-fixed constants. Over a closed cell
// both sum_f S_f and sum_f M_f vanish to round-off (the triangles close the
// cell), so the space conservation law holds exactly with constant volumes.
#pragma once

#include <memory>
#include <vector>

#include "cfd/bc/boundary_condition.h"
#include "cfd/mesh/mesh.h"
#include "cfd/motion/rigid_motion.h"
#include "cfd/solver/pimple_solver.h"

namespace kelvin::cfd {

class RigidMeshMotion {
 public:
  // `mesh` must still hold its body-fixed geometry (no placement yet); it is
  // moved by Apply() and must outlive this object. The body is a prescribed
  // motion or a free body (cfd/motion/free_body.h).
  RigidMeshMotion(Mesh& mesh, RigidMotion motion);
  RigidMeshMotion(Mesh& mesh, std::shared_ptr<const BodyKinematics> body);

  // Places the mesh at the pose of time t and writes F_mesh on every face.
  void Apply(double t, std::vector<double>& mesh_flux) const;
  // Mesh flux of a pose (the mesh placement is not touched).
  void MeshFlux(const Pose& pose, std::vector<double>& mesh_flux) const;
  // The wall velocity of the body at time t, for MovingWall.
  MovingWall::Motion WallMotion(double t) const;
  // Earth position (z-up frame) of the reference point at `pose`.
  Vector3 CentreAt(const Pose& pose) const;
  // Rigid-body velocity u_b = V + Omega x (x - c) at the earth-frame point x
  // (z-up frame) at time t.
  Vector3 PointVelocity(const Vector3& x, double t) const;

  const BodyKinematics& body() const { return *body_; }
  // The prescribed motion, or null for a free body.
  const RigidMotion* prescribed() const { return prescribed_; }
  const Mesh& mesh() const { return mesh_; }
  // Body-fixed first moments M_f of the face areas about the reference point.
  const std::vector<Vector3>& face_moments() const { return face_moment_; }

  // Connects Apply() to the solver's moving-mesh stage.
  void Attach(PimpleSolver& solver) const;

 private:
  Mesh& mesh_;
  std::shared_ptr<const BodyKinematics> body_;
  const RigidMotion* prescribed_ = nullptr;
  std::vector<Vector3> body_face_areas_;
  std::vector<Vector3> face_moment_;
};

}  // namespace kelvin::cfd
