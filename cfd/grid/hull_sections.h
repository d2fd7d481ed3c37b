// Hulls described by their transverse sections, for the structured grid
// generator. Ship axes: x forward from the aft end, y transverse, z up with
// the calm waterline at z = 0. A section at station x is, for each depth z
// between its keel z_keel(x) < 0 and the waterline, one interval
// [y_min(x, z), y_max(x, z)] of the hull (simply connected below z = 0).
#pragma once

#include <array>
#include <span>
#include <string>
#include <vector>

#include "cfd/geometry/triangle_surface.h"

namespace kelvin::cfd {

class HullSections {
 public:
  virtual ~HullSections() = default;
  // Longitudinal extent of the hull below the waterline (m).
  virtual double x_aft() const = 0;
  virtual double x_fore() const = 0;
  // Lowest z of the section at x (m, < 0), for x_aft <= x <= x_fore.
  virtual double KeelZ(double x) const = 0;
  // (y_min, y_max) of the section at x at each depth z (m); (0, 0) where the
  // depth is below the keel.
  virtual std::vector<std::array<double, 2>> Breadths(double x,
                                                      std::span<const double> z) const = 0;
  // Names the hull in messages.
  virtual std::string name() const = 0;
  double length() const { return x_fore() - x_aft(); }
};

// The Wigley parabolic hull y = ±(B/2)(1 - (2 xi / L)^2)(1 - (z/T)^2),
// xi = x - L/2, from x = 0 to L.
class WigleySections final : public HullSections {
 public:
  WigleySections(double L, double B, double T);
  double x_aft() const override { return 0.0; }
  double x_fore() const override { return L_; }
  double KeelZ(double) const override { return -T_; }
  std::vector<std::array<double, 2>> Breadths(double x, std::span<const double> z) const override;
  std::string name() const override;
  // Exact displacement volume 4/9 L B T.
  double Volume() const { return 4.0 / 9.0 * L_ * B_ * T_; }

 private:
  double L_, B_, T_;
};

// Sections cut from a triangulated hull surface (already in ship axes, e.g.
// from LoadHull). The x extent is that of the surface below z = 0.
class SurfaceSections final : public HullSections {
 public:
  explicit SurfaceSections(TriangleSurface surface);
  double x_aft() const override { return x_aft_; }
  double x_fore() const override { return x_fore_; }
  double KeelZ(double x) const override;
  std::vector<std::array<double, 2>> Breadths(double x, std::span<const double> z) const override;
  std::string name() const override { return surface_.source; }

 private:
  // Segments (y0, z0, y1, z1) where the plane x cuts the surface below z = 0.
  std::vector<std::array<double, 4>> Slice(double x) const;

  TriangleSurface surface_;
  double x_aft_ = 0, x_fore_ = 0;
};

}  // namespace kelvin::cfd
