// Simulator benchmark (issue: simulator). Measures, in one run:
//  1. fast time: simulated seconds per wall second of a full-scale KVLCC2
//     35 deg turning circle with CVODE (target >= 100,000x real time);
//  2. real time: cost per fixed step of the ERKStep integrator (target
//     < 5 us), against a plain hand-written classical RK4 loop on the same
//     model as the peer (the ratio shows what SUNDIALS' stepping costs).
// Prints a Markdown section; with --write FILE it replaces the section
// between the simulator markers in FILE (BENCHMARKS.md).
#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cstring>
#include <string>
#include <vector>

#include "simulator/maneuvers/runner.h"
#include "tools/bench/markdown_section.h"

namespace {

using Clock = std::chrono::steady_clock;
using kelvin::sim::StateVector;

double Median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

}  // namespace

int main(int argc, char** argv) {
  std::string write_to;
  std::string ship_file = "data/ships/kvlcc2.yaml";
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--write") && i + 1 < argc) write_to = argv[++i];
    else if (!std::strcmp(argv[i], "--ship") && i + 1 < argc) ship_file = argv[++i];
  }
  using namespace kelvin::sim;
  const ShipParameters model_ship = LoadShip(ship_file);
  const ShipParameters full = ScaleShip(model_ship, model_ship.scale, false);
  const MmgModel<double> model(full);
  const ManeuverSpec spec = ManeuverSpec::Parse("turning:35:stbd");

  // 1. Fast time with CVODE (default tolerances, output every 1% of L/U).
  RunOptions opt;
  std::vector<double> factors;
  double simulated = 0;
  long steps = 0;
  for (int rep = 0; rep < 20; ++rep) {
    const auto t0 = Clock::now();
    const ManeuverResult r = RunManeuver(model, spec, opt);
    const double wall = std::chrono::duration<double>(Clock::now() - t0).count();
    simulated = r.trajectory.samples().back().t;
    steps = r.integrator_steps;
    factors.push_back(simulated / wall);
  }
  const double factor = Median(factors);

  // 2. Fixed-step cost: ERKStep vs a plain RK4 loop, same model, same step.
  const double h = 0.5;  // s at full scale (L/U0/80)
  const long n_steps = 200000;
  SimulatorOptions fixed;
  fixed.method = SimulatorOptions::Method::kFixedStep;
  fixed.fixed_step = h;
  const double U0 = full.approach_speed, n0 = SelfPropulsionRps(model, U0);
  std::vector<double> erk_us, rk4_us;
  StateVector erk_end{}, rk4_end{};
  for (int rep = 0; rep < 5; ++rep) {
    Simulator sim(model, fixed);
    sim.Reset(0.0, {0, 0, 0, U0, 0, 0}, 35.0 * M_PI / 180.0, n0);
    const auto t0 = Clock::now();
    for (long i = 0; i < n_steps; ++i) sim.Step();
    erk_us.push_back(std::chrono::duration<double, std::micro>(Clock::now() - t0).count() / n_steps);
    erk_end = sim.state();

    double y[6] = {0, 0, 0, U0, 0, 0}, k1[6], k2[6], k3[6], k4[6], tmp[6];
    const double delta = 35.0 * M_PI / 180.0;
    const auto t1 = Clock::now();
    for (long i = 0; i < n_steps; ++i) {
      model.Derivative(y, delta, n0, k1);
      for (int j = 0; j < 6; ++j) tmp[j] = y[j] + 0.5 * h * k1[j];
      model.Derivative(tmp, delta, n0, k2);
      for (int j = 0; j < 6; ++j) tmp[j] = y[j] + 0.5 * h * k2[j];
      model.Derivative(tmp, delta, n0, k3);
      for (int j = 0; j < 6; ++j) tmp[j] = y[j] + h * k3[j];
      model.Derivative(tmp, delta, n0, k4);
      for (int j = 0; j < 6; ++j) y[j] += h / 6 * (k1[j] + 2 * k2[j] + 2 * k3[j] + k4[j]);
    }
    rk4_us.push_back(std::chrono::duration<double, std::micro>(Clock::now() - t1).count() / n_steps);
    for (int j = 0; j < 6; ++j) rk4_end[j] = y[j];
  }
  const double erk = Median(erk_us), rk4 = Median(rk4_us);

  std::string md;
  md += "## Simulator (MMG 3DoF, SUNDIALS)\n\n";
  md += "Produced by `build/release/tools/bench/simulator_bench --write BENCHMARKS.md` (one run, one core).\n\n";
  md += "| measure | value | target |\n| --- | --- | --- |\n";
  md += fmt::format("| full-scale KVLCC2 35 deg turning circle, CVODE: simulated s per wall s (median of 20) | "
                    "{:.3g}x real time ({:.0f} s simulated, {} steps) | >= 100,000x |\n",
                    factor, simulated, steps);
  md += fmt::format("| fixed-step ERKStep (Zonneveld 4th order, 5 stages): cost per step (median of 5 x {}) | "
                    "{:.3f} us | < 5 us |\n",
                    n_steps, erk);
  md += fmt::format("| peer: plain classical RK4 loop (4 stages) on the same model | {:.3f} us per step | - |\n", rk4);
  md += fmt::format("| ERKStep / plain RK4, per right-hand-side evaluation (5 vs 4 stages) | {:.2f} | - |\n\n",
                    (erk / 5) / (rk4 / 4));
  fmt::print("{}", md);
  (void)erk_end;
  (void)rk4_end;
  if (!write_to.empty()) kelvin::bench::ReplaceMarkdownSection(write_to, "simulator", md);
  return 0;
}
