#include "cfd/motion/mesh_motion.h"

#include "data/schema/errors.h"

namespace kelvin::cfd {

RigidMeshMotion::RigidMeshMotion(Mesh& mesh, RigidMotion motion)
    : RigidMeshMotion(mesh, std::make_shared<const RigidMotion>(std::move(motion))) {
  prescribed_ = static_cast<const RigidMotion*>(body_.get());
}

RigidMeshMotion::RigidMeshMotion(Mesh& mesh, std::shared_ptr<const BodyKinematics> body)
    : mesh_(mesh), body_(std::move(body)) {
  KELVIN_CHECK(body_ != nullptr, "a body for the rigid mesh motion");
  KELVIN_CHECK(
      mesh.placement_rotation().isIdentity(0.0) && mesh.placement_translation().isZero(0.0),
      "a rigid mesh motion starts from the body-fixed geometry");
  const Vector3& c = body_->centre();
  const auto points = mesh.points();
  body_face_areas_.assign(mesh.face_areas().begin(), mesh.face_areas().end());
  face_moment_.assign(mesh.n_faces(), Vector3::Zero());
  // The same triangles as Mesh::ComputeGeometry: one for a triangle, a fan
  // around the point average otherwise.
  for (int f = 0; f < mesh.n_faces(); ++f) {
    const std::span<const int> fp = mesh.face(f);
    const std::size_t n = fp.size();
    Vector3 m = Vector3::Zero();
    if (n == 3) {
      const Vector3 &a = points[fp[0]], &b = points[fp[1]], &d = points[fp[2]];
      m = ((a + b + d) / 3.0 - c).cross(0.5 * (b - a).cross(d - a));
    } else {
      Vector3 mid = Vector3::Zero();
      for (int p : fp) mid += points[p];
      mid /= static_cast<double>(n);
      for (std::size_t i = 0; i < n; ++i) {
        const Vector3& a = points[fp[i]];
        const Vector3& b = points[fp[(i + 1) % n]];
        m += ((a + b + mid) / 3.0 - c).cross(0.5 * (b - a).cross(mid - a));
      }
    }
    face_moment_[f] = m;
  }
}

void RigidMeshMotion::MeshFlux(const Pose& pose, std::vector<double>& mesh_flux) const {
  const Eigen::Matrix3d R = pose.Rotation();
  const Vector3 v_body = R.transpose() * pose.Velocity();
  const Vector3 w_body = R.transpose() * pose.AngularVelocity();
  mesh_flux.resize(mesh_.n_faces());
  for (int f = 0; f < mesh_.n_faces(); ++f) {
    mesh_flux[f] = v_body.dot(body_face_areas_[f]) + w_body.dot(face_moment_[f]);
  }
}

void RigidMeshMotion::Apply(double t, std::vector<double>& mesh_flux) const {
  const Pose pose = body_->At(t);
  mesh_.SetPlacement(pose.Rotation(), pose.Translation(body_->centre()));
  MeshFlux(pose, mesh_flux);
}

Vector3 RigidMeshMotion::CentreAt(const Pose& pose) const {
  return pose.Rotation() * body_->centre() + pose.Translation(body_->centre());
}

MovingWall::Motion RigidMeshMotion::WallMotion(double t) const {
  const Pose pose = body_->At(t);
  MovingWall::Motion m;
  m.velocity = pose.Velocity();
  m.angular_velocity = pose.AngularVelocity();
  m.centre = CentreAt(pose);
  return m;
}

Vector3 RigidMeshMotion::PointVelocity(const Vector3& x, double t) const {
  const Pose pose = body_->At(t);
  return pose.Velocity() + pose.AngularVelocity().cross(x - CentreAt(pose));
}

void RigidMeshMotion::Attach(PimpleSolver& solver) const {
  solver.SetMeshMotion([this](double t, std::vector<double>& mesh_flux) { Apply(t, mesh_flux); });
}

}  // namespace kelvin::cfd
