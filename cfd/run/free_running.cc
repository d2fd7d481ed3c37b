#include "cfd/run/free_running.h"

#include <fmt/format.h>

#include <cmath>
#include <numbers>

#include "data/schema/errors.h"

namespace kelvin::cfd {
namespace {

constexpr double kDeg = 180.0 / std::numbers::pi;

std::string ScalarName(std::size_t i) { return fmt::format("free_body_{}", i); }

PlanarLoad Sum(const PlanarLoad& a, const PlanarLoad& b) { return {a.X + b.X, a.Y + b.Y, a.N + b.N}; }

}  // namespace

FreeRunningCoupler::FreeRunningCoupler(const Case& c)
    : body_(c.free_body),
      motion_(*c.motion),
      hull_(c.hull_patches),
      rho_(c.settings.rho),
      nu_(c.settings.nu),
      length_(c.free_running ? c.free_running->ship.principal.Lpp : 0.0) {
  KELVIN_CHECK(body_ != nullptr && c.motion != nullptr, "a free-running case (motion: {kind: free})");
  for (const auto& a : c.actuators) actuators_.push_back(a.get());
}

void FreeRunningCoupler::RestoreScalars(const CheckpointScalars& scalars) {
  std::vector<double> packed;
  for (std::size_t i = 0;; ++i) {
    const auto it = scalars.find(ScalarName(i));
    if (it == scalars.end()) break;
    packed.push_back(it->second);
  }
  if (packed.empty()) {
    throw DataFileError("the checkpoint has no free-body state (free_body_*); the case runs a free body");
  }
  body_->SetState(FreeBodyState::Unpack(packed));
  travelled_ = scalars.count("free_body_travelled") ? scalars.at("free_body_travelled") : 0.0;
  for (BodyActuator* a : actuators_) a->RestoreScalars(scalars);
}

void FreeRunningCoupler::Start(PimpleSolver& solver, History& h, const RunStart& start) {
  if (start.restarted && !actuators_.empty()) {
    cell_source_.assign(solver.mesh().n_cells(), Vector3::Zero());
    for (const BodyActuator* a : actuators_) a->ApplyRestored(solver, cell_source_);
    solver.SetCellSource(cell_source_);
  }
  columns_.trajectory = h.Add("body/trajectory", 3, "m, m, rad", "x0, y0 (starboard) and heading psi of the reference point");
  columns_.velocity = h.Add("body/velocity", 3, "m/s, m/s, rad/s", "u, v, r in ship axes (x forward, y starboard)");
  columns_.hull = h.Add("body/hull_load", 3, "N, N, N m", "X, Y, N of the water on the hull patches, ship axes");
  columns_.actuators = h.Add("body/actuator_load", 3, "N, N, N m", "X, Y, N of the actuators (propeller), ship axes");
  columns_.constraint = h.Add("body/constraint_load", 3, "N, N, N m",
                              "X, Y, N the carriage supplies on the held degrees of freedom (0 on free ones)");
  columns_.change = h.Add("body/coupling_change", 1, "1",
                          "velocity change of the last outer iteration's coupling correction / speed scale");
  for (BodyActuator* a : actuators_) a->Start(h);
}

void FreeRunningCoupler::BeforeStep(PimpleSolver& /*solver*/, double t_new, double dt) {
  body_->BeginStep(t_new, dt);
  for (BodyActuator* a : actuators_) a->BeforeStep(t_new, dt);
}

void FreeRunningCoupler::AfterOuterIteration(PimpleSolver& solver, int outer) {
  hull_loads_ = ComputeHullLoads(solver, hull_, rho_, nu_, body_->placed(), body_->centre());
  actuator_load_ = {};
  if (!actuators_.empty()) {
    cell_source_.assign(solver.mesh().n_cells(), Vector3::Zero());
    for (BodyActuator* a : actuators_) a->Update(solver, *body_, outer, cell_source_, actuator_load_);
    solver.SetCellSource(cell_source_);
  }
  change_ = body_->Correct(Sum(hull_loads_.Total(), actuator_load_), length_);
  motion_.MeshFlux(body_->At(body_->time()), mesh_flux_);
  solver.SetMeshFlux(mesh_flux_);
}

std::string FreeRunningCoupler::Diverged() const {
  std::string why;
  if (body_->Diverged(&why)) return why;
  for (const BodyActuator* a : actuators_) {
    if (std::string w = a->Diverged(); !w.empty()) return w;
  }
  return {};
}

void FreeRunningCoupler::AfterStep(const PimpleSolver& /*solver*/, const StepRecord& /*record*/, History& h) {
  const Pose p = body_->Trajectory();
  const auto& nu = body_->velocities();
  const PlanarLoad hull = hull_loads_.Total();
  const PlanarLoad& k = body_->constraint_load();
  h.Set(columns_.trajectory, Vector3(p.x0, p.y0, p.psi));
  h.Set(columns_.velocity, Vector3(nu[0], nu[1], nu[2]));
  h.Set(columns_.hull, Vector3(hull.X, hull.Y, hull.N));
  h.Set(columns_.actuators, Vector3(actuator_load_.X, actuator_load_.Y, actuator_load_.N));
  h.Set(columns_.constraint, Vector3(k.X, k.Y, k.N));
  h.Set(columns_.change, change_);
  const FreeBodyState s = body_->state();
  travelled_ += std::hypot(s.pos[0] - s.pos_old[0], s.pos[1] - s.pos_old[1]);
  for (BodyActuator* a : actuators_) a->AfterStep(*body_, h);
}

void FreeRunningCoupler::AddCheckpointScalars(CheckpointScalars& scalars) const {
  const std::vector<double> packed = body_->state().Pack();
  for (std::size_t i = 0; i < packed.size(); ++i) scalars[ScalarName(i)] = packed[i];
  scalars["free_body_travelled"] = travelled_;
  for (const BodyActuator* a : actuators_) a->AddCheckpointScalars(scalars);
}

void FreeRunningCoupler::WriteHistory(data::H5Writer& writer) const {
  for (const BodyActuator* a : actuators_) a->WriteHistory(writer);
}

std::vector<std::string> FreeRunningCoupler::Finish(const PimpleSolver& /*solver*/) {
  const Pose p = body_->Trajectory();
  const auto& nu = body_->velocities();
  std::vector<std::string> lines = {
      fmt::format("free body at t = {:.4g} s: u {:.5g} m/s, v {:.5g} m/s, r {:.5g} deg/s; x0 {:.4g} m, y0 {:.4g} m, "
                  "heading {:.4g} deg; {:.4g} m travelled{}",
                  body_->time(), nu[0], nu[1], nu[2] * kDeg, p.x0, p.y0, p.psi * kDeg, travelled_,
                  length_ > 0.0 ? fmt::format(" ({:.3g} ship lengths)", travelled_ / length_) : ""),
      fmt::format("coupling: {} scheme, last outer iteration changed the velocities by {:.2e} of the speed scale",
                  body_->options().coupling == BodyCoupling::kStabilised ? "stabilised" : "explicit", change_)};
  for (BodyActuator* a : actuators_) {
    for (std::string& l : a->Finish()) lines.push_back(std::move(l));
  }
  return lines;
}

}  // namespace kelvin::cfd
