#include "cfd/geometry/placement_check.h"

#include <fmt/format.h>

#include <cmath>

namespace kelvin::cfd {

namespace {

const char* kUnitKeys = "geometry.length_unit, geometry.waterline_z (m, after length_unit)";

void CheckDraft(const Hydrostatics& h, const HullPlacement& p, std::vector<std::string>& out) {
  if (std::abs(h.draft - p.T) <= 0.05 * p.T) return;
  out.push_back(fmt::format(
      "the surface's deepest point is {:.4g} m below the waterline but the ship file's principal.d is {:.4g} m "
      "({:+.1f}%): check {}",
      h.draft, p.T, 100 * (h.draft / p.T - 1), kUnitKeys));
}

void CheckDisplacement(const Hydrostatics& h, const HullPlacement& p, std::vector<std::string>& out) {
  if (!(p.displacement > 0) || std::abs(h.volume - p.displacement) <= 0.05 * p.displacement) return;
  out.push_back(fmt::format(
      "the surface displaces {:.4g} m^3 below the waterline but the ship file's principal.displacement is {:.4g} "
      "m^3 ({:+.1f}%): check {}",
      h.volume, p.displacement, 100 * (h.volume / p.displacement - 1), kUnitKeys));
}

void CheckExtent(const HullPlacement& p, double lo, double hi, std::vector<std::string>& out) {
  if (lo >= -0.1 * p.Lpp && hi <= 1.1 * p.Lpp) return;
  out.push_back(fmt::format(
      "the underwater hull spans x = {:.4g} to {:.4g} m from the AP, expected about 0 to Lpp = {:.4g} m: check "
      "geometry.x_ap (m, after length_unit) and geometry.bow_direction",
      lo, hi, p.Lpp));
}

void CheckBowDirection(const Hydrostatics& h, const HullPlacement& p, std::vector<std::string>& out) {
  const double mid = 0.5 * p.Lpp;
  const double lcf = (h.lcf - mid) / p.Lpp, lcb = (h.lcb - mid) / p.Lpp;
  if (!(lcf > 0.02 && lcb > 0)) return;
  out.push_back(fmt::format(
      "the waterplane is fuller forward than aft (centre of flotation {:.1f}% Lpp and centre of buoyancy {:.1f}% "
      "Lpp ahead of midship; ships have the fuller waterline aft): the bow and stern look swapped, check "
      "geometry.bow_direction (now '{}')",
      100 * lcf, 100 * lcb, p.bow_towards_minus_x ? "-x" : "+x"));
}

}  // namespace

std::vector<std::string> CheckPlacement(const Hydrostatics& h, const HullPlacement& p) {
  std::vector<std::string> out;
  CheckDraft(h, p, out);
  CheckDisplacement(h, p, out);
  CheckExtent(p, h.x_min, h.x_max, out);
  CheckBowDirection(h, p, out);
  return out;
}

}  // namespace kelvin::cfd
