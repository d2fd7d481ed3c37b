#include "data/reference/friction_lines.h"

#include <fmt/format.h>

#include <cmath>

#include "data/schema/errors.h"

namespace kelvin::data {

double Ittc57FrictionCoefficient(double reynolds) {
  if (!(reynolds > 100.0) || !std::isfinite(reynolds)) {
    throw ModelError(
        fmt::format("Reynolds number {}: the ITTC-1957 friction line needs a finite Re above 100 "
                    "(log10 Re - 2 > 0)",
                    reynolds));
  }
  const double lg = std::log10(reynolds) - 2.0;
  return 0.075 / (lg * lg);
}

}  // namespace kelvin::data
