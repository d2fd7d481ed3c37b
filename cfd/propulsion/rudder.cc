#include "cfd/propulsion/rudder.h"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "cfd/propulsion/cell_overlap.h"
#include "data/schema/errors.h"

namespace kelvin::cfd {

namespace {

constexpr double kPi = std::numbers::pi;
// Blade positions are tabulated every kAngleStep and blended linearly.
constexpr double kAngleStep = 5.0 * kPi / 180.0;
// Least share of the blade box inside the mesh (the sampled volume is within 1% of the
// box on the grids the tests use; a larger shortfall is a blade through the domain boundary).
constexpr double kMinBladeShare = 0.95;

[[noreturn]] void BadOption(const std::string& name, const std::string& key, double value,
                            const std::string& expected) {
  throw ConfigError(fmt::format("{}.{} = {}: expected {}", name, key, value, expected));
}

std::string Format(const Vector3& v) { return fmt::format("({}, {}, {})", v.x(), v.y(), v.z()); }

// A box in body-fixed grid axes: centre, unit axes (columns) and half
// extents along them.
struct Box {
  Vector3 centre;
  Eigen::Matrix3d axes = Eigen::Matrix3d::Identity();
  Vector3 half;
  double Volume() const { return 8.0 * half.prod(); }
};

// The box, carried by the mesh placement (x_E = R x_B + t), as an overlap
// region whose densities are the body-axis coordinates (their integrals
// give the first moment of the inside part).
OverlapRegion BoxRegion(const Box& box, const Eigen::Matrix3d& R, const Vector3& t) {
  OverlapRegion region;
  const Eigen::Matrix3d to_local = box.axes.transpose() * R.transpose();
  const Vector3 origin = R * box.centre + t;
  region.distance = [box, to_local, origin](const Vector3& x, double grow) {
    const Vector3 local = to_local * (x - origin);
    return (local.cwiseAbs() - box.half - Vector3::Constant(grow)).cwiseMax(0.0).norm();
  };
  region.depth = [box, to_local, origin](const Vector3& x) {
    return (box.half - (to_local * (x - origin)).cwiseAbs()).minCoeff();
  };
  region.sample = [box, to_local, origin, R, t](const Vector3& x, std::span<double> densities) {
    const Vector3 local = to_local * (x - origin);
    if ((local.cwiseAbs().array() > box.half.array()).any()) return false;
    const Vector3 body = R.transpose() * (x - t);
    for (int d = 0; d < 3; ++d) densities[static_cast<std::size_t>(d)] = body[d];
    return true;
  };
  region.n_densities = 3;
  region.feature = 2.0 * box.half.minCoeff();
  // Only the tetrahedra that straddle the box's faces are split (depth):
  // three levels hold the blade's volume within about 1% (RudderLoads) at a
  // cost the 17 tabulated positions can afford on coarse stern cells.
  region.max_splits = 3;
  return region;
}

// The blade at angle delta: turned about the stock, the leading edge to
// port for delta > 0.
Box BladeBox(const RudderOptions& o, double delta) {
  const double c = o.chord();
  Box box{Vector3(o.stock.x(), o.stock.y(), o.stock.z() - 0.5 * o.span), Eigen::Matrix3d::Identity(),
          Vector3(0.5 * c, 0.5 * o.thickness * c, 0.5 * o.span)};
  box.axes.col(0) = Vector3(std::cos(delta), std::sin(delta), 0.0);
  box.axes.col(1) = Vector3(-std::sin(delta), std::cos(delta), 0.0);
  return box;
}

Box SampleBox(const RudderOptions& o) {
  const double c = o.chord();
  return {Vector3(o.stock.x() + 0.5 * c + o.sample_distance * c, o.stock.y(), o.stock.z() - 0.5 * o.span),
          Eigen::Matrix3d::Identity(), Vector3(0.5 * o.sample_length * c, 0.5 * o.thickness * c, 0.5 * o.span)};
}

// A box's cells: index, volume weight (sum 1) and centroid of the inside
// part (body axes).
struct BoxCells {
  std::vector<int> cells;
  std::vector<double> weights;
  std::vector<Vector3> centroids;
  double volume = 0.0;  // the box's volume the cells hold
};

BoxCells SampleBoxCells(const Mesh& mesh, const Box& box) {
  BoxCells out;
  const OverlapRegion region = BoxRegion(box, mesh.placement_rotation(), mesh.placement_translation());
  for (const CellOverlap& o : SampleOverlap(mesh, region)) {
    const double v = o.fraction * mesh.cell_volumes()[o.cell];
    out.cells.push_back(o.cell);
    out.weights.push_back(v);
    out.centroids.push_back(Vector3(o.integrals[0], o.integrals[1], o.integrals[2]) / v);
    out.volume += v;
  }
  for (double& w : out.weights) w /= out.volume;
  return out;
}

// rho U times the velocity induced at x by a point force F on the water at
// the origin in a stream along e (the header's linearized response).
Vector3 PointForceResponse(const Vector3& x, const Vector3& F, const Vector3& e) {
  const double a = x.dot(e), r = x.norm();
  const Vector3 b = x - a * e;
  const double F_e = F.dot(e);
  const Vector3 F_perp = F - F_e * e;
  const double h = 1.0 / (r * (r - a));
  const Vector3 grad_h = -h * h * ((2.0 * r - a) / r * x - r * e);
  const Vector3 grad_G = (F_e / (r * r * r) * x + h * F_perp + F_perp.dot(b) * grad_h) / (4.0 * kPi);
  return -grad_G;
}

// rho U times the sample-mean velocity induced per unit force on the water
// (columns: unit force along grid x, y, z) by a blade position, e = -x.
Eigen::Matrix3d InducedMatrix(const BoxCells& blade, const BoxCells& sample, bool waterline_image) {
  const Vector3 e = -Vector3::UnitX();
  Eigen::Matrix3d M = Eigen::Matrix3d::Zero();
  for (int k = 0; k < 3; ++k) {
    const Vector3 F = Vector3::Unit(k);
    const Vector3 F_image(F.x(), F.y(), -F.z());
    Vector3 sum = Vector3::Zero();
    for (std::size_t s = 0; s < sample.cells.size(); ++s) {
      for (std::size_t b = 0; b < blade.cells.size(); ++b) {
        const Vector3& y = blade.centroids[b];
        Vector3 u = PointForceResponse(sample.centroids[s] - y, F, e);
        if (waterline_image) u += PointForceResponse(sample.centroids[s] - Vector3(y.x(), y.y(), -y.z()), F_image, e);
        sum += sample.weights[s] * blade.weights[b] * u;
      }
    }
    M.col(k) = sum;
  }
  return M;
}

}  // namespace

double FujiiLiftSlope(double aspect_ratio) { return 6.13 * aspect_ratio / (aspect_ratio + 2.25); }

void RudderOptions::Validate() const {
  if (!(area > 0) || !std::isfinite(area)) BadOption(name, "area", area, "a positive rudder area A_R (m^2)");
  if (!(span > 0) || !std::isfinite(span)) BadOption(name, "span", span, "a positive rudder span H_R (m)");
  for (int d = 0; d < 3; ++d) {
    if (!std::isfinite(stock[d])) {
      throw ConfigError(fmt::format("{}.stock = {}: expected finite coordinates (m)", name, Format(stock)));
    }
  }
  if (!(thickness > 0 && thickness <= 1)) BadOption(name, "thickness", thickness, "a blade thickness / chord in (0, 1]");
  if (!(sample_length > 0) || !std::isfinite(sample_length)) {
    BadOption(name, "sample_length", sample_length, "a positive length in chords");
  }
  if (!(sample_distance > 0.5 * sample_length) || !std::isfinite(sample_distance)) {
    BadOption(name, "sample_distance", sample_distance,
              fmt::format("more than half the sample length ({} chords): the sample box ahead of the leading edge",
                          0.5 * sample_length));
  }
  if (!(lift_slope >= 0) || !std::isfinite(lift_slope)) {
    BadOption(name, "lift_slope", lift_slope, "a non-negative f_alpha (1/rad; 0: Fujii's formula)");
  }
  if (!(stall_angle > 0 && stall_angle <= 0.5 * kPi)) {
    BadOption(name, "stall_angle_deg", stall_angle * 180 / kPi, "an angle in (0, 90] deg");
  }
  if (!(max_angle >= 0 && max_angle <= 0.5 * kPi)) {
    BadOption(name, "max_angle_deg", max_angle * 180 / kPi, "an angle in [0, 90] deg (the ship's rudder limit)");
  }
  if (!(force_relaxation > 0 && force_relaxation <= 1)) {
    BadOption(name, "force_relaxation", force_relaxation, "a value in (0, 1]");
  }
  if (!(min_cells_across >= 0)) BadOption(name, "min_cells_across", min_cells_across, "a non-negative value");
}

Rudder::Rudder(const Mesh& mesh, RudderOptions options) : options_(std::move(options)), n_cells_(mesh.n_cells()) {
  options_.Validate();
  KELVIN_CHECK(mesh.placement_rotation().isIdentity(0.0) && mesh.placement_translation().isZero(0.0),
               "Rudder needs the body-fixed mesh (construct it before any placement)");
  lift_slope_ = options_.lift_slope > 0 ? options_.lift_slope : FujiiLiftSlope(options_.aspect_ratio());
  const std::string what = fmt::format("(chord {:.4g} m, span {:.4g} m, top at z = {:.4g} m)", options_.chord(),
                                       options_.span, options_.stock.z());
  if (SampleBoxCells(mesh, BladeBox(options_, 0.0)).cells.empty()) {
    throw ConfigError(fmt::format("{}.stock = {}: the rudder blade {} contains no cell of mesh '{}': expected the "
                                  "rudder inside the mesh",
                                  options_.name, Format(options_.stock), what, mesh.source()));
  }
  const BoxCells sample = SampleBoxCells(mesh, SampleBox(options_));
  if (sample.cells.empty()) {
    throw ConfigError(fmt::format("{}.sample_distance = {}: the inflow sample box {} chords ahead of the rudder {} "
                                  "contains no cell of mesh '{}'",
                                  options_.name, options_.sample_distance, options_.sample_distance, what,
                                  mesh.source()));
  }
  sample_cells_ = sample.cells;
  sample_weight_ = sample.weights;
  const int n_side = static_cast<int>(std::ceil(options_.max_angle / kAngleStep - 1e-9));
  for (int k = -n_side; k <= n_side; ++k) {
    const double angle = k * kAngleStep;
    const Box box = BladeBox(options_, angle);
    const BoxCells cells = SampleBoxCells(mesh, box);
    if (cells.cells.empty()) {
      throw ConfigError(fmt::format("{}.stock = {}: the rudder blade {} at {:g} deg contains no cell of mesh '{}': "
                                    "expected the rudder inside the mesh",
                                    options_.name, Format(options_.stock), what, angle * 180 / kPi, mesh.source()));
    }
    BladePosition pos{angle, cells.cells, cells.weights, {}, InducedMatrix(cells, sample, options_.waterline_image), {}};
    for (int c : pos.cells) pos.volumes.push_back(mesh.cell_volumes()[c]);
    CheckWalls(mesh, pos);
    const double share = cells.volume / box.Volume();
    if (share < kMinBladeShare) {
      throw ConfigError(fmt::format("{}.stock = {}: only {:.1f}% of the rudder blade {} at {:g} deg lies inside mesh "
                                    "'{}': expected the whole blade inside the mesh (its force would act on the "
                                    "part inside only)",
                                    options_.name, Format(options_.stock), 100 * share, what, angle * 180 / kPi,
                                    mesh.source()));
    }
    if (k == 0) blade_share_ = share;
    positions_.push_back(std::move(pos));
  }
  Localize(nullptr, n_cells_);
  const BladePosition& amidships = positions_[static_cast<std::size_t>(n_side)];
  std::vector<double> v = amidships.volumes;
  std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2), v.end());
  cells_across_ = options_.chord() / std::cbrt(v[v.size() / 2]);
  if (cells_across_ < options_.min_cells_across) {
    spdlog::warn("{}: only {:.1f} cells across the rudder chord (c = {:.4g} m; {} or more recommended): the blade's "
                 "force is smeared and its inflow sample coarse",
                 options_.name, cells_across_, options_.chord(), options_.min_cells_across);
  }
}

std::pair<std::size_t, double> Rudder::Bracket(double delta) const {
  const double limit = positions_.back().angle;
  const double d = std::clamp(delta, -limit, limit);
  const double u = (d + limit) / kAngleStep;
  const std::size_t k = std::min(static_cast<std::size_t>(std::floor(u)), positions_.size() - 2);
  return {k, u - static_cast<double>(k)};
}

void Rudder::Localize(std::shared_ptr<const DomainPart> part, int n_cells) {
  part_ = std::move(part);
  n_cells_ = n_cells;
  sample_own_ = OwnEntries(part_.get(), sample_cells_);
  for (BladePosition& pos : positions_) pos.own = OwnEntries(part_.get(), pos.cells);
}

Eigen::Matrix3d Rudder::Induced(double delta) const {
  if (positions_.size() == 1) return positions_[0].induced;
  const auto [k, s] = Bracket(delta);
  return (1.0 - s) * positions_[k].induced + s * positions_[k + 1].induced;
}

void Rudder::CheckWalls(const Mesh& mesh, const BladePosition& pos) const {
  std::vector<char> in_blade(static_cast<std::size_t>(mesh.n_cells()), 0);
  for (int c : pos.cells) in_blade[static_cast<std::size_t>(c)] = 1;
  for (const Patch& patch : mesh.patches()) {
    if (patch.kind != PatchKind::kWall) continue;
    for (int f = patch.start; f < patch.start + patch.size; ++f) {
      if (!in_blade[static_cast<std::size_t>(mesh.owner()[f])]) continue;
      throw ConfigError(fmt::format("{}.stock = {}: the rudder blade at {:g} deg touches wall patch '{}' at face "
                                    "centre {} of mesh '{}': expected the blade clear of the hull (move the rudder aft "
                                    "or down)",
                                    options_.name, Format(options_.stock), pos.angle * 180 / kPi, patch.name,
                                    Format(mesh.face_centres()[f]), mesh.source()));
    }
  }
}

double Rudder::NormalForceCoefficient(double alpha) const {
  const double a = std::remainder(alpha, 2.0 * kPi);
  if (std::abs(a) <= options_.stall_angle) return lift_slope_ * std::sin(a);
  return std::copysign(lift_slope_ * std::sin(options_.stall_angle), a);
}

RudderState Rudder::Update(const PimpleSolver& solver, const BodyVelocity& body_velocity, const Eigen::Matrix3d& R,
                           double delta, double rho, std::vector<Vector3>& cell_source) {
  KELVIN_CHECK(rho > 0, "positive density");
  Vector3 w_E = Vector3::Zero();
  for (std::size_t k = 0; k < sample_own_.entries.size(); ++k) {
    const int c = sample_own_.cells[k];
    Vector3 u = solver.U()[c];
    if (body_velocity) u -= body_velocity(c);
    w_E += sample_weight_[static_cast<std::size_t>(sample_own_.entries[k])] * u;
  }
  if (part_) part_->SumInPlace(std::span<double>(w_E.data(), 3));
  const Vector3 w_B = R.transpose() * w_E;
  RudderState s;
  s.delta = delta;
  s.u_sample = -w_B.x();
  s.v_sample = -w_B.y();
  Vector3 w_free = w_B;
  const double U_ref = std::hypot(w_B.x(), w_B.y());
  if (state_.started && U_ref > 0.0) {
    const Vector3 F_water = -state_.F_N * Vector3(-std::sin(state_.delta), std::cos(state_.delta), 0.0);
    w_free -= Induced(state_.delta) * F_water / (rho * U_ref);
  }
  s.u_R = -w_free.x();
  s.v_R = -w_free.y();
  s.alpha_R = delta - std::atan2(s.v_R, s.u_R);
  const double F_new = 0.5 * rho * options_.area * (s.u_R * s.u_R + s.v_R * s.v_R) * NormalForceCoefficient(s.alpha_R);
  s.F_N = state_.started ? state_.F_N + options_.force_relaxation * (F_new - state_.F_N) : F_new;
  state_ = {s.F_N, delta, true};
  Apply(s.F_N, delta, rho, R, cell_source);
  return s;
}

void Rudder::ApplyState(double rho, const Eigen::Matrix3d& R, std::vector<Vector3>& cell_source) const {
  if (state_.started) Apply(state_.F_N, state_.delta, rho, R, cell_source);
}

void Rudder::Apply(double F_N, double delta, double rho, const Eigen::Matrix3d& R,
                   std::vector<Vector3>& cell_source) const {
  if (cell_source.empty()) cell_source.assign(static_cast<std::size_t>(n_cells_), Vector3::Zero());
  KELVIN_CHECK(static_cast<int>(cell_source.size()) == n_cells_, "one cell source per mesh cell");
  const Vector3 F_water_E = R * (-F_N * Vector3(-std::sin(delta), std::cos(delta), 0.0));
  auto add = [&](const BladePosition& pos, double share) {
    for (std::size_t k = 0; k < pos.own.entries.size(); ++k) {
      const auto i = static_cast<std::size_t>(pos.own.entries[k]);
      cell_source[static_cast<std::size_t>(pos.own.cells[k])] += share * pos.weights[i] * F_water_E / (rho * pos.volumes[i]);
    }
  };
  if (positions_.size() == 1) {
    add(positions_[0], 1.0);
    return;
  }
  const auto [k, s] = Bracket(delta);
  add(positions_[k], 1.0 - s);
  add(positions_[k + 1], s);
}

Vector3 Rudder::centroid() const { return BladeBox(options_, 0.0).centre; }

PlanarLoad Rudder::BodyLoad(const RudderState& state, const Vector3& centre) const {
  const double X = -state.F_N * std::sin(state.delta);
  const double Y = -state.F_N * std::cos(state.delta);  // ship axes, y to starboard
  const Vector3 arm = centroid() - centre;
  const double x = arm.x(), y = -arm.y();
  return {X, Y, x * Y - y * X};
}

}  // namespace kelvin::cfd
