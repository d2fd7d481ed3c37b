// Identification benchmark (issue 9): a full joint fit of the 20 MMG hull
// coefficients to 10 runs x 5 periods x 200 samples (30,000 residuals) with
// 5% noise, including both weighting passes, the covariance and the
// identifiability analysis; target < 2 s on one core. The peer, measured in
// the same run, is one dense least-squares solve of a system of the same
// size (Eigen HouseholderQR, 30,000 x 20): the floor for any fit of this
// data, so the ratio shows what Ceres, the Jets, the two passes and the
// covariance cost on top.
// Prints a Markdown section; with --write FILE it replaces the section
// between the identification markers in FILE (BENCHMARKS.md). With
// --write-campaign FILE it also writes the benchmark campaign (HDF5).
#include <fmt/format.h>

#include <Eigen/Dense>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <ctime>
#include <fstream>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include "data/schema/captive_io.h"
#include "identification/joint_fit.h"
#include "identification/virtual_captive.h"
#include "tools/bench/markdown_section.h"

namespace {

using Clock = std::chrono::steady_clock;

double Median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

double Seconds(Clock::time_point a, Clock::time_point b) {
  return std::chrono::duration<double>(b - a).count();
}

// Processor time of this process (s): less sensitive than wall time to
// other work on a shared machine.
double CpuSeconds() { return static_cast<double>(std::clock()) / CLOCKS_PER_SEC; }

std::string LoadAverage() {
  std::ifstream in("/proc/loadavg");
  std::string one;
  in >> one;
  return one.empty() ? "unknown" : one;
}

}  // namespace

int main(int argc, char** argv) {
  using namespace kelvin::ident;
  std::string write_to, campaign_out;
  std::string ship_file = "data/ships/kvlcc2.yaml";
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--write") && i + 1 < argc)
      write_to = argv[++i];
    else if (!std::strcmp(argv[i], "--ship") && i + 1 < argc)
      ship_file = argv[++i];
    else if (!std::strcmp(argv[i], "--write-campaign") && i + 1 < argc)
      campaign_out = argv[++i];
  }
  const kelvin::sim::ShipParameters ship = kelvin::sim::LoadShip(ship_file);
  const kelvin::sim::MmgModel<double> model(ship);
  constexpr double kDeg = std::numbers::pi / 180.0;
  // 10 runs, each with 1000 analysed samples: 2 static drift (20 s at 50 Hz
  // after the ramp), 2 pure sway, 2 pure yaw, 4 yaw with drift (5 periods of
  // 200 samples after one ramp-up period).
  kelvin::data::CampaignDesign d;
  d.U = ship.approach_speed;
  d.drift_angles = {10 * kDeg, 20 * kDeg};
  d.sway_amplitudes = {0.1, 0.2};
  d.yaw_amplitudes = {0.3, 0.6};
  d.yaw_drift_angles = {4 * kDeg, 8 * kDeg, 12 * kDeg, 16 * kDeg};
  kelvin::data::VirtualCaptiveOptions o;
  o.periods = 5;
  o.samples_per_period = 200;
  o.steady_duration = 20.0;
  o.steady_rate = 50.0;
  kelvin::data::CaptiveCampaign campaign = GenerateCampaign(model, d, o);
  AddForceNoise(campaign, 0.05, 1);
  if (!campaign_out.empty()) kelvin::data::WriteCampaignH5(campaign, campaign_out);

  constexpr int kRepeats = 5;
  std::vector<double> fit_times, fit_cpu, peer_times;
  JointFitResult fit;
  for (int k = 0; k < kRepeats; ++k) {
    const auto t0 = Clock::now();
    const double c0 = CpuSeconds();
    fit = FitCampaign(campaign, {}, "bench");
    fit_cpu.push_back(CpuSeconds() - c0);
    fit_times.push_back(Seconds(t0, Clock::now()));
  }
  // Peer: a dense least-squares solve of the same size.
  const Eigen::Index rows = fit.residuals, cols = kCoefficientCount;
  std::mt19937_64 rng(3);
  std::normal_distribution<double> normal;
  Eigen::MatrixXd a(rows, cols);
  Eigen::VectorXd b(rows);
  for (Eigen::Index i = 0; i < rows; ++i) {
    for (Eigen::Index j = 0; j < cols; ++j) a(i, j) = normal(rng);
    b(i) = normal(rng);
  }
  double checksum = 0;
  for (int k = 0; k < kRepeats; ++k) {
    const auto t0 = Clock::now();
    const Eigen::VectorXd x = a.householderQr().solve(b);
    peer_times.push_back(Seconds(t0, Clock::now()));
    checksum += x.sum();
  }
  const double t_fit = Median(fit_times), t_peer = Median(peer_times);
  int identified = 0;
  for (int i = 0; i < kCoefficientCount; ++i) identified += fit.Identified(i) ? 1 : 0;

  std::string md = "## Identification (joint Ceres fit of the MMG hull coefficients)\n\n";
  md +=
      "Produced by `build/release/tools/bench/identification_bench --write BENCHMARKS.md` (one "
      "run, one core).\n\n";
  md += "| measure | value | target |\n| --- | --- | --- |\n";
  md += fmt::format(
      "| full joint fit, KVLCC2, 10 runs x 5 periods x 200 samples ({} residuals, 5% noise; both "
      "weighting "
      "passes, covariance, identifiability; {} of 20 coefficients identified): median of {} | "
      "{:.3f} s processor "
      "time, {:.3f} s wall (1-min load average {} on 2 cores) | < 2 s |\n",
      fit.residuals, identified, kRepeats, Median(fit_cpu), t_fit, LoadAverage());
  md += fmt::format(
      "| peer: one dense least-squares solve of the same size (Eigen HouseholderQR, {} x {}) | "
      "{:.4f} s | - |\n",
      rows, cols, t_peer);
  md += fmt::format("| joint fit / dense QR solve | {:.1f} | - |\n\n", t_fit / t_peer);
  fmt::print("{}", md);
  fmt::print("(peer checksum {:.3g})\n", checksum);
  if (!write_to.empty()) kelvin::bench::ReplaceMarkdownSection(write_to, "identification", md);
  return 0;
}
