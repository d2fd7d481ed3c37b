#include "cfd/campaign/run_samples.h"

#include <fmt/format.h>

#include <array>
#include <string_view>

#include "data/schema/errors.h"

namespace kelvin::cfd {
namespace {

namespace fs = std::filesystem;

// The extra channels beside X, Y, N in the samples and in the campaign file.
constexpr std::array<std::string_view, 9> kExtraChannels = {
    "X_pressure", "Y_pressure", "N_pressure", "X_viscous", "Y_viscous",
    "N_viscous",  "X_prime",    "Y_prime",    "N_prime"};

// Channel k of a sample (const or not).
template <typename Sample>
auto& Extra(Sample& s, std::size_t k) {
  switch (k) {
    case 0:
      return s.loads.pressure.X;
    case 1:
      return s.loads.pressure.Y;
    case 2:
      return s.loads.pressure.N;
    case 3:
      return s.loads.viscous.X;
    case 4:
      return s.loads.viscous.Y;
    case 5:
      return s.loads.viscous.N;
    case 6:
      return s.prime.X;
    case 7:
      return s.prime.Y;
    default:
      return s.prime.N;
  }
}

}  // namespace

void WriteSamples(const fs::path& path, const std::vector<CaptiveSample>& samples, int step,
                  int steps, const RunCost& cost, const Settle& settle) {
  data::H5Writer w(path);
  w.SetAttribute("/", "kind", "kelvin captive CFD run samples");
  w.SetAttribute("/", "step", static_cast<double>(step));
  w.SetAttribute("/", "steps", static_cast<double>(steps));
  w.SetAttribute("/", "cpu_seconds", cost.cpu_seconds);
  w.SetAttribute("/", "courant_max", cost.courant_max);
  w.SetAttribute("/", "cells", cost.cells);
  if (settle.settled >= 0) {
    w.SetAttribute("/", "settled", static_cast<double>(settle.settled));
    w.SetAttribute("/", "settle_change", settle.change);
    w.SetAttribute("/", "t_settle", settle.t_settle);
  }
  WriteCaptiveHistory(w, samples);
  w.Commit();
}

std::vector<CaptiveSample> ReadSamples(const fs::path& path, const RigidMotion& motion) {
  const data::H5Reader r(path);
  auto col = [&](std::string_view name) { return r.Read("captive/" + std::string(name)).values; };
  const std::vector<double> t = col("time");
  std::vector<CaptiveSample> out(t.size());
  for (std::size_t i = 0; i < t.size(); ++i) {
    out[i].time = t[i];
    out[i].pose = motion.At(t[i]);
  }
  for (std::size_t k = 0; k < kExtraChannels.size(); ++k) {
    const std::vector<double> v = col(kExtraChannels[k]);
    if (v.size() != t.size()) {
      throw DataFileError(fmt::format("{}: captive/{} has {} samples; expected {} (one per captive/time)",
                                      path.string(), kExtraChannels[k], v.size(), t.size()));
    }
    for (std::size_t i = 0; i < t.size(); ++i) Extra(out[i], k) = v[i];
  }
  return out;
}

void WriteExtraChannels(data::H5Writer& w, const std::string& run,
                        const std::vector<CaptiveSample>& samples) {
  for (std::size_t k = 0; k < kExtraChannels.size(); ++k) {
    std::vector<double> v;
    for (const CaptiveSample& s : samples) v.push_back(Extra(s, k));
    const bool prime = k >= 6;
    w.WriteArray(fmt::format("runs/{}/{}", run, kExtraChannels[k]), v, {v.size()},
                 prime ? "1" : (k % 3 == 2 ? "N m" : "N"),
                 prime
                     ? "prime system: forces / (0.5 rho Lpp T U^2), moment / (0.5 rho Lpp^2 T U^2)"
                     : (k < 3 ? "pressure part" : "viscous part"));
  }
}

}  // namespace kelvin::cfd
