#include "simulator/maneuvers/maneuver.h"

#include <fmt/format.h>

#include <charconv>
#include <cmath>
#include <limits>

#include "data/schema/errors.h"

namespace kelvin::sim {

namespace {

constexpr double kDeg = M_PI / 180.0;
constexpr double kInf = std::numeric_limits<double>::infinity();

constexpr const char* kForms =
    "turning:<deg>:stbd|port, zigzag:<rudder deg>/<heading deg>:stbd|port, spiral:<max deg>:<step deg>, or "
    "stopping";

[[noreturn]] void BadSpec(std::string_view text, const std::string& why) {
  throw ArgumentError(fmt::format("maneuver '{}': {}; expected {}", text, why, kForms));
}

std::vector<std::string_view> Split(std::string_view s, char sep) {
  std::vector<std::string_view> parts;
  std::size_t start = 0;
  while (true) {
    const std::size_t pos = s.find(sep, start);
    parts.push_back(s.substr(start, pos == std::string_view::npos ? std::string_view::npos : pos - start));
    if (pos == std::string_view::npos) break;
    start = pos + 1;
  }
  return parts;
}

double ParseDegrees(std::string_view text, std::string_view part, const char* what) {
  double v = 0;
  const auto res = std::from_chars(part.data(), part.data() + part.size(), v);
  if (res.ec != std::errc() || res.ptr != part.data() + part.size() || part.empty() || !std::isfinite(v)) {
    BadSpec(text, fmt::format("{} '{}' is not a number", what, part));
  }
  if (!(v > 0 && v <= 90)) BadSpec(text, fmt::format("{} {} deg is outside (0, 90]", what, v));
  return v * kDeg;
}

int ParseSide(std::string_view text, std::string_view part) {
  if (part == "stbd" || part == "starboard") return +1;
  if (part == "port") return -1;
  BadSpec(text, fmt::format("side '{}' is not stbd or port", part));
}

}  // namespace

ManeuverSpec ManeuverSpec::Parse(std::string_view text) {
  const auto parts = Split(text, ':');
  ManeuverSpec s;
  if (parts[0] == "turning") {
    if (parts.size() != 3) BadSpec(text, "turning needs a rudder angle and a side");
    s.kind = Kind::kTurning;
    s.rudder = ParseDegrees(text, parts[1], "rudder angle");
    s.side = ParseSide(text, parts[2]);
  } else if (parts[0] == "zigzag") {
    if (parts.size() != 3) BadSpec(text, "zigzag needs <rudder>/<heading> and a side");
    const auto angles = Split(parts[1], '/');
    if (angles.size() != 2) BadSpec(text, fmt::format("'{}' is not <rudder>/<heading>", parts[1]));
    s.kind = Kind::kZigZag;
    s.rudder = ParseDegrees(text, angles[0], "rudder angle");
    s.heading = ParseDegrees(text, angles[1], "heading change");
    s.side = ParseSide(text, parts[2]);
  } else if (parts[0] == "spiral") {
    if (parts.size() != 3) BadSpec(text, "spiral needs a maximum rudder angle and a step");
    s.kind = Kind::kSpiral;
    s.rudder = ParseDegrees(text, parts[1], "maximum rudder angle");
    const double step = ParseDegrees(text, parts[2], "rudder step");
    if (step > s.rudder) BadSpec(text, "the rudder step exceeds the maximum angle");
    // Dieudonne: from +max down to -max, then back up to +max.
    const int n = static_cast<int>(std::floor(s.rudder / step + 1e-9));
    for (int i = n; i >= -n; --i) s.spiral_rudders.push_back(i * step);
    for (int i = -n + 1; i <= n; ++i) s.spiral_rudders.push_back(i * step);
  } else if (parts[0] == "stopping") {
    if (parts.size() != 1) BadSpec(text, "stopping takes no parameters");
    s.kind = Kind::kStopping;
    s.rudder = 0.0;
  } else {
    BadSpec(text, fmt::format("unknown maneuver kind '{}'", parts[0]));
  }
  return s;
}

std::string ManeuverSpec::ToString() const {
  const char* side_name = side > 0 ? "stbd" : "port";
  switch (kind) {
    case Kind::kTurning: return fmt::format("turning:{:g}:{}", rudder / kDeg, side_name);
    case Kind::kZigZag: return fmt::format("zigzag:{:g}/{:g}:{}", rudder / kDeg, heading / kDeg, side_name);
    case Kind::kSpiral: {
      const double step = spiral_rudders.size() > 1 ? spiral_rudders[0] - spiral_rudders[1] : rudder;
      return fmt::format("spiral:{:g}:{:g}", rudder / kDeg, step / kDeg);
    }
    case Kind::kStopping: return "stopping";
  }
  return "?";
}

std::string_view PhaseName(ManeuverPhase phase) {
  switch (phase) {
    case ManeuverPhase::kApproach: return "approach";
    case ManeuverPhase::kExecute: return "execute";
    case ManeuverPhase::kSteady: return "steady";
    case ManeuverPhase::kFinished: return "finished";
  }
  return "?";
}

ManeuverController::ManeuverController(const ManeuverSpec& spec, const ShipParameters& ship, double approach_speed,
                                       double approach_rps)
    : spec_(spec), L_(ship.principal.Lpp), U0_(approach_speed), n0_(approach_rps) {
  if (!(U0_ > 0)) throw ModelError(fmt::format("approach speed {} m/s: expected a positive speed", U0_));
  const double max_rudder = ship.limits.rudder_max;
  if (spec_.rudder > max_rudder + 1e-12) {
    throw ArgumentError(fmt::format("maneuver '{}': rudder angle {:g} deg exceeds the maximum of ship '{}' ({:g} deg)",
                                    spec_.ToString(), spec_.rudder / kDeg, ship.name, max_rudder / kDeg));
  }
  if (spec_.kind == ManeuverSpec::Kind::kStopping && !ship.propeller.reverse_kt) {
    throw ModelError(fmt::format(
        "ship '{}' has no reverse-thrust data (propeller.reverse_KT): a crash stop needs K_T for n < 0, which "
        "the ship file does not give",
        ship.name));
  }
  const double T_ref = L_ / U0_;
  switch (spec_.kind) {
    case ManeuverSpec::Kind::kTurning: time_limit_ = 100 * T_ref; break;
    case ManeuverSpec::Kind::kZigZag: time_limit_ = 60 * T_ref; break;
    case ManeuverSpec::Kind::kSpiral:
      if (spec_.hold_time <= 0) spec_.hold_time = 15 * T_ref;
      time_limit_ = spec_.hold_time * static_cast<double>(spec_.spiral_rudders.size()) + T_ref;
      break;
    case ManeuverSpec::Kind::kStopping: time_limit_ = 200 * T_ref; break;
  }
}

void ManeuverController::Start(ManeuverPlant& sim) {
  t0_ = sim.time();
  psi0_ = sim.heading();
  phase_ = ManeuverPhase::kExecute;
  execute_times_ = {t0_};
  // Room for every execute, so that StepManeuver never allocates (real time).
  execute_times_.reserve(8 + spec_.spiral_rudders.size());
  time_limit_ += t0_;
  next_time_event_ = kInf;
  switch (spec_.kind) {
    case ManeuverSpec::Kind::kTurning:
    case ManeuverSpec::Kind::kZigZag:
      sign_ = spec_.side;
      sim.SetRudderOrder(sign_ * spec_.rudder);
      break;
    case ManeuverSpec::Kind::kSpiral:
      spiral_index_ = 0;
      sim.SetRudderOrder(spec_.spiral_rudders[0]);
      next_time_event_ = t0_ + spec_.hold_time;
      break;
    case ManeuverSpec::Kind::kStopping:
      sim.SetRpsOrder(-n0_);
      break;
  }
}

std::optional<double> ManeuverController::NextHeadingEvent() const {
  if (spec_.kind != ManeuverSpec::Kind::kZigZag || phase_ == ManeuverPhase::kFinished) return std::nullopt;
  return psi0_ + sign_ * spec_.heading;
}

void ManeuverController::OnHeadingEvent(ManeuverPlant& sim) {
  if (spec_.kind != ManeuverSpec::Kind::kZigZag) return;
  sign_ = -sign_;
  sim.SetRudderOrder(sign_ * spec_.rudder);
  ++reversals_;
  execute_times_.push_back(sim.time());
}

double ManeuverController::NextTimeEvent() const { return next_time_event_; }

void ManeuverController::OnTimeEvent(ManeuverPlant& sim) {
  if (spec_.kind != ManeuverSpec::Kind::kSpiral) return;
  ++spiral_index_;
  if (spiral_index_ < spec_.spiral_rudders.size()) {
    sim.SetRudderOrder(spec_.spiral_rudders[spiral_index_]);
    execute_times_.push_back(sim.time());
    next_time_event_ += spec_.hold_time;
  } else {
    next_time_event_ = kInf;
    phase_ = ManeuverPhase::kFinished;
  }
}

bool ManeuverController::Finished(const ManeuverPlant& sim) const {
  if (phase_ == ManeuverPhase::kFinished) return true;
  if (sim.time() >= time_limit_) return true;
  switch (spec_.kind) {
    case ManeuverSpec::Kind::kTurning:
      // Three half turns: 90 and 180 deg for advance and tactical diameter,
      // then a steady turn well established past 360 deg.
      return spec_.side * (sim.heading() - psi0_) >= 3.0 * M_PI;
    case ManeuverSpec::Kind::kZigZag:
      return reversals_ >= 4;
    case ManeuverSpec::Kind::kSpiral:
      return false;
    case ManeuverSpec::Kind::kStopping:
      return sim.surge_speed() <= 0.0;
  }
  return true;
}

namespace {
constexpr int kPackedFixed = 11;
}  // namespace

std::vector<double> ManeuverController::Pack() const {
  std::vector<double> p = {t0_, psi0_, time_limit_, static_cast<double>(phase_), static_cast<double>(reversals_),
                           static_cast<double>(sign_), static_cast<double>(spiral_index_), next_time_event_,
                           reverse_thrust_ ? 1.0 : 0.0, spec_.hold_time, static_cast<double>(execute_times_.size())};
  p.insert(p.end(), execute_times_.begin(), execute_times_.end());
  return p;
}

void ManeuverController::Unpack(std::span<const double> p) {
  if (p.size() < kPackedFixed || p.size() != kPackedFixed + static_cast<std::size_t>(p[kPackedFixed - 1])) {
    throw DataFileError(fmt::format("maneuver '{}': the saved controller state has {} numbers, which is not the state "
                                    "of a maneuver controller",
                                    spec_.ToString(), p.size()));
  }
  t0_ = p[0];
  psi0_ = p[1];
  time_limit_ = p[2];
  phase_ = static_cast<ManeuverPhase>(static_cast<int>(p[3]));
  reversals_ = static_cast<int>(p[4]);
  sign_ = static_cast<int>(p[5]);
  spiral_index_ = static_cast<std::size_t>(p[6]);
  next_time_event_ = p[7];
  reverse_thrust_ = p[8] != 0.0;
  spec_.hold_time = p[9];
  execute_times_.assign(p.begin() + kPackedFixed, p.end());
}

void StepManeuver(Simulator& sim, ManeuverController& controller) {
  const double psi_before = sim.heading();
  sim.Step();
  AfterManeuverStep(sim, controller, psi_before);
}

void AfterManeuverStep(ManeuverPlant& plant, ManeuverController& controller, double psi_before) {
  if (const auto h = controller.NextHeadingEvent()) {
    const double a = psi_before - *h, b = plant.heading() - *h;
    if (a != 0.0 && a * b <= 0.0) controller.OnHeadingEvent(plant);
  }
  if (plant.time() >= controller.NextTimeEvent() - 1e-9) controller.OnTimeEvent(plant);
}

double SelfPropulsionRps(const MmgModel<double>& model, double U) {
  const ShipParameters& ship = model.ship();
  const auto& pp = ship.propeller;
  const double resistance = -model.HullForces(U, 0.0, 0.0).X;
  const double thrust = resistance / (1.0 - pp.t_P);
  const double u_a = U * (1.0 - pp.w_P0);
  const double D = pp.D_p;
  const double rhoD4 = ship.principal.rho * D * D * D * D;
  // rho D^4 (k0 n^2 + k1 (u_a/D) n + k2 (u_a/D)^2) = thrust
  const double a = pp.k0, b = pp.k1 * u_a / D, c = pp.k2 * (u_a / D) * (u_a / D) - thrust / rhoD4;
  const double disc = b * b - 4 * a * c;
  if (!(a > 0) || disc < 0) {
    throw ModelError(fmt::format("ship '{}': no propeller speed gives X = 0 at U = {} m/s (K_T polynomial)",
                                 ship.name, U));
  }
  const double n = (-b + std::sqrt(disc)) / (2 * a);
  if (!(n > 0)) {
    throw ModelError(fmt::format("ship '{}': self-propulsion at U = {} m/s needs no thrust (R0' <= 0?)", ship.name, U));
  }
  return n;
}

}  // namespace kelvin::sim
