#include "cfd/freesurface/wave_analysis.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

#include "data/schema/errors.h"

namespace kelvin::cfd {

namespace {
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// eta at the centre of edge e of the face `face`, from the face value and
// its least-squares gradient (the face value where it has none).
double EdgeElevation(const PatchSurface& s, std::span<const double> eta, const std::vector<Vector3>& grad, int face,
                     const Vector3& point) {
  if (!s.valid_gradient(face)) return eta[face];
  return eta[face] + grad[face].dot(point - s.centres()[face]);
}
}  // namespace

std::vector<double> WaveCut(const PatchSurface& surface, std::span<const double> eta, double y0,
                            std::span<const double> x) {
  KELVIN_CHECK(static_cast<int>(eta.size()) == surface.size(), "one elevation per patch face");
  std::vector<Vector3> grad;
  surface.Gradient(eta, grad);
  const auto& edges = surface.edges();
  // Radius of each face about its centre (edge centres bound it for convex faces).
  const int n = surface.size();
  std::vector<double> radius(n, 0.0);
  for (int i = 0; i < n; ++i) {
    for (int e : surface.face_edges(i)) {
      const double len = edges[e].normal.norm();
      radius[i] = std::max(radius[i], (edges[e].centre - surface.centres()[i]).norm() + 0.5 * len);
    }
  }
  std::vector<double> out(x.size(), kNaN);
  for (std::size_t k = 0; k < x.size(); ++k) {
    const Vector3 p(x[k], y0, 0.0);
    for (int i = 0; i < n; ++i) {
      if ((p - surface.centres()[i]).head<2>().norm() > radius[i]) continue;
      bool inside = true;
      for (int e : surface.face_edges(i)) {
        // Outward normal of face i across edge e.
        const Vector3 nrm = edges[e].face == i ? edges[e].normal : Vector3(-edges[e].normal);
        if ((p - edges[e].centre).dot(nrm) > 1e-12 * nrm.norm()) {
          inside = false;
          break;
        }
      }
      if (!inside) continue;
      out[k] = surface.valid_gradient(i) ? eta[i] + grad[i].dot(p - surface.centres()[i]) : eta[i];
      break;
    }
  }
  return out;
}

WaveProfile HullWaveProfile(const PatchSurface& surface, std::span<const double> eta, int hull_patch) {
  KELVIN_CHECK(static_cast<int>(eta.size()) == surface.size(), "one elevation per patch face");
  std::vector<Vector3> grad;
  surface.Gradient(eta, grad);
  struct Point {
    double x, y, eta;
  };
  std::vector<Point> points;
  for (const auto& e : surface.edges()) {
    if (e.neighbour >= 0 || e.rim_patch != hull_patch) continue;
    points.push_back({e.centre.x(), e.centre.y(), EdgeElevation(surface, eta, grad, e.face, e.centre)});
  }
  std::sort(points.begin(), points.end(), [](const Point& a, const Point& b) {
    const bool pa = a.y >= 0.0, pb = b.y >= 0.0;
    return pa != pb ? pb : a.x < b.x;
  });
  WaveProfile w;
  for (const Point& p : points) {
    w.x.push_back(p.x);
    w.y.push_back(p.y);
    w.eta.push_back(p.eta);
  }
  return w;
}

Vector3 WaterlineForce(const PatchSurface& surface, std::span<const double> eta, int hull_patch, double rho,
                       double g) {
  KELVIN_CHECK(static_cast<int>(eta.size()) == surface.size(), "one elevation per patch face");
  std::vector<Vector3> grad;
  surface.Gradient(eta, grad);
  Vector3 f = Vector3::Zero();
  for (const auto& e : surface.edges()) {
    if (e.neighbour >= 0 || e.rim_patch != hull_patch) continue;
    const double h = EdgeElevation(surface, eta, grad, e.face, e.centre);
    f += 0.5 * rho * g * h * h * e.normal;
  }
  return f;
}

}  // namespace kelvin::cfd
