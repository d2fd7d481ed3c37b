// kelvin simulate: IMO maneuvers of an MMG ship model in fast time.
#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "simulator/mmg/derivative_set.h"
#include "data/schema/errors.h"
#include "simulator/maneuvers/identified_range.h"
#include "simulator/maneuvers/runner.h"
#include "simulator/mmg/surrogate.h"
#include "tools/kelvin/commands.h"

namespace kelvin::cli {

namespace {

struct SimulateArgs {
  std::string ship_file;
  std::vector<std::string> maneuvers{"turning:35:stbd"};
  std::string integrator = "cvode";
  double step = 0.0;
  double speed = 0.0;
  std::string scale = "model";
  bool friction_correction = false;
  double output_interval = 0.0;
  std::string output_dir = "results/simulate";
  std::string derivatives;
};

std::string FileStem(const std::string& ship, const std::string& maneuver) {
  std::string s = ship + "_" + maneuver;
  for (char& c : s) {
    if (c == ':' || c == '/' || c == ' ') c = '_';
  }
  return s;
}

void RunSimulate(const SimulateArgs& a) {
  sim::ShipParameters ship = sim::LoadShip(a.ship_file);
  std::optional<sim::DerivativeSet> set;
  if (!a.derivatives.empty()) set = sim::LoadDerivativeSet(a.derivatives);
  ship = sim::SurrogateShip(std::move(ship), a.ship_file, set ? &*set : nullptr);
  if (set) spdlog::info("hull derivatives and added masses from {} ({})", a.derivatives, set->name);
  if (a.scale == "full") {
    ship = sim::ScaleShip(ship, ship.scale, a.friction_correction);
    ship.scale_name = "full scale";
  } else if (a.scale != "model") {
    throw ArgumentError(fmt::format("--scale '{}': expected 'model' or 'full'", a.scale));
  }
  sim::RunOptions opt;
  if (a.integrator == "cvode") {
    opt.integrator.method = sim::SimulatorOptions::Method::kAdaptive;
  } else if (a.integrator == "fixed") {
    opt.integrator.method = sim::SimulatorOptions::Method::kFixedStep;
    // Default step: Lpp / U0 / 200, about 0.03 s at model scale.
    const double U0 = a.speed > 0 ? a.speed : ship.approach_speed;
    opt.integrator.fixed_step = a.step > 0 ? a.step : ship.principal.Lpp / std::max(U0, 1e-3) / 200.0;
  } else {
    throw ArgumentError(fmt::format("--integrator '{}': expected 'cvode' or 'fixed'", a.integrator));
  }
  opt.approach_speed = a.speed;
  opt.output_interval = a.output_interval;
  std::vector<sim::ManeuverSpec> specs;
  for (const auto& m : a.maneuvers) specs.push_back(sim::ManeuverSpec::Parse(m));

  const sim::MmgModel<double> model(ship);
  for (const auto& spec : specs) {
    Progress progress(100.0, {.label = spec.ToString(), .unit = "%"});
    const sim::ManeuverResult res = sim::RunManeuver(model, spec, opt, &progress);
    const std::filesystem::path out =
        std::filesystem::path(a.output_dir) / (FileStem(ship.name, spec.ToString()) + ".h5");
    sim::WriteManeuverResult(res, out, a.integrator);
    fmt::print("{}", sim::FormatManeuverReport(res));
    if (set) {
      const std::string w = sim::ExtrapolationWarning(*set, res.trajectory, res.Lpp, spec.ToString());
      if (!w.empty()) fmt::print("  {}\n", w);
    }
    fmt::print("  written: {}\n", out.string());
  }
}

}  // namespace

Command AddSimulateCommand(CLI::App& app) {
  auto args = std::make_shared<SimulateArgs>();
  CLI::App* cmd = app.add_subcommand("simulate", "Run IMO maneuvers of an MMG ship model in fast time");
  cmd->add_option("ship", args->ship_file, "Ship file (data/ships/<ship>.yaml)")->required()->check(CLI::ExistingFile);
  cmd->add_option("-m,--maneuver", args->maneuvers,
                  "turning:<deg>:stbd|port, zigzag:<deg>/<deg>:stbd|port, spiral:<max>:<step>, stopping "
                  "(repeatable)")
      ->capture_default_str();
  cmd->add_option("--integrator", args->integrator, "cvode (adaptive) or fixed (ERK, fixed step)")
      ->capture_default_str();
  cmd->add_option("--step", args->step, "Fixed step in s (default Lpp/U0/200)");
  cmd->add_option("--speed", args->speed, "Approach speed in m/s (default: the ship file's)");
  cmd->add_option("--scale", args->scale, "model or full (Froude-scaled to the ship's full scale)")
      ->capture_default_str();
  cmd->add_flag("--friction-correction", args->friction_correction,
                "Correct R0' by the ITTC-1957 friction line when scaling");
  cmd->add_option("--output-interval", args->output_interval, "Seconds between recorded samples");
  cmd->add_option("--derivatives", args->derivatives, "Derivative set replacing the ship file's hull section")
      ->check(CLI::ExistingFile);
  cmd->add_option("-o,--output", args->output_dir, "Output directory")->capture_default_str();
  return {cmd, [args] { RunSimulate(*args); }};
}

}  // namespace kelvin::cli
