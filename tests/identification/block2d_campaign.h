// The coarse CFD captive campaign of the 2D block (data/cases/captive_cfd/
// block2d_campaign.yaml: 5 runs, 390 steps, seconds on one core) written into
// a scratch directory, with absolute paths to its ship and case and its run
// directories in <dir>/runs.
#pragma once

#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>

#include "tests/test_utilities/test_utilities.h"

namespace kelvin::testing {

inline std::filesystem::path CaptiveCfdDataDir() { return SourceDir() / "data/cases/captive_cfd"; }

// Writes <dir>/campaign.yaml; `extra_tests` (YAML lines of the tests:
// section) are added before its omega_prime, `extra_cfd` (lines of the cfd:
// section) before its jobs.
inline std::filesystem::path WriteBlock2dCampaign(const std::filesystem::path& dir,
                                                  const std::string& extra_tests = "",
                                                  const std::string& extra_cfd = "") {
  const std::filesystem::path data = CaptiveCfdDataDir();
  std::string text = ReadText(data / "block2d_campaign.yaml");
  auto replace = [&](const std::string& from, const std::string& to) {
    const auto at = text.find(from);
    if (at == std::string::npos)
      throw std::logic_error("block2d_campaign.yaml has no '" + from + "'");
    text.replace(at, from.size(), to);
  };
  replace("ship: block2d_ship.yaml", "ship: " + (data / "block2d_ship.yaml").string());
  replace("case: block2d_case.yaml", "case: " + (data / "block2d_case.yaml").string());
  replace("directory: ../results/block2d_cfd", "directory: " + (dir / "runs").string());
  if (!extra_tests.empty()) replace("  omega_prime:", extra_tests + "  omega_prime:");
  if (!extra_cfd.empty()) replace("  jobs:", extra_cfd + "  jobs:");
  std::filesystem::create_directories(dir);
  const std::filesystem::path path = dir / "campaign.yaml";
  std::ofstream(path) << text;
  return path;
}

}  // namespace kelvin::testing
