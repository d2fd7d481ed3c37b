#include "cfd/bc/curved_wall_pressure.h"

#include <algorithm>
#include <cmath>

namespace kelvin::cfd {

Vector3 CellVelocityFromFluxes(const Mesh& mesh, std::span<const double> face_flux, int c) {
  const auto offsets = mesh.cell_face_offsets();
  const auto faces = mesh.cell_faces();
  const Vector3& xc = mesh.cell_centres()[c];
  Vector3 sum = Vector3::Zero();
  for (int k = offsets[c]; k < offsets[c + 1]; ++k) {
    const int f = faces[k];
    const double outward = mesh.owner()[f] == c ? face_flux[f] : -face_flux[f];
    sum += outward * (mesh.face_centres()[f] - xc);
  }
  return sum / mesh.cell_volumes()[c];
}

void CurvedWallPressure::Update(const BcContext& ctx, std::span<const double>) {
  const Patch& patch = ctx.patch;
  Resize(patch.size);
  // The mesh moves rigidly: the fit is redone on the placed geometry.
  curvature_.Update(ctx.mesh, patch);
  capped_ = 0;
  for (int i = 0; i < patch.size; ++i) {
    const int f = patch.start + i;
    const Vector3 n = ctx.mesh.face_areas()[f] / ctx.mesh.face_area_magnitudes()[f];
    const double d = 1.0 / DeltaCoeff(ctx.mesh, f);
    double g = 0.0;
    if (!ctx.face_flux.empty()) {
      const Vector3 u = CellVelocityFromFluxes(ctx.mesh, ctx.face_flux, ctx.mesh.owner()[f]);
      const Vector3 ut = u - n * n.dot(u);
      g = ut.dot(curvature_.shape(i) * ut);
      const double cap = 0.5 * ut.squaredNorm() / d;
      if (std::abs(g) > cap) {
        g = std::copysign(cap, g);
        ++capped_;
      }
    }
    vi_[i] = 1.0;
    vb_[i] = g * d;
    gi_[i] = 0.0;
    gb_[i] = g;
  }
}

}  // namespace kelvin::cfd
