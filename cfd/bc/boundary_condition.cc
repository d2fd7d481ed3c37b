#include "cfd/bc/boundary_condition.h"

namespace kelvin::cfd {

void MovingWall::Update(const BcContext& ctx, std::span<const Vector3>) {
  Resize(ctx.patch.size);
  const Motion m = motion_(ctx.time);
  for (int i = 0; i < ctx.patch.size; ++i) {
    const int f = ctx.patch.start + i;
    const Vector3& x = ctx.mesh.face_centres()[f];
    SetFixed(i, DeltaCoeff(ctx.mesh, f), m.velocity + m.angular_velocity.cross(x - m.centre));
  }
}

void Slip::Update(const BcContext& ctx, std::span<const Vector3> cell_values) {
  Resize(ctx.patch.size);
  for (int i = 0; i < ctx.patch.size; ++i) {
    const int f = ctx.patch.start + i;
    const Vector3 n = ctx.mesh.face_areas()[f] / ctx.mesh.face_area_magnitudes()[f];
    const Vector3& u = cell_values[ctx.mesh.owner()[f]];
    const double dc = DeltaCoeff(ctx.mesh, f);
    // Diagonal part implicit, the off-diagonal part of (I - n n) explicit.
    const Vector3 nn = n.cwiseProduct(n);
    vi_[i] = Vector3::Ones() - nn;
    vb_[i] = (u - n * n.dot(u)) - vi_[i].cwiseProduct(u);
    gi_[i] = -dc * nn;
    gb_[i] = -dc * (n * n.dot(u) - nn.cwiseProduct(u));
  }
}

}  // namespace kelvin::cfd
