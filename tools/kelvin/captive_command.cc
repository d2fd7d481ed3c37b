// kelvin captive: runs a captive test campaign (static drift, pure sway, pure
// yaw, yaw with drift) and writes the force histories in the captive HDF5
// schema that `kelvin identify` reads.
#include <fmt/format.h>

#include <memory>
#include <string>

#include "identification/campaign_file.h"
#include "identification/captive_io.h"
#include "tools/kelvin/commands.h"

namespace kelvin::cli {

namespace {

struct CaptiveArgs {
  std::string campaign_file;
  std::string output;
};

void RunCaptive(const CaptiveArgs& a) {
  const ident::CampaignFile file = ident::LoadCampaignFile(a.campaign_file);
  const ident::CaptiveCampaign campaign = ident::RunCampaign(file);
  const std::string out = a.output.empty() ? "results/" + file.name + ".h5" : a.output;
  ident::WriteCampaignH5(campaign, out);
  fmt::print("campaign '{}' ({} runs, solver mmg: virtual captive tests of {})\n", file.name, campaign.runs.size(),
             file.ship_file.string());
  for (const auto& run : campaign.runs) {
    fmt::print("  {:<24} {:<16} {} samples\n", run.name, ident::MotionKindName(run.motion.kind), run.time.size());
  }
  fmt::print("  written: {}\n", out);
}

}  // namespace

Command AddCaptiveCommand(CLI::App& app) {
  auto args = std::make_shared<CaptiveArgs>();
  CLI::App* cmd = app.add_subcommand("captive", "Run a captive test campaign and write its force histories");
  cmd->add_option("campaign", args->campaign_file, "Campaign file (data/cases/<campaign>.yaml)")
      ->required()
      ->check(CLI::ExistingFile);
  cmd->add_option("-o,--output", args->output, "Campaign HDF5 (default results/<name>.h5)");
  return {cmd, [args] { RunCaptive(*args); }};
}

}  // namespace kelvin::cli
