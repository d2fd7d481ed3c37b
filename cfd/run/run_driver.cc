#include "cfd/run/run_driver.h"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <ctime>
#include <limits>
#include <set>

#include "cfd/freesurface/linearized_free_surface.h"
#include "cfd/io/checkpoint.h"
#include "cfd/parallel/run_checkpoint.h"
#include "data/report/progress.h"
#include "data/schema/errors.h"

namespace kelvin::cfd {
namespace {

namespace fs = std::filesystem;

// The centre of the cell with the largest Courant number, where the mesh is
// at this step. On ranks the cell is one of the whole mesh; its owner knows
// where it is.
Vector3 CourantLocation(const Mesh& mesh, const DomainPart* part, int cell) {
  if (!part || !part->parallel()) {
    return cell >= 0 ? mesh.cell_centres()[cell] : Vector3::Constant(std::numeric_limits<double>::quiet_NaN());
  }
  const int local = part->OwnedCell(cell);
  Vector3 x = local >= 0 ? mesh.cell_centres()[local] : Vector3::Zero();
  part->SumInPlace(std::span<double>(x.data(), 3));
  return x;
}

// The driver's own history columns.
struct CoreColumns {
  History::Column time, courant, res_U, res_p, continuity, wall, outer, pressure_iterations, cpu, courant_location;
  std::vector<History::Column> pressure, viscous;  // per output.forces patch

  CoreColumns(History& h, const Mesh& mesh, std::span<const int> force_patches) {
    time = h.Add("time", 1, "s", "simulated time at the end of each step");
    courant = h.Add("courant", 1, "1", "maximum Courant number");
    res_U = h.Add("residuals/U", 1, "1", "initial normalized momentum residual of the step");
    res_p = h.Add("residuals/p", 1, "1", "initial normalized pressure residual of the step");
    continuity = h.Add("continuity", 1, "1", "max_cells |sum F| / sum |F| after the correction");
    wall = h.Add("wall_time", 1, "s", "wall-clock time since the start of the time loop");
    outer = h.Add("outer_iterations", 1, "1", "PIMPLE outer iterations of the step");
    pressure_iterations = h.Add("pressure_iterations", 1, "1", "pressure CG iterations of the step");
    cpu = h.Add("cpu_time", 1, "s", "process CPU time since the start of the time loop");
    courant_location = h.Add("courant_location", 3, "m",
                             "centre of the cell with the largest Courant number (mesh position at that step)");
    for (int k : force_patches) {
      const std::string& name = mesh.patches()[k].name;
      pressure.push_back(h.Add("forces/" + name + "/pressure", 3, "N", "pressure force on the patch"));
      viscous.push_back(h.Add("forces/" + name + "/viscous", 3, "N", "viscous force on the patch"));
    }
  }

  void Fill(History& h, const Mesh& mesh, const DomainPart* part, const StepRecord& r,
            std::span<const int> force_patches) const {
    const StepSummary& s = r.step;
    h.Set(time, s.time);
    h.Set(courant, s.courant_max);
    h.Set(res_U, s.initial_residual_U);
    h.Set(res_p, s.initial_residual_p);
    h.Set(continuity, s.continuity_error);
    h.Set(wall, r.wall_seconds);
    h.Set(outer, static_cast<double>(s.outer_iterations));
    h.Set(pressure_iterations, static_cast<double>(s.pressure_iterations));
    h.Set(cpu, r.cpu_seconds);
    h.Set(courant_location, CourantLocation(mesh, part, s.courant_cell));
    for (std::size_t k = 0; k < force_patches.size(); ++k) {
      const PatchForce f = r.forces.Sum(force_patches[k]);
      h.Set(pressure[k], f.pressure);
      h.Set(viscous[k], f.viscous);
    }
  }
};

// The ship_loads group of the output.forces patches about the motion's centre.
SteadyGroup ShipLoadGroup(const Case& c, const StepForces& forces, double time) {
  const BodyKinematics& body = c.motion->body();
  const PlanarLoad l = forces.ShipLoads(*c.mesh, c.force_patches, body.At(time), body.centre()).Total();
  const double arm = c.settings.time.steady->ship_load_arm > 0.0 ? c.settings.time.steady->ship_load_arm
                                                                 : c.settings.reference.length;
  return ShipLoadGroup(l, arm);
}

// The groups of the steady criterion at this step.
std::vector<SteadyGroup> SteadyGroups(const Case& c, const StepForces& forces, double time) {
  std::vector<SteadyGroup> groups;
  const auto& steady = c.settings.time.steady;
  if (!steady) return groups;
  const PatchForce f = forces.Sum(c.force_patches);
  for (SteadyQuantity q : steady->quantities) {
    if (q == SteadyQuantity::kDrag) {
      const Vector3& d = c.settings.reference.direction;
      const double rp = f.pressure.dot(d), rf = f.viscous.dot(d);
      groups.push_back({{rp + rf, rp, rf}, rp + rf});
    } else if (q == SteadyQuantity::kForce) {
      const Vector3 t = f.total();
      groups.push_back({{t.x(), t.y(), t.z()}, t.norm()});
    } else if (q == SteadyQuantity::kShipLoads) {
      groups.push_back(ShipLoadGroup(c, forces, time));
    }
  }
  return groups;
}

std::span<const double> SteadyEta(const Case& c) {
  const auto& steady = c.settings.time.steady;
  if (!steady || !c.free_surface) return {};
  const auto& q = steady->quantities;
  if (std::find(q.begin(), q.end(), SteadyQuantity::kEta) == q.end()) return {};
  return c.free_surface->eta();
}

std::string DivergenceMessage(const StepSummary& s, const History& h, History::Column courant,
                              History::Column location, const fs::path& last_checkpoint) {
  std::string m = fmt::format(
      "diverged at step {} (t = {:.6g} s): non-finite residual or field (U residual {:.3g}, p residual {:.3g}, "
      "Courant {:.3g}); last good checkpoint: {}",
      s.step, s.time, s.initial_residual_U, s.initial_residual_p, s.courant_max,
      last_checkpoint.empty() ? "none" : last_checkpoint.string());
  if (h.rows() == 0) return m;
  // Where the blow-up began: the first of the last run of steps whose
  // Courant number exceeds twice the median of the run (by the last finite
  // step the growth has usually spread far from its origin).
  const std::span<const double> co = h.Values(courant);
  const auto [onset, grew, median] = CourantGrowthOnset(co);
  const std::span<const double> x = h.Values(location).subspan(3 * onset, 3);
  const int step = s.step - static_cast<int>(co.size() - onset);
  m += grew ? fmt::format("; the largest Courant number rose above twice the run's median ({:.3g}) from step {} "
                          "on, {:.3g} then, in the cell at ({:.4g}, {:.4g}, {:.4g}) m",
                          median, step, co[onset], x[0], x[1], x[2])
            : fmt::format("; the largest Courant number of the last finite step ({}), {:.3g}, was in the cell at "
                          "({:.4g}, {:.4g}, {:.4g}) m",
                          step, co[onset], x[0], x[1], x[2]);
  return m + " (history.h5 courant_location has every step)";
}

std::vector<int> PatchesToCompute(const Case& c, std::span<Monitor* const> monitors) {
  std::set<int> all(c.force_patches.begin(), c.force_patches.end());
  for (Monitor* m : monitors) {
    for (int k : m->ForcePatches()) all.insert(k);
  }
  return {all.begin(), all.end()};
}

class Loop {
 public:
  Loop(Case& c, std::span<Monitor* const> monitors, const RunDriverOptions& options)
      : c_(c), solver_(*c.solver), monitors_(monitors), options_(options),
        time_control_(c.settings.time, c.free_surface), core_(history_, *c.mesh, c.force_patches),
        patches_(PatchesToCompute(c, monitors)) {}

  RunDriverSummary Run();

 private:
  // A checkpoint every checkpoint_interval steps, and on the last step
  // unless the caller keeps none there (interval < 0: never).
  bool CheckpointDue(bool last) const {
    const int interval = options_.checkpoint_interval;
    if (options_.checkpoint.empty()) return false;
    if (last) return options_.checkpoint_at_end && interval >= 0;
    return interval > 0 && solver_.step() % interval == 0;
  }
  void Start();
  std::string MonitorDivergence() const {
    for (Monitor* m : monitors_) {
      if (std::string why = m->Diverged(); !why.empty()) return why;
    }
    return {};
  }
  // The signal that asked for a stop (0: none). On ranks the launcher
  // forwards it to each at its own moment: the largest over the ranks, so
  // that all stop after the same step.
  int StopRequested() const {
    const int signal = options_.stop_requested ? options_.stop_requested() : 0;
    const DomainPart* part = solver_.part();
    return part && part->parallel() ? static_cast<int>(part->Max(signal)) : signal;
  }
  void Checkpoint();
  void WriteHistory() const;
  void WriteHistoryFile() const;

  Case& c_;
  PimpleSolver& solver_;
  std::span<Monitor* const> monitors_;
  const RunDriverOptions& options_;
  TimeControl time_control_;
  History history_;
  CoreColumns core_;
  std::vector<int> patches_;
  StepForces forces_;
  RunDriverSummary summary_;
  int last_checkpoint_step_ = -1;  // step of this run's last checkpoint (-1: none yet)
};

void Loop::Start() {
  CheckpointScalars scalars;
  const bool restarted = !options_.restart.empty();
  if (restarted) {
    scalars = ReadCheckpointScalars(options_.restart);
    for (Monitor* m : monitors_) m->RestoreScalars(scalars);
    ReadRunCheckpoint(options_.restart, solver_);
  }
  time_control_.Start(solver_, restarted, scalars, c_.settings.reference.velocity());
  if (restarted) {
    try {
      const CheckpointArrays arrays = ReadCheckpointArrays(options_.restart);
      time_control_.RestorePhase(scalars, arrays);
      for (Monitor* m : monitors_) m->RestoreArrays(arrays);
    } catch (const DataFileError& e) {
      throw DataFileError(fmt::format("{}: {}", options_.restart.string(), e.what()));
    }
  }
  const RunStart start{restarted, scalars};
  for (Monitor* m : monitors_) m->Start(solver_, history_, start);
  solver_.SetOuterIterationHook([this](int outer) {
    for (Monitor* m : monitors_) m->AfterOuterIteration(solver_, outer);
  });
}

void Loop::WriteHistory() const {
  if (options_.history.empty() || history_.rows() == 0) return;
  OnFirstRank(solver_.part(), [this] { WriteHistoryFile(); });
}

void Loop::WriteHistoryFile() const {
  data::H5Writer w(options_.history);
  history_.Write(w);
  const SteadyStatus& st = time_control_.status();
  if (st.enabled) {
    w.WriteArray("steady/change", std::vector<double>{st.force_change}, {1}, "1",
                 "relative change of the monitored forces over the time.steady window at the last step");
    w.WriteArray("steady/eta_change", std::vector<double>{st.eta_change}, {1}, "1",
                 "relative L2 change of eta over the time.steady window at the last step (0: not monitored)");
    w.WriteArray("steady/converged", std::vector<double>{st.settled ? 1.0 : 0.0}, {1}, "1",
                 "1 when the steady criterion was met before time.end");
  }
  for (Monitor* m : monitors_) m->WriteHistory(w);
  w.Commit();
}

void Loop::Checkpoint() {
  for (Monitor* m : monitors_) m->BeforeCheckpoint(solver_);
  CheckpointScalars scalars = time_control_.CheckpointScalars();
  for (Monitor* m : monitors_) m->AddCheckpointScalars(scalars);
  try {
    CheckpointArrays arrays = time_control_.CheckpointArrays();
    for (Monitor* m : monitors_) m->AddCheckpointArrays(arrays);
    WriteRunCheckpoint(options_.checkpoint, solver_, scalars, arrays);
    summary_.last_checkpoint = options_.checkpoint;
    last_checkpoint_step_ = solver_.step();
    WriteHistory();
  } catch (const DataFileError& e) {
    // Written atomically: the file under its name is still the last good one.
    throw DataFileError(fmt::format(
        "the run stopped at step {}: {}; {}", solver_.step(), e.what(),
        last_checkpoint_step_ >= 0
            ? fmt::format("the checkpoint of step {} is kept ({})", last_checkpoint_step_, options_.checkpoint.string())
            : std::string("no checkpoint of this run had been written")));
  }
}

RunDriverSummary Loop::Run() {
  Start();
  const int total_steps = time_control_.StepsToEnd(solver_.time());
  Progress::Options po;
  po.label = options_.label;
  po.enabled = options_.progress && (!solver_.part() || solver_.part()->rank == 0);
  Progress progress(std::max(total_steps, 1), po);
  const auto start = std::chrono::steady_clock::now();
  const std::clock_t cpu_start = std::clock();
  for (int i = 0; i < total_steps; ++i) {
    if (options_.step_budget > 0 && summary_.steps >= options_.step_budget) {
      summary_.status = RunDriverSummary::Status::kStopped;
      break;
    }
    const std::clock_t cpu_before = std::clock();
    const double dt = time_control_.NextTimeStep();
    for (Monitor* m : monitors_) m->BeforeStep(solver_, solver_.time() + dt, dt);
    const StepSummary s = solver_.Step(dt);
    const double step_cpu = static_cast<double>(std::clock() - cpu_before) / CLOCKS_PER_SEC;
    summary_.outer_iterations += s.outer_iterations;
    ++summary_.steps;
    if (!s.finite) {
      summary_.status = RunDriverSummary::Status::kDiverged;
      summary_.message =
          DivergenceMessage(s, history_, core_.courant, core_.courant_location, summary_.last_checkpoint);
      break;
    }
    if (const std::string why = MonitorDivergence(); !why.empty()) {
      summary_.status = RunDriverSummary::Status::kDiverged;
      summary_.message = fmt::format("diverged at step {} (t = {:.6g} s): {}; last good checkpoint: {}", s.step,
                                     s.time, why,
                                     summary_.last_checkpoint.empty() ? "none" : summary_.last_checkpoint.string());
      break;
    }
    forces_.Compute(solver_, patches_, c_.settings.rho, c_.settings.nu);
    time_control_.Record(solver_, SteadyGroups(c_, forces_, solver_.time()), SteadyEta(c_));
    StepRecord record{s, forces_, time_control_.status()};
    record.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    record.cpu_seconds = static_cast<double>(std::clock() - cpu_start) / CLOCKS_PER_SEC;
    record.step_cpu_seconds = step_cpu;
    record.last = i + 1 == total_steps || time_control_.settled();
    history_.NewRow();
    core_.Fill(history_, *c_.mesh, c_.part.get(), record, c_.force_patches);
    for (Monitor* m : monitors_) m->AfterStep(solver_, record, history_);
    const bool done = std::any_of(monitors_.begin(), monitors_.end(), [](const Monitor* m) { return m->Done(); });
    const bool checkpointed = CheckpointDue(record.last || done);
    if (checkpointed) Checkpoint();
    if (const int signal = StopRequested(); signal != 0) {
      if (!checkpointed && !options_.checkpoint.empty()) Checkpoint();
      summary_.status = RunDriverSummary::Status::kInterrupted;
      summary_.message = fmt::format(
          "interrupted by signal {} after step {} (t = {:.6g} s); {}", signal, s.step, s.time,
          options_.checkpoint.empty() ? std::string("no checkpoint (none was asked for)")
                                      : fmt::format("checkpoint {} (continue with --restart {})",
                                                    options_.checkpoint.string(), options_.checkpoint.string()));
      break;
    }
    progress.Update(i + 1, fmt::format("step {} t={:.4g} Co={:.3g} U={:.2e} p={:.2e}", s.step, s.time,
                                       s.courant_max, s.initial_residual_U, s.initial_residual_p));
    if (time_control_.settled() || done) break;
  }
  solver_.SetOuterIterationHook(nullptr);
  WriteHistory();
  const bool completed = summary_.status == RunDriverSummary::Status::kCompleted;
  progress.Finish(completed                                                       ? "done"
                  : summary_.status == RunDriverSummary::Status::kDiverged    ? "diverged"
                  : summary_.status == RunDriverSummary::Status::kInterrupted ? "interrupted"
                                                                              : "stopped");
  summary_.time = solver_.time();
  summary_.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  summary_.steady = time_control_.status();
  if (completed && summary_.steps > 0) {
    for (Monitor* m : monitors_) {
      for (std::string& line : m->Finish(solver_)) summary_.report.push_back(std::move(line));
    }
  }
  return summary_;
}

}  // namespace

void StepForces::Compute(const PimpleSolver& solver, std::span<const int> patches, double rho, double nu) {
  faces_.clear();
  sums_.clear();
  part_ = solver.part();
  for (int k : patches) Set(k, ComputePatchFaceForces(solver, k, rho, nu));
  if (!part_ || !part_->parallel()) return;
  // One reduction for every patch's sums (the same patches on every rank).
  std::vector<double> sums;
  for (const auto& [k, f] : sums_) sums.insert(sums.end(), {f.pressure.x(), f.pressure.y(), f.pressure.z(),
                                                            f.viscous.x(), f.viscous.y(), f.viscous.z()});
  part_->SumInPlace(sums);
  std::size_t i = 0;
  for (auto& [k, f] : sums_) {
    f.pressure = Vector3(sums[i], sums[i + 1], sums[i + 2]);
    f.viscous = Vector3(sums[i + 3], sums[i + 4], sums[i + 5]);
    i += 6;
  }
}

HullLoads StepForces::ShipLoads(const Mesh& mesh, std::span<const int> patches, const Pose& pose,
                                const Vector3& centre_body) const {
  std::vector<const PatchFaceForces*> faces;
  for (int k : patches) faces.push_back(&Faces(k));
  HullLoads l = SumHullLoads(mesh, patches, faces, pose, centre_body);
  SumOverRanks(part_, l);
  return l;
}

void StepForces::Set(int patch, PatchFaceForces faces) {
  PatchForce sum;
  for (std::size_t i = 0; i < faces.pressure.size(); ++i) {
    sum.pressure += faces.pressure[i];
    sum.viscous += faces.viscous[i];
  }
  sums_[patch] = sum;
  faces_[patch] = std::move(faces);
}

const PatchFaceForces& StepForces::Faces(int patch) const {
  const auto it = faces_.find(patch);
  KELVIN_CHECK(it != faces_.end(), "the face forces of a patch the run computes");
  return it->second;
}

PatchForce StepForces::Sum(int patch) const {
  const auto it = sums_.find(patch);
  KELVIN_CHECK(it != sums_.end(), "the force of a patch the run computes");
  return it->second;
}

PatchForce StepForces::Sum(std::span<const int> patches) const {
  PatchForce f;
  for (int k : patches) {
    const PatchForce p = Sum(k);
    f.pressure += p.pressure;
    f.viscous += p.viscous;
  }
  return f;
}

CourantOnset CourantGrowthOnset(std::span<const double> courant) {
  KELVIN_CHECK(!courant.empty(), "a Courant history");
  std::vector<double> sorted(courant.begin(), courant.end());
  std::nth_element(sorted.begin(), sorted.begin() + static_cast<std::ptrdiff_t>(sorted.size() / 2), sorted.end());
  CourantOnset o;
  o.median = sorted[sorted.size() / 2];
  o.step = courant.size() - 1;
  o.grew = courant.back() > 2.0 * o.median;
  while (o.grew && o.step > 0 && courant[o.step - 1] > 2.0 * o.median) --o.step;
  return o;
}

SteadyGroup ShipLoadGroup(const PlanarLoad& load, double arm) {
  return {{load.X, load.Y, load.N / arm}, std::hypot(load.X, load.Y)};
}

RunDriverSummary RunDriver(Case& c, std::span<Monitor* const> monitors, const RunDriverOptions& options) {
  Loop loop(c, monitors, options);
  return loop.Run();
}

}  // namespace kelvin::cfd
