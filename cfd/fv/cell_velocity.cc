#include "cfd/fv/cell_velocity.h"

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

}  // namespace kelvin::cfd
