#include "cfd/mesh/dual_mesh.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <random>
#include <tuple>

#include "cfd/mesh/mesh_builder.h"
#include "data/schema/errors.h"

namespace kelvin::cfd {

void DualMeshOptions::Validate() const {
  for (int d = 0; d < 3; ++d) {
    if (!(max[d] > min[d])) throw ConfigError(fmt::format("dual mesh: max[{}] must exceed min[{}]", d, d));
    if (divisions[d] < 1) throw ConfigError(fmt::format("dual mesh: divisions[{}] = {}; expected >= 1", d, divisions[d]));
  }
  if (!(perturbation >= 0.0 && perturbation < 0.3)) {
    throw ConfigError(fmt::format("dual mesh: perturbation = {}; expected in [0, 0.3)", perturbation));
  }
}

Mesh MakeDualMesh(const DualMeshOptions& opt) {
  opt.Validate();
  const int nx = opt.divisions[0], ny = opt.divisions[1], nz = opt.divisions[2];
  const int nv = (nx + 1) * (ny + 1);
  auto vid = [&](int i, int j) { return i + (nx + 1) * j; };
  // 2D primal vertices.
  std::vector<Eigen::Vector2d> xv(nv);
  std::mt19937 rng(opt.seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const double hx = (opt.max.x() - opt.min.x()) / nx, hy = (opt.max.y() - opt.min.y()) / ny;
  for (int j = 0; j <= ny; ++j) {
    for (int i = 0; i <= nx; ++i) {
      Eigen::Vector2d x(opt.min.x() + i * hx, opt.min.y() + j * hy);
      const double a = u(rng), b = u(rng);
      if (i > 0 && i < nx && j > 0 && j < ny) x += opt.perturbation * Eigen::Vector2d(a * hx, b * hy);
      xv[vid(i, j)] = x;
    }
  }
  // Triangles (alternating diagonals).
  std::vector<std::array<int, 3>> tri;
  for (int j = 0; j < ny; ++j) {
    for (int i = 0; i < nx; ++i) {
      const int a = vid(i, j), b = vid(i + 1, j), c = vid(i + 1, j + 1), d = vid(i, j + 1);
      if ((i + j) % 2 == 0) {
        tri.push_back({a, b, c});
        tri.push_back({a, c, d});
      } else {
        tri.push_back({a, b, d});
        tri.push_back({b, c, d});
      }
    }
  }
  // Edges -> adjacent triangles.
  std::map<std::pair<int, int>, std::vector<int>> edge_tris;
  for (int t = 0; t < static_cast<int>(tri.size()); ++t) {
    for (int k = 0; k < 3; ++k) {
      int a = tri[t][k], b = tri[t][(k + 1) % 3];
      if (a > b) std::swap(a, b);
      edge_tris[{a, b}].push_back(t);
    }
  }
  // 2D points: vertices, then edge midpoints, then triangle centroids.
  std::vector<Eigen::Vector2d> p2(xv);
  std::map<std::pair<int, int>, int> mid;
  for (const auto& [e, ts] : edge_tris) {
    mid[e] = static_cast<int>(p2.size());
    p2.push_back(0.5 * (xv[e.first] + xv[e.second]));
  }
  std::vector<int> cen(tri.size());
  for (std::size_t t = 0; t < tri.size(); ++t) {
    cen[t] = static_cast<int>(p2.size());
    p2.push_back((xv[tri[t][0]] + xv[tri[t][1]] + xv[tri[t][2]]) / 3.0);
  }
  const int np2 = static_cast<int>(p2.size());
  std::vector<Vector3> points;
  for (int k = 0; k <= nz; ++k) {
    const double z = opt.min.z() + (opt.max.z() - opt.min.z()) * k / nz;
    for (const auto& p : p2) points.emplace_back(p.x(), p.y(), z);
  }
  auto pid = [&](int p, int k) { return p + np2 * k; };
  auto cell = [&](int v, int k) { return v + nv * k; };
  // Side of a boundary edge: 0 xmin, 1 xmax, 2 ymin, 3 ymax.
  auto side = [&](int a, int b) {
    const int ia = a % (nx + 1), ja = a / (nx + 1), ib = b % (nx + 1), jb = b / (nx + 1);
    if (ia == 0 && ib == 0) return 0;
    if (ia == nx && ib == nx) return 1;
    if (ja == 0 && jb == 0) return 2;
    return 3;
  };
  const std::array<Vector3, 4> outward = {Vector3(-1, 0, 0), Vector3(1, 0, 0), Vector3(0, -1, 0), Vector3(0, 1, 0)};
  auto area = [&](const std::vector<int>& f) {
    Vector3 c = Vector3::Zero();
    for (int p : f) c += points[p];
    c /= static_cast<double>(f.size());
    Vector3 s = Vector3::Zero();
    for (std::size_t i = 0; i < f.size(); ++i) s += (points[f[i]] - c).cross(points[f[(i + 1) % f.size()]] - c);
    return Vector3(0.5 * s);
  };
  static const std::array<const char*, 6> kNames = {"xmin", "xmax", "ymin", "ymax", "zmin", "zmax"};
  MeshBuilder builder;
  for (int s = 0; s < 6; ++s) builder.AddPatch(kNames[s], opt.kinds[s]);
  auto add_internal = [&](int a, int b, std::vector<int> f, const Vector3& a_to_b) {
    if (area(f).dot(a_to_b) < 0) std::reverse(f.begin(), f.end());
    builder.AddInternalFace(a, b, std::move(f));
  };
  for (int k = 0; k < nz; ++k) {
    for (const auto& [e, ts] : edge_tris) {
      const auto [a, b] = e;
      const Vector3 ab(xv[b].x() - xv[a].x(), xv[b].y() - xv[a].y(), 0.0);
      const int m = mid.at(e);
      if (ts.size() == 2) {
        add_internal(cell(a, k), cell(b, k),
                     {pid(cen[ts[0]], k), pid(m, k), pid(cen[ts[1]], k), pid(cen[ts[1]], k + 1), pid(m, k + 1),
                      pid(cen[ts[0]], k + 1)},
                     ab);
      } else {
        add_internal(cell(a, k), cell(b, k), {pid(cen[ts[0]], k), pid(m, k), pid(m, k + 1), pid(cen[ts[0]], k + 1)},
                     ab);
        // Boundary halves of the edge for a and for b.
        const int s = side(a, b);
        for (int v : {a, b}) {
          std::vector<int> f = {pid(v, k), pid(m, k), pid(m, k + 1), pid(v, k + 1)};
          if (area(f).dot(outward[s]) < 0) std::reverse(f.begin(), f.end());
          builder.AddBoundaryFace(s, cell(v, k), std::move(f));
        }
      }
    }
  }
  // Polygons of the dual cells (sorted by angle around their point average).
  std::vector<std::vector<int>> polygon(nv);
  for (const auto& [e, ts] : edge_tris) {
    polygon[e.first].push_back(mid.at(e));
    polygon[e.second].push_back(mid.at(e));
    if (ts.size() == 1) {
      // Boundary vertices are corners of their own cell.
      for (int v : {e.first, e.second}) {
        if (std::find(polygon[v].begin(), polygon[v].end(), v) == polygon[v].end()) polygon[v].push_back(v);
      }
    }
  }
  for (int t = 0; t < static_cast<int>(tri.size()); ++t) {
    for (int v : tri[t]) polygon[v].push_back(cen[t]);
  }
  for (int v = 0; v < nv; ++v) {
    Eigen::Vector2d c = Eigen::Vector2d::Zero();
    for (int p : polygon[v]) c += p2[p];
    c /= static_cast<double>(polygon[v].size());
    std::sort(polygon[v].begin(), polygon[v].end(), [&](int a, int b) {
      return std::atan2(p2[a].y() - c.y(), p2[a].x() - c.x()) < std::atan2(p2[b].y() - c.y(), p2[b].x() - c.x());
    });
  }
  for (int k = 0; k <= nz; ++k) {
    for (int v = 0; v < nv; ++v) {
      std::vector<int> f;
      for (int p : polygon[v]) f.push_back(pid(p, k));  // counter-clockwise: normal +z
      if (k == 0) {
        std::reverse(f.begin(), f.end());
        builder.AddBoundaryFace(4, cell(v, 0), std::move(f));
      } else if (k == nz) {
        builder.AddBoundaryFace(5, cell(v, nz - 1), std::move(f));
      } else {
        builder.AddInternalFace(cell(v, k - 1), cell(v, k), std::move(f));
      }
    }
  }
  return std::move(builder).Build(std::move(points), "<dual mesh>");
}

}  // namespace kelvin::cfd
