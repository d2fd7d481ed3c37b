#include "bridge/geo.h"

#include <fmt/format.h>

#include <cmath>

#include "data/schema/errors.h"

namespace kelvin::bridge {

namespace {
constexpr double kDeg = M_PI / 180.0;
constexpr double kWgs84A = 6378137.0;                  // m, semi-major axis
constexpr double kWgs84F = 1.0 / 298.257223563;        // flattening
constexpr double kWgs84E2 = kWgs84F * (2.0 - kWgs84F);  // first eccentricity squared
}  // namespace

LocalOrigin::LocalOrigin(GeoPoint origin) : origin_(origin) {
  if (!(std::abs(origin.latitude) < 89.0)) {
    throw ArgumentError(fmt::format("origin latitude {} deg: expected a latitude between -89 and 89 deg",
                                    origin.latitude));
  }
  if (!(std::abs(origin.longitude) <= 180.0)) {
    throw ArgumentError(fmt::format("origin longitude {} deg: expected a longitude between -180 and 180 deg",
                                    origin.longitude));
  }
  const double s = std::sin(origin.latitude * kDeg);
  const double w = std::sqrt(1.0 - kWgs84E2 * s * s);
  normal_radius_ = kWgs84A / w;
  meridian_radius_ = kWgs84A * (1.0 - kWgs84E2) / (w * w * w);
  cos_latitude_ = std::cos(origin.latitude * kDeg);
}

GeoPoint LocalOrigin::ToGeodetic(double x_north, double y_east) const {
  GeoPoint p;
  p.latitude = origin_.latitude + x_north / meridian_radius_ / kDeg;
  double lon = origin_.longitude + y_east / (normal_radius_ * cos_latitude_) / kDeg;
  if (lon > 180.0) lon -= 360.0;
  if (lon <= -180.0) lon += 360.0;
  p.longitude = lon;
  return p;
}

void LocalOrigin::ToLocal(const GeoPoint& p, double* x_north, double* y_east) const {
  *x_north = (p.latitude - origin_.latitude) * kDeg * meridian_radius_;
  double dlon = p.longitude - origin_.longitude;
  if (dlon > 180.0) dlon -= 360.0;
  if (dlon < -180.0) dlon += 360.0;
  *y_east = dlon * kDeg * normal_radius_ * cos_latitude_;
}

}  // namespace kelvin::bridge
