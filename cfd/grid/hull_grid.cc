#include "cfd/grid/hull_grid.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <tuple>

#include "cfd/grid/spacing.h"
#include "data/schema/errors.h"

namespace kelvin::cfd {

namespace {

// Lines leave the inner boundary with slope tau (dz per unit horizontal
// distance) and relax to horizontal over one relaxation length l for the
// whole grid, l = max(kRelaxFraction * draft, kOffsetDecay * beam). tau is
// made k-Lipschitz along z with k = kLipschitz / l, so neighbouring lines
// approach each other by at most kLipschitz of their spacing.
constexpr double kRelaxFraction = 0.4;
constexpr double kLipschitz = 0.5;
// The relaxation length is at least kOffsetDecay times the largest beam, so
// the lines' horizontal speed 1 - f R'(d) >= 1 - 1/(2e) stays positive.
constexpr double kOffsetDecay = 2.0;
// Largest change of a line's far-field depth per unit x.
constexpr double kXSlope = 0.15;
// Fraction of the wall-normal tilt the lines start with (0 = horizontal lines,
// whose non-orthogonality at a V keel reaches atan(dy/dz) there).
constexpr double kTiltFraction = 0.5;
// Steepest section slope |dy/dz| the topology accepts (a flat bottom or a
// round U-section has an unbounded slope at the keel).
constexpr double kMaxSectionSlope = 4.0;

void RequirePositive(const char* key, double v) {
  if (!(v > 0) || !std::isfinite(v)) {
    throw ConfigError(
        fmt::format("hull grid option '{}' = {}: expected a finite number > 0", key, v));
  }
}

void RequireCells(const char* key, int n, int min) {
  if (n < min || n > 100000) {
    throw ConfigError(fmt::format("hull grid option '{}' = {}: expected an integer in [{}, 100000]",
                                  key, n, min));
  }
}

struct Face {
  int owner;
  int neighbour;  // -1 on the boundary
  std::array<int, 4> points;
};

}  // namespace

void HullGridOptions::Validate() const {
  RequirePositive("upstream", upstream);
  RequirePositive("downstream", downstream);
  RequirePositive("half_width", half_width);
  RequirePositive("depth", depth);
  RequireCells("cells_hull", cells_hull, 2);
  RequireCells("cells_upstream", cells_upstream, 1);
  RequireCells("cells_downstream", cells_downstream, 1);
  RequireCells("cells_girth", cells_girth, 2);
  RequireCells("cells_below_keel", cells_below_keel, 1);
  RequireCells("cells_normal", cells_normal, 2);
  RequirePositive("end_spacing", end_spacing);
  RequirePositive("free_surface_spacing", free_surface_spacing);
  RequirePositive("keel_spacing", keel_spacing);
  RequirePositive("y_plus", y_plus);
  if (!(wave_froude >= 0.0) || !std::isfinite(wave_froude)) {
    throw ConfigError(fmt::format("hull grid option 'waves.froude' = {}: expected a finite number >= 0", wave_froude));
  }
  if (wave_froude > 0.0) RequirePositive("waves.cells_per_wavelength", cells_per_wave);
  if (!(reynolds >= 1e3) || !std::isfinite(reynolds)) {
    throw ConfigError(fmt::format(
        "hull grid option 'reynolds' = {}: expected a finite number >= 1000", reynolds));
  }
}

HullGridOptions HullGridOptions::Coarsened(double ratio) const {
  HullGridOptions o = *this;
  auto scale = [ratio](int n, int min) {
    return std::max(min, static_cast<int>(std::lround(n / ratio)));
  };
  o.cells_hull = scale(cells_hull, 2);
  o.cells_upstream = scale(cells_upstream, 1);
  o.cells_downstream = scale(cells_downstream, 1);
  o.cells_girth = scale(cells_girth, 2);
  o.cells_below_keel = scale(cells_below_keel, 1);
  o.cells_normal = scale(cells_normal, 2);
  o.y_plus = y_plus * ratio;
  o.cells_per_wave = cells_per_wave / ratio;
  return o;
}

int HullGridOptions::CellCount() const {
  return (cells_hull + cells_upstream + cells_downstream) * 2 * (cells_girth + cells_below_keel) *
         cells_normal;
}

Mesh MakeHullGrid(const HullSections& hull, const HullGridOptions& o, HullGridInfo* info) {
  o.Validate();
  const double xa = hull.x_aft(), xf = hull.x_fore(), L = xf - xa;
  const double W = o.half_width * L, D = o.depth * L;
  const double h_wall = FirstCellHeight(o.y_plus, o.reynolds, L);
  // Largest spacing on the free surface away from the hull (0: no cap).
  const double h_wave =
      o.wave_froude > 0.0 ? 2.0 * std::numbers::pi * o.wave_froude * o.wave_froude * L / o.cells_per_wave : 0.0;
  // A capped distribution, or the error naming the option whose count is short.
  auto capped = [&](const char* key, int n, double length, double h1) {
    try {
      return CappedGeometricNodes(n, length, h1, h_wave);
    } catch (const ConfigError& e) {
      throw ConfigError(fmt::format("hull grid option '{}' = {} with waves at Fn {} and {} cells per wavelength ({:.4g} m): {}",
                                    key, n, o.wave_froude, o.cells_per_wave, h_wave, e.what()));
    }
  };

  // Stations.
  const std::vector<double> sx = TwoSidedNodes(o.cells_hull, L, o.end_spacing * L / o.cells_hull,
                                               o.end_spacing * L / o.cells_hull);
  const std::vector<double> up =
      capped("cells_upstream", o.cells_upstream, o.upstream * L, sx[o.cells_hull] - sx[o.cells_hull - 1]);
  const std::vector<double> down = capped("cells_downstream", o.cells_downstream, o.downstream * L, sx[1] - sx[0]);
  std::vector<double> x;
  for (int i = o.cells_downstream; i >= 1; --i) x.push_back(xa - down[i]);
  for (double s : sx) x.push_back(xa + s);
  x.back() = xf;
  for (int i = 1; i <= o.cells_upstream; ++i) x.push_back(xf + up[i]);
  const int k_aft = o.cells_downstream, k_fore = o.cells_downstream + o.cells_hull;
  const int nx = static_cast<int>(x.size()) - 1;  // cells along x
  const int ng = o.cells_girth, nj = o.cells_girth + o.cells_below_keel, ni = o.cells_normal;

  // Point indices: [k][side][i][j], side 0 = -y, 1 = +y; inner points on the
  // centreplane are shared by both sides.
  auto slot = [&](int k, int side, int i, int j) {
    return ((static_cast<std::size_t>(k) * 2 + side) * (ni + 1) + i) * (nj + 1) + j;
  };
  std::vector<int> pid(static_cast<std::size_t>(nx + 1) * 2 * (ni + 1) * (nj + 1), -1);
  std::vector<Vector3> points;
  points.reserve(pid.size());
  double max_tilt = 0.0;
  // Hull-to-side distribution, normalised to [0, 1].
  std::vector<double> sigma = capped("cells_normal", ni, W, h_wall);
  for (double& v : sigma) v /= W;

  struct Station {
    double draft;
    std::vector<double> z;
    std::vector<double> f[2];
    bool on_hull;
    std::vector<double> tilt[2];  // initial slope dz/dd of the lines
  };
  std::vector<Station> stations(nx + 1);
  for (int k = 0; k <= nx; ++k) {
    const double xk = x[k];
    const double keel = hull.KeelZ(std::clamp(xk, xa, xf));
    const double draft = -keel;
    if (!(D > 1.05 * draft)) {
      throw ConfigError(fmt::format(
          "hull grid option 'depth' = {} hull lengths puts the bottom at z = {:.6g} m, above "
          "or too close to the keel at z = {:.6g} m of {}",
          o.depth, -D, keel, hull.name()));
    }
    // Nodes along the inner boundary: hull from the waterline to the keel,
    // then the centreplane down to the bottom.
    const std::vector<double> zg =
        TwoSidedNodes(ng, draft, o.free_surface_spacing * draft / ng, o.keel_spacing * draft / ng);
    const std::vector<double> zb =
        GeometricNodes(o.cells_below_keel, D - draft, zg[ng] - zg[ng - 1]);
    std::vector<double> z(nj + 1);
    for (int j = 0; j <= ng; ++j) z[j] = -zg[j];
    z[ng] = keel;
    for (int m = 1; m <= o.cells_below_keel; ++m) z[ng + m] = keel - zb[m];
    z[nj] = -D;

    // Half-breadths of the two sides (zero off the hull and at its ends).
    std::vector<double> f[2];
    f[0].assign(nj + 1, 0.0);
    f[1].assign(nj + 1, 0.0);
    const bool on_hull = k > k_aft && k < k_fore;
    if (on_hull) {
      const auto br = hull.Breadths(xk, std::span<const double>(z.data(), ng + 1));
      if (!(br[0][1] > br[0][0])) {
        throw DataFileError(fmt::format(
            "{}: the section at x = {:.6g} m does not reach the waterline z = 0 (a bulb "
            "or a raked stem?); the built-in generator needs sections from the waterline "
            "to the keel: use mesh method 'snappy'",
            hull.name(), xk));
      }
      for (int j = 0; j < ng; ++j) {
        if (br[j][0] > 1e-9 * L || br[j][1] < -1e-9 * L) {
          throw DataFileError(fmt::format(
              "{}: the section at x = {:.6g} m, z = {:.6g} m spans y = [{:.6g}, {:.6g}] m and "
              "does not contain the centreplane y = 0; use mesh method 'snappy'",
              hull.name(), xk, z[j], br[j][0], br[j][1]));
        }
        if (!(br[j][1] > br[j][0])) {
          throw DataFileError(fmt::format(
              "{}: the section at x = {:.6g} m has no hull at z = {:.6g} m above its keel "
              "at z = {:.6g} m (not simply connected); use mesh method 'snappy'",
              hull.name(), xk, z[j], keel));
        }
        f[0][j] = std::max(0.0, -br[j][0]);
        f[1][j] = std::max(0.0, br[j][1]);
      }
    }
    stations[k] = {draft, std::move(z), {std::move(f[0]), std::move(f[1])}, on_hull, {}};
  }
  // Lines relax to horizontal, and their offsets from the hull shape fade,
  // over one length for the whole grid, so that far from the hull the nodes
  // of neighbouring lines stand one above the other and the lines of
  // neighbouring stations run alongside.
  double relax = 0.0;
  for (const Station& st : stations) {
    const double beam = *std::max_element(st.f[0].begin(), st.f[0].end()) +
                        *std::max_element(st.f[1].begin(), st.f[1].end());
    relax = std::max({relax, kOffsetDecay * beam, kRelaxFraction * st.draft});
  }
  const double lip = kLipschitz / relax;
  // The offset f fades as f (1 - R(d)) with R(d) = 1 - (1 + d/l) exp(-d/l)
  // normalised to R(W) = 1: R'(0) = 0, so a line's first step from the wall
  // is unchanged, and R' <= 1 / (e l) keeps the lines moving outwards.
  const double fade_norm = 1.0 - (1.0 + W / relax) * std::exp(-W / relax);
  auto fade = [&](double d) {
    return (1.0 - (1.0 + d / relax) * std::exp(-d / relax)) / fade_norm;
  };
  for (int k = 0; k <= nx; ++k) {
    const double xk = x[k];
    const std::vector<double>& z = stations[k].z;
    const std::vector<double>(&f)[2] = stations[k].f;
    const bool on_hull = stations[k].on_hull;
    for (int side = 0; side < 2; ++side) {
      const std::vector<double>& fs = f[side];
      // Raw slope d(half-breadth)/dz: the wall-normal direction.
      std::vector<double> tau(nj + 1, 0.0);
      if (on_hull) {
        for (int j = 1; j < ng; ++j) tau[j] = (fs[j + 1] - fs[j - 1]) / (z[j + 1] - z[j - 1]);
        tau[ng] = 0.5 * (fs[ng] - fs[ng - 1]) / (z[ng] - z[ng - 1]);
        for (int j = 1; j <= ng; ++j) {
          if (std::abs(tau[j]) > kMaxSectionSlope) {
            throw DataFileError(fmt::format(
                "{}: the section at x = {:.6g} m is too flat at z = {:.6g} m (|dy/dz| = "
                "{:.3g} > {}); the built-in generator needs V-shaped sections: use mesh "
                "method 'snappy'",
                hull.name(), xk, z[j], std::abs(tau[j]), kMaxSectionSlope));
          }
          // Lines leave at kTiltFraction of the normal's tilt: fully normal
          // lines shear the cells where the tilt fades in x and along the girth.
          tau[j] *= kTiltFraction;
        }
      }
      // Lipschitz envelopes; their mean is Lipschitz too.
      std::vector<double> ts(nj + 1);
      for (int j = 0; j <= nj; ++j) {
        double hi = -1e300, lo = 1e300;
        for (int m = 0; m <= nj; ++m) {
          hi = std::max(hi, tau[m] - lip * std::abs(z[j] - z[m]));
          lo = std::min(lo, tau[m] + lip * std::abs(z[j] - z[m]));
        }
        // |tilt| <= lip * (distance to z = 0 and to the bottom): the lines
        // j = 0 and j = nj stay on those planes and no line crosses them.
        const double bound = lip * std::min(-z[j], z[j] + D);
        ts[j] = std::clamp(0.5 * (hi + lo), -bound, bound);
      }
      stations[k].tilt[side] = std::move(ts);
    }
  }
  // The same envelopes along x keep the surfaces j = const from tilting
  // steeply in x where the hull's beam vanishes at bow and stern. The bounds
  // are the same for every station, so the result stays Lipschitz in z.
  const double lip_x = kXSlope / relax;
  for (int side = 0; side < 2; ++side) {
    for (int j = 0; j <= nj; ++j) {
      std::vector<double> smooth(nx + 1);
      for (int k = 0; k <= nx; ++k) {
        double hi = -1e300, lo = 1e300;
        for (int m = 0; m <= nx; ++m) {
          hi = std::max(hi, stations[m].tilt[side][j] - lip_x * std::abs(x[k] - x[m]));
          lo = std::min(lo, stations[m].tilt[side][j] + lip_x * std::abs(x[k] - x[m]));
        }
        smooth[k] = 0.5 * (hi + lo);
      }
      for (int k = 0; k <= nx; ++k) {
        stations[k].tilt[side][j] = smooth[k];
        max_tilt = std::max(max_tilt, std::atan(std::abs(smooth[k])) * 180.0 / std::numbers::pi);
      }
    }
  }
  for (int k = 0; k <= nx; ++k) {
    const double xk = x[k];
    const std::vector<double>(&f)[2] = stations[k].f;
    const std::vector<double>& z = stations[k].z;
    for (int side = 0; side < 2; ++side) {
      const std::vector<double>& fs = f[side];
      const std::vector<double>& ts = stations[k].tilt[side];
      for (int j = 0; j <= nj; ++j) {
        const double sign = side == 0 ? -1.0 : 1.0;
        for (int i = 0; i <= ni; ++i) {
          if (i == 0 && fs[j] == 0.0 && side == 1 && (f[0][j] == 0.0)) {
            pid[slot(k, 1, 0, j)] = pid[slot(k, 0, 0, j)];
            continue;
          }
          const double di = sigma[i] * W;
          const double y = (i == ni) ? sign * W : sign * (fs[j] + di - fs[j] * fade(di));
          const double zz = z[j] - ts[j] * relax * (1.0 - std::exp(-di / relax));
          pid[slot(k, side, i, j)] = static_cast<int>(points.size());
          points.emplace_back(xk, y, zz);
        }
      }
    }
  }

  // Cells: k outermost keeps the matrix bandwidth near 2 ni nj.
  auto cell = [&](int k, int side, int i, int j) { return ((k * 2 + side) * ni + i) * nj + j; };
  auto centre = [&](int k, int side, int i, int j) {
    Vector3 c = Vector3::Zero();
    for (int a = 0; a < 2; ++a)
      for (int b = 0; b < 2; ++b)
        for (int e = 0; e < 2; ++e) c += points[pid[slot(k + a, side, i + b, j + e)]];
    return Vector3(c / 8.0);
  };
  enum PatchId { kHull, kFreeSurface, kInlet, kOutlet, kSide, kBottom, kNumPatches };
  std::vector<Face> internal;
  std::vector<std::vector<Face>> boundary(kNumPatches);
  auto newell = [&](const std::array<int, 4>& q) {
    Vector3 n = Vector3::Zero();
    for (int m = 0; m < 4; ++m) n += points[q[m]].cross(points[q[(m + 1) % 4]]);
    return n;
  };
  auto add_internal = [&](int c0, int c1, std::array<int, 4> q, const Vector3& x0,
                          const Vector3& x1) {
    if (c0 > c1) {
      std::swap(c0, c1);
      if (newell(q).dot(x0 - x1) < 0) std::reverse(q.begin(), q.end());
    } else if (newell(q).dot(x1 - x0) < 0) {
      std::reverse(q.begin(), q.end());
    }
    internal.push_back({c0, c1, q});
  };
  auto add_boundary = [&](int patch, int c0, std::array<int, 4> q, const Vector3& x0) {
    Vector3 fc = Vector3::Zero();
    for (int p : q) fc += points[p];
    fc /= 4.0;
    if (newell(q).dot(fc - x0) < 0) std::reverse(q.begin(), q.end());
    boundary[patch].push_back({c0, -1, q});
  };
  for (int k = 0; k < nx; ++k) {
    for (int side = 0; side < 2; ++side) {
      for (int i = 0; i < ni; ++i) {
        for (int j = 0; j < nj; ++j) {
          const int c = cell(k, side, i, j);
          const Vector3 xc = centre(k, side, i, j);
          auto P = [&](int kk, int ii, int jj) { return pid[slot(kk, side, ii, jj)]; };
          // +x face.
          const std::array<int, 4> fx = {P(k + 1, i, j), P(k + 1, i + 1, j), P(k + 1, i + 1, j + 1),
                                         P(k + 1, i, j + 1)};
          if (k + 1 < nx)
            add_internal(c, cell(k + 1, side, i, j), fx, xc, centre(k + 1, side, i, j));
          else
            add_boundary(kInlet, c, fx, xc);
          if (k == 0)
            add_boundary(kOutlet, c,
                         {P(0, i, j), P(0, i + 1, j), P(0, i + 1, j + 1), P(0, i, j + 1)}, xc);
          // +i face.
          const std::array<int, 4> fi = {P(k, i + 1, j), P(k + 1, i + 1, j), P(k + 1, i + 1, j + 1),
                                         P(k, i + 1, j + 1)};
          if (i + 1 < ni)
            add_internal(c, cell(k, side, i + 1, j), fi, xc, centre(k, side, i + 1, j));
          else
            add_boundary(kSide, c, fi, xc);
          if (i == 0) {
            const std::array<int, 4> f0 = {P(k, 0, j), P(k + 1, 0, j), P(k + 1, 0, j + 1),
                                           P(k, 0, j + 1)};
            if (k >= k_aft && k < k_fore && j < ng) {
              add_boundary(kHull, c, f0, xc);
            } else if (side == 1) {
              for (int m = 0; m < 4; ++m) {
                KELVIN_CHECK(
                    f0[m] == (std::array<int, 4>{pid[slot(k, 0, 0, j)], pid[slot(k + 1, 0, 0, j)],
                                                 pid[slot(k + 1, 0, 0, j + 1)],
                                                 pid[slot(k, 0, 0, j + 1)]})[m],
                    "centreplane face not shared by the port and starboard blocks");
              }
              add_internal(cell(k, 0, 0, j), c, f0, centre(k, 0, 0, j), xc);
            }
          }
          // +j face (downwards).
          const std::array<int, 4> fj = {P(k, i, j + 1), P(k + 1, i, j + 1), P(k + 1, i + 1, j + 1),
                                         P(k, i + 1, j + 1)};
          if (j + 1 < nj)
            add_internal(c, cell(k, side, i, j + 1), fj, xc, centre(k, side, i, j + 1));
          else
            add_boundary(kBottom, c, fj, xc);
          if (j == 0)
            add_boundary(kFreeSurface, c,
                         {P(k, i, 0), P(k + 1, i, 0), P(k + 1, i + 1, 0), P(k, i + 1, 0)}, xc);
        }
      }
    }
  }
  std::sort(internal.begin(), internal.end(), [](const Face& a, const Face& b) {
    return std::tie(a.owner, a.neighbour) < std::tie(b.owner, b.neighbour);
  });

  std::vector<std::vector<int>> faces;
  std::vector<int> owner, neighbour;
  faces.reserve(internal.size() + 6 * 2 * nx * ni);
  for (const Face& fc : internal) {
    faces.emplace_back(fc.points.begin(), fc.points.end());
    owner.push_back(fc.owner);
    neighbour.push_back(fc.neighbour);
  }
  const char* names[kNumPatches] = {"hull", "freeSurface", "inlet", "outlet", "side", "bottom"};
  std::vector<Patch> patches;
  for (int p = 0; p < kNumPatches; ++p) {
    Patch patch;
    patch.name = names[p];
    patch.kind = p == kHull ? PatchKind::kWall : PatchKind::kPatch;
    patch.start = static_cast<int>(faces.size());
    patch.size = static_cast<int>(boundary[p].size());
    for (const Face& fc : boundary[p]) {
      faces.emplace_back(fc.points.begin(), fc.points.end());
      owner.push_back(fc.owner);
    }
    patches.push_back(patch);
  }
  if (info) {
    info->first_cell_height = h_wall;
    info->max_line_tilt_deg = max_tilt;
  }
  return Mesh(std::move(points), std::move(faces), std::move(owner), std::move(neighbour),
              std::move(patches), fmt::format("hull grid of {}", hull.name()));
}

double HullPatchVolume(const Mesh& mesh) {
  const int p = mesh.FindPatch("hull");
  if (p < 0) throw DataFileError(fmt::format("{}: no patch named 'hull'", mesh.source()));
  const Patch& patch = mesh.patches()[p];
  double v = 0.0;
  for (int f = patch.start; f < patch.start + patch.size; ++f) {
    const auto& face = mesh.faces()[f];
    const Vector3& c = mesh.face_centres()[f];
    for (std::size_t m = 0; m < face.size(); ++m) {
      const Vector3& a = mesh.points()[face[m]];
      const Vector3& b = mesh.points()[face[(m + 1) % face.size()]];
      const Vector3 s = 0.5 * (b - a).cross(c - a);
      v -= (a.z() + b.z() + c.z()) / 3.0 * s.z();
    }
  }
  return v;
}

YPlusEstimate EstimateYPlus(const Mesh& mesh, double reynolds, double length) {
  const int p = mesh.FindPatch("hull");
  if (p < 0) throw DataFileError(fmt::format("{}: no patch named 'hull'", mesh.source()));
  const Patch& patch = mesh.patches()[p];
  std::vector<double> y_plus, area;
  for (int f = patch.start; f < patch.start + patch.size; ++f) {
    const Vector3 n = mesh.face_areas()[f] / mesh.face_area_magnitudes()[f];
    const double y =
        std::abs((mesh.face_centres()[f] - mesh.cell_centres()[mesh.owner()[f]]).dot(n));
    y_plus.push_back(YPlusAt(y, reynolds, length));
    area.push_back(mesh.face_area_magnitudes()[f]);
  }
  YPlusEstimate e;
  e.stats = SummarizeWall("hull", y_plus, area);
  e.min = e.stats.y_plus_min;
  e.mean = e.stats.y_plus_mean;
  e.max = e.stats.y_plus_max;
  return e;
}

}  // namespace kelvin::cfd
