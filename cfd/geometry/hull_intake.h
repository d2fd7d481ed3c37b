// A user's hull surface taken in: read, placed in ship axes, repaired,
// validated and checked against its ship file, with one report of what was
// found and changed. `kelvin hull` prints it; `kelvin mesh` writes it into
// each grid's quality.txt and prints its warnings.
#pragma once

#include <string>
#include <vector>

#include "cfd/geometry/hydrostatics.h"
#include "cfd/geometry/surface_repair.h"
#include "cfd/geometry/triangle_surface.h"

namespace kelvin::cfd {

struct HullIntake {
  TriangleSurface surface;  // ship axes, repaired, outward normals
  SurfaceCheck check;       // after repair
  RepairReport repair;
  Hydrostatics hydrostatics;
  std::vector<std::string> warnings;  // CheckPlacement's
  // "surface: ...\n  repair: ...\n  check: ...\n  WARNING: ...\n" lines.
  std::string Report() const;
};

// Throws DataFileError (from the reader, the repair or ValidateHull) for a
// surface that cannot be used.
HullIntake TakeInHull(const HullPlacement& placement, int stations = 21);

}  // namespace kelvin::cfd
