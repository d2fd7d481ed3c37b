// The NMEA formatters' inputs: any fix (NaN, infinities, huge values, any
// satellite count) into any buffer size. A sentence that comes out fits its
// buffer, is NUL terminated, at most 82 characters of printable ASCII
// "$...*hh\r\n" with the right checksum.
#include <fuzzer/FuzzedDataProvider.h>

#include <bit>
#include <cstdio>
#include <string_view>
#include <vector>

#include "bridge/nmea.h"

namespace {

using Formatter = std::size_t (*)(const kelvin::bridge::NmeaFix&, std::span<char>);

void Require(bool ok) {
  if (!ok) __builtin_trap();
}

double AnyDouble(FuzzedDataProvider& in) { return std::bit_cast<double>(in.ConsumeIntegral<std::uint64_t>()); }

void CheckSentence(const std::vector<char>& buf, std::size_t n) {
  if (n == 0) return;
  Require(n < buf.size() && buf[n] == '\0' && n <= kelvin::bridge::kNmeaMaxSentence && n >= 6);
  const std::string_view s(buf.data(), n);
  Require(s.front() == '$' && s.substr(n - 2) == "\r\n" && s[n - 5] == '*');
  for (char c : s.substr(0, n - 2)) Require(c >= 0x20 && c < 0x7f);
  char hex[3];
  std::snprintf(hex, sizeof hex, "%02X", kelvin::bridge::NmeaChecksum(s.substr(1, n - 6)));
  Require(s.substr(n - 4, 2) == std::string_view(hex, 2));
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  FuzzedDataProvider in(data, size);
  kelvin::bridge::NmeaFix fix;
  fix.mode = in.ConsumeBool() ? kelvin::bridge::NmeaFixMode::kSimulated : kelvin::bridge::NmeaFixMode::kAutonomous;
  fix.satellites = in.ConsumeIntegral<int>();
  for (double* v : {&fix.utc_seconds, &fix.position.latitude, &fix.position.longitude, &fix.speed_over_ground,
                    &fix.course_over_ground, &fix.heading, &fix.yaw_rate, &fix.rudder_angle}) {
    *v = AnyDouble(in);
  }
  std::vector<char> buf(in.ConsumeIntegralInRange<std::size_t>(0, 128));
  for (Formatter f : {kelvin::bridge::FormatRmc, kelvin::bridge::FormatGga, kelvin::bridge::FormatVtg,
                      kelvin::bridge::FormatHdt, kelvin::bridge::FormatRot, kelvin::bridge::FormatRsa}) {
    CheckSentence(buf, f(fix, buf));
  }
  return 0;
}
