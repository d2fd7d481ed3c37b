#include "cfd/propulsion/propeller.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "data/schema/errors.h"

namespace kelvin::cfd {

void PropellerOptions::Validate() const {
  if (!(mesh_share > 0 && mesh_share <= 1)) {
    throw ConfigError(fmt::format("{}.mesh_share = {}: expected a value in (0, 1]", name, mesh_share));
  }
  if (!(thrust_relaxation > 0 && thrust_relaxation <= 1)) {
    throw ConfigError(
        fmt::format("{}.thrust_relaxation = {}: expected a value in (0, 1]", name, thrust_relaxation));
  }
}

Propeller::Propeller(ActuatorDisk disk, sim::OpenWaterCurve curve, PropellerOptions options)
    : disk_(std::move(disk)), curve_(std::move(curve)), options_(std::move(options)) {
  options_.Validate();
  curve_.Validate(options_.name, options_.name + ".open_water");
  if (std::abs(disk_.mesh_share() / options_.mesh_share - 1.0) > 0.05) {
    throw ConfigError(fmt::format("{}.mesh_share = {}: the disk's cells hold {:.4f} of its cylinder; expected the "
                                  "share within 5% (1, or 1/2, 1/4 for a disk cut by symmetry planes)",
                                  options_.name, options_.mesh_share, disk_.mesh_share()));
  }
}

double Propeller::EffectiveInflow(double U_disk, double thrust, double rho) const {
  if (!(U_disk > 0)) {
    throw ConfigError(fmt::format(
        "{}.open_water: the flow through the disk is reversed (U_disk = {} m/s): outside the first quadrant the "
        "open-water table covers (J in [{}, {}])",
        options_.name, U_disk, curve_.J_min(), curve_.J_max()));
  }
  if (options_.correction == PropellerOptions::InflowCorrection::kDiskMomentum) {
    return U_disk - thrust / (2.0 * rho * disk_.area() * U_disk);
  }
  return AnnularInflow(U_disk, thrust, rho);
}

// Root of F(U_A) = sum_c w_c (U_A + sqrt(U_A^2 + 2 L_c / rho)) / 2 - U_disk,
// F increasing; Newton from U_disk, kept inside a bracket that bisection
// shrinks whenever a Newton step leaves it. A negative loading (windmilling)
// clamps the radicand at zero.
double Propeller::AnnularInflow(double U_disk, double thrust, double rho) const {
  const std::vector<double>& w = disk_.axial_weights();
  const std::vector<double>& load = disk_.loading_per_unit_thrust();
  const double mesh_thrust = options_.mesh_share * thrust;
  auto F = [&](double u, double* dF) {
    double f = -U_disk, d = 0.0;
    for (std::size_t c = 0; c < w.size(); ++c) {
      const double s = std::sqrt(std::max(u * u + 2.0 * mesh_thrust * load[c] / rho, 1e-300));
      f += 0.5 * w[c] * (u + s);
      d += 0.5 * w[c] * (1.0 + u / s);
    }
    if (dF) *dF = d;
    return f;
  };
  double hi = U_disk + std::abs(U_disk), lo = U_disk - std::abs(U_disk);
  while (F(hi, nullptr) < 0) hi += 2.0 * (hi - lo);
  for (int k = 0; k < 200 && F(lo, nullptr) > 0; ++k) lo -= 2.0 * (hi - lo);
  double u = std::clamp(U_disk, lo, hi);
  for (int it = 0; it < 100 && hi - lo > 1e-14 * std::abs(U_disk); ++it) {
    double dF = 0.0;
    const double f = F(u, &dF);
    if (std::abs(f) <= 1e-15 * std::abs(U_disk)) break;
    (f > 0 ? hi : lo) = u;
    const double newton = dF > 0 ? u - f / dF : lo - 1.0;
    u = newton > lo && newton < hi ? newton : 0.5 * (lo + hi);
  }
  return u;
}

void Propeller::Apply(double thrust, double torque, double rho, const Eigen::Matrix3d& R,
                      std::vector<Vector3>& cell_source) const {
  const double share = options_.mesh_share;
  disk_.AddBodyForce(share * thrust, options_.apply_torque ? share * torque : 0.0, rho, R, cell_source);
}

PropellerState Propeller::Update(const PimpleSolver& solver, const BodyVelocity& body_velocity,
                                 const Eigen::Matrix3d& R, double n, double rho, std::vector<Vector3>& cell_source,
                                 bool start_up) {
  if (!(n > 0) || !std::isfinite(n)) {
    throw ConfigError(fmt::format("{}.n = {} 1/s: expected a positive rate (the open-water table is the first "
                                  "quadrant)",
                                  options_.name, n));
  }
  const double D = disk_.options().diameter;
  PropellerState s;
  s.n = n;
  s.U_disk = disk_.DiskVelocity(solver.U(), body_velocity, R);
  if (start_up) {
    s.U_A = s.U_disk > 0 ? EffectiveInflow(s.U_disk, state_.thrust, rho) : 0.0;
    const double J = s.U_A / (n * D);
    s.J = std::clamp(J, curve_.J_min(), curve_.J_max());
    s.clamped = s.J != J || !(s.U_disk > 0);
  } else {
    s.U_A = EffectiveInflow(s.U_disk, state_.thrust, rho);
    s.J = s.U_A / (n * D);
  }
  if (!curve_.Covers(s.J)) {
    throw ConfigError(fmt::format(
        "{}.open_water: J = {:.6g} (U_A = {:.6g} m/s, U_disk = {:.6g} m/s, n = {} 1/s, D = {} m) is outside the "
        "table's range [{}, {}]",
        options_.name, s.J, s.U_A, s.U_disk, n, D, curve_.J_min(), curve_.J_max()));
  }
  s.K_T = curve_.KT(s.J);
  s.K_Q = curve_.KQ(s.J);
  const double T_new = rho * n * n * std::pow(D, 4) * s.K_T;
  const double Q_new = rho * n * n * std::pow(D, 5) * s.K_Q;
  const bool first = state_.n == 0.0;
  const double a = first ? 1.0 : options_.thrust_relaxation;
  s.T = state_.thrust + a * (T_new - state_.thrust);
  s.Q = state_.torque + a * (Q_new - state_.torque);
  state_ = {s.T, s.Q, n};
  Apply(s.T, s.Q, rho, R, cell_source);
  return s;
}

PropellerState Propeller::UpdateFixedLoad(const PimpleSolver& solver, const BodyVelocity& body_velocity,
                                          const Eigen::Matrix3d& R, double thrust, double torque, double rho,
                                          std::vector<Vector3>& cell_source) {
  PropellerState s;
  s.n = state_.n;
  s.U_disk = disk_.DiskVelocity(solver.U(), body_velocity, R);
  s.U_A = s.U_disk > 0 ? EffectiveInflow(s.U_disk, thrust, rho) : s.U_disk;
  s.T = thrust;
  s.Q = torque;
  state_.thrust = thrust;
  state_.torque = torque;
  Apply(thrust, torque, rho, R, cell_source);
  return s;
}

}  // namespace kelvin::cfd
