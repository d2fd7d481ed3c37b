#include "cfd/verification/gci.h"

#include <fmt/format.h>

#include <cmath>

#include "data/schema/errors.h"

namespace kelvin::cfd {

double RepresentativeCellSize(double volume, double cells) { return std::cbrt(volume / cells); }

GciResult ComputeGci(double h1, double h2, double h3, double phi1, double phi2, double phi3) {
  if (!(h1 > 0 && h2 > h1 && h3 > h2)) {
    throw ArgumentError(fmt::format("GCI needs grid sizes h1 < h2 < h3 (finest first), got {}, {}, {}", h1, h2, h3));
  }
  GciResult g;
  g.r21 = h2 / h1;
  g.r32 = h3 / h2;
  if (g.r21 < 1.1 || g.r32 < 1.1) {
    throw ArgumentError(fmt::format("GCI needs refinement ratios of at least 1.1 (1.3 recommended), got {} and {}",
                                    g.r21, g.r32));
  }
  const double eps21 = phi2 - phi1, eps32 = phi3 - phi2;
  g.R = eps32 != 0 ? eps21 / eps32 : 0.0;
  if (g.R > 0 && g.R < 1) {
    g.convergence = Convergence::kMonotonic;
  } else if (g.R < 0 && g.R > -1) {
    g.convergence = Convergence::kOscillatory;
  } else {
    g.convergence = Convergence::kDivergent;
  }
  if (eps21 == 0 || eps32 == 0) {
    // Identical values on two grids: no order can be inferred.
    g.p = 0;
  } else {
    const double s = eps32 / eps21 > 0 ? 1.0 : -1.0;
    const double ln_ratio = std::log(std::abs(eps32 / eps21));
    double p = std::abs(ln_ratio) / std::log(g.r21);
    for (g.iterations = 1; g.iterations <= 200; ++g.iterations) {
      const double num = std::pow(g.r21, p) - s, den = std::pow(g.r32, p) - s;
      const double q = (num > 0 && den > 0) ? std::log(num / den) : 0.0;
      const double next = std::abs(ln_ratio + q) / std::log(g.r21);
      if (std::abs(next - p) < 1e-12 * std::max(1.0, p)) {
        p = next;
        break;
      }
      p = next;
    }
    g.p = p;
  }
  const double r21p = std::pow(g.r21, g.p), r32p = std::pow(g.r32, g.p);
  g.phi_ext = r21p != 1 ? (r21p * phi1 - phi2) / (r21p - 1) : phi1;
  g.e_a21 = std::abs((phi1 - phi2) / phi1);
  g.e_ext21 = std::abs((g.phi_ext - phi1) / g.phi_ext);
  g.gci21 = r21p != 1 ? 1.25 * g.e_a21 / (r21p - 1) : 0.0;
  const double e_a32 = std::abs((phi2 - phi3) / phi2);
  g.gci32 = r32p != 1 ? 1.25 * e_a32 / (r32p - 1) : 0.0;
  g.asymptotic_ratio = g.gci21 > 0 ? g.gci32 / (r21p * g.gci21) : 0.0;
  return g;
}

std::string GciResult::Report(const std::string& name) const {
  const char* kind = convergence == Convergence::kMonotonic     ? "monotonic"
                     : convergence == Convergence::kOscillatory ? "oscillatory"
                                                                : "divergent";
  return fmt::format(
      "{}: r21 {:.4g}, r32 {:.4g}, R {:.4g} ({}), p {:.4g}, extrapolated {:.6g}, e_a21 {:.3g}%, e_ext21 {:.3g}%, "
      "GCI21 {:.3g}%, GCI32 {:.3g}%, GCI32/(r^p GCI21) {:.4g}",
      name, r21, r32, R, kind, p, phi_ext, 100 * e_a21, 100 * e_ext21, 100 * gci21, 100 * gci32, asymptotic_ratio);
}

}  // namespace kelvin::cfd
