#include "cfd/geometry/spheroid_surface.h"

#include <fmt/format.h>

#include <cmath>
#include <numbers>

#include "data/schema/errors.h"

namespace kelvin::cfd {

std::pair<std::string, std::string> SpheroidShape::Problem() const {
  const std::pair<const char*, double> fields[] = {
      {"length", length}, {"diameter", diameter}, {"depth", depth}};
  for (const auto& [key, v] : fields) {
    if (!(v > 0) || !std::isfinite(v)) return {key, "a finite length > 0 (m)"};
  }
  if (diameter > length) {
    return {"diameter",
            fmt::format("at most the length {} m (a prolate spheroid or a sphere)", length)};
  }
  if (!(depth > 0.5 * diameter)) {
    return {"depth",
            fmt::format("more than half the diameter, {} m, so that the body lies below z = 0",
                        0.5 * diameter)};
  }
  return {};
}

void SpheroidShape::Validate() const {
  const auto [key, expected] = Problem();
  if (key.empty()) return;
  const double v = key == "length" ? length : key == "diameter" ? diameter : depth;
  throw ConfigError(fmt::format("spheroid '{}' = {}: expected {}", key, v, expected));
}

TriangleSurface SpheroidSurface(const SpheroidShape& shape, int rings, int segments) {
  shape.Validate();
  TriangleSurface s;
  s.source = fmt::format("spheroid L={} D={} depth={}", shape.length, shape.diameter, shape.depth);
  const double a = 0.5 * shape.length, b = 0.5 * shape.diameter;
  // Ring i (1..rings-1) at polar angle theta = pi i / rings from the aft end.
  s.vertices.emplace_back(0.0, 0.0, -shape.depth);  // aft pole
  for (int i = 1; i < rings; ++i) {
    const double theta = std::numbers::pi * i / rings;
    const double x = a * (1.0 - std::cos(theta)), r = b * std::sin(theta);
    for (int j = 0; j < segments; ++j) {
      const double phi = 2.0 * std::numbers::pi * j / segments;
      s.vertices.emplace_back(x, r * std::cos(phi), -shape.depth + r * std::sin(phi));
    }
  }
  const int fore = static_cast<int>(s.vertices.size());
  s.vertices.emplace_back(shape.length, 0.0, -shape.depth);
  const auto at = [&](int ring, int j) { return 1 + (ring - 1) * segments + (j % segments); };
  // Counter-clockwise seen from outside: x grows along the axis, phi turns
  // from +y to +z, so (x, phi) is a left-handed pair on the outer surface.
  for (int j = 0; j < segments; ++j) {
    s.triangles.push_back({0, at(1, j + 1), at(1, j)});
    for (int i = 1; i + 1 < rings; ++i) {
      s.triangles.push_back({at(i, j), at(i, j + 1), at(i + 1, j + 1)});
      s.triangles.push_back({at(i, j), at(i + 1, j + 1), at(i + 1, j)});
    }
    s.triangles.push_back({fore, at(rings - 1, j), at(rings - 1, j + 1)});
  }
  return s;
}

}  // namespace kelvin::cfd
