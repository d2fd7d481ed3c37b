#include "cfd/run/rudder_actuator.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "cfd/run/case_config.h"
#include "data/schema/errors.h"

namespace kelvin::cfd {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

RudderOptions RudderFromShip(const FreeRunningSettings& fr, const ConfigNode& node) {
  const sim::RudderParameters& rp = fr.ship.rudder;
  const std::string ship = fr.ship_file.string();
  if (!fr.ship.has_rudder) {
    node.Fail(fmt::format("a rudder: section needs the ship file's rudder (A_R, H_R, x_R_prime, z_top); {} has none",
                          ship));
  }
  if (!rp.z_top) {
    throw ConfigError(fmt::format("{}: rudder.z_top: expected the depth of the blade's top below the waterline (m) "
                                  "for the CFD rudder",
                                  ship));
  }
  RudderOptions o;
  o.name = fmt::format("{} (the blade of {}: rudder.A_R, H_R, x_R_prime, z_top)", node.Where(), ship);
  o.area = rp.A_R;
  o.span = rp.H_R;
  o.stock = Vector3(fr.body.centre.x() + rp.x_R_prime * fr.ship.principal.Lpp, 0.0, -*rp.z_top);
  o.thickness = node.Get<double>("thickness", o.thickness);
  o.sample_distance = node.Get<double>("sample_distance", o.sample_distance);
  o.sample_length = node.Get<double>("sample_length", o.sample_length);
  o.stall_angle = node.Get<double>("stall_angle_deg", o.stall_angle / kDeg) * kDeg;
  o.lift_slope = node.Get<double>("lift_slope", 0.0);
  o.waterline_image = node.Get<bool>("waterline_image", true);
  o.force_relaxation = node.Get<double>("force_relaxation", o.force_relaxation);
  o.max_angle = fr.ship.limits.rudder_max;
  return o;
}

}  // namespace

std::unique_ptr<BodyActuator> LoadRudderActuator(const Case& c, const ConfigNode& root) {
  if (!root.Has("rudder")) return nullptr;
  const ConfigNode node = root["rudder"];
  if (!c.free_running) node.Fail("no rudder: section without motion: {kind: free} (the blade acts on a free body)");
  node.ExpectKeys({"angle_deg", "thickness", "sample_distance", "sample_length", "stall_angle_deg", "lift_slope",
                   "waterline_image", "force_relaxation"});
  const FreeRunningSettings& fr = *c.free_running;
  const SteeringGear gear{fr.ship.limits.rudder_max, fr.ship.limits.rudder_rate};
  const double order = node.Get<double>("angle_deg", 0.0) * kDeg;
  if (std::abs(order) > gear.max_angle + 1e-12) {
    node["angle_deg"].Fail(fmt::format("an angle within the ship's rudder_max_deg ({:g} deg)", gear.max_angle / kDeg));
  }
  std::unique_ptr<RudderActuator> a;
  ValidateAt(node, [&] {
    // On ranks the blade and its sample are found on the whole mesh, as serially.
    Rudder rudder(c.whole_mesh ? *c.whole_mesh : *c.mesh, RudderFromShip(fr, node));
    if (c.part) rudder.Localize(c.part, c.mesh->n_cells());
    a = std::make_unique<RudderActuator>(std::move(rudder), gear, order, c.settings.rho);
  });
  return a;
}

RudderActuator::RudderActuator(Rudder rudder, SteeringGear gear, double initial_order, double rho)
    : rudder_(std::move(rudder)), gear_(gear), rho_(rho) {
  SetOrder(initial_order);
  delta_ = order_;
}

void RudderActuator::SetOrder(double order) { order_ = std::clamp(order, -gear_.max_angle, gear_.max_angle); }

void RudderActuator::BeforeStep(double t_new, double dt) {
  t_ = t_new;
  dt_ = dt;
  const double step = gear_.rate * dt;
  delta_ += std::clamp(order_ - delta_, -step, step);
}

void RudderActuator::Update(const PimpleSolver& solver, const FreeBody& body, int /*outer*/,
                            std::vector<Vector3>& cell_source, PlanarLoad& load) {
  const Pose pose = body.At(t_);
  const Vector3 centre = pose.Rotation() * body.centre() + pose.Translation(body.centre());
  const Vector3 V = pose.Velocity(), W = pose.AngularVelocity();
  const auto x = solver.mesh().cell_centres();
  auto body_velocity = [&](int c) { return Vector3(V + W.cross(x[c] - centre)); };
  last_ = rudder_.Update(solver, body_velocity, solver.mesh().placement_rotation(), delta_, rho_, cell_source);
  const PlanarLoad l = rudder_.BodyLoad(last_, body.centre());
  load.X += l.X;
  load.Y += l.Y;
  load.N += l.N;
}

void RudderActuator::ApplyRestored(const PimpleSolver& solver, std::vector<Vector3>& cell_source) const {
  rudder_.ApplyState(rho_, solver.mesh().placement_rotation(), cell_source);
}

void RudderActuator::Start(History& h) {
  state_col_ = h.Add("rudder/state", 3, "rad, rad, N", "blade angle delta, helm order and normal force F_N");
  inflow_col_ = h.Add("rudder/inflow", 5, "m/s, m/s, rad, m/s, m/s",
                      "effective inflow u_R (from ahead), v_R (towards starboard) and angle alpha_R; the sampled u, v "
                      "before the blade's induced velocity is removed");
}

void RudderActuator::AfterStep(const FreeBody& /*body*/, History& h) {
  h.Set(state_col_, Vector3(last_.delta, order_, last_.F_N));
  const std::vector<double> inflow = {last_.u_R, last_.v_R, last_.alpha_R, last_.u_sample, last_.v_sample};
  h.Set(inflow_col_, std::span<const double>(inflow));
  const double alpha = std::abs(last_.alpha_R);
  max_alpha_ = std::max(max_alpha_, alpha);
  if (alpha > Rudder::kValidatedAngle) time_beyond_ += dt_;
}

void RudderActuator::AddCheckpointScalars(CheckpointScalars& s) const {
  const Rudder::State r = rudder_.GetState();
  s["rudder_F_N"] = r.F_N;
  s["rudder_applied_delta"] = r.delta;
  s["rudder_started"] = r.started ? 1.0 : 0.0;
  s["rudder_delta"] = delta_;
  s["rudder_order"] = order_;
  s["rudder_max_alpha"] = max_alpha_;
  s["rudder_time_beyond"] = time_beyond_;
}

void RudderActuator::RestoreScalars(const CheckpointScalars& s) {
  auto get = [&](const char* name) {
    const auto it = s.find(name);
    if (it == s.end()) throw DataFileError(fmt::format("the checkpoint has no {}; the case runs a rudder", name));
    return it->second;
  };
  rudder_.SetState({get("rudder_F_N"), get("rudder_applied_delta"), get("rudder_started") != 0.0});
  delta_ = get("rudder_delta");
  order_ = get("rudder_order");
  // Diagnostics only: checkpoints written before they existed restart with 0.
  const auto diagnostic = [&](const char* name) {
    const auto it = s.find(name);
    return it == s.end() ? 0.0 : it->second;
  };
  max_alpha_ = diagnostic("rudder_max_alpha");
  time_beyond_ = diagnostic("rudder_time_beyond");
}

std::vector<std::string> RudderActuator::Finish() {
  std::vector<std::string> lines = {fmt::format("rudder at the last step: delta {:.3g} deg, F_N {:.4g} N, inflow u_R {:.4g} m/s, v_R {:.4g} m/s, "
                      "alpha_R {:.3g} deg ({:.1f} cells across the chord)",
                      last_.delta / kDeg, last_.F_N, last_.u_R, last_.v_R, last_.alpha_R / kDeg,
                      rudder_.cells_across_chord())};
  if (max_alpha_ > Rudder::kValidatedAngle) {
    lines.push_back(fmt::format(
        "WARNING: the rudder's angle of attack reached {:.1f} deg and stayed beyond {:.0f} deg for {:.3g} s: there "
        "the body-force blade's normal force falls below its lift curve (in a uniform stream -3% at 25 deg and -7% at "
        "30 deg with 10 cells across the chord, BENCHMARKS.md rudder_stream), so the rudder force of those steps is "
        "low",
        max_alpha_ / kDeg, Rudder::kValidatedAngle / kDeg, time_beyond_));
  }
  return lines;
}

}  // namespace kelvin::cfd
