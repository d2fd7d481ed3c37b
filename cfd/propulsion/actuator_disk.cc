#include "cfd/propulsion/actuator_disk.h"

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

[[noreturn]] void BadOption(const std::string& name, const std::string& key, const std::string& value,
                            const std::string& expected) {
  throw ConfigError(fmt::format("{}.{} = {}: expected {}", name, key, value, expected));
}

std::string Format(const Vector3& v) { return fmt::format("({}, {}, {})", v.x(), v.y(), v.z()); }

// Position of x relative to the disk: axial coordinate a and the radial
// vector (perpendicular to the axis).
struct DiskCoordinates {
  double a;
  Vector3 radial;
};

DiskCoordinates ToDisk(const ActuatorDiskOptions& o, const Vector3& x) {
  const Vector3 d = x - o.centre;
  const double a = d.dot(o.axis);
  return {a, d - a * o.axis};
}

// Unnormalized axial load g(r') of the distribution (0 outside the annulus).
double AxialShape(const ActuatorDiskOptions& o, double r_prime) {
  if (o.distribution == ActuatorDiskOptions::Distribution::kUniform) return 1.0;
  const double r_star = std::clamp((r_prime - o.hub_ratio) / (1.0 - o.hub_ratio), 0.0, 1.0);
  return r_star * std::sqrt(1.0 - r_star);
}

// Analytic integral of g over the cylinder; that of r f_theta = r g / r' is
// R times it for both distributions.
double AnalyticAxialIntegral(const ActuatorDiskOptions& o) {
  const double R = 0.5 * o.diameter, h = o.hub_ratio;
  if (o.distribution == ActuatorDiskOptions::Distribution::kUniform) return o.thickness * kPi * R * R * (1 - h * h);
  // r = R ((1 - h) r* + h): int_0^1 r* sqrt(1 - r*) dr* = 4/15 and
  // int_0^1 r*^2 sqrt(1 - r*) dr* = 16/105.
  return o.thickness * 2 * kPi * R * R * (1 - h) * ((1 - h) * 16.0 / 105.0 + h * 4.0 / 15.0);
}

// Distance from x to the annular cylinder grown by `grow` on every side
// (0 inside it).
double DistanceToDisk(const ActuatorDiskOptions& o, const Vector3& x, double grow) {
  const DiskCoordinates dc = ToDisk(o, x);
  const double R = 0.5 * o.diameter, r = dc.radial.norm();
  const double ea = std::max(std::abs(dc.a) - 0.5 * o.thickness - grow, 0.0);
  const double er = std::max({r - R - grow, o.hub_ratio * R - grow - r, 0.0});
  return std::hypot(ea, er);
}

// The annular cylinder as an overlap region: densities f_x ~ g(r') and
// f_theta ~ g(r') / r'.
OverlapRegion DiskRegion(const ActuatorDiskOptions& o) {
  OverlapRegion region;
  region.distance = [&o](const Vector3& x, double grow) { return DistanceToDisk(o, x, grow); };
  region.sample = [&o](const Vector3& x, std::span<double> densities) {
    const DiskCoordinates dc = ToDisk(o, x);
    const double r_prime = dc.radial.norm() / (0.5 * o.diameter);
    if (std::abs(dc.a) > 0.5 * o.thickness || r_prime > 1.0 || r_prime < o.hub_ratio) return false;
    const double g = AxialShape(o, r_prime);
    densities[0] = g;
    densities[1] = g / std::max(r_prime, 1e-12);
    return true;
  };
  region.n_densities = 2;
  region.feature = std::min(o.thickness, 0.5 * o.diameter * (1.0 - o.hub_ratio));
  return region;
}

}  // namespace

void ActuatorDiskOptions::Validate() const {
  for (int d = 0; d < 3; ++d) {
    if (!std::isfinite(centre[d])) BadOption(name, "centre", Format(centre), "finite coordinates (m)");
  }
  if (!(std::abs(axis.norm() - 1.0) < 1e-9)) BadOption(name, "axis", Format(axis), "a unit vector");
  if (!(diameter > 0) || !std::isfinite(diameter)) {
    BadOption(name, "diameter", fmt::format("{}", diameter), "a positive finite value (m)");
  }
  if (!(hub_ratio >= 0 && hub_ratio < 0.5)) BadOption(name, "hub_ratio", fmt::format("{}", hub_ratio), "a value in [0, 0.5)");
  if (!(thickness > 0) || !std::isfinite(thickness)) {
    BadOption(name, "thickness", fmt::format("{}", thickness), "a positive finite value (m)");
  }
  if (sense != 1 && sense != -1) BadOption(name, "sense", fmt::format("{}", sense), "+1 or -1");
  if (!(min_cells_across >= 0)) {
    BadOption(name, "min_cells_across", fmt::format("{}", min_cells_across), "a non-negative value");
  }
}

ActuatorDisk::ActuatorDisk(const Mesh& mesh, ActuatorDiskOptions options)
    : options_(std::move(options)), n_cells_(mesh.n_cells()) {
  options_.Validate();
  KELVIN_CHECK(mesh.placement_rotation().isIdentity(0.0) && mesh.placement_translation().isZero(0.0),
               "ActuatorDisk needs the body-fixed mesh (construct it before any placement)");
  const std::vector<CellLoad> loads = SampleCells(mesh);
  if (loads.empty()) {
    throw ConfigError(fmt::format("{}.centre = {}: the disk (D = {} m, thickness {} m) contains no cell of mesh '{}'",
                                  options_.name, Format(options_.centre), options_.diameter, options_.thickness,
                                  mesh.source()));
  }
  Normalize(mesh, loads);
  CheckWalls(mesh);
  CheckResolution();
  own_ = OwnEntries(nullptr, cells_);
}

void ActuatorDisk::Localize(std::shared_ptr<const DomainPart> part, int n_cells) {
  part_ = std::move(part);
  n_cells_ = n_cells;
  own_ = OwnEntries(part_.get(), cells_);
}

std::vector<ActuatorDisk::CellLoad> ActuatorDisk::SampleCells(const Mesh& mesh) const {
  std::vector<CellLoad> loads;
  for (const CellOverlap& o : SampleOverlap(mesh, DiskRegion(options_))) {
    loads.push_back({o.cell, o.fraction, o.integrals[0], o.integrals[1]});
  }
  return loads;
}

void ActuatorDisk::Normalize(const Mesh& mesh, const std::vector<CellLoad>& loads) {
  double axial_sum = 0.0, torque_sum = 0.0;
  for (const CellLoad& l : loads) {
    const DiskCoordinates dc = ToDisk(options_, mesh.cell_centres()[l.cell]);
    const double r = dc.radial.norm();
    const Vector3 e_theta = r > 1e-12 * options_.diameter ? Vector3(options_.axis.cross(dc.radial / r)) : Vector3::Zero();
    cells_.push_back(l.cell);
    fraction_.push_back(l.fraction);
    volume_.push_back(mesh.cell_volumes()[l.cell]);
    e_theta_.push_back(e_theta);
    axial_weight_.push_back(l.axial);
    tangential_weight_.push_back(e_theta.isZero() ? 0.0 : l.tangential);
    axial_sum += l.axial;
    torque_sum += tangential_weight_.back() * r;
    discrete_volume_ += l.fraction * volume_.back();
  }
  KELVIN_CHECK(axial_sum > 0 && torque_sum > 0, "a disk with cells carries load");
  for (double& w : axial_weight_) w /= axial_sum;
  for (double& w : tangential_weight_) w /= torque_sum;
  for (std::size_t i = 0; i < cells_.size(); ++i) {
    loading_.push_back(options_.thickness * axial_weight_[i] / (fraction_[i] * volume_[i]));
  }
  const double analytic = AnalyticAxialIntegral(options_);
  ratio_thrust_ = axial_sum / analytic;
  ratio_torque_ = torque_sum / (0.5 * options_.diameter * analytic);
}

void ActuatorDisk::CheckWalls(const Mesh& mesh) const {
  std::vector<char> in_disk(mesh.n_cells(), 0);
  for (int c : cells_) in_disk[c] = 1;
  const double r_hub = 0.5 * options_.hub_ratio * options_.diameter;
  for (const Patch& patch : mesh.patches()) {
    if (patch.kind != PatchKind::kWall) continue;
    for (int f = patch.start; f < patch.start + patch.size; ++f) {
      const int owner = mesh.owner()[f];
      const double half_cell = 0.5 * std::cbrt(mesh.cell_volumes()[owner]);
      // Within the hub radius (grown by half a cell, as the annulus is) the
      // wall is the shaft boss the propeller sits on: the loading is zero
      // there, so the disk may meet it.
      if (ToDisk(options_, mesh.face_centres()[f]).radial.norm() < r_hub + half_cell) continue;
      if (in_disk[owner] || DistanceToDisk(options_, mesh.face_centres()[f], half_cell) == 0.0) {
        throw ConfigError(fmt::format(
            "{}.centre = {}: the disk (D = {} m, thickness {} m) touches wall patch '{}' at face centre {} of mesh "
            "'{}': expected the disk clear of the hull by at least half a cell outside the hub radius",
            options_.name, Format(options_.centre), options_.diameter, options_.thickness, patch.name,
            Format(mesh.face_centres()[f]), mesh.source()));
      }
    }
  }
}

void ActuatorDisk::CheckResolution() {
  std::vector<double> v = volume_;
  std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2), v.end());
  cells_across_ = options_.diameter / std::cbrt(v[v.size() / 2]);
  if (cells_across_ < options_.min_cells_across) {
    spdlog::warn("{}: only {:.1f} cells across the disk diameter (D = {} m; {} or more recommended): the body force "
                 "is smeared over a coarse disk, and its induced velocity and the wake are under-resolved",
                 options_.name, cells_across_, options_.diameter, options_.min_cells_across);
  }
}

double ActuatorDisk::area() const { return kPi * options_.diameter * options_.diameter / 4.0; }

double ActuatorDisk::mesh_share() const {
  const double R = 0.5 * options_.diameter;
  return discrete_volume_ / (options_.thickness * kPi * R * R * (1.0 - options_.hub_ratio * options_.hub_ratio));
}

void ActuatorDisk::AddBodyForce(double thrust, double torque, double rho, const Eigen::Matrix3d& R,
                                std::vector<Vector3>& cell_source) const {
  if (cell_source.empty()) cell_source.assign(static_cast<std::size_t>(n_cells_), Vector3::Zero());
  KELVIN_CHECK(static_cast<int>(cell_source.size()) == n_cells_, "one cell source per mesh cell");
  KELVIN_CHECK(rho > 0, "positive density");
  const Vector3 axial_E = -thrust * (R * options_.axis);
  const double tangential = options_.sense * torque;
  for (std::size_t k = 0; k < own_.entries.size(); ++k) {
    const auto i = static_cast<std::size_t>(own_.entries[k]);
    const Vector3 force_E = axial_weight_[i] * axial_E + tangential * tangential_weight_[i] * (R * e_theta_[i]);
    cell_source[static_cast<std::size_t>(own_.cells[k])] += force_E / (rho * volume_[i]);
  }
}

double ActuatorDisk::DiskVelocity(const VectorField& U, const std::function<Vector3(int cell)>& body_velocity,
                                  const Eigen::Matrix3d& R) const {
  const Vector3 through_E = -(R * options_.axis);
  double sum = 0.0;
  for (std::size_t k = 0; k < own_.entries.size(); ++k) {
    const int c = own_.cells[k];
    Vector3 u = U[c];
    if (body_velocity) u -= body_velocity(c);
    sum += axial_weight_[static_cast<std::size_t>(own_.entries[k])] * u.dot(through_E);
  }
  return part_ ? part_->Sum(sum) : sum;
}

}  // namespace kelvin::cfd
