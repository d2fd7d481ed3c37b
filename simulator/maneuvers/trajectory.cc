#include "simulator/maneuvers/trajectory.h"

#include <algorithm>
#include <cmath>

namespace kelvin::sim {

namespace {

double Hermite(double t0, double t1, double y0, double y1, double d0, double d1, double t) {
  const double h = t1 - t0;
  if (h <= 0) return y0;
  const double s = (t - t0) / h;
  const double s2 = s * s, s3 = s2 * s;
  return (2 * s3 - 3 * s2 + 1) * y0 + (s3 - 2 * s2 + s) * h * d0 + (-2 * s3 + 3 * s2) * y1 + (s3 - s2) * h * d1;
}

// Time derivative of the Hermite interpolant.
double HermiteSlope(double t0, double t1, double y0, double y1, double d0, double d1, double t) {
  const double h = t1 - t0;
  if (h <= 0) return d0;
  const double s = (t - t0) / h;
  const double s2 = s * s;
  return ((6 * s2 - 6 * s) * y0 + (-6 * s2 + 6 * s) * y1) / h + (3 * s2 - 4 * s + 1) * d0 + (3 * s2 - 2 * s) * d1;
}

double Dx(const TrajectorySample& s) { return s.u * std::cos(s.psi) - s.v * std::sin(s.psi); }
double Dy(const TrajectorySample& s) { return s.u * std::sin(s.psi) + s.v * std::cos(s.psi); }

}  // namespace

void Trajectory::Record(const Simulator& sim, int phase) {
  const auto& y = sim.state();
  Add({sim.time(), y[kX], y[kY], y[kPsi], y[kU], y[kV], y[kR], sim.rudder(), sim.rps()}, phase);
}

void Trajectory::Add(const TrajectorySample& s, int phase) {
  if (!samples_.empty() && s.t <= samples_.back().t) {
    samples_.back() = s;  // an event at an output instant: keep the later state
    phases_.back() = phase;
    return;
  }
  samples_.push_back(s);
  phases_.push_back(phase);
}

std::size_t Trajectory::Bracket(double t) const {
  const auto it = std::upper_bound(samples_.begin(), samples_.end(), t,
                                   [](double v, const TrajectorySample& s) { return v < s.t; });
  std::size_t i = static_cast<std::size_t>(it - samples_.begin());
  if (i == 0) return 0;
  if (i >= samples_.size()) return samples_.size() - 2;
  return i - 1;
}

TrajectorySample Trajectory::At(double t) const {
  if (samples_.size() < 2) return samples_.empty() ? TrajectorySample{} : samples_.front();
  const std::size_t i = Bracket(t);
  const TrajectorySample& a = samples_[i];
  const TrajectorySample& b = samples_[i + 1];
  const double w = (t - a.t) / (b.t - a.t);
  TrajectorySample s{};
  s.t = t;
  s.x = Hermite(a.t, b.t, a.x, b.x, Dx(a), Dx(b), t);
  s.y = Hermite(a.t, b.t, a.y, b.y, Dy(a), Dy(b), t);
  s.psi = Hermite(a.t, b.t, a.psi, b.psi, a.r, b.r, t);
  s.u = a.u + w * (b.u - a.u);
  s.v = a.v + w * (b.v - a.v);
  s.r = a.r + w * (b.r - a.r);
  s.delta = a.delta + w * (b.delta - a.delta);
  s.n = a.n + w * (b.n - a.n);
  return s;
}

double Trajectory::FirstCrossing(double t_from, double level, double TrajectorySample::*field,
                                 int direction) const {
  for (std::size_t i = 1; i < samples_.size(); ++i) {
    if (samples_[i].t <= t_from) continue;
    const double fa = direction * (samples_[i - 1].*field - level);
    const double fb = direction * (samples_[i].*field - level);
    if (fa < 0 && fb >= 0) {
      double lo = std::max(samples_[i - 1].t, t_from), hi = samples_[i].t;
      for (int it = 0; it < 80; ++it) {
        const double mid = 0.5 * (lo + hi);
        if (direction * (At(mid).*field - level) < 0) lo = mid; else hi = mid;
      }
      return 0.5 * (lo + hi);
    }
  }
  return -1.0;
}

double Trajectory::PathLength(double t_a, double t_b) const {
  // Integral of the speed of the Hermite position interpolant, by 5-point
  // Gauss-Legendre on each piece between samples, so that the path length is
  // consistent with the interpolated positions.
  static constexpr double kNodes[5] = {-0.9061798459386640, -0.5384693101056831, 0.0, 0.5384693101056831,
                                       0.9061798459386640};
  static constexpr double kWeights[5] = {0.2369268850561891, 0.4786286704993665, 0.5688888888888889,
                                         0.4786286704993665, 0.2369268850561891};
  double total = 0;
  for (std::size_t i = 0; i + 1 < samples_.size(); ++i) {
    const TrajectorySample& a = samples_[i];
    const TrajectorySample& b = samples_[i + 1];
    const double lo = std::max(a.t, t_a), hi = std::min(b.t, t_b);
    if (hi <= lo) continue;
    const double mid = 0.5 * (lo + hi), half = 0.5 * (hi - lo);
    for (int k = 0; k < 5; ++k) {
      const double t = mid + half * kNodes[k];
      const double vx = HermiteSlope(a.t, b.t, a.x, b.x, Dx(a), Dx(b), t);
      const double vy = HermiteSlope(a.t, b.t, a.y, b.y, Dy(a), Dy(b), t);
      total += half * kWeights[k] * std::hypot(vx, vy);
    }
  }
  return total;
}

void Trajectory::Write(data::H5Writer& out, const std::string& group) const {
  struct Column {
    const char* name;
    const char* units;
    const char* description;
    double TrajectorySample::*field;
  };
  static const Column kColumns[] = {
      {"time", "s", "simulation time", &TrajectorySample::t},
      {"x", "m", "earth-fixed x of midship (initial heading direction)", &TrajectorySample::x},
      {"y", "m", "earth-fixed y of midship (to starboard of the initial heading)", &TrajectorySample::y},
      {"psi", "rad", "heading, positive to starboard", &TrajectorySample::psi},
      {"u", "m/s", "surge velocity", &TrajectorySample::u},
      {"v", "m/s", "sway velocity at midship", &TrajectorySample::v},
      {"r", "rad/s", "yaw rate", &TrajectorySample::r},
      {"rudder", "rad", "rudder angle, positive turns to starboard", &TrajectorySample::delta},
      {"rps", "1/s", "propeller revolutions per second", &TrajectorySample::n},
  };
  std::vector<double> col(samples_.size());
  for (const Column& c : kColumns) {
    for (std::size_t i = 0; i < samples_.size(); ++i) col[i] = samples_[i].*c.field;
    out.WriteArray(group + "/" + c.name, col, {col.size()}, c.units, c.description);
  }
  std::vector<double> ph(phases_.begin(), phases_.end());
  out.WriteArray(group + "/phase", ph, {ph.size()}, "1", "maneuver phase: 0 approach, 1 execute, 2 steady, 3 finished");
}

}  // namespace kelvin::sim
