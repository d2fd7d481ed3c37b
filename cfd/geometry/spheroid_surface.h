// A prolate spheroid (a sphere when the length equals the diameter) as a
// closed triangulated surface: the test body for fully submerged bodies
// under the linearized free surface (cfd/grid/README.md, "Submerged bodies").
#pragma once

#include <string>
#include <utility>

#include "cfd/geometry/triangle_surface.h"

namespace kelvin::cfd {

struct SpheroidShape {
  double length = 0;    // m, along x (the axis of revolution)
  double diameter = 0;  // m
  double depth = 0;     // m, of the axis below z = 0
  // The first field that is out of range and what was expected of it
  // ({"", ""} when the shape is valid).
  std::pair<std::string, std::string> Problem() const;
  // Throws ConfigError naming the field, the value and what was expected.
  void Validate() const;
};

// The spheroid from x = 0 (aft end) to x = length with its axis at y = 0,
// z = -depth; `rings` latitude rings (uniform in the polar angle, so the
// ends are finer) and `segments` points around each ring; one vertex at
// each end. Closed, consistently oriented, normals outward.
TriangleSurface SpheroidSurface(const SpheroidShape& shape, int rings = 64, int segments = 64);

}  // namespace kelvin::cfd
