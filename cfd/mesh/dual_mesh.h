// Polyhedral mesh generator: the median dual of a triangulated rectangle,
// extruded in z. Each cell is a polygonal prism around one vertex of a
// structured triangulation (diagonals alternate, so cells have 4 to 12 side
// faces and the interior side faces are kinked six-point faces). Interior
// vertices can be randomly perturbed. Patches: xmin, xmax, ymin, ymax, zmin,
// zmax.
#pragma once

#include <array>

#include "cfd/mesh/mesh.h"

namespace kelvin::cfd {

struct DualMeshOptions {
  Vector3 min = Vector3(0, 0, 0);  // m
  Vector3 max = Vector3(1, 1, 1);  // m
  // Triangulation intervals along x and y (cells = (nx + 1)(ny + 1) per
  // layer) and layers along z.
  std::array<int, 3> divisions = {8, 8, 1};
  double perturbation = 0.0;  // of the vertex spacing, interior vertices only
  unsigned seed = 1;
  std::array<PatchKind, 6> kinds = {PatchKind::kWall, PatchKind::kWall, PatchKind::kWall,
                                    PatchKind::kWall, PatchKind::kWall, PatchKind::kWall};
  void Validate() const;
};

Mesh MakeDualMesh(const DualMeshOptions& options);

}  // namespace kelvin::cfd
