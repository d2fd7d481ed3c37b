#include "cfd/geometry/hydrostatics.h"

#include <fmt/format.h>

#include <cmath>

#include "data/schema/config.h"
#include "data/schema/errors.h"

namespace kelvin::cfd {

namespace fs = std::filesystem;

std::vector<std::array<Eigen::Vector3d, 3>> ClipBelowWaterline(const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                                               const Eigen::Vector3d& c) {
  // Sutherland-Hodgman against the half-space z <= 0.
  const Eigen::Vector3d in[3] = {a, b, c};
  Eigen::Vector3d poly[4];
  int n = 0;
  for (int i = 0; i < 3; ++i) {
    const Eigen::Vector3d& p = in[i];
    const Eigen::Vector3d& q = in[(i + 1) % 3];
    const bool p_in = p.z() <= 0, q_in = q.z() <= 0;
    if (p_in) poly[n++] = p;
    if (p_in != q_in) {
      const double t = p.z() / (p.z() - q.z());
      poly[n] = p + t * (q - p);
      poly[n].z() = 0.0;
      ++n;
    }
  }
  std::vector<std::array<Eigen::Vector3d, 3>> out;
  for (int k = 1; k + 1 < n; ++k) out.push_back({poly[0], poly[k], poly[k + 1]});
  return out;
}

double UnderwaterVolume(const TriangleSurface& s) {
  double v = 0;
  for (const auto& t : s.triangles) {
    for (const auto& tri : ClipBelowWaterline(s.vertices[t[0]], s.vertices[t[1]], s.vertices[t[2]])) {
      const Eigen::Vector3d N = 0.5 * (tri[1] - tri[0]).cross(tri[2] - tri[0]);
      v += (tri[0].z() + tri[1].z() + tri[2].z()) / 3.0 * N.z();
    }
  }
  return v;
}

double SectionArea(const TriangleSurface& s, double xs) {
  double area = 0;
  for (const auto& t : s.triangles) {
    const Eigen::Vector3d& a0 = s.vertices[t[0]];
    const Eigen::Vector3d& b0 = s.vertices[t[1]];
    const Eigen::Vector3d& c0 = s.vertices[t[2]];
    const double xmin = std::min({a0.x(), b0.x(), c0.x()}), xmax = std::max({a0.x(), b0.x(), c0.x()});
    if (xs < xmin || xs > xmax || xmin == xmax) continue;
    for (const auto& tri : ClipBelowWaterline(a0, b0, c0)) {
      // Segment where the plane x = xs cuts this triangle.
      Eigen::Vector3d pts[3];
      int n = 0;
      for (int i = 0; i < 3 && n < 2; ++i) {
        const Eigen::Vector3d& p = tri[i];
        const Eigen::Vector3d& q = tri[(i + 1) % 3];
        const double dp = p.x() - xs, dq = q.x() - xs;
        if ((dp < 0 && dq >= 0) || (dp >= 0 && dq < 0)) pts[n++] = p + (dp / (dp - dq)) * (q - p);
      }
      if (n < 2) continue;
      const Eigen::Vector3d N = (tri[1] - tri[0]).cross(tri[2] - tri[0]);
      // Counter-clockwise around the section seen from +x: tangent (-n_z, n_y).
      Eigen::Vector3d p = pts[0], q = pts[1];
      if ((q.y() - p.y()) * (-N.z()) + (q.z() - p.z()) * N.y() < 0) std::swap(p, q);
      area += 0.5 * (p.y() + q.y()) * (q.z() - p.z());
    }
  }
  return area;
}

Hydrostatics ComputeHydrostatics(const TriangleSurface& s, double Lpp, double B, double T, int stations) {
  Hydrostatics h;
  double xv = 0, xwp = 0;
  double xlo = 1e300, xhi = -1e300, ylo = 1e300, yhi = -1e300, zlo = 0;
  for (const auto& t : s.triangles) {
    for (const auto& tri : ClipBelowWaterline(s.vertices[t[0]], s.vertices[t[1]], s.vertices[t[2]])) {
      const Eigen::Vector3d N = 0.5 * (tri[1] - tri[0]).cross(tri[2] - tri[0]);
      double sx = 0, sz = 0, sxz = 0;
      for (const auto& p : tri) {
        sx += p.x();
        sz += p.z();
        sxz += p.x() * p.z();
        zlo = std::min(zlo, p.z());
        h.x_min = std::min(h.x_min, p.x());
        h.x_max = std::max(h.x_max, p.x());
        if (p.z() == 0.0) {
          xlo = std::min(xlo, p.x());
          xhi = std::max(xhi, p.x());
          ylo = std::min(ylo, p.y());
          yhi = std::max(yhi, p.y());
        }
      }
      h.wetted_area += N.norm();
      h.volume += sz / 3.0 * N.z();
      xv += N.z() / 12.0 * (sxz + sx * sz);  // integral of x z over the triangle, times n_z
      h.waterplane_area -= N.z();
      xwp -= N.z() * sx / 3.0;
    }
  }
  h.lcb = h.volume != 0 ? xv / h.volume : 0;
  // A submerged body has no waterline and no waterplane (what the sum leaves
  // of a closed surface is round-off).
  if (xhi < xlo) h.waterplane_area = xwp = 0;
  h.lcf = h.waterplane_area != 0 ? xwp / h.waterplane_area : 0;
  h.draft = -zlo;
  h.lwl = xhi > xlo ? xhi - xlo : 0;
  h.bwl = yhi > ylo ? yhi - ylo : 0;
  const double Am = SectionArea(s, 0.5 * Lpp);
  h.Cb = h.volume / (Lpp * B * T);
  h.Cm = Am / (B * T);
  h.Cwp = h.waterplane_area / (Lpp * B);
  h.Cp = Am > 0 ? h.volume / (Am * Lpp) : 0;
  for (int i = 0; i < stations; ++i) {
    const double x = Lpp * i / (stations - 1);
    h.sectional_areas.emplace_back(x, SectionArea(s, x));
  }
  return h;
}

std::string Hydrostatics::Report() const {
  std::string r = fmt::format(
      "  displacement volume  {:.6g} m^3\n  wetted area          {:.6g} m^2\n  waterplane area      {:.6g} m^2\n"
      "  LCB from AP          {:.6g} m\n  LCF from AP          {:.6g} m\n  draft                {:.6g} m\n"
      "  Lwl x Bwl            {:.6g} x {:.6g} m\n  Cb {:.4f}  Cm {:.4f}  Cwp {:.4f}  Cp {:.4f}\n  sectional areas (x m: A m^2):",
      volume, wetted_area, waterplane_area, lcb, lcf, draft, lwl, bwl, Cb, Cm, Cwp, Cp);
  for (const auto& [x, a] : sectional_areas) r += fmt::format(" {:.4g}:{:.4g}", x, a);
  return r + "\n";
}

HullPlacement LoadHullPlacement(const fs::path& ship_file) {
  const auto root = data::ConfigNode::LoadFile(ship_file);
  HullPlacement p;
  const auto ship = root["ship"];
  p.name = ship.Get<std::string>("name");
  p.scale = ship.Get<double>("scale", 1.0);
  const auto pr = root["principal"];
  p.Lpp = pr.GetPositive("Lpp");
  p.B = pr.GetPositive("B");
  p.T = pr.GetPositive("d");
  if (pr.Has("displacement")) p.displacement = pr.GetPositive("displacement");
  const auto g = root["geometry"];
  g.ExpectKeys({"file", "length_unit", "x_ap", "waterline_z", "bow_direction", "repair", "merge_tolerance",
                "short_edge", "submerged"});
  fs::path file = g.Get<std::string>("file");
  if (file.is_relative()) file = ship_file.parent_path() / file;
  p.file = file;
  p.length_unit = g.GetPositive("length_unit");
  p.x_ap = g.Get<double>("x_ap", 0.0);
  p.waterline_z = g.Get<double>("waterline_z");
  const std::string dir = g.Get<std::string>("bow_direction", "+x");
  if (dir == "-x") {
    p.bow_towards_minus_x = true;
  } else if (dir != "+x") {
    g["bow_direction"].Fail("'+x' or '-x'");
  }
  p.repair = g.Get<bool>("repair", true);
  p.submerged = g.Get<bool>("submerged", false);
  if (g.Has("merge_tolerance")) p.repair_options.merge_tolerance = g.GetPositive("merge_tolerance");
  if (g.Has("short_edge")) p.repair_options.short_edge = g.GetPositive("short_edge");
  return p;
}

TriangleSurface LoadHull(const HullPlacement& p, SurfaceCheck* check, RepairReport* repair) {
  TriangleSurface s = ReadSurface(p.file);
  const double sgn = p.bow_towards_minus_x ? -1.0 : 1.0;
  for (auto& v : s.vertices) {
    // x forward from AP; a flip of x also flips y to keep the axes right-handed.
    v = Eigen::Vector3d(sgn * (v.x() * p.length_unit - p.x_ap), sgn * v.y() * p.length_unit,
                        v.z() * p.length_unit - p.waterline_z);
  }
  if (p.repair) {
    RepairOptions o = p.repair_options;
    o.waterline_z = 0.0;
    s = RepairSurface(s, o, repair);
  }
  const SurfaceCheck c = ValidateHull(s, 0.0, p.submerged);
  if (check) *check = c;
  return s;
}

double WigleyHalfBeam(double L, double B, double T, double x, double z) {
  const double xi = 2.0 * (x - 0.5 * L) / L, zeta = z / T;
  const double bx = std::abs(xi) >= 1.0 ? 0.0 : 0.5 * B * (1.0 - xi * xi);
  return bx * (1.0 - zeta * zeta);
}

TriangleSurface WigleySurface(double L, double B, double T, double freeboard, int nx, int nz) {
  TriangleSurface s;
  s.source = fmt::format("Wigley hull L={} B={} T={}", L, B, T);
  auto half_beam = [&](double x, double z) { return WigleyHalfBeam(L, B, T, x, z); };
  // Vertex grid on each side; the keel (z = -T) and the ends (x = 0, L)
  // have zero half-beam and are shared by both sides.
  std::vector<int> port((nx + 1) * (nz + 1)), stbd((nx + 1) * (nz + 1));
  const double zt = freeboard;
  for (int i = 0; i <= nx; ++i) {
    const double x = L * i / nx;
    for (int k = 0; k <= nz; ++k) {
      const double z = -T + (T + zt) * k / nz;
      const double y = half_beam(x, z);
      const int id = i * (nz + 1) + k;
      port[id] = static_cast<int>(s.vertices.size());
      s.vertices.emplace_back(x, y, z);
      if (y == 0.0) {
        stbd[id] = port[id];
      } else {
        stbd[id] = static_cast<int>(s.vertices.size());
        s.vertices.emplace_back(x, -y, z);
      }
    }
  }
  auto add = [&](int a, int b, int c) {
    if (a == b || b == c || a == c) return;
    // A panel with all corners on the centreplane (at the ends, next to the
    // keel) has zero width: the port and starboard copies would cancel.
    if (s.vertices[a].y() == 0 && s.vertices[b].y() == 0 && s.vertices[c].y() == 0) return;
    s.triangles.push_back({a, b, c});
  };
  for (int i = 0; i < nx; ++i) {
    for (int k = 0; k < nz; ++k) {
      const int a = i * (nz + 1) + k, b = (i + 1) * (nz + 1) + k, c = (i + 1) * (nz + 1) + k + 1,
                d = i * (nz + 1) + k + 1;
      // Port side (y > 0): outward normal +y.
      add(port[a], port[c], port[b]);
      add(port[a], port[d], port[c]);
      // Starboard side (y < 0): outward normal -y.
      add(stbd[a], stbd[b], stbd[c]);
      add(stbd[a], stbd[c], stbd[d]);
    }
  }
  // Flat deck at z = freeboard, normal +z.
  for (int i = 0; i < nx; ++i) {
    const int a = i * (nz + 1) + nz, b = (i + 1) * (nz + 1) + nz;
    add(stbd[a], stbd[b], port[b]);
    add(stbd[a], port[b], port[a]);
  }
  return s;
}

}  // namespace kelvin::cfd
