// Earth positions from the simulator's local frame (x north, y east, metres
// from an origin) to WGS-84 latitude and longitude, on the tangent plane at
// the origin with the ellipsoid's radii of curvature there. Within the few
// kilometres a maneuver covers, the error of this plane against the ellipsoid
// is below a centimetre.
#pragma once

namespace kelvin::bridge {

struct GeoPoint {
  double latitude = 0;   // deg, north positive
  double longitude = 0;  // deg, east positive
};

class LocalOrigin {
 public:
  // Throws kelvin::ArgumentError unless |latitude| < 89 deg and
  // |longitude| <= 180 deg (the plane has no meaning at the poles).
  explicit LocalOrigin(GeoPoint origin);

  GeoPoint ToGeodetic(double x_north, double y_east) const;
  // The inverse of ToGeodetic (used to check NMEA positions).
  void ToLocal(const GeoPoint& p, double* x_north, double* y_east) const;

  const GeoPoint& origin() const { return origin_; }
  double meridian_radius() const { return meridian_radius_; }  // m, M at the origin
  double normal_radius() const { return normal_radius_; }      // m, N at the origin

 private:
  GeoPoint origin_;
  double meridian_radius_ = 0;
  double normal_radius_ = 0;
  double cos_latitude_ = 1;
};

}  // namespace kelvin::bridge
