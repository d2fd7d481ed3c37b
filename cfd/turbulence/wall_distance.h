// Distance to the nearest wall for the SST blending functions, from the
// solution of a Poisson equation (Tucker 2003, "Differential equation-based
// wall distance computation for DES and RANS", J. Comput. Phys. 190:229;
// also OpenFOAM's `Poisson` wallDist method):
//   lap(phi) = -1, phi = 0 on walls, zero gradient elsewhere,
//   d = sqrt(|grad phi|^2 + 2 phi) - |grad phi|,
// exact for a single plane wall and accurate near any wall, which is where
// the blending functions need it. Cells next to a wall get the exact normal
// distance of their centre to the wall face (the wall functions use it).
#pragma once

#include <vector>

#include "cfd/mesh/mesh.h"
#include "cfd/parallel/domain_part.h"

namespace kelvin::cfd {

// `wall_patches` lists patch indices. Returns one distance per cell (m),
// ghost cells included on a decomposed mesh (`part`, null: serial).
// Throws ConfigError when the list is empty.
std::vector<double> WallDistance(const Mesh& mesh, const std::vector<int>& wall_patches,
                                 const DomainPart* part = nullptr);

}  // namespace kelvin::cfd
