#include "data/schema/captive_run.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "data/schema/errors.h"

namespace kelvin::data {

namespace {

constexpr std::array<std::string_view, 5> kKindNames = {"static_drift", "pure_sway", "pure_yaw",
                                                        "yaw_drift", "circular_motion"};

[[noreturn]] void Fail(std::string_view source, std::string_view run, std::string_view what) {
  throw DataFileError(fmt::format("{}: run '{}': {}", source, run, what));
}

void RequirePositive(std::string_view source, const CaptiveRun& run, std::string_view key,
                     double value) {
  if (!(value > 0) || !std::isfinite(value)) {
    Fail(source, run.name,
         fmt::format("attribute '{}' = {}: expected a finite positive number for {} motion", key,
                     value, MotionKindName(run.motion.kind)));
  }
}

}  // namespace

std::string_view MotionKindName(MotionKind kind) { return kKindNames[static_cast<int>(kind)]; }

MotionKind ParseMotionKind(std::string_view name, std::string_view where) {
  for (std::size_t i = 0; i < kKindNames.size(); ++i) {
    if (kKindNames[i] == name) return static_cast<MotionKind>(i);
  }
  throw DataFileError(fmt::format("{}: unknown motion kind '{}'; valid kinds: {}", where, name,
                                  fmt::join(kKindNames, ", ")));
}

bool IsHarmonic(MotionKind kind) {
  return kind == MotionKind::kPureSway || kind == MotionKind::kPureYaw ||
         kind == MotionKind::kYawDrift;
}

double MotionParameters::Period() const {
  return IsHarmonic(kind) ? 2.0 * std::numbers::pi / omega : 0.0;
}

BodyKinematics KinematicsAt(const MotionParameters& m, double Lpp, double t) {
  BodyKinematics k;
  if (m.kind == MotionKind::kCircularMotion) {
    k.u = m.U * std::cos(m.beta);
    k.v = -m.U * std::sin(m.beta);
    k.r = m.r_prime * m.U / Lpp;
    return k;
  }
  // Earth-frame motion of midship: velocities (xd, yd), accelerations
  // (xdd, ydd), heading psi and its rates.
  double xd = m.U, xdd = 0, yd = 0, ydd = 0, psi = 0, psid = 0, psidd = 0;
  const double w = m.omega;
  switch (m.kind) {
    case MotionKind::kStaticDrift: {
      psi = m.beta;
      if (t < m.t_ramp) {
        const double a = std::numbers::pi / m.t_ramp;
        xd = 0.5 * m.U * (1.0 - std::cos(a * t));
        xdd = 0.5 * m.U * a * std::sin(a * t);
      }
      break;
    }
    case MotionKind::kPureSway:
      yd = -m.y_a * w * std::cos(w * t);
      ydd = m.y_a * w * w * std::sin(w * t);
      break;
    case MotionKind::kPureYaw:
    case MotionKind::kYawDrift:
      yd = m.U * m.psi_a * std::cos(w * t);
      ydd = -m.U * m.psi_a * w * std::sin(w * t);
      psi = (m.kind == MotionKind::kYawDrift ? m.beta : 0.0) + m.psi_a * std::cos(w * t);
      psid = -m.psi_a * w * std::sin(w * t);
      psidd = -m.psi_a * w * w * std::cos(w * t);
      break;
    case MotionKind::kCircularMotion:
      break;
  }
  const double c = std::cos(psi), s = std::sin(psi);
  k.u = xd * c + yd * s;
  k.v = -xd * s + yd * c;
  k.r = psid;
  k.du = xdd * c + ydd * s + k.r * k.v;
  k.dv = -xdd * s + ydd * c - k.r * k.u;
  k.dr = psidd;
  return k;
}

std::array<double, 3> RigidBodyInertia(const CaptiveShip& ship, const BodyKinematics& k) {
  const double m = ship.mass, xg = ship.x_G;
  return {m * (k.du - k.v * k.r - xg * k.r * k.r), m * (k.dv + k.u * k.r + xg * k.dr),
          (ship.I_zG + m * xg * xg) * k.dr + m * xg * (k.dv + k.u * k.r)};
}

std::string DescribeWindow(const CaptiveRun& run, std::size_t begin, std::size_t end) {
  if (end <= begin || end > run.time.size()) return "no samples";
  const std::string state = run.settled == 1   ? fmt::format("settled, change {:.2g} over the window", run.settle_change)
                            : run.settled == 0 ? fmt::format("NOT settled, change {:.2g} over the last window",
                                                             run.settle_change)
                                               : std::string("no steady criterion");
  return fmt::format("t = {:.4g} to {:.4g} s ({} samples; {})", run.time[begin], run.time[end - 1], end - begin,
                     state);
}

AnalysisWindow SelectWindow(const CaptiveRun& run, std::string_view source) {
  const std::vector<double>& t = run.time;
  AnalysisWindow w;
  if (t.empty()) Fail(source, run.name, "channel 'time' is empty");
  const double t_end = t.back();
  if (!IsHarmonic(run.motion.kind)) {
    const double t0 = std::max(run.motion.t_ramp, run.t_settle);
    while (w.begin < t.size() && t[w.begin] < t0) ++w.begin;
    w.end = t.size();
    if (w.end - w.begin < static_cast<std::size_t>(kMinSteadySamples)) {
      Fail(source, run.name,
           fmt::format("channels 'X', 'Y', 'N': {} samples after the ramp-up (t >= t_ramp = {} s, "
                       "last t = {} s); "
                       "a steady run needs at least {}",
                       w.end - w.begin, run.motion.t_ramp, t_end, kMinSteadySamples));
    }
    if (run.t_settle > run.motion.t_ramp && w.end - w.begin < static_cast<std::size_t>(kMinSteadySamples)) {
      Fail(source, run.name,
           fmt::format("channels 'X', 'Y', 'N': {} samples in the settled part (t >= t_settle = {} s); a steady run "
                       "needs at least {}",
                       w.end - w.begin, run.t_settle, kMinSteadySamples));
    }
    return w;
  }
  const double T = run.motion.Period();
  // Sampling tolerance: half the smallest step near the ends is enough to
  // decide whether a sample sits on a period boundary.
  const double dt = t.size() > 1 ? (t.back() - t.front()) / static_cast<double>(t.size() - 1) : T;
  const double tol = 0.25 * dt;
  const double k0 = std::ceil((run.motion.t_ramp - tol) / T);
  // The last sample stands for the interval [t_end, t_end + dt): uniform
  // samples at T, T + dt, ..., 2T - dt cover one whole period.
  const double k1 = std::floor((t_end + dt + tol) / T);
  w.periods = static_cast<int>(k1 - std::max(k0, 0.0));
  if (w.periods < 1) {
    Fail(source, run.name,
         fmt::format(
             "channels 'X', 'Y', 'N': less than one whole period ({:.4g} s) after the ramp-up "
             "(t_ramp = {} s, last t = {} s)",
             T, run.motion.t_ramp, t_end));
  }
  const double t0 = std::max(k0, 0.0) * T - tol;
  const double t1 = k1 * T - tol;  // the sample on the closing boundary belongs to the next period
  while (w.begin < t.size() && t[w.begin] < t0) ++w.begin;
  w.end = w.begin;
  while (w.end < t.size() && t[w.end] < t1) ++w.end;
  if (t.front() > t0 + 2.0 * tol) {
    Fail(source, run.name,
         fmt::format("channel 'time' starts at {} s, after the first analysed period begins ({} s)",
                     t.front(), t0 + tol));
  }
  return w;
}

void ValidateCampaign(const CaptiveCampaign& c, std::string_view source) {
  const CaptiveShip& s = c.ship;
  const std::array<std::pair<std::string_view, double>, 5> positive = {
      {{"Lpp", s.Lpp}, {"d", s.d}, {"rho", s.rho}, {"mass", s.mass}, {"I_zG", s.I_zG}}};
  for (const auto& [key, value] : positive) {
    if (!(value > 0) || !std::isfinite(value)) {
      throw DataFileError(fmt::format(
          "{}: ship attribute '{}' = {}: expected a finite positive number", source, key, value));
    }
  }
  if (!std::isfinite(s.x_G)) {
    throw DataFileError(
        fmt::format("{}: ship attribute 'x_G' = {}: expected a finite number", source, s.x_G));
  }
  if (c.runs.empty()) throw DataFileError(fmt::format("{}: the campaign holds no runs", source));
  for (std::size_t r = 0; r < c.runs.size(); ++r) {
    const std::string& name = c.runs[r].name;
    if (name.empty() || name.find('/') != std::string::npos) {
      throw DataFileError(
          fmt::format("{}: run {}: name '{}' is empty or contains '/'", source, r, name));
    }
    for (std::size_t q = 0; q < r; ++q) {
      if (c.runs[q].name == name) {
        throw DataFileError(
            fmt::format("{}: run '{}' appears twice (runs {} and {})", source, name, q, r));
      }
    }
  }
  for (const CaptiveRun& run : c.runs) {
    const MotionParameters& m = run.motion;
    RequirePositive(source, run, "U", m.U);
    if (!std::isfinite(m.beta) || std::abs(m.beta) >= 0.5 * std::numbers::pi) {
      Fail(source, run.name,
           fmt::format("attribute 'beta' = {}: expected |beta| < pi/2 rad", m.beta));
    }
    if (!(m.t_ramp >= 0) || !std::isfinite(m.t_ramp)) {
      Fail(source, run.name,
           fmt::format("attribute 't_ramp' = {}: expected a finite number >= 0 s", m.t_ramp));
    }
    if (m.kind == MotionKind::kStaticDrift) RequirePositive(source, run, "t_ramp", m.t_ramp);
    if (IsHarmonic(m.kind)) RequirePositive(source, run, "omega", m.omega);
    if (m.kind == MotionKind::kPureSway) RequirePositive(source, run, "y_a", m.y_a);
    if (m.kind == MotionKind::kPureYaw || m.kind == MotionKind::kYawDrift) {
      RequirePositive(source, run, "psi_a", m.psi_a);
    }
    if (m.kind == MotionKind::kCircularMotion && !(std::isfinite(m.r_prime) && m.r_prime != 0)) {
      Fail(source, run.name,
           fmt::format("attribute 'r_prime' = {}: expected a finite non-zero yaw rate", m.r_prime));
    }
    const std::size_t n = run.time.size();
    if (n < 2)
      Fail(source, run.name, fmt::format("channel 'time' has {} samples; expected at least 2", n));
    for (std::size_t i = 0; i < n; ++i) {
      if (!std::isfinite(run.time[i]) || (i > 0 && !(run.time[i] > run.time[i - 1]))) {
        Fail(source, run.name,
             fmt::format(
                 "channel 'time': sample {} (t = {}) is not finite or not after the previous one",
                 i, run.time[i]));
      }
    }
    for (int c_i = 0; c_i < 3; ++c_i) {
      const std::vector<double>& f = run.force[c_i];
      if (f.size() != n) {
        Fail(source, run.name,
             fmt::format("channel '{}' has {} samples but 'time' has {}", kChannelNames[c_i],
                         f.size(), n));
      }
      for (std::size_t i = 0; i < n; ++i) {
        if (!std::isfinite(f[i])) {
          Fail(source, run.name,
               fmt::format("channel '{}': sample {} (t = {} s) is {}", kChannelNames[c_i], i,
                           run.time[i], f[i]));
        }
      }
    }
    SelectWindow(run, source);
  }
}

}  // namespace kelvin::data
