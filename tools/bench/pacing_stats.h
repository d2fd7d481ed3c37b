// The pacing statistics of the bridge benchmarks (bridge_pacing_bench,
// bridge_flood_bench): publish instants on CLOCK_MONOTONIC against the ideal
// schedule of period T, and the acceptance limits of BENCHMARKS.md's
// bridge_pacing section.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

namespace kelvin::bench {

struct Stats {
  long samples = 0;
  double mean_period_error_ms = 0;  // mean(t_k - t_{k-1}) - T
  double p50_jitter_ms = 0;         // median of |t_k - t_{k-1} - T|
  double p99_jitter_ms = 0;         // 99th percentile of |t_k - t_{k-1} - T|
  double max_jitter_ms = 0;
  double drift_ms = 0;              // (t_N - t_0) - N T: lag accumulated over the run
  double slope_us_per_s = 0;        // least-squares slope of the schedule error
};

// The acceptance limits of the bridge's pacing.
constexpr double kMaxMeanPeriodErrorMs = 0.1;
constexpr double kMaxP99JitterMs = 2.0;
constexpr double kMaxDriftMs = 2.0;

inline Stats Analyse(const std::vector<std::int64_t>& t, double period) {
  Stats s;
  const std::size_t n = t.size();
  s.samples = static_cast<long>(n);
  if (n < 3) return s;
  const double T = period * 1e9;
  std::vector<double> jit;
  jit.reserve(n - 1);
  for (std::size_t k = 1; k < n; ++k) jit.push_back(std::abs(static_cast<double>(t[k] - t[k - 1]) - T));
  std::sort(jit.begin(), jit.end());
  const double total = static_cast<double>(t[n - 1] - t[0]);
  const auto quantile = [&jit](double q) {
    return jit[static_cast<std::size_t>(q * static_cast<double>(jit.size() - 1))] * 1e-6;
  };
  s.mean_period_error_ms = (total / static_cast<double>(n - 1) - T) * 1e-6;
  s.p50_jitter_ms = quantile(0.5);
  s.p99_jitter_ms = quantile(0.99);
  s.max_jitter_ms = jit[jit.size() - 1] * 1e-6;
  s.drift_ms = (total - static_cast<double>(n - 1) * T) * 1e-6;
  // Slope of e_k = t_k - t_0 - k T against time.
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (std::size_t k = 0; k < n; ++k) {
    const double x = static_cast<double>(k) * period;
    const double e = static_cast<double>(t[k] - t[0]) - static_cast<double>(k) * T;
    sx += x;
    sy += e;
    sxx += x * x;
    sxy += x * e;
  }
  const double m = static_cast<double>(n);
  s.slope_us_per_s = (m * sxy - sx * sy) / (m * sxx - sx * sx) * 1e-3;
  return s;
}

inline bool Accepted(const Stats& b) {
  return std::abs(b.mean_period_error_ms) < kMaxMeanPeriodErrorMs && b.p99_jitter_ms < kMaxP99JitterMs &&
         std::abs(b.drift_ms) < kMaxDriftMs;
}

}  // namespace kelvin::bench
