#include "cfd/verification/flat_plate.h"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <ctime>
#include <memory>

#include "cfd/mesh/mesh_builder.h"
#include "cfd/solver/pimple_solver.h"
#include "data/schema/errors.h"

namespace kelvin::cfd {

double SchoenherrFrictionLine(double re) {
  // f(C) = 0.242 / sqrt(C) - log10(Re C) decreases in C: bisection.
  double lo = 1e-5, hi = 0.1;
  for (int i = 0; i < 200; ++i) {
    const double mid = 0.5 * (lo + hi);
    (0.242 / std::sqrt(mid) - std::log10(re * mid) > 0.0 ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

double PrandtlSchlichtingLocal(double re_x) { return std::pow(2.0 * std::log10(re_x) - 0.65, -2.3); }

void FlatPlateOptions::Validate() const {
  auto positive = [](double v, const char* name) {
    if (!(v > 0.0) || !std::isfinite(v)) throw ConfigError(fmt::format("flat plate: {} = {}; expected > 0", name, v));
  };
  positive(reynolds, "reynolds");
  positive(length, "length");
  positive(speed, "speed");
  positive(upstream, "upstream");
  positive(height, "height");
  positive(y_plus, "y_plus");
  positive(refinement, "refinement");
  if (!(leading_edge_ratio >= 1.0)) {
    throw ConfigError(fmt::format("flat plate: leading_edge_ratio = {}; expected >= 1", leading_edge_ratio));
  }
  if (cells_x < 4 || cells_y < 4 || cells_upstream < 2) {
    throw ConfigError(fmt::format("flat plate: cells ({}, {}, upstream {}) too few; expected >= 4, 4, 2", cells_x,
                                  cells_y, cells_upstream));
  }
}

namespace {

// Growth ratio g of n cells whose first cell is `first` and whose sizes sum
// to `length` (g = 1 for a uniform spacing).
double GrowthRatio(double length, double first, int n) {
  if (first * n >= length) return 1.0;
  double lo = 1.0, hi = 2.0;
  while (first * (std::pow(hi, n) - 1.0) / (hi - 1.0) < length) hi *= 2.0;
  for (int i = 0; i < 200; ++i) {
    const double mid = 0.5 * (lo + hi);
    (first * (std::pow(mid, n) - 1.0) / (mid - 1.0) < length ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

// The geometric mapping of a base grid with n0 cells and growth g0, sampled
// with n cells: coordinates from 0 to length, finest at 0.
std::vector<double> Sample(double length, double g0, int n0, int n) {
  std::vector<double> x(n + 1);
  for (int i = 0; i <= n; ++i) {
    const double xi = static_cast<double>(i) / n;
    x[i] = g0 == 1.0 ? length * xi : length * (std::pow(g0, n0 * xi) - 1.0) / (std::pow(g0, n0) - 1.0);
  }
  x[n] = length;
  return x;
}

// Friction velocity estimate at x for the wall-normal spacing.
double FrictionVelocityEstimate(const FlatPlateOptions& o, double x_over_l) {
  const double cf = PrandtlSchlichtingLocal(o.reynolds * x_over_l);
  return o.speed * std::sqrt(0.5 * cf);
}

}  // namespace

Mesh MakeFlatPlateMesh(const FlatPlateOptions& o) {
  o.Validate();
  const double L = o.length;
  const double nu = o.speed * L / o.reynolds;
  const int nx = std::max(4, static_cast<int>(std::lround(o.cells_x * o.refinement)));
  const int ny = std::max(4, static_cast<int>(std::lround(o.cells_y * o.refinement)));
  const int nu_cells = std::max(2, static_cast<int>(std::lround(o.cells_upstream * o.refinement)));
  // Along the plate.
  const double dx_le = L / o.cells_x / o.leading_edge_ratio;
  const double gx = GrowthRatio(L, dx_le, o.cells_x);
  const std::vector<double> xp = Sample(L, gx, o.cells_x, nx);
  // Run-up, mirrored, matching the leading-edge size of the base grid.
  const double gu = GrowthRatio(o.upstream * L, dx_le, o.cells_upstream);
  const std::vector<double> xu = Sample(o.upstream * L, gu, o.cells_upstream, nu_cells);
  std::vector<double> x;
  for (int i = nu_cells; i > 0; --i) x.push_back(-xu[i]);
  x.insert(x.end(), xp.begin(), xp.end());
  // Wall-normal: the first cell centre at the target y+ at x = L/2.
  const double dy1 = 2.0 * o.y_plus * nu / FrictionVelocityEstimate(o, 0.5);
  const double gy = GrowthRatio(o.height * L, dy1, o.cells_y);
  const std::vector<double> y = Sample(o.height * L, gy, o.cells_y, ny);
  const double dz = 0.01 * L;

  const int ncx = static_cast<int>(x.size()) - 1;
  auto pid = [&](int i, int j, int k) { return i + (ncx + 1) * (j + (ny + 1) * k); };
  auto cid = [&](int i, int j) { return i + ncx * j; };
  std::vector<Vector3> points((ncx + 1) * (ny + 1) * 2);
  for (int k = 0; k < 2; ++k) {
    for (int j = 0; j <= ny; ++j) {
      for (int i = 0; i <= ncx; ++i) points[pid(i, j, k)] = Vector3(x[i], y[j], k * dz);
    }
  }
  MeshBuilder b;
  const int inlet = b.AddPatch("inlet", PatchKind::kPatch);
  const int outlet = b.AddPatch("outlet", PatchKind::kPatch);
  const int top = b.AddPatch("top", PatchKind::kPatch);
  const int runup = b.AddPatch("runup", PatchKind::kSymmetry);
  const int plate = b.AddPatch("plate", PatchKind::kWall);
  const int front = b.AddPatch("front", PatchKind::kEmpty);
  const int back = b.AddPatch("back", PatchKind::kEmpty);
  for (int j = 0; j < ny; ++j) {
    for (int i = 0; i < ncx; ++i) {
      const int c = cid(i, j);
      // +x face at i + 1.
      std::vector<int> fx = {pid(i + 1, j, 0), pid(i + 1, j + 1, 0), pid(i + 1, j + 1, 1), pid(i + 1, j, 1)};
      if (i + 1 < ncx) {
        b.AddInternalFace(c, cid(i + 1, j), fx);
      } else {
        b.AddBoundaryFace(outlet, c, fx);
      }
      if (i == 0) b.AddBoundaryFace(inlet, c, {pid(0, j, 0), pid(0, j, 1), pid(0, j + 1, 1), pid(0, j + 1, 0)});
      // +y face at j + 1.
      std::vector<int> fy = {pid(i, j + 1, 0), pid(i, j + 1, 1), pid(i + 1, j + 1, 1), pid(i + 1, j + 1, 0)};
      if (j + 1 < ny) {
        b.AddInternalFace(c, cid(i, j + 1), fy);
      } else {
        b.AddBoundaryFace(top, c, fy);
      }
      if (j == 0) {
        b.AddBoundaryFace(i < nu_cells ? runup : plate, c,
                          {pid(i, 0, 0), pid(i + 1, 0, 0), pid(i + 1, 0, 1), pid(i, 0, 1)});
      }
      b.AddBoundaryFace(front, c, {pid(i, j, 0), pid(i, j + 1, 0), pid(i + 1, j + 1, 0), pid(i + 1, j, 0)});
      b.AddBoundaryFace(back, c, {pid(i, j, 1), pid(i + 1, j, 1), pid(i + 1, j + 1, 1), pid(i, j + 1, 1)});
    }
  }
  return std::move(b).Build(std::move(points), fmt::format("flat plate Re_L = {:.3g}", o.reynolds));
}

FlatPlateResult RunFlatPlate(const FlatPlateOptions& o, const FlatPlateRunOptions& run) {
  const Mesh mesh = MakeFlatPlateMesh(o);
  const double U = o.speed, L = o.length;
  const double nu = U * L / o.reynolds;
  const Vector3 U_inf(U, 0, 0);
  std::vector<std::unique_ptr<BoundaryCondition<Vector3>>> ub;
  std::vector<std::unique_ptr<BoundaryCondition<double>>> pb;
  for (const Patch& patch : mesh.patches()) {
    if (patch.name == "inlet") {
      ub.push_back(std::make_unique<FixedValue<Vector3>>(U_inf));
      pb.push_back(std::make_unique<ZeroGradient<double>>());
    } else if (patch.name == "outlet" || patch.name == "top") {
      if (patch.name == "outlet") {
        ub.push_back(std::make_unique<ZeroGradient<Vector3>>());
      } else {
        ub.push_back(std::make_unique<InletOutlet<Vector3>>(U_inf));
      }
      pb.push_back(std::make_unique<FixedValue<double>>(0.0));
    } else if (patch.name == "runup") {
      ub.push_back(std::make_unique<Slip>());
      pb.push_back(std::make_unique<ZeroGradient<double>>());
    } else if (patch.name == "plate") {
      ub.push_back(std::make_unique<FixedValue<Vector3>>(Vector3(0, 0, 0), PatchRole::kWall));
      pb.push_back(std::make_unique<ZeroGradient<double>>());
    } else {
      ub.push_back(std::make_unique<Empty<Vector3>>());
      pb.push_back(std::make_unique<Empty<double>>());
    }
  }
  auto Uf = std::make_unique<VectorField>("U", mesh, std::move(ub));
  for (auto& v : Uf->values()) v = U_inf;
  auto pf = std::make_unique<ScalarField>("p", mesh, std::move(pb));
  const std::vector<TurbulencePatchRole> roles = TurbulencePatchRoles(*Uf, *pf);
  PhysicsOptions physics;
  physics.nu = nu;
  SchemeOptions schemes;
  schemes.convection = ConvectionScheme::kLinearUpwind;
  PimpleOptions pimple;
  pimple.n_outer = run.n_outer;
  pimple.n_correctors = 2;
  pimple.relax_U = pimple.relax_U_final = run.relax_U;
  pimple.relax_p = pimple.relax_p_final = run.relax_p;
  pimple.pressure_solver.amg.strong_threshold = 0.5;
  pimple.pressure_solver.relative_tolerance = 1e-4;
  pimple.pressure_final_relative_tolerance = 1e-6;
  pimple.momentum_solver.relative_tolerance = 1e-6;
  PimpleSolver solver(mesh, physics, schemes, pimple, std::move(Uf), std::move(pf));
  KOmegaSstOptions sst;
  sst.inflow = run.inflow;
  sst.inflow.reference_speed = U;
  sst.relax = run.turbulence_relax;
  sst.wall_omega = run.wall_omega;
  if (!run.laminar) {
    auto model = std::make_unique<KOmegaSst>(mesh, nu, sst, roles);
    if (run.initial_viscosity_ratio > 0.0) {
      for (double& w : model->omega().values()) w = sst.inflow.k(nu) / (run.initial_viscosity_ratio * nu);
    }
    solver.SetTurbulence(std::move(model));
  }

  const int plate = mesh.FindPatch("plate");
  const Patch& pp = mesh.patches()[plate];
  const int ni = mesh.n_internal_faces();
  const double span = [&] {
    double a = 0.0;
    for (int f = pp.start; f < pp.start + pp.size; ++f) a += mesh.face_area_magnitudes()[f];
    return a / L;
  }();
  // Kinematic wall shear stress (x component) on plate face f: the model's
  // value, or nu (u_P - u_w) / y when laminar.
  auto tau_x = [&](int f) {
    if (solver.turbulence()) return solver.turbulence()->wall_shear_stress()[f - ni][0];
    const int c = mesh.owner()[f];
    return nu * solver.U()[c][0] / std::abs(mesh.cell_centres()[c][1] - mesh.face_centres()[f][1]);
  };
  auto friction = [&]() {
    double fx = 0.0;
    for (int f = pp.start; f < pp.start + pp.size; ++f) fx += tau_x(f) * mesh.face_area_magnitudes()[f];
    return fx / (0.5 * U * U * L * span);
  };
  // The plate face whose centre is nearest to x.
  auto nearest_face = [&](double x) {
    int face = pp.start;
    for (int f = pp.start; f < pp.start + pp.size; ++f) {
      if (std::abs(mesh.face_centres()[f][0] - x) < std::abs(mesh.face_centres()[face][0] - x)) face = f;
    }
    return face;
  };
  // Pseudo time step from the plate cell at x = L/2.
  const double dx_cell = mesh.face_area_magnitudes()[nearest_face(0.5 * L)] / span;
  const double dt = run.courant * dx_cell / U;
  const int steps_per_flow = std::max(1, static_cast<int>(std::ceil(L / (U * dt))));

  FlatPlateResult r;
  r.cells = mesh.n_cells();
  double area = 0.0;
  for (int c = 0; c < mesh.n_cells(); ++c) area += mesh.cell_volumes()[c];
  r.h = std::sqrt(area / span / mesh.n_cells());
  std::vector<double> history;
  r.dt = dt;
  const auto start = std::chrono::steady_clock::now();
  const int step_limit = run.fixed_steps > 0 ? run.fixed_steps : run.max_steps;
  for (int step = 0; step < step_limit; ++step) {
    const auto step_start = std::chrono::steady_clock::now();
    const std::clock_t step_cpu_start = std::clock();
    const StepSummary s = solver.Step(dt);
    if (!s.finite) throw ModelError(fmt::format("flat plate Re_L = {:.3g}: diverged at step {}", o.reynolds, s.step));
    if (solver.turbulence()) {
      r.bounded_cells += solver.turbulence_summary().bounded_k + solver.turbulence_summary().bounded_omega;
    }
    history.push_back(friction());
    r.max_residual = std::max(s.initial_residual_U, s.initial_residual_p);
    if (solver.turbulence()) {
      const TurbulenceSummary& t = solver.turbulence_summary();
      r.max_residual = std::max({r.max_residual, t.initial_residual_k, t.initial_residual_omega});
    }
    r.step_seconds.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - step_start).count());
    r.step_cpu_seconds.push_back(static_cast<double>(std::clock() - step_cpu_start) / CLOCKS_PER_SEC);
    r.steps = step + 1;
    if (run.fixed_steps <= 0 && static_cast<int>(history.size()) > run.min_flow_throughs * steps_per_flow) {
      const double now = history.back();
      const double before = history[history.size() - 1 - steps_per_flow];
      r.C_F_change = std::abs(now - before) / std::abs(now);
      if (r.C_F_change < run.tolerance && r.max_residual < run.residual_tolerance) {
        r.converged = true;
        break;
      }
    }
    if (run.progress && step % 50 == 0) {
      spdlog::info("flat plate Re {:.3g}: step {} C_F {:.6e} Co {:.3g} res U {:.2e} p {:.2e} k {:.2e} omega {:.2e}",
                   o.reynolds, s.step, history.back(), s.courant_max, s.initial_residual_U, s.initial_residual_p,
                   solver.turbulence_summary().initial_residual_k, solver.turbulence_summary().initial_residual_omega);
    }
  }
  r.seconds_per_step =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() / std::max(r.steps, 1);
  r.C_F = history.empty() ? 0.0 : history.back();
  if (solver.turbulence()) {
    for (const WallPatchStats& w : solver.turbulence()->WallStats()) {
      if (w.patch == "plate") r.wall = w;
    }
  }
  for (int f = pp.start; f < pp.start + pp.size; ++f) {
    r.x.push_back(mesh.face_centres()[f][0]);
    r.cf.push_back(tau_x(f) / (0.5 * U * U));
  }
  // Profile: the column of cells above the plate face nearest to 0.8 L.
  const int face = nearest_face(0.8 * L);
  r.x_profile = mesh.face_centres()[face][0];
  const double u_tau = std::sqrt(std::abs(tau_x(face)));
  const double x0 = r.x_profile;
  std::vector<std::pair<double, int>> column;
  for (int c = 0; c < mesh.n_cells(); ++c) {
    const Vector3& xc = mesh.cell_centres()[c];
    const double half = 0.5 * mesh.face_area_magnitudes()[face] / span;
    if (std::abs(xc[0] - x0) < 0.5 * half) column.emplace_back(xc[1], c);
  }
  std::sort(column.begin(), column.end());
  const auto* model = dynamic_cast<const KOmegaSst*>(solver.turbulence());
  for (const auto& [yc, c] : column) {
    r.y_plus.push_back(yc * u_tau / nu);
    r.u_plus.push_back(solver.U()[c][0] / u_tau);
    if (model) {
      r.nut_plus.push_back(model->nu_t()[c] / nu);
      r.k_plus.push_back(model->k()[c] / (u_tau * u_tau));
      r.f1.push_back(model->F1()[c]);
      r.nut_unlimited_plus.push_back(model->k()[c] / model->omega()[c] / nu);
      r.omega_plus.push_back(model->omega()[c] * nu / (u_tau * u_tau));
      r.strain_plus.push_back(std::sqrt(model->strain_rate_squared()[c]) * nu / (u_tau * u_tau));
    }
  }
  return r;
}

}  // namespace kelvin::cfd
