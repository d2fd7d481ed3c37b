// The velocity of a cell from the volume fluxes through its faces, for
// conditions that see the fluxes but not the velocity field (the curved-wall
// pressure, the local-flow free surface).
#pragma once

#include <span>

#include "cfd/mesh/mesh.h"

namespace kelvin::cfd {

// u = sum_f F_f (x_f - x_c) / V with F outward from c: the cell mean of a
// solenoidal flow (sum_f F_f (x_f - x_c) is the integral of
// div(u (x) (x - x_c)) = u + (x - x_c) div u), exact at the centroid for a
// linear one. In the mesh frame when the fluxes are relative to the mesh.
Vector3 CellVelocityFromFluxes(const Mesh& mesh, std::span<const double> face_flux, int c);

}  // namespace kelvin::cfd
