#include "cfd/run/maneuver_pilot.h"

#include <fmt/format.h>

#include <cmath>

#include "cfd/run/propeller_actuator.h"
#include "data/schema/errors.h"
#include "simulator/maneuvers/runner.h"

namespace kelvin::cfd {
namespace {

constexpr int kSampleFields = 9;  // t, x, y, psi, u, v, r, delta, n

template <typename T>
T* FindActuator(const Case& c) {
  for (const auto& a : c.actuators) {
    if (auto* p = dynamic_cast<T*>(a.get())) return p;
  }
  return nullptr;
}

}  // namespace

void RequireManeuverSection(const data::ConfigNode& root, const std::string& kind_override) {
  if (kind_override.empty() || root.Has("maneuver")) return;
  throw ArgumentError(fmt::format("--maneuver {}: the case {} has no maneuver: section; expected a free-running case "
                                  "with maneuver: {{kind, execute_time}}",
                                  kind_override, root.source()));
}

std::optional<ManeuverPilotSettings> LoadManeuverPilot(const data::ConfigNode& root, const Case& c,
                                                       const std::filesystem::path& output_directory,
                                                       const std::string& kind_override) {
  RequireManeuverSection(root, kind_override);
  if (!root.Has("maneuver")) return std::nullopt;
  const data::ConfigNode node = root["maneuver"];
  node.ExpectKeys({"kind", "execute_time", "output"});
  if (!c.free_running) node.Fail("no maneuver: section without motion: {kind: free} (a maneuver needs a free body)");
  ManeuverPilotSettings s;
  const data::ConfigNode kind = node["kind"];
  try {
    s.spec = sim::ManeuverSpec::Parse(kind_override.empty() ? kind.As<std::string>() : kind_override);
  } catch (const ArgumentError& e) {
    if (!kind_override.empty()) throw ArgumentError(fmt::format("--maneuver {}: {}", kind_override, e.what()));
    kind.Fail(fmt::format("a maneuver definition ({})", e.what()));
  }
  if (s.spec.kind == sim::ManeuverSpec::Kind::kStopping) {
    kind.Fail("turning, zigzag or spiral: a crash stop needs reverse thrust, which the body-force propeller has no "
              "curve for");
  }
  if (!FindActuator<RudderActuator>(c)) {
    node.Fail(fmt::format("a rudder: section as well: maneuver '{}' steers with the rudder, and the case has none",
                          s.spec.ToString()));
  }
  const FreeBodyOptions& body = c.free_running->body;
  try {  // the maneuver within the ship's limits (the pilot's controller refuses it otherwise)
    sim::ManeuverController check(s.spec, c.free_running->ship, body.initial[0] > 0 ? body.initial[0] : 1.0, 1.0);
  } catch (const InputError& e) {
    kind.Fail(fmt::format("a maneuver the ship can fly ({})", e.what()));
  }
  if (!(body.free[0] && body.free[1] && body.free[2])) {
    node.Fail("motion.free: [surge, sway, yaw]: a maneuver moves the ship in all three degrees of freedom");
  }
  s.execute_time = node.GetPositive("execute_time");
  if (s.execute_time < body.release_time) {
    node["execute_time"].Fail(fmt::format("an execute after the body's release at {} s (motion.release_time)",
                                          body.release_time));
  }
  s.output = output_directory / node.Get<std::string>("output", "maneuver.h5");
  return s;
}

ManeuverPilot::ManeuverPilot(const Case& c, ManeuverPilotSettings settings)
    : settings_(std::move(settings)),
      body_(c.free_body),
      rudder_(FindActuator<RudderActuator>(c)),
      propeller_(FindActuator<PropellerActuator>(c)),
      ship_(c.free_running->ship),
      approach_speed_(c.free_running->body.initial[0]),
      approach_rps_(propeller_ ? propeller_->options().n : 0.0),
      controller_(settings_.spec, ship_, approach_speed_, approach_rps_) {
  KELVIN_CHECK(body_ && rudder_, "a maneuver pilot needs the free body and its rudder (LoadManeuverPilot checks)");
}

double ManeuverPilot::heading() const { return body_->Trajectory().psi; }
double ManeuverPilot::surge_speed() const { return body_->velocities()[0]; }
void ManeuverPilot::SetRudderOrder(double delta_order) { rudder_->SetOrder(delta_order); }
void ManeuverPilot::SetRpsOrder(double /*n_order*/) {
  KELVIN_CHECK(false, "CFD maneuvers keep the propeller rate (LoadManeuverPilot refuses a crash stop)");
}

void ManeuverPilot::Record() {
  const Pose p = body_->Trajectory();
  const auto& nu = body_->velocities();
  const double n = propeller_ ? propeller_->last().n : 0.0;
  const int phase = started_ ? static_cast<int>(controller_.phase()) : static_cast<int>(sim::ManeuverPhase::kApproach);
  trajectory_.Add({t_, p.x0, p.y0, p.psi, nu[0], nu[1], nu[2], rudder_->angle(), n}, phase);
}

void ManeuverPilot::AfterStep(const PimpleSolver& /*solver*/, const StepRecord& record, History& /*history*/) {
  t_ = record.step.time;
  Record();
  if (!started_) {
    if (t_ >= settings_.execute_time - 1e-9) {
      controller_.Start(*this);
      started_ = true;
    }
  } else {
    sim::AfterManeuverStep(*this, controller_, psi_before_);
  }
  psi_before_ = heading();
}

bool ManeuverPilot::Done() const { return started_ && controller_.Finished(*this); }

void ManeuverPilot::AddCheckpointScalars(CheckpointScalars& s) const {
  s["maneuver_started"] = started_ ? 1.0 : 0.0;
  s["maneuver_psi_before"] = psi_before_;
  s["maneuver_time"] = t_;
}

void ManeuverPilot::AddCheckpointArrays(CheckpointArrays& arrays) const {
  std::vector<double> samples, phases;
  for (std::size_t i = 0; i < trajectory_.size(); ++i) {
    const sim::TrajectorySample& q = trajectory_[i];
    samples.insert(samples.end(), {q.t, q.x, q.y, q.psi, q.u, q.v, q.r, q.delta, q.n});
    phases.push_back(trajectory_.phases()[i]);
  }
  const std::string spec = settings_.spec.ToString();
  arrays["maneuver_spec"] = std::vector<double>(spec.begin(), spec.end());
  arrays["maneuver_trajectory"] = std::move(samples);
  arrays["maneuver_phases"] = std::move(phases);
  if (started_) arrays["maneuver_controller"] = controller_.Pack();
}

void ManeuverPilot::RestoreScalars(const CheckpointScalars& s) {
  auto get = [&](const char* name) {
    const auto it = s.find(name);
    if (it == s.end()) {
      throw DataFileError(fmt::format("the checkpoint has no {}; the case flies maneuver '{}'", name,
                                      settings_.spec.ToString()));
    }
    return it->second;
  };
  started_ = get("maneuver_started") != 0.0;
  psi_before_ = get("maneuver_psi_before");
  t_ = get("maneuver_time");
}

void ManeuverPilot::RestoreArrays(const CheckpointArrays& arrays) {
  auto get = [&](const char* name) -> const std::vector<double>& {
    const auto it = arrays.find(name);
    if (it == arrays.end()) {
      throw DataFileError(fmt::format("the checkpoint has no {}; the case flies maneuver '{}'", name,
                                      settings_.spec.ToString()));
    }
    return it->second;
  };
  const std::vector<double>& code = get("maneuver_spec");
  const std::string spec(code.begin(), code.end());
  if (spec != settings_.spec.ToString()) {
    throw DataFileError(fmt::format("the checkpoint is of maneuver '{}'; the case flies maneuver '{}' (restart it "
                                    "with the case and maneuver it was written by)",
                                    spec, settings_.spec.ToString()));
  }
  const std::vector<double>& samples = get("maneuver_trajectory");
  const std::vector<double>& phases = get("maneuver_phases");
  if (samples.size() != kSampleFields * phases.size()) {
    throw DataFileError(fmt::format("the checkpoint's maneuver trajectory has {} numbers for {} samples", samples.size(),
                                    phases.size()));
  }
  trajectory_ = {};
  for (std::size_t i = 0; i < phases.size(); ++i) {
    const double* q = samples.data() + kSampleFields * i;
    trajectory_.Add({q[0], q[1], q[2], q[3], q[4], q[5], q[6], q[7], q[8]}, static_cast<int>(phases[i]));
  }
  if (started_) controller_.Unpack(get("maneuver_controller"));
}

std::vector<std::string> ManeuverPilot::Finish(const PimpleSolver& solver) {
  std::vector<std::string> lines;
  if (!started_) {
    return {fmt::format("WARNING: maneuver '{}' never executed: the run ended at t = {:.4g} s, before execute_time {} s",
                        settings_.spec.ToString(), t_, settings_.execute_time)};
  }
  sim::ManeuverResult res;
  res.spec = settings_.spec;
  res.source = "cfd";
  res.ship_name = ship_.name;
  res.Lpp = ship_.principal.Lpp;
  res.scale = ship_.scale;
  res.approach_speed = approach_speed_;
  res.approach_rps = approach_rps_;
  res.trajectory = trajectory_;
  res.execute_times = controller_.execute_times();
  res.integrator_steps = static_cast<long>(trajectory_.size());
  sim::ComputeManeuverMetrics(res, controller_, ship_.limits.rudder_max, t_);
  OnFirstRank(solver.part(), [&] { sim::WriteManeuverResult(res, settings_.output, "kelvin CFD (free running)"); });
  if (!controller_.Finished(*this)) {
    lines.push_back(fmt::format("WARNING: maneuver '{}' not finished by t = {:.4g} s (time.end): its metrics are "
                                "partial; run longer",
                                settings_.spec.ToString(), t_));
  }
  std::string report = sim::FormatManeuverReport(res);
  std::size_t start = 0;
  while (start < report.size()) {
    const std::size_t end = report.find('\n', start);
    lines.push_back(report.substr(start, end == std::string::npos ? std::string::npos : end - start));
    if (end == std::string::npos) break;
    start = end + 1;
  }
  lines.push_back(fmt::format("maneuver written to {}", settings_.output.string()));
  return lines;
}

}  // namespace kelvin::cfd
