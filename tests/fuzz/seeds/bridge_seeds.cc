// Bridge seeds: helm messages as the filter receives them (the receiver's
// clock, then the LCM encoding: valid, clamped, NaN, out of range, stale,
// from the future, truncated, with a trailing byte) and NMEA fixes.
#include <cmath>
#include <cstring>
#include <limits>
#include <vector>

#include "kelvin/helm_command_t.hpp"
#include "tests/fuzz/seeds/seeds.h"

namespace kelvin::fuzz {
namespace {

constexpr std::int64_t kNow = 1700000000000000;  // us

std::string Helm(std::int64_t age_us, std::int32_t source, double rudder, double rps) {
  kelvin::helm_command_t m;
  m.utime = kNow - age_us;
  m.source_id = source;
  m.rudder_order = rudder;
  m.rps_order = rps;
  std::string out(sizeof kNow, '\0');
  std::memcpy(out.data(), &kNow, sizeof kNow);
  std::vector<char> buf(static_cast<std::size_t>(m.getEncodedSize()));
  m.encode(buf.data(), 0, static_cast<int>(buf.size()));
  return out.append(buf.data(), buf.size());
}

// FuzzedDataProvider takes integers from the end of the input, last byte most
// significant, a signed value as its offset from the minimum: each value goes
// in front of the ones taken before it.
template <typename T>
void Prepend(std::string& seed, T value) {
  std::string bytes(sizeof value, '\0');
  std::memcpy(bytes.data(), &value, sizeof value);
  seed.insert(0, bytes);
}

// A fix in the Strait of Dover at 12 kn, in nmea_fuzzer's order.
std::string NmeaFix(bool simulated, std::uint8_t buffer) {
  std::string seed;
  Prepend(seed, static_cast<std::uint8_t>(simulated));
  Prepend(seed, std::uint32_t{0x80000009});  // INT_MIN + raw: 9 satellites
  for (double v : {1700000000.25, 51.0123, 1.4567, 6.17, 0.5, 0.52, 0.01, -0.1}) Prepend(seed, v);
  Prepend(seed, buffer);
  return seed;
}

}  // namespace

void WriteBridgeSeeds(const std::filesystem::path& out) {
  const auto dir = out / "helm_filter";
  const std::string valid = Helm(1000, 1, 0.1, 5.0);
  WriteSeed(dir, "valid", valid);
  WriteSeed(dir, "clamped", Helm(1000, 2, 0.7, 25.0));
  WriteSeed(dir, "nan", Helm(1000, 1, std::nan(""), 5.0));
  WriteSeed(dir, "infinite", Helm(1000, 1, 0.0, std::numeric_limits<double>::infinity()));
  WriteSeed(dir, "out_of_range", Helm(1000, 1, 3.0, -50.0));
  WriteSeed(dir, "stale", Helm(5000000, 1, 0.1, 5.0));
  WriteSeed(dir, "future", Helm(-5000000, 1, 0.1, 5.0));
  WriteSeed(dir, "truncated", valid.substr(0, valid.size() - 3));
  WriteSeed(dir, "trailing", valid + '\0');
  WriteSeed(out / "nmea", "autonomous", NmeaFix(false, 100));
  WriteSeed(out / "nmea", "simulated_short_buffer", NmeaFix(true, 40));
  std::string fix(80, '\0');
  for (std::size_t i = 0; i < fix.size(); ++i) fix[i] = static_cast<char>(i * 37 + 11);
  WriteSeed(out / "nmea", "pattern", fix);
  WriteSeed(out / "nmea", "zeros", std::string(80, '\0'));
}

}  // namespace kelvin::fuzz
