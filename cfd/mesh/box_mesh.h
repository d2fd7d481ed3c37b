// Built-in graded box mesh generator. Patches are named xmin, xmax, ymin,
// ymax, zmin, zmax. Optional random perturbation of the interior points
// (skewed, non-orthogonal hexahedra) and an optional polyhedral variant where
// every other block is split 2x2x2 (2x2x1 in 2D), so the unsplit blocks become
// polyhedra with split faces, as snappyHexMesh writes them. An optional block
// obstacle (a range of blocks removed) gives a body in a box: its faces form
// the wall patch `obstacle`.
#pragma once

#include <array>

#include "cfd/mesh/mesh.h"

namespace kelvin::cfd {

struct BoxMeshOptions {
  Vector3 min = Vector3(0, 0, 0);  // m
  Vector3 max = Vector3(1, 1, 1);  // m
  std::array<int, 3> cells = {10, 10, 10};
  // Ratio of the last to the first cell size along each axis (OpenFOAM's
  // simpleGrading).
  std::array<double, 3> grading = {1.0, 1.0, 1.0};
  // Random displacement of interior points, as a fraction of the local
  // spacing along each axis (0 = none; keep below 0.3).
  double perturbation = 0.0;
  unsigned seed = 1;
  // Checkerboard 2:1 refinement (see above).
  bool polyhedral = false;
  // Patch kinds for xmin, xmax, ymin, ymax, zmin, zmax.
  std::array<PatchKind, 6> kinds = {PatchKind::kWall, PatchKind::kWall, PatchKind::kWall,
                                    PatchKind::kWall, PatchKind::kWall, PatchKind::kWall};
  // Obstacle: the blocks with index i in [obstacle_min[d], obstacle_max[d])
  // along every axis d are removed (none when any max <= min).
  std::array<int, 3> obstacle_min = {0, 0, 0};
  std::array<int, 3> obstacle_max = {0, 0, 0};
  bool has_obstacle() const;
  // Throws ConfigError on a bad value.
  void Validate() const;
};

Mesh MakeBoxMesh(const BoxMeshOptions& options);

}  // namespace kelvin::cfd
