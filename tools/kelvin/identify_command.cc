// kelvin identify: MMG hull derivatives and added masses from captive runs
// (a campaign HDF5 file, or CSV runs with a ship file), with standard errors,
// identifiability warnings and a PMM cross-check.
#include <fmt/format.h>

#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "data/schema/appendage_runs.h"
#include "data/schema/captive_io.h"
#include "data/schema/errors.h"
#include "identification/derivative_set_io.h"
#include "identification/interaction_fit.h"
#include "identification/joint_fit.h"
#include "identification/pmm_analysis.h"
#include "identification/virtual_captive.h"
#include "simulator/mmg/ship_parameters.h"
#include "tools/kelvin/commands.h"

namespace kelvin::cli {

namespace {

struct IdentifyArgs {
  std::vector<std::string> inputs;
  std::string output;
  std::string h5_output;
  std::string ship_file;
  std::string loss = "none";
  double loss_scale = 3.0;
  double min_noise = 0.01;
  double max_relative_std_error = 0.25;
  double min_joint_excitation = 0.01;
  std::vector<std::string> priors;
  std::vector<std::string> fixed;
  std::vector<std::string> bounds;
  bool keep_unidentifiable = false;
};

// "NAME=VALUE" -> (NAME, VALUE); throws ArgumentError naming the option.
std::pair<std::string, std::string> SplitAssignment(const std::string& option,
                                                    const std::string& text,
                                                    const std::string& form) {
  const auto eq = text.find('=');
  if (eq == std::string::npos || eq == 0) {
    throw ArgumentError(fmt::format("{} '{}': expected {}", option, text, form));
  }
  return {text.substr(0, eq), text.substr(eq + 1)};
}

double ParseDouble(const std::string& option, const std::string& text) {
  std::size_t used = 0;
  double v = 0;
  try {
    v = std::stod(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used == 0 || used != text.size())
    throw ArgumentError(fmt::format("{}: '{}' is not a number", option, text));
  return v;
}

// The interaction coefficients from the campaign's runs with the propeller
// and rudder (a CFD campaign's tests.appendages), if it has any.
std::optional<ident::InteractionFitResult> FitAppendages(const std::string& source,
                                                         const data::CaptiveCampaign& campaign) {
  if (!data::HasAppendageRuns(source)) return std::nullopt;
  const data::AppendageCampaign appendages = data::ReadAppendageRuns(source);
  const sim::ShipParameters ship = sim::LoadShip(appendages.geometry.ship_file);
  ident::InteractionFitOptions o;
  o.propeller = ship.propeller;
  o.rudder = ship.rudder;
  if (!appendages.runs.empty()) o.bare_X = ident::BareStraightX(campaign, appendages.runs.front().u);
  return ident::FitInteraction(appendages, o, source);
}

void PrintInteraction(const ident::InteractionFitResult& r) {
  fmt::print("interaction coefficients from the runs with propeller and rudder:\n");
  fmt::print("{:<14} {:>10} {:>10} {:>5} {:>11}  {}\n", "coefficient", "value", "ship file", "runs", "rms", "");
  for (const ident::InteractionCoefficient& k : r.coefficients) {
    if (k.identified) {
      fmt::print("{:<14} {:>10.4g} {:>10.4g} {:>5} {:>11.3g}  {}\n", k.name, k.value, k.ship, k.runs, k.rms, k.units);
    } else {
      fmt::print("{:<14} {:>10.4g} {:>10.4g}  (kept)\n", k.name, k.value, k.ship);
    }
  }
  for (const std::string& w : r.warnings) fmt::print("warning: {}\n", w);
}

void RunIdentify(const IdentifyArgs& a) {
  namespace fs = std::filesystem;
  ident::JointFitOptions options;
  if (a.loss == "huber") {
    options.loss = ident::JointFitOptions::Loss::kHuber;
  } else if (a.loss == "cauchy") {
    options.loss = ident::JointFitOptions::Loss::kCauchy;
  } else if (a.loss != "none") {
    throw ArgumentError(fmt::format("--loss '{}': expected 'none', 'huber' or 'cauchy'", a.loss));
  }
  options.loss_scale = a.loss_scale;
  options.min_noise_fraction = a.min_noise;
  options.max_relative_std_error = a.max_relative_std_error;
  options.min_joint_excitation = a.min_joint_excitation;
  options.fix_unidentifiable = !a.keep_unidentifiable;
  for (const std::string& p : a.priors) {
    const auto [name, rest] =
        SplitAssignment("--prior", p, "NAME=MEAN:SIGMA (e.g. Y_vvr=0.38:0.05)");
    const auto colon = rest.find(':');
    if (colon == std::string::npos) {
      throw ArgumentError(
          fmt::format("--prior '{}': expected NAME=MEAN:SIGMA (e.g. Y_vvr=0.38:0.05)", p));
    }
    options.priors[name] = {ParseDouble("--prior " + name, rest.substr(0, colon)),
                            ParseDouble("--prior " + name, rest.substr(colon + 1))};
  }
  for (const std::string& f : a.fixed) {
    const auto [name, value] = SplitAssignment("--fix", f, "NAME=VALUE (e.g. m_x_prime=0.022)");
    options.fixed[name] = ParseDouble("--fix " + name, value);
  }
  for (const std::string& b : a.bounds) {
    const auto [name, rest] =
        SplitAssignment("--bound", b, "NAME=LOWER:UPPER (e.g. m_x_prime=0:0.1)");
    const auto colon = rest.find(':');
    if (colon == std::string::npos) {
      throw ArgumentError(
          fmt::format("--bound '{}': expected NAME=LOWER:UPPER (e.g. m_x_prime=0:0.1)", b));
    }
    options.bounds[name] = {ParseDouble("--bound " + name, rest.substr(0, colon)),
                            ParseDouble("--bound " + name, rest.substr(colon + 1))};
  }
  // Option errors are argument errors: check before reading any data.
  options.Validate();

  data::CaptiveCampaign campaign;
  std::string source;
  bool any_csv = false, any_h5 = false;
  for (const std::string& in : a.inputs) {
    const std::string ext = fs::path(in).extension().string();
    if (ext == ".csv") {
      any_csv = true;
    } else if (ext == ".h5" || ext == ".hdf5") {
      any_h5 = true;
    } else {
      throw ArgumentError(fmt::format("input '{}': expected a campaign .h5 file or .csv runs", in));
    }
  }
  if (any_csv && any_h5)
    throw ArgumentError("inputs: give either one campaign .h5 file or .csv runs, not both");
  if (any_h5) {
    if (a.inputs.size() != 1) throw ArgumentError("inputs: give one campaign .h5 file");
    source = a.inputs.front();
    campaign = data::ReadCampaignH5(source);
  } else {
    if (a.ship_file.empty())
      throw ArgumentError("--ship is required with .csv runs (the ship data of the campaign)");
    campaign.ship = ident::CaptiveShipFrom(sim::LoadShip(a.ship_file));
    campaign.description = "CSV runs";
    for (const std::string& in : a.inputs) campaign.runs.push_back(data::ReadRunCsv(in));
    source = fmt::format("{}", fmt::join(a.inputs, ", "));
    data::ValidateCampaign(campaign, source);
  }

  const ident::PmmAnalysis pmm = ident::AnalyseCampaign(campaign, source);
  const ident::JointFitResult fit = ident::FitCampaign(campaign, options, source);
  const std::optional<ident::InteractionFitResult> interaction =
      any_h5 ? FitAppendages(source, campaign) : std::nullopt;
  const ident::IdentificationReport report{source, &campaign, &fit, &pmm, interaction ? &*interaction : nullptr};
  const fs::path yaml_path(a.output);
  const fs::path h5_path =
      a.h5_output.empty() ? fs::path(yaml_path).replace_extension(".h5") : fs::path(a.h5_output);
  if (h5_path == yaml_path)
    throw ArgumentError(fmt::format("--h5 '{}' is the YAML output", h5_path.string()));
  ident::WriteDerivativeH5(report, h5_path);
  ident::WriteDerivativeYaml(report, yaml_path);

  fmt::print("{} runs, {} residuals; solver: {}\n", campaign.runs.size(), fit.residuals,
             fit.converged ? "converged" : "NOT converged");
  fmt::print("{:<11} {:>12} {:>11}  {}\n", "coefficient", "value", "std error", "status");
  for (int i = 0; i < ident::kCoefficientCount; ++i) {
    fmt::print("{:<11} {:>12.6g} {:>11.3g}  {}\n", sim::HullCoefficients<double>::kNames[i],
               fit.coefficients[i], fit.std_error[i], ident::CoefficientStatusName(fit.status[i]));
  }
  for (std::size_t r = 0; r < pmm.runs.size(); ++r) {
    if (data::IsHarmonic(pmm.runs[r].kind)) continue;
    fmt::print("samples used, run {}: {}\n", pmm.runs[r].run,
               data::DescribeWindow(campaign.runs[r], pmm.runs[r].window.begin, pmm.runs[r].window.end));
  }
  for (const std::string& w : fit.warnings) fmt::print("warning: {}\n", w);
  if (interaction) PrintInteraction(*interaction);
  fmt::print("  written: {}\n  written: {}\n", yaml_path.string(), h5_path.string());
}

}  // namespace

Command AddIdentifyCommand(CLI::App& app) {
  auto args = std::make_shared<IdentifyArgs>();
  CLI::App* cmd = app.add_subcommand(
      "identify",
      "Fit MMG hull derivatives and added masses to captive runs (PMM analysis + joint Ceres fit)");
  cmd->add_option("inputs", args->inputs,
                  "Campaign HDF5 file, or CSV runs (data/schema/captive_schema.md)")
      ->required();
  cmd->add_option("-o,--output", args->output, "Derivative set (YAML, with standard errors)")
      ->required();
  cmd->add_option("--h5", args->h5_output,
                  "HDF5 output with the covariance and fitted forces (default: -o with .h5)");
  cmd->add_option("--ship", args->ship_file, "Ship file for CSV runs (data/ships/<ship>.yaml)");
  cmd->add_option("--loss", args->loss, "Robust loss: none, huber or cauchy")
      ->capture_default_str();
  cmd->add_option("--loss-scale", args->loss_scale,
                  "Robust loss scale in noise standard deviations")
      ->capture_default_str();
  cmd->add_option("--min-noise", args->min_noise,
                  "Noise floor per run and channel, fraction of the channel RMS")
      ->capture_default_str();
  cmd->add_option("--max-rel-std-error", args->max_relative_std_error,
                  "Flag a coefficient whose standard error exceeds this fraction of its value")
      ->capture_default_str();
  cmd->add_option("--min-joint-excitation", args->min_joint_excitation,
                  "Flag a cross term (e.g. Y_vrr) whose regressor reaches less than this fraction "
                  "of max|v'|^a max|r'|^b (0: off)")
      ->capture_default_str();
  cmd->add_option("--prior", args->priors, "Gaussian prior NAME=MEAN:SIGMA (repeatable)");
  cmd->add_option("--fix", args->fixed, "Hold a coefficient NAME=VALUE (repeatable)");
  cmd->add_option(
      "--bound", args->bounds,
      "Bounds NAME=LOWER:UPPER (repeatable; 'inf' allowed; added masses default to >= 0)");
  cmd->add_flag("--keep-unidentifiable", args->keep_unidentifiable,
                "Report flagged coefficients at their fitted values instead of dropping them");
  return {cmd, [args] { RunIdentify(*args); }};
}

}  // namespace kelvin::cli
