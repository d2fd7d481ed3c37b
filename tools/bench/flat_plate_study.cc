// One zero-pressure-gradient flat-plate run with k-omega SST (or laminar on
// the same mesh), printed with the reference friction lines: the driver for
// grid and y+ studies of cfd/verification/flat_plate.h and the cost
// comparison of the SST benchmark (seconds per step, laminar vs SST).
//
//   flat_plate_study --re 1e7 --y-plus 50 --cells-y 60 --cells-x 120 [--laminar] [--profile] [--cf]
//                    [--steps N [--timing-skip K]] [--write-poly-mesh DIR]
//
// --steps N runs exactly N steps (no convergence stop) and prints a
// "timing:" line with the mean wall time of the steps after the first K;
// --write-poly-mesh DIR writes the mesh as DIR/constant/polyMesh (for the
// OpenFOAM side of tools/bench/sst_cost_bench.py) before the run.
#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <string>

#include "cfd/grid/mesh_writer.h"
#include "cfd/verification/flat_plate.h"
#include "data/reference/friction_lines.h"

int main(int argc, char** argv) {
  using namespace kelvin::cfd;
  CLI::App app("flat-plate run with k-omega SST");
  FlatPlateOptions o;
  FlatPlateRunOptions r;
  bool profile = false, cf = false;
  int timing_skip = 3;
  std::string poly_mesh_dir;
  app.add_option("--re", o.reynolds, "plate Reynolds number U L / nu")->check(CLI::PositiveNumber);
  app.add_option("--y-plus", o.y_plus, "target first-cell-centre y+")->check(CLI::PositiveNumber);
  app.add_option("--cells-y", o.cells_y, "wall-normal cells")->check(CLI::Range(4, 100000));
  app.add_option("--cells-x", o.cells_x, "cells along the plate")->check(CLI::Range(4, 100000));
  app.add_option("--refinement", o.refinement, "systematic refinement factor")->check(CLI::PositiveNumber);
  app.add_option("--leading-edge-ratio", o.leading_edge_ratio, "mean / leading-edge cell size")->check(CLI::Range(1.0, 1e3));
  app.add_option("--courant", r.courant, "pseudo-time Courant number at L/2")->check(CLI::PositiveNumber);
  app.add_option("--max-steps", r.max_steps, "step limit")->check(CLI::PositiveNumber);
  app.add_option("--turbulence-relax", r.turbulence_relax, "implicit relaxation of k and omega (1: none)")
      ->check(CLI::Range(0.05, 1.0));
  app.add_option("--viscosity-ratio", r.inflow.viscosity_ratio, "inflow nu_t / nu")->check(CLI::PositiveNumber);
  app.add_option("--intensity", r.inflow.intensity, "inflow turbulence intensity")->check(CLI::Range(1e-6, 0.5));
  app.add_option("--initial-viscosity-ratio", r.initial_viscosity_ratio, "initial nu_t / nu (turbulent start)")
      ->check(CLI::NonNegativeNumber);
  app.add_option("--steps", r.fixed_steps, "run exactly N steps, no convergence stop (benchmarks)")
      ->check(CLI::PositiveNumber);
  app.add_option("--timing-skip", timing_skip, "start-up steps excluded from the timing line (with --steps)")
      ->check(CLI::NonNegativeNumber);
  app.add_option("--write-poly-mesh", poly_mesh_dir, "write the mesh to DIR/constant/polyMesh before the run");
  const std::map<std::string, KOmegaSstOptions::WallOmega> wall_omega{
      {"sublayer", KOmegaSstOptions::WallOmega::kDiscreteSublayer},
      {"point", KOmegaSstOptions::WallOmega::kPointValue}};
  app.add_option("--wall-omega", r.wall_omega,
                 "wall cells' viscous omega: sublayer (consistent with the discrete equation) or point (OpenFOAM's)")
      ->transform(CLI::CheckedTransformer(wall_omega, CLI::ignore_case));
  app.add_flag("--laminar", r.laminar, "no turbulence model (cost baseline)");
  app.add_flag("--progress", r.progress, "log every 50 steps");
  app.add_flag("--profile", profile, "print the u+ profile at 0.8 L");
  app.add_flag("--cf", cf, "print local c_f along the plate");
  CLI11_PARSE(app, argc, argv);
  try {
    if (!poly_mesh_dir.empty()) WritePolyMesh(MakeFlatPlateMesh(o), poly_mesh_dir);
    const FlatPlateResult res = RunFlatPlate(o, r);
    const double ittc = kelvin::data::Ittc57FrictionCoefficient(o.reynolds);
    const double sch = SchoenherrFrictionLine(o.reynolds);
    fmt::print(
        "Re_L {:.3g} y+ target {:g}: C_F {:.5e} (ITTC-57 {:+.2f}%, Schoenherr {:+.2f}%), converged {} after {} steps "
        "(change {:.1e}, largest residual {:.1e}), {} cells, h {:.4g} m, {:.4f} s/step, plate y+ min/mean/max {:.1f}/{:.1f}/{:.1f}, bounded {}\n",
        o.reynolds, o.y_plus, res.C_F, 100 * (res.C_F / ittc - 1), 100 * (res.C_F / sch - 1), res.converged, res.steps,
        res.C_F_change, res.max_residual, res.cells, res.h, res.seconds_per_step, res.wall.y_plus_min, res.wall.y_plus_mean,
        res.wall.y_plus_max, res.bounded_cells);
    if (r.fixed_steps > 0) {
      const std::size_t skip = std::min<std::size_t>(timing_skip, res.step_seconds.size() - 1);
      double wall = 0.0, cpu = 0.0;
      for (std::size_t i = skip; i < res.step_seconds.size(); ++i) {
        wall += res.step_seconds[i];
        cpu += res.step_cpu_seconds[i];
      }
      const double n = static_cast<double>(res.step_seconds.size() - skip);
      fmt::print("timing: {} cells, dt {:.9g} s, {} steps, first {} excluded, wall {:.6f} s/step, cpu {:.6f} s/step\n",
                 res.cells, res.dt, res.steps, skip, wall / n, cpu / n);
    }
    if (profile) {
      for (std::size_t i = 0; i < res.y_plus.size() && res.y_plus[i] < 3000; ++i) {
        const bool sst = !res.nut_plus.empty();
        fmt::print("  y+ {:9.2f} u+ {:7.3f} log law (B 5.0-5.2) {:7.3f}-{:7.3f}  nu_t/nu {:9.2f}", res.y_plus[i],
                   res.u_plus[i], std::log(res.y_plus[i]) / 0.41 + 5.0, std::log(res.y_plus[i]) / 0.41 + 5.2,
                   sst ? res.nut_plus[i] : 0.0);
        if (sst) {
          // nu_t / (kappa u_tau y) is 1 in a log layer with kappa = 0.41.
          fmt::print("  nu_t/(0.41 y+ nu) {:6.3f}  (k/omega)/nu {:9.2f}  F1 {:6.4f}", res.nut_plus[i] / (0.41 * res.y_plus[i]),
                     res.nut_unlimited_plus[i], res.f1[i]);
          // Log-layer values of the k-omega model are k+ = 1/sqrt(beta*),
          // omega+ y+ = 1/(sqrt(beta*) kappa) and S+ y+ = 1/kappa.
          fmt::print("  k+ {:6.3f} omega+ y+ {:6.3f} S+ y+ {:6.3f}", res.k_plus[i], res.omega_plus[i] * res.y_plus[i],
                     res.strain_plus[i] * res.y_plus[i]);
        }
        fmt::print("\n");
      }
    }
    if (cf) {
      const std::size_t stride = std::max<std::size_t>(1, res.x.size() / 12);
      for (std::size_t i = 0; i < res.x.size(); i += stride) {
        fmt::print("  x/L {:.4f} c_f {:.4e} Prandtl-Schlichting {:.4e}\n", res.x[i] / o.length, res.cf[i],
                   PrandtlSchlichtingLocal(o.reynolds * res.x[i] / o.length));
      }
    }
  } catch (const std::exception& e) {
    fmt::print(stderr, "flat_plate_study: {}\n", e.what());
    return 1;
  }
  return 0;
}
