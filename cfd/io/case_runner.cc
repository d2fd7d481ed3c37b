#include "cfd/io/case_runner.h"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <ctime>
#include <cmath>
#include <limits>
#include <map>

#include "cfd/freesurface/resistance.h"
#include "cfd/io/checkpoint.h"
#include "cfd/io/vtu_writer.h"
#include "cfd/motion/ship_forces.h"
#include "data/report/progress.h"
#include "data/schema/h5_file.h"

namespace kelvin::cfd {

namespace fs = std::filesystem;
using data::ConfigNode;

namespace {

// Pressure and viscous force on a patch (N): p is kinematic, so times rho.
std::pair<Vector3, Vector3> PatchForce(const PimpleSolver& s, int patch_index, double rho, double nu) {
  const PatchFaceForces ff = ComputePatchFaceForces(s, patch_index, rho, nu);
  Vector3 fp = Vector3::Zero(), fv = Vector3::Zero();
  for (std::size_t i = 0; i < ff.pressure.size(); ++i) {
    fp += ff.pressure[i];
    fv += ff.viscous[i];
  }
  return {fp, fv};
}

}  // namespace

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

RunSummary RunCase(const fs::path& case_file, const RunOptions& options) {
  const ConfigNode root = ConfigNode::LoadFile(case_file);
  CaseOverrides overrides;
  overrides.poly_mesh = options.poly_mesh_override;
  Case c = LoadCase(root, case_file.parent_path(), overrides);
  if (!options.output_override.empty()) c.output_directory = options.output_override;
  PimpleSolver& solver = *c.solver;
  const Mesh& mesh = *c.mesh;
  spdlog::info("mesh quality:\n{}", mesh.Quality().Report());
  const double nu = root["physics"].GetPositive("nu");
  fs::create_directories(c.output_directory);
  RunSummary summary;
  summary.output_directory = c.output_directory;
  CheckpointScalars restored;
  if (!options.restart.empty()) restored = ReadCheckpoint(options.restart, solver);
  // Steady resistance (the `resistance:` section): uniform start, time-step
  // ramp, convergence stop and resistance.h5 (cfd/freesurface/resistance.h).
  std::unique_ptr<ResistanceMonitor> resistance;
  if (root.Has("resistance")) {
    resistance = LoadResistance(root["resistance"], solver, root["physics"], case_file.parent_path());
    resistance->Start(solver, !options.restart.empty(), restored);
  }
  // Scales of the per-step resistance coefficients in history.h5:
  // output.resistance, or else those of the resistance section.
  ResistanceReference coefficients = c.resistance;
  if (!coefficients.enabled() && resistance) {
    coefficients.speed = resistance->speed();
    coefficients.direction = resistance->direction();
    coefficients.area = resistance->wetted_area();
  }

  std::vector<std::vector<double>> history;  // rows: time, Co, resU, resp, continuity, forces...
  std::vector<CaptiveSample> captive_rows;      // ship-axis loads (motion with output.captive)
  std::vector<int> force_patch_index;
  for (const std::string& name : c.force_patches) force_patch_index.push_back(mesh.FindPatch(name));
  PvdSeries pvd(c.output_directory / "fields.pvd");
  std::map<std::string, PvdSeries> surface_pvd;
  auto write_fields = [&]() {
    VtuCellData u{"U", 3, {}}, p{"p", 1, {}};
    for (int i = 0; i < mesh.n_cells(); ++i) {
      for (int k = 0; k < 3; ++k) u.values.push_back(solver.U()[i][k]);
      p.values.push_back(solver.p()[i]);
    }
    const fs::path file = c.output_directory / fmt::format("fields_{:06d}.vtu", solver.step());
    std::vector<VtuCellData> cell_data = {u, p};
    if (solver.turbulence()) {
      for (TurbulenceOutput& t : solver.turbulence()->CellOutputs()) {
        cell_data.push_back({t.name, t.components, std::move(t.values)});
      }
    }
    WriteVtu(file, mesh, cell_data);
    pvd.Add(solver.time(), file);
    // Patches whose conditions have their own unknowns (eta): a surface file
    // with those, p and U per face, in a series of their own.
    for (int k = 0; k < solver.p().n_patches(); ++k) {
      auto fields = solver.p().bc(k).FaceFields();
      if (fields.empty()) continue;
      const Patch& patch = mesh.patches()[k];
      std::vector<VtuCellData> data;
      for (auto& [name, values] : fields) data.push_back({name, 1, std::move(values)});
      VtuCellData pf{"p", 1, {}}, uf{"U", 3, {}};
      for (int f = patch.start; f < patch.start + patch.size; ++f) {
        pf.values.push_back(solver.p().boundary()[f - mesh.n_internal_faces()]);
        for (int d = 0; d < 3; ++d) uf.values.push_back(solver.U().boundary()[f - mesh.n_internal_faces()][d]);
      }
      data.push_back(std::move(pf));
      data.push_back(std::move(uf));
      const fs::path surface_file = c.output_directory / fmt::format("{}_{:06d}.vtp", patch.name, solver.step());
      WritePatchVtp(surface_file, mesh, patch, data);
      auto [series, inserted] = surface_pvd.try_emplace(patch.name, c.output_directory / (patch.name + ".pvd"));
      series->second.Add(solver.time(), surface_file);
    }
  };
  // Turbulence per step: residuals of k and omega, cells lifted by the bound
  // step, and y+ (min, mean, max) on each wall patch.
  std::vector<std::array<double, 4>> turbulence_rows;
  // output.resistance: C_T, C_F (viscous), C_P (pressure) per step.
  std::vector<std::array<double, 3>> resistance_rows;
  auto add_coefficients = [&](const Vector3& fp, const Vector3& fv) {
    const double q = 0.5 * c.rho * coefficients.speed * coefficients.speed * coefficients.area;
    const double cp = fp.dot(coefficients.direction) / q, cf = fv.dot(coefficients.direction) / q;
    resistance_rows.push_back({cp + cf, cf, cp});
  };
  // Centre of the cell with the largest Courant number, per step: where a
  // run that blows up was growing fastest.
  std::vector<Vector3> courant_locations;
  ForceConvergence steady(c.steady);
  std::vector<std::vector<WallPatchStats>> wall_rows;
  constexpr std::size_t kForceColumn = 9;
  auto write_history = [&]() {
    data::H5Writer w(c.output_directory / "history.h5");
    const std::size_t rows = history.size();
    auto column = [&](std::size_t col) {
      std::vector<double> v(rows);
      for (std::size_t r = 0; r < rows; ++r) v[r] = history[r][col];
      return v;
    };
    w.WriteArray("time", column(0), {rows}, "s", "simulated time at the end of each step");
    w.WriteArray("courant", column(1), {rows}, "1", "maximum Courant number");
    w.WriteArray("residuals/U", column(2), {rows}, "1", "initial normalized momentum residual of the step");
    w.WriteArray("residuals/p", column(3), {rows}, "1", "initial normalized pressure residual of the step");
    w.WriteArray("continuity", column(4), {rows}, "1", "max_cells |sum F| / sum |F| after the correction");
    w.WriteArray("wall_time", column(5), {rows}, "s", "wall-clock time since the start of the time loop");
    w.WriteArray("outer_iterations", column(6), {rows}, "1", "PIMPLE outer iterations of the step");
    w.WriteArray("pressure_iterations", column(7), {rows}, "1", "pressure CG iterations of the step");
    w.WriteArray("cpu_time", column(8), {rows}, "s", "process CPU time since the start of the time loop");
    if (courant_locations.size() == rows) {
      std::vector<double> v(rows * 3);
      for (std::size_t r = 0; r < rows; ++r) {
        for (int d = 0; d < 3; ++d) v[r * 3 + d] = courant_locations[r][d];
      }
      w.WriteArray("courant_location", v, {rows, 3}, "m",
                   "centre of the cell with the largest Courant number (mesh position at that step)");
    }
    for (std::size_t k = 0; k < c.force_patches.size(); ++k) {
      std::vector<double> fp(rows * 3), fv(rows * 3);
      for (std::size_t r = 0; r < rows; ++r) {
        for (int d = 0; d < 3; ++d) {
          fp[r * 3 + d] = history[r][kForceColumn + 6 * k + d];
          fv[r * 3 + d] = history[r][kForceColumn + 6 * k + 3 + d];
        }
      }
      w.WriteArray("forces/" + c.force_patches[k] + "/pressure", fp, {rows, 3}, "N", "pressure force on the patch");
      w.WriteArray("forces/" + c.force_patches[k] + "/viscous", fv, {rows, 3}, "N", "viscous force on the patch");
    }
    if (!captive_rows.empty()) WriteCaptiveHistory(w, captive_rows);
    if (!resistance_rows.empty()) {
      const std::size_t n = resistance_rows.size();
      const char* names[3] = {"resistance/C_T", "resistance/C_F", "resistance/C_P"};
      const char* what[3] = {"total resistance coefficient F.d / (rho U^2 S / 2) of the force patches",
                             "viscous (friction) part of C_T", "pressure part of C_T"};
      for (int j = 0; j < 3; ++j) {
        std::vector<double> v(n);
        for (std::size_t r = 0; r < n; ++r) v[r] = resistance_rows[r][j];
        w.WriteArray(names[j], v, {n}, "1", what[j]);
      }
      w.WriteArray("resistance/reference", std::vector<double>{coefficients.speed, coefficients.area, c.rho}, {3},
                   "m/s, m^2, kg/m^3", "reference speed U, area S and density rho of the coefficients");
    }
    if (c.steady.enabled()) {
      w.WriteArray("steady/change", std::vector<double>{steady.change()}, {1}, "1",
                   "relative range of the monitored force over the time.steady window at the last step");
      w.WriteArray("steady/converged", std::vector<double>{summary.steady_converged ? 1.0 : 0.0}, {1}, "1",
                   "1 when the force settled within the tolerance before time.end");
    }
    if (!turbulence_rows.empty()) {
      const std::size_t n = turbulence_rows.size();
      const char* names[4] = {"turbulence/residuals/k", "turbulence/residuals/omega", "turbulence/bounded/k",
                              "turbulence/bounded/omega"};
      const char* what[4] = {"initial normalized residual of k", "initial normalized residual of omega",
                             "cells the bound step lifted to the floor (k)",
                             "cells the bound step lifted to the floor (omega)"};
      for (int j = 0; j < 4; ++j) {
        std::vector<double> v(n);
        for (std::size_t r = 0; r < n; ++r) v[r] = turbulence_rows[r][j];
        w.WriteArray(names[j], v, {n}, "1", what[j]);
      }
      for (std::size_t k = 0; k < wall_rows.front().size(); ++k) {
        std::vector<double> v(n * 3);
        for (std::size_t r = 0; r < n; ++r) {
          v[3 * r] = wall_rows[r][k].y_plus_min;
          v[3 * r + 1] = wall_rows[r][k].y_plus_mean;
          v[3 * r + 2] = wall_rows[r][k].y_plus_max;
        }
        w.WriteArray("turbulence/y_plus/" + wall_rows.front()[k].patch, v, {n, 3}, "1",
                     "first-cell y+ on the wall patch: min, area-weighted mean, max");
      }
    }
    w.Commit();
  };

  const int total_steps = static_cast<int>(std::ceil((c.end_time - solver.time()) / c.dt - 1e-9));
  Progress::Options po;
  po.label = "kelvin run";
  po.enabled = options.progress;
  Progress progress(std::max(total_steps, 1), po);
  const auto start = std::chrono::steady_clock::now();
  const std::clock_t cpu_start = std::clock();
  for (int i = 0; i < total_steps; ++i) {
    const StepSummary s = solver.Step(resistance ? resistance->TimeStep(c.dt) : c.dt);
    summary.outer_iterations += s.outer_iterations;
    ++summary.steps;
    if (!s.finite) {
      summary.status = RunSummary::Status::kDiverged;
      summary.message = fmt::format(
          "diverged at step {} (t = {:.6g} s): non-finite residual or field (U residual {:.3g}, p residual {:.3g}, "
          "Courant {:.3g}); last good checkpoint: {}",
          s.step, s.time, s.initial_residual_U, s.initial_residual_p, s.courant_max,
          summary.last_checkpoint.empty() ? "none" : summary.last_checkpoint.string());
      if (!courant_locations.empty()) {
        // Where the blow-up began: the first of the last run of steps whose
        // Courant number exceeds twice the median of the run (by the last
        // finite step the growth has usually spread far from its origin).
        std::vector<double> co;
        for (const auto& row : history) co.push_back(row[1]);
        const auto [onset, grew, median] = CourantGrowthOnset(co);
        const Vector3& x = courant_locations[onset];
        const int step = s.step - static_cast<int>(co.size() - onset);
        summary.message +=
            grew ? fmt::format("; the largest Courant number rose above twice the run's median ({:.3g}) from step {} "
                               "on, {:.3g} then, in the cell at ({:.4g}, {:.4g}, {:.4g}) m",
                               median, step, co[onset], x.x(), x.y(), x.z())
                 : fmt::format("; the largest Courant number of the last finite step ({}), {:.3g}, was in the cell at "
                               "({:.4g}, {:.4g}, {:.4g}) m",
                               step, co[onset], x.x(), x.y(), x.z());
        summary.message += " (history.h5 courant_location has every step)";
      }
      break;
    }
    const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    const double cpu = static_cast<double>(std::clock() - cpu_start) / CLOCKS_PER_SEC;
    std::vector<double> row = {s.time, s.courant_max, s.initial_residual_U, s.initial_residual_p, s.continuity_error,
                               wall, static_cast<double>(s.outer_iterations),
                               static_cast<double>(s.pressure_iterations), cpu};
    for (const std::string& name : c.force_patches) {
      const auto [fp, fv] = PatchForce(solver, mesh.FindPatch(name), c.rho, nu);
      for (int d = 0; d < 3; ++d) row.push_back(fp[d]);
      for (int d = 0; d < 3; ++d) row.push_back(fv[d]);
    }
    if (c.resistance.enabled() || c.steady.enabled()) {
      // Summed pressure and viscous force of the force patches (the row holds
      // them per patch after kForceColumn).
      Vector3 fp = Vector3::Zero(), fv = Vector3::Zero();
      for (std::size_t k = 0; k < c.force_patches.size(); ++k) {
        for (int d = 0; d < 3; ++d) {
          fp[d] += row[kForceColumn + 6 * k + d];
          fv[d] += row[kForceColumn + 6 * k + 3 + d];
        }
      }
      if (c.resistance.enabled()) add_coefficients(fp, fv);
      if (c.steady.enabled() && steady.Add(fp + fv)) summary.steady_converged = true;
      summary.steady_change = steady.change();
    }
    history.push_back(std::move(row));
    courant_locations.push_back(s.courant_cell >= 0 ? mesh.cell_centres()[s.courant_cell]
                                                    : Vector3::Constant(std::numeric_limits<double>::quiet_NaN()));
    bool converged = false;
    if (resistance) {
      const auto [fp, fv] = PatchForce(solver, resistance->hull_patch(), c.rho, nu);
      converged = resistance->Record(solver, fp, fv);
      // Without output.resistance: the same per-step coefficients from the hull
      // force along the inflow, so that kelvin gci reads either kind of run.
      if (!c.resistance.enabled()) add_coefficients(fp, fv);
      // The steady criterion of the resistance section is this run's steady state.
      if (converged) summary.steady_converged = true;
    }
    if (c.motion && c.captive_length > 0.0) {
      captive_rows.push_back(MakeCaptiveSample(solver, *c.motion, force_patch_index, c.rho, nu,
                                            {c.rho, c.captive_length, c.captive_draft,
                                             c.motion->motion().options().speed}));
    }
    const bool last = i + 1 == total_steps || converged || summary.steady_converged;
    if ((last && c.vtu_interval >= 0) || (c.vtu_interval > 0 && solver.step() % c.vtu_interval == 0)) {
      write_fields();
    }
    if ((last && c.checkpoint_interval >= 0) ||
        (c.checkpoint_interval > 0 && solver.step() % c.checkpoint_interval == 0)) {
      summary.last_checkpoint = c.output_directory / "checkpoint.h5";
      WriteCheckpoint(summary.last_checkpoint, solver,
                      resistance ? resistance->CheckpointScalars() : CheckpointScalars{});
      write_history();
    }
    if (const TurbulenceModel* t = solver.turbulence()) {
      const TurbulenceSummary& ts = solver.turbulence_summary();
      turbulence_rows.push_back({ts.initial_residual_k, ts.initial_residual_omega, double(ts.bounded_k),
                                 double(ts.bounded_omega)});
      wall_rows.push_back(t->WallStats());
      if (ts.bounded_k + ts.bounded_omega > 0) {
        spdlog::warn("step {}: the bound step lifted {} k and {} omega cells to the floor", s.step, ts.bounded_k,
                     ts.bounded_omega);
      }
    }
    progress.Update(i + 1, fmt::format("step {} t={:.4g} Co={:.3g} U={:.2e} p={:.2e}", s.step, s.time,
                                       s.courant_max, s.initial_residual_U, s.initial_residual_p));
    if (converged || summary.steady_converged) break;
  }
  if (!history.empty()) write_history();
  progress.Finish(summary.status == RunSummary::Status::kCompleted ? "done" : "diverged");
  summary.time = solver.time();
  summary.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (summary.status == RunSummary::Status::kCompleted) {
    summary.message = fmt::format("completed {} steps to t = {:.6g} s; results in {}", summary.steps, summary.time,
                                  summary.output_directory.string());
    if (resistance && summary.steps > 0) {
      summary.message += "\n  " + resistance->Write(c.output_directory / "resistance.h5", solver);
    }
    if (c.steady.enabled()) {
      summary.message +=
          summary.steady_converged
              ? fmt::format("\n  steady: force settled (range {:.3g} of |F| over {} steps)", summary.steady_change,
                            c.steady.window)
              : fmt::format("\n  steady: NOT settled by time.end (range {:.3g} of |F| over {} steps, tolerance {:.3g})",
                            summary.steady_change, c.steady.window, c.steady.tolerance);
    }
    if (c.resistance.enabled() && !resistance_rows.empty()) {
      const auto& r = resistance_rows.back();
      summary.message += fmt::format("\n  resistance: C_T {:.5e} = C_F {:.5e} + C_P {:.5e} (U {:.4g} m/s, S {:.5g} m^2)",
                                     r[0], r[1], r[2], c.resistance.speed, c.resistance.area);
    }
    if (!wall_rows.empty()) {
      for (const WallPatchStats& w : wall_rows.back()) {
        summary.message += fmt::format("\n  y+ on {}: min {:.3g}, mean {:.3g}, max {:.3g}", w.patch, w.y_plus_min,
                                       w.y_plus_mean, w.y_plus_max);
      }
    }
  }
  return summary;
}

}  // namespace kelvin::cfd
