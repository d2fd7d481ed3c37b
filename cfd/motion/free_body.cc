#include "cfd/motion/free_body.h"

#include <fmt/format.h>

#include <Eigen/Dense>
#include <cmath>

#include "cfd/motion/rigid_motion.h"
#include "data/schema/errors.h"

namespace kelvin::cfd {
namespace {

constexpr std::array<const char*, 3> kDof = {"surge", "sway", "yaw"};
constexpr int kPacked = 20;

std::array<double, 3> LoadArray(const PlanarLoad& l) { return {l.X, l.Y, l.N}; }

}  // namespace

void FreeBodyOptions::Validate(const std::string& where) const {
  auto fail = [&](const std::string& key, double value, const std::string& expected) {
    throw ConfigError(fmt::format("{}.{} = {:.6g}: expected {}", where, key, value, expected));
  };
  if (!(mass > 0.0) || !std::isfinite(mass)) fail("mass", mass, "a positive finite mass in kg");
  if (!(I_zG > 0.0) || !std::isfinite(I_zG)) fail("I_zG", I_zG, "a positive finite yaw inertia in kg m^2");
  if (!std::isfinite(x_G)) fail("x_G", x_G, "a finite position in m");
  for (int i = 0; i < 3; ++i) {
    if (!std::isfinite(initial[i])) fail(fmt::format("initial.{}", "uvr"[i]), initial[i], "a finite velocity");
    if (!(added_mass[i] >= 0.0) || !std::isfinite(added_mass[i])) {
      fail(fmt::format("coupling.added_mass[{}]", i), added_mass[i], "a finite added mass >= 0");
    }
  }
  if (!(ramp_time >= 0.0) || !std::isfinite(ramp_time)) fail("ramp_time", ramp_time, "a finite time >= 0 s");
  if (!(release_time >= ramp_time) || !std::isfinite(release_time)) {
    fail("release_time", release_time, fmt::format("a finite time >= ramp_time ({:.6g} s)", ramp_time));
  }
  if (!(relaxation > 0.0 && relaxation <= 1.0)) fail("coupling.relaxation", relaxation, "a value in (0, 1]");
  if (!(divergence_factor > 1.0)) fail("divergence_factor", divergence_factor, "a factor > 1");
  if (!std::isfinite(external.X) || !std::isfinite(external.Y) || !std::isfinite(external.N)) {
    throw ConfigError(fmt::format("{}.external_load: expected finite X, Y (N) and N (N m)", where));
  }
  if (!centre.allFinite()) throw ConfigError(fmt::format("{}.centre: expected 3 finite coordinates in m", where));
}

std::vector<double> FreeBodyState::Pack() const {
  std::vector<double> p = {time, static_cast<double>(steps)};
  for (const auto* a : {&nu, &nu_old, &pos, &pos_old, &placed}) p.insert(p.end(), a->begin(), a->end());
  p.insert(p.end(), {load.X, load.Y, load.N});
  return p;
}

FreeBodyState FreeBodyState::Unpack(const std::vector<double>& p) {
  if (p.size() != kPacked) {
    throw DataFileError(fmt::format("free-body state of {} values in the checkpoint; expected {}", p.size(), kPacked));
  }
  FreeBodyState s;
  s.time = p[0];
  s.steps = static_cast<int>(p[1]);
  std::size_t k = 2;
  for (auto* a : {&s.nu, &s.nu_old, &s.pos, &s.pos_old, &s.placed}) {
    for (double& x : *a) x = p[k++];
  }
  s.load = {p[k], p[k + 1], p[k + 2]};
  return s;
}

FreeBody::FreeBody(FreeBodyOptions options) : options_(std::move(options)) {
  options_.Validate("motion");
  for (int i = 0; i < 3; ++i) accepted_.nu[i] = HeldVelocity(i, 0.0);
  accepted_.nu_old = accepted_.nu;
  accepted_.pos = {0.0, 0.0, options_.initial_heading};
  accepted_.pos_old = accepted_.pos;
  accepted_.placed = accepted_.pos;
  SetState(accepted_);
}

double FreeBody::nominal_speed() const { return std::hypot(options_.initial[0], options_.initial[1]); }

bool FreeBody::IsFree(int i) const { return options_.free[i] && t_ > options_.release_time; }
bool FreeBody::released() const { return t_ > options_.release_time; }

double FreeBody::HeldVelocity(int i, double t) const {
  return options_.initial[i] * StartupFactor(t, options_.ramp_time);
}
double FreeBody::HeldAcceleration(int i, double t) const {
  return options_.initial[i] * StartupFactorRate(t, options_.ramp_time);
}

FreeBody::Coefficients FreeBody::Bdf() const {
  if (options_.bdf2 && accepted_.steps >= 1) return {1.5, 2.0, 0.5};
  return {1.0, 1.0, 0.0};
}

FreeBodyState FreeBody::state() const {
  if (!in_step_) return accepted_;
  FreeBodyState s;
  s.time = t_;
  s.steps = accepted_.steps + 1;
  s.nu = nu_;
  s.nu_old = accepted_.nu;
  s.pos = pos_;
  s.pos_old = accepted_.pos;
  s.placed = {placed_.x0, placed_.y0, placed_.psi};
  s.load = last_load_;
  return s;
}

void FreeBody::SetState(const FreeBodyState& s) {
  accepted_ = s;
  in_step_ = false;
  t_ = s.time;
  nu_ = s.nu;
  pos_ = s.pos;
  last_load_ = s.load;
  placed_ = MakePose(s.placed);
  pose_ = placed_;
}

Pose FreeBody::MakePose(const std::array<double, 3>& pos) const {
  Pose p;
  p.x0 = pos[0];
  p.y0 = pos[1];
  p.psi = pos[2];
  const double c = std::cos(p.psi), s = std::sin(p.psi);
  p.dx0 = nu_[0] * c - nu_[1] * s;
  p.dy0 = nu_[0] * s + nu_[1] * c;
  p.r = nu_[2];
  return p;
}

void FreeBody::IntegratePose() {
  const auto [a, b, c] = Bdf();
  const auto& p0 = accepted_.pos;
  const auto& p1 = accepted_.pos_old;
  pos_[2] = (b * p0[2] - c * p1[2] + dt_ * nu_[2]) / a;
  const double cs = std::cos(pos_[2]), sn = std::sin(pos_[2]);
  const double dx0 = nu_[0] * cs - nu_[1] * sn, dy0 = nu_[0] * sn + nu_[1] * cs;
  pos_[0] = (b * p0[0] - c * p1[0] + dt_ * dx0) / a;
  pos_[1] = (b * p0[1] - c * p1[1] + dt_ * dy0) / a;
  // The kinematics the flow sees: the placed mesh with the iterate's velocities.
  pose_ = MakePose({placed_.x0, placed_.y0, placed_.psi});
}

Pose FreeBody::At(double /*t*/) const { return pose_; }

Eigen::Matrix3d FreeBody::MassMatrix() const {
  const double m = options_.mass, xg = options_.x_G;
  Eigen::Matrix3d M;
  M << m, 0, 0, 0, m, m * xg, 0, m * xg, options_.I_zG + m * xg * xg;
  return M;
}

std::array<double, 3> FreeBody::Inertia(const std::array<double, 3>& nu, const std::array<double, 3>& rate) const {
  const double m = options_.mass, xg = options_.x_G;
  const double u = nu[0], v = nu[1], r = nu[2];
  return {m * (rate[0] - v * r - xg * r * r), m * (rate[1] + u * r + xg * rate[2]),
          (options_.I_zG + m * xg * xg) * rate[2] + m * xg * (rate[1] + u * r)};
}

void FreeBody::BeginStep(double t_new, double dt) {
  KELVIN_CHECK(dt > 0.0 && t_new > accepted_.time, "a free-body step forward in time");
  if (in_step_) accepted_ = state();
  in_step_ = true;
  t_ = t_new;
  dt_ = dt;
  const std::array<double, 3> n0 = accepted_.nu, n1 = accepted_.nu_old;
  std::array<double, 3> rate{};
  if (options_.coupling == BodyCoupling::kExplicit) {
    // Forward Euler with the load of the previous step, solved for the free
    // accelerations with the held ones prescribed.
    for (int i = 0; i < 3; ++i) rate[i] = IsFree(i) ? 0.0 : HeldAcceleration(i, t_);
    const std::array<double, 3> f = LoadArray(last_load_), ext = LoadArray(options_.external);
    const std::array<double, 3> base = Inertia(n0, rate);
    std::array<double, 3> acc = SolveFree(MassMatrix(), {f[0] + ext[0] - base[0], f[1] + ext[1] - base[1], f[2] + ext[2] - base[2]});
    for (int i = 0; i < 3; ++i) nu_[i] = IsFree(i) ? n0[i] + dt * acc[i] : HeldVelocity(i, t_);
  } else {
    const bool extrapolate = accepted_.steps >= 1;
    for (int i = 0; i < 3; ++i) {
      nu_[i] = IsFree(i) ? (extrapolate ? 2.0 * n0[i] - n1[i] : n0[i]) : HeldVelocity(i, t_);
    }
  }
  IntegratePose();
  placed_ = MakePose(pos_);
  pose_ = placed_;
}

std::array<double, 3> FreeBody::SolveFree(const Eigen::Matrix3d& A, const std::array<double, 3>& rhs) const {
  std::vector<int> idx;
  for (int i = 0; i < 3; ++i) {
    if (IsFree(i)) idx.push_back(i);
  }
  std::array<double, 3> x{};
  if (idx.empty()) return x;
  const int n = static_cast<int>(idx.size());
  Eigen::MatrixXd a(n, n);
  Eigen::VectorXd b(n);
  for (int i = 0; i < n; ++i) {
    b[i] = rhs[idx[i]];
    for (int j = 0; j < n; ++j) a(i, j) = A(idx[i], idx[j]);
  }
  const Eigen::VectorXd sol = a.ldlt().solve(b);
  for (int i = 0; i < n; ++i) x[idx[i]] = sol[i];
  return x;
}

std::array<double, 3> FreeBody::Rates() const {
  const auto [a, b, c] = Bdf();
  std::array<double, 3> rate{};
  for (int i = 0; i < 3; ++i) {
    rate[i] = IsFree(i) ? (a * nu_[i] - b * accepted_.nu[i] + c * accepted_.nu_old[i]) / dt_ : HeldAcceleration(i, t_);
  }
  return rate;
}

double FreeBody::Correct(const PlanarLoad& load, double length) {
  KELVIN_CHECK(in_step_, "a free-body correction inside a step");
  last_load_ = load;
  const std::array<double, 3> f = LoadArray(load), ext = LoadArray(options_.external);
  double change = 0.0;
  if (options_.coupling == BodyCoupling::kStabilised) {
    const std::array<double, 3> inertia = Inertia(nu_, Rates());
    const std::array<double, 3> residual = {f[0] + ext[0] - inertia[0], f[1] + ext[1] - inertia[1],
                                            f[2] + ext[2] - inertia[2]};
    const auto& ma = options_.added_mass;
    Eigen::Matrix3d J = MassMatrix();
    J.diagonal() += Eigen::Vector3d(ma[0], ma[1], ma[2]);
    J *= Bdf().a / dt_;
    const std::array<double, 3> d = SolveFree(J, residual);
    for (int i = 0; i < 3; ++i) nu_[i] += options_.relaxation * d[i];
    IntegratePose();
    const double scale = nominal_speed() > 0.0 ? nominal_speed() : 1.0;
    change = std::hypot(d[0], d[1], 0.5 * length * d[2]) * options_.relaxation / scale;
  }
  // What the carriage supplies on the held degrees of freedom.
  const std::array<double, 3> inertia = Inertia(nu_, Rates());
  constraint_ = {};
  if (!IsFree(0)) constraint_.X = inertia[0] - f[0] - ext[0];
  if (!IsFree(1)) constraint_.Y = inertia[1] - f[1] - ext[1];
  if (!IsFree(2)) constraint_.N = inertia[2] - f[2] - ext[2];
  return change;
}

bool FreeBody::Diverged(std::string* why) const {
  const double scale = nominal_speed() > 0.0 ? nominal_speed() : 1.0;
  const double limit = options_.divergence_factor * scale;
  for (int i = 0; i < 3; ++i) {
    if (!std::isfinite(nu_[i]) || !std::isfinite(pos_[i])) {
      if (why) *why = fmt::format("the body's {} state is not finite at t = {:.6g} s", kDof[i], t_);
      return true;
    }
  }
  const double speed = std::hypot(nu_[0], nu_[1]);
  if (speed > limit) {
    if (why) {
      *why = fmt::format(
          "the body speed {:.4g} m/s (u {:.4g}, v {:.4g}) at t = {:.6g} s exceeds {:.3g} times the initial speed "
          "scale {:.4g} m/s (motion.divergence_factor)",
          speed, nu_[0], nu_[1], t_, options_.divergence_factor, scale);
    }
    return true;
  }
  return false;
}

}  // namespace kelvin::cfd
