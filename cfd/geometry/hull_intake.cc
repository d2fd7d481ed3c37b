#include "cfd/geometry/hull_intake.h"

#include <fmt/format.h>

#include "cfd/geometry/placement_check.h"

namespace kelvin::cfd {

std::string HullIntake::Report() const {
  std::string r = fmt::format("  surface: {} ({} triangles, {} vertices)\n", surface.source,
                              surface.triangles.size(), surface.vertices.size());
  r += fmt::format("  repair: {}\n", repair.Summary());
  if (repair.self_intersections_above > 0) {
    r += fmt::format("  note: {} self-intersecting triangle pairs above the waterline (outside the domain)\n",
                     repair.self_intersections_above);
  }
  r += fmt::format("  check: {}\n", check.Summary());
  if (check.non_manifold_edges > 0) {
    r += fmt::format(
        "  note: {} non-manifold edges (edges shared by three or more triangles, e.g. a rudder or skeg joined to "
        "the hull); they are meshed as they are\n",
        check.non_manifold_edges);
  }
  for (const auto& w : warnings) r += "  WARNING: " + w + "\n";
  return r;
}

HullIntake TakeInHull(const HullPlacement& placement, int stations) {
  HullIntake in;
  in.surface = LoadHull(placement, &in.check, &in.repair);
  in.hydrostatics = ComputeHydrostatics(in.surface, placement.Lpp, placement.B, placement.T, stations);
  in.warnings = CheckPlacement(in.hydrostatics, placement);
  return in;
}

}  // namespace kelvin::cfd
