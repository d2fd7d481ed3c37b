#include "cfd/propulsion/cell_overlap.h"

#include <algorithm>
#include <cmath>

#include "data/schema/errors.h"

namespace kelvin::cfd {

namespace {

constexpr int kSamplesPerEdge = 4;  // stratified samples per tetrahedron: 4^3

struct Integrals {
  double volume = 0.0;
  std::vector<double> density;
};

struct Sampler {
  const OverlapRegion& region;
  std::vector<double> at;  // densities at one sample point

  // The tetrahedron (p0, p1, p2, p3) at kSamplesPerEdge^3 stratified points
  // folded from the unit cube.
  void Tetrahedron(const Vector3& p0, const Vector3& p1, const Vector3& p2, const Vector3& p3, Integrals& out) {
    const double dV = std::abs((p1 - p0).dot((p2 - p0).cross(p3 - p0))) / 6.0 /
                      (kSamplesPerEdge * kSamplesPerEdge * kSamplesPerEdge);
    for (int i = 0; i < kSamplesPerEdge; ++i) {
      for (int j = 0; j < kSamplesPerEdge; ++j) {
        for (int k = 0; k < kSamplesPerEdge; ++k) {
          double s = (i + 0.5) / kSamplesPerEdge, t = (j + 0.5) / kSamplesPerEdge, u = (k + 0.5) / kSamplesPerEdge;
          if (s + t > 1.0) {
            s = 1.0 - s;
            t = 1.0 - t;
          }
          if (t + u > 1.0) {
            const double tmp = u;
            u = 1.0 - s - t;
            t = 1.0 - tmp;
          } else if (s + t + u > 1.0) {
            const double tmp = u;
            u = s + t + u - 1.0;
            s = 1.0 - t - tmp;
          }
          const Vector3 x = p0 + s * (p1 - p0) + t * (p2 - p0) + u * (p3 - p0);
          if (!region.sample(x, at)) continue;
          out.volume += dV;
          for (std::size_t d = 0; d < at.size(); ++d) out.density[d] += at[d] * dV;
        }
      }
    }
  }

  // A tetrahedron that may overlap the region: split at the edge midpoints
  // into 8 (4 corners and the central octahedron cut along one diagonal)
  // until its edges are below a quarter of the feature size; tetrahedra
  // clear of the region are skipped.
  void Adaptive(const Vector3& p0, const Vector3& p1, const Vector3& p2, const Vector3& p3, Integrals& out,
                int depth) {
    const Vector3 centroid = 0.25 * (p0 + p1 + p2 + p3);
    const double radius = std::max({(p0 - centroid).norm(), (p1 - centroid).norm(), (p2 - centroid).norm(),
                                    (p3 - centroid).norm()});
    if (region.distance(centroid, 0.0) > radius) return;
    if (region.depth && region.depth(centroid) > radius) {
      Tetrahedron(p0, p1, p2, p3, out);
      return;
    }
    const double edge = std::max({(p1 - p0).norm(), (p2 - p0).norm(), (p3 - p0).norm(), (p2 - p1).norm(),
                                  (p3 - p1).norm(), (p3 - p2).norm()});
    if (depth >= region.max_splits || edge <= 0.25 * region.feature) {
      Tetrahedron(p0, p1, p2, p3, out);
      return;
    }
    const Vector3 m01 = 0.5 * (p0 + p1), m02 = 0.5 * (p0 + p2), m03 = 0.5 * (p0 + p3);
    const Vector3 m12 = 0.5 * (p1 + p2), m13 = 0.5 * (p1 + p3), m23 = 0.5 * (p2 + p3);
    const int d = depth + 1;
    Adaptive(p0, m01, m02, m03, out, d);
    Adaptive(m01, p1, m12, m13, out, d);
    Adaptive(m02, m12, p2, m23, out, d);
    Adaptive(m03, m13, m23, p3, out, d);
    Adaptive(m02, m13, m01, m03, out, d);
    Adaptive(m02, m13, m03, m23, out, d);
    Adaptive(m02, m13, m23, m12, out, d);
    Adaptive(m02, m13, m12, m01, out, d);
  }

  Integrals Cell(const Mesh& mesh, int c) {
    Integrals in;
    in.density.assign(static_cast<std::size_t>(region.n_densities), 0.0);
    const auto offsets = mesh.cell_face_offsets();
    const Vector3& xc = mesh.cell_centres()[c];
    for (int k = offsets[c]; k < offsets[c + 1]; ++k) {
      const int f = mesh.cell_faces()[k];
      const auto pts = mesh.face(f);
      for (std::size_t i = 0; i < pts.size(); ++i) {
        const Vector3& a = mesh.points()[pts[i]];
        const Vector3& b = mesh.points()[pts[(i + 1) % pts.size()]];
        Adaptive(xc, mesh.face_centres()[f], a, b, in, 0);
      }
    }
    return in;
  }
};

}  // namespace

double CellRadius(const Mesh& mesh, int c) {
  double radius = 0.0;
  const auto offsets = mesh.cell_face_offsets();
  for (int k = offsets[c]; k < offsets[c + 1]; ++k) {
    for (int p : mesh.face(mesh.cell_faces()[k])) {
      radius = std::max(radius, (mesh.points()[p] - mesh.cell_centres()[c]).norm());
    }
  }
  return radius;
}

std::vector<CellOverlap> SampleOverlap(const Mesh& mesh, const OverlapRegion& region) {
  KELVIN_CHECK(region.distance && region.sample && region.feature > 0 && region.n_densities >= 0,
               "an overlap region with its distance, sample and feature size");
  Sampler sampler{region, std::vector<double>(static_cast<std::size_t>(region.n_densities), 0.0)};
  std::vector<CellOverlap> out;
  for (int c = 0; c < mesh.n_cells(); ++c) {
    if (region.distance(mesh.cell_centres()[c], 0.0) > CellRadius(mesh, c)) continue;
    Integrals in = sampler.Cell(mesh, c);
    if (in.volume <= 0.0) continue;
    out.push_back({c, in.volume / mesh.cell_volumes()[c], std::move(in.density)});
  }
  return out;
}

}  // namespace kelvin::cfd
