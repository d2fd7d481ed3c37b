#include "cfd/run/steady_criterion.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "data/schema/errors.h"

namespace kelvin::cfd {
namespace {
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

double L2Norm(std::span<const double> a) {
  double n2 = 0.0;
  for (double x : a) n2 += x * x;
  return std::sqrt(n2);
}

double L2Distance(std::span<const double> a, std::span<const double> b) {
  double d2 = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) d2 += (a[i] - b[i]) * (a[i] - b[i]);
  return std::sqrt(d2);
}
}  // namespace

void SteadyCriterionOptions::Validate() const {
  if (window_steps < 1) throw ConfigError(fmt::format("window_steps = {}; expected >= 1", window_steps));
  if (!(window >= 0.0) || !std::isfinite(window)) {
    throw ConfigError(fmt::format("window = {} s; expected >= 0 s of pseudo-time", window));
  }
  if (!(tolerance > 0.0 && tolerance < 1.0)) {
    throw ConfigError(fmt::format("tolerance = {}; expected a relative change in (0, 1)", tolerance));
  }
}

SteadyCriterion::SteadyCriterion(SteadyCriterionOptions options)
    : options_(options), force_change_(kNaN), eta_change_(kNaN) {
  options_.Validate();
}

// Layout: [samples, then per sample: time, groups, per group: scale,
// values, the values..., then the eta size and eta...].
std::vector<double> SteadyCriterion::Save() const {
  std::vector<double> out{static_cast<double>(samples_.size())};
  for (const Sample& s : samples_) {
    out.push_back(s.time);
    out.push_back(static_cast<double>(s.groups.size()));
    for (const SteadyGroup& g : s.groups) {
      out.push_back(g.scale);
      out.push_back(static_cast<double>(g.values.size()));
      out.insert(out.end(), g.values.begin(), g.values.end());
    }
    out.push_back(static_cast<double>(s.eta.size()));
    out.insert(out.end(), s.eta.begin(), s.eta.end());
  }
  return out;
}

void SteadyCriterion::Load(std::span<const double> saved) {
  std::size_t at = 0;
  auto next = [&]() {
    if (at >= saved.size()) {
      throw DataFileError(fmt::format("the steady criterion's window ends early ({} numbers)", saved.size()));
    }
    return saved[at++];
  };
  auto count = [&]() {
    const double n = next();
    if (!(n >= 0.0) || n != std::floor(n) || n > static_cast<double>(saved.size())) {
      throw DataFileError(fmt::format("the steady criterion's window has a count of {} at position {}", n, at - 1));
    }
    return static_cast<std::size_t>(n);
  };
  std::deque<Sample> samples(count());
  for (Sample& s : samples) {
    s.time = next();
    s.groups.resize(count());
    for (SteadyGroup& g : s.groups) {
      g.scale = next();
      g.values.resize(count());
      for (double& v : g.values) v = next();
    }
    s.eta.resize(count());
    for (double& v : s.eta) v = next();
  }
  if (at != saved.size()) {
    throw DataFileError(fmt::format("the steady criterion's window has {} numbers after its end", saved.size() - at));
  }
  for (const Sample& s : samples) {
    bool same = s.groups.size() == samples.front().groups.size() && s.eta.size() == samples.front().eta.size();
    for (std::size_t g = 0; same && g < s.groups.size(); ++g) {
      same = s.groups[g].values.size() == samples.front().groups[g].values.size();
    }
    if (!same) throw DataFileError("the steady criterion's window holds samples of different sizes");
  }
  samples_ = std::move(samples);
  Update();
}

void SteadyCriterion::Add(double time, std::span<const SteadyGroup> groups, std::span<const double> eta) {
  KELVIN_CHECK(!groups.empty(), "at least one monitored group");
  samples_.push_back({time, {groups.begin(), groups.end()}, {eta.begin(), eta.end()}});
  // Keep the newest sample that is at least one window old, and all later ones.
  const std::size_t keep = static_cast<std::size_t>(options_.window_steps) + 1;
  while (samples_.size() > keep && samples_[1].time <= time - options_.window) samples_.pop_front();
  Update();
}

void SteadyCriterion::Update() {
  force_change_ = eta_change_ = kNaN;
  if (samples_.empty()) return;
  const double time = samples_.back().time;
  if (samples_.front().time > time - options_.window * (1.0 - 1e-9)) return;
  if (samples_.size() < static_cast<std::size_t>(options_.window_steps) + 1) return;
  Measure();
}

void SteadyCriterion::Measure() {
  const Sample& now = samples_.back();
  force_change_ = 0.0;
  for (std::size_t g = 0; g < now.groups.size(); ++g) {
    double df = 0.0;
    for (const Sample& s : samples_) {
      KELVIN_CHECK(s.groups.size() == now.groups.size() && s.groups[g].values.size() == now.groups[g].values.size(),
                   "same monitored groups in every sample");
      for (std::size_t k = 0; k < s.groups[g].values.size(); ++k) {
        df = std::max(df, std::abs(s.groups[g].values[k] - now.groups[g].values[k]));
      }
    }
    const double scale = std::abs(now.groups[g].scale);
    force_change_ = std::max(force_change_, scale > 0.0 ? df / scale : (df > 0.0 ? kInf : 0.0));
  }
  const double eta_norm = L2Norm(now.eta);
  double de = 0.0;
  for (const Sample& s : samples_) {
    KELVIN_CHECK(s.eta.size() == now.eta.size(), "the same eta field in every sample");
    de = std::max(de, L2Distance(s.eta, now.eta));
  }
  eta_change_ = now.eta.empty() ? 0.0 : (eta_norm > 0.0 ? de / eta_norm : (de > 0.0 ? 1.0 : 0.0));
}

bool SteadyCriterion::Settled() const {
  return std::isfinite(force_change_) && std::isfinite(eta_change_) && force_change_ < options_.tolerance &&
         eta_change_ < options_.tolerance;
}

}  // namespace kelvin::cfd
