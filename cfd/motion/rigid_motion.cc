#include "cfd/motion/rigid_motion.h"

#include <fmt/format.h>

#include <array>
#include <cmath>
#include <numbers>
#include <vector>

#include "data/schema/errors.h"

namespace kelvin::cfd {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kDeg = kPi / 180.0;

constexpr std::array<std::string_view, 5> kKindNames = {"static_drift", "pure_sway", "pure_yaw",
                                                        "yaw_drift", "circular_motion"};

bool UsesDrift(PrescribedMotion k) {
  return k == PrescribedMotion::kStaticDrift || k == PrescribedMotion::kYawDrift ||
         k == PrescribedMotion::kCircularMotion;
}
bool UsesYawAmplitude(PrescribedMotion k) {
  return k == PrescribedMotion::kPureYaw || k == PrescribedMotion::kYawDrift;
}

}  // namespace

std::string_view PrescribedMotionName(PrescribedMotion kind) {
  return kKindNames[static_cast<int>(kind)];
}

bool MotionOptions::harmonic() const {
  return kind == PrescribedMotion::kPureSway || kind == PrescribedMotion::kPureYaw ||
         kind == PrescribedMotion::kYawDrift;
}

double MotionOptions::omega() const { return harmonic() ? 2.0 * kPi / period : 0.0; }

double MotionOptions::EndTime() const {
  if (!harmonic() || periods <= 0) return 0.0;
  // Whole periods are counted from the first period boundary at or after the ramp.
  const double first = std::ceil(ramp_time / period - 1e-12);
  return (first + periods) * period;
}

void MotionOptions::Validate() const {
  auto fail = [](std::string_view key, double value, std::string_view expected) {
    throw ConfigError(fmt::format("motion.{} = {:.6g}: expected {}", key, value, expected));
  };
  if (!(speed > 0.0) || !std::isfinite(speed))
    fail("speed", speed, "a finite carriage speed > 0 m/s");
  if (!(ramp_time >= 0.0) || !std::isfinite(ramp_time))
    fail("ramp_time", ramp_time, "a finite time >= 0 s");
  if (!std::isfinite(drift_angle) || std::abs(drift_angle) >= 0.5 * kPi) {
    fail("drift_angle_deg", drift_angle / kDeg, "|angle| < 90 degrees");
  }
  if (!UsesDrift(kind) && drift_angle != 0.0) {
    fail("drift_angle_deg", drift_angle / kDeg,
         fmt::format("0 (not used by {})", PrescribedMotionName(kind)));
  }
  if (harmonic()) {
    if (!(period > 0.0) || !std::isfinite(period)) fail("period", period, "a finite period > 0 s");
    if (periods < 0) fail("periods", periods, "a number of whole periods >= 1");
  }
  if (kind == PrescribedMotion::kPureSway &&
      (!(sway_amplitude > 0.0) || !std::isfinite(sway_amplitude))) {
    fail("sway_amplitude", sway_amplitude, "a finite amplitude > 0 m");
  }
  if (UsesYawAmplitude(kind) && (!(yaw_amplitude > 0.0) || yaw_amplitude >= 0.5 * kPi)) {
    fail("yaw_amplitude_deg", yaw_amplitude / kDeg, "an amplitude in (0, 90) degrees");
  }
  if (kind == PrescribedMotion::kCircularMotion && (!std::isfinite(yaw_rate) || yaw_rate == 0.0)) {
    fail("yaw_rate", yaw_rate, "a finite non-zero yaw rate in rad/s (positive turns to starboard)");
  }
  if (!centre.allFinite()) throw ConfigError("motion.centre: expected 3 finite coordinates in m");
}

MotionOptions LoadMotionOptions(const data::ConfigNode& node) {
  MotionOptions o;
  const std::string kind = node.Get<std::string>("kind");
  bool found = false;
  for (std::size_t i = 0; i < kKindNames.size(); ++i) {
    if (kind == kKindNames[i]) {
      o.kind = static_cast<PrescribedMotion>(i);
      found = true;
    }
  }
  if (!found) node["kind"].Fail(fmt::format("one of {}, or free (a free-running body)", fmt::join(kKindNames, ", ")));
  // Only the keys of this kind are accepted, so a misplaced amplitude is an error.
  std::vector<std::string> keys = {"kind", "speed", "ramp_time", "centre"};
  if (UsesDrift(o.kind)) keys.push_back("drift_angle_deg");
  if (o.harmonic()) {
    keys.push_back("period");
    keys.push_back("periods");
  }
  if (o.kind == PrescribedMotion::kPureSway) keys.push_back("sway_amplitude");
  if (UsesYawAmplitude(o.kind)) keys.push_back("yaw_amplitude_deg");
  if (o.kind == PrescribedMotion::kCircularMotion) keys.push_back("yaw_rate");
  node.ExpectKeys(keys);
  o.speed = node.GetPositive("speed");
  o.ramp_time = node.Has("ramp_time") ? node.GetPositive("ramp_time", /*allow_zero=*/true) : 0.0;
  if (o.kind == PrescribedMotion::kStaticDrift || o.kind == PrescribedMotion::kCircularMotion ||
      o.kind == PrescribedMotion::kYawDrift) {
    o.drift_angle = node.Get<double>("drift_angle_deg", 0.0) * kDeg;
  }
  if (o.harmonic()) {
    o.period = node.GetPositive("period");
    o.periods = node.Get<int>("periods", 0);
    if (o.periods < 0 || (node.Has("periods") && o.periods == 0))
      node["periods"].Fail("a number of periods >= 1");
  }
  if (o.kind == PrescribedMotion::kPureSway) o.sway_amplitude = node.GetPositive("sway_amplitude");
  if (UsesYawAmplitude(o.kind)) o.yaw_amplitude = node.GetPositive("yaw_amplitude_deg") * kDeg;
  if (o.kind == PrescribedMotion::kCircularMotion) o.yaw_rate = node.Get<double>("yaw_rate");
  if (node.Has("centre")) {
    const std::vector<double> c = node["centre"].As<std::vector<double>>();
    if (c.size() != 3) node["centre"].Fail("a list of 3 coordinates in m (grid axes)");
    o.centre = Eigen::Vector3d(c[0], c[1], c[2]);
  }
  try {
    o.Validate();
  } catch (const ConfigError& e) {
    throw ConfigError(fmt::format("{}: {}", node.Where(), e.what()));
  }
  return o;
}

double Pose::u() const { return dx0 * std::cos(psi) + dy0 * std::sin(psi); }
double Pose::v() const { return -dx0 * std::sin(psi) + dy0 * std::cos(psi); }

Eigen::Matrix3d Pose::Rotation() const {
  // Heading to starboard is a clockwise turn seen from above: -psi about z up.
  const double c = std::cos(psi), s = std::sin(psi);
  Eigen::Matrix3d R;
  R << c, s, 0.0, -s, c, 0.0, 0.0, 0.0, 1.0;
  return R;
}

Eigen::Vector3d Pose::Translation(const Eigen::Vector3d& centre) const {
  return centre + Eigen::Vector3d(x0, -y0, 0.0) - Rotation() * centre;
}

Eigen::Vector3d Pose::Velocity() const { return Eigen::Vector3d(dx0, -dy0, 0.0); }
Eigen::Vector3d Pose::AngularVelocity() const { return Eigen::Vector3d(0.0, 0.0, -r); }

RigidMotion::RigidMotion(MotionOptions options) : options_(std::move(options)) {
  options_.Validate();
}

double StartupFactor(double t, double t_ramp) {
  if (t_ramp <= 0.0 || t >= t_ramp) return 1.0;
  if (t <= 0.0) return 0.0;
  return 0.5 * (1.0 - std::cos(kPi * t / t_ramp));
}

double StartupFactorRate(double t, double t_ramp) {
  if (t_ramp <= 0.0 || t >= t_ramp || t <= 0.0) return 0.0;
  return 0.5 * kPi / t_ramp * std::sin(kPi * t / t_ramp);
}

double StartupFactorIntegral(double t, double t_ramp) {
  if (t <= 0.0) return 0.0;
  if (t_ramp <= 0.0) return t;
  if (t >= t_ramp) return t - 0.5 * t_ramp;
  return 0.5 * t - 0.5 * t_ramp / kPi * std::sin(kPi * t / t_ramp);
}

double RigidMotion::Ramp(double t) const { return StartupFactor(t, options_.ramp_time); }
double RigidMotion::RampRate(double t) const { return StartupFactorRate(t, options_.ramp_time); }
double RigidMotion::RampIntegral(double t) const { return StartupFactorIntegral(t, options_.ramp_time); }

Pose RigidMotion::At(double t) const {
  const MotionOptions& o = options_;
  const double U = o.speed;
  const double s = Ramp(t), ds = RampRate(t);
  Pose p;
  p.x0 = U * RampIntegral(t);
  p.dx0 = U * s;
  const double w = o.omega();
  switch (o.kind) {
    case PrescribedMotion::kStaticDrift:
      p.psi = o.drift_angle;
      break;
    case PrescribedMotion::kPureSway: {
      const double sn = std::sin(w * t), cs = std::cos(w * t);
      p.y0 = -s * o.sway_amplitude * sn;
      p.dy0 = -ds * o.sway_amplitude * sn - s * o.sway_amplitude * w * cs;
      break;
    }
    case PrescribedMotion::kPureYaw:
    case PrescribedMotion::kYawDrift: {
      const double sn = std::sin(w * t), cs = std::cos(w * t);
      const double a = U * o.yaw_amplitude / w;
      const double beta = o.kind == PrescribedMotion::kYawDrift ? o.drift_angle : 0.0;
      p.psi = beta + s * o.yaw_amplitude * cs;
      p.r = ds * o.yaw_amplitude * cs - s * o.yaw_amplitude * w * sn;
      p.y0 = s * a * sn;
      p.dy0 = ds * a * sn + s * a * w * cs;
      break;
    }
    case PrescribedMotion::kCircularMotion: {
      // Course chi = r * integral(s): the path has the constant radius U / r.
      const double chi = o.yaw_rate * RampIntegral(t);
      const double radius = U / o.yaw_rate;
      p.x0 = radius * std::sin(chi);
      p.y0 = radius * (1.0 - std::cos(chi));
      p.dx0 = U * s * std::cos(chi);
      p.dy0 = U * s * std::sin(chi);
      p.psi = o.drift_angle + chi;
      p.r = o.yaw_rate * s;
      break;
    }
  }
  return p;
}

}  // namespace kelvin::cfd
