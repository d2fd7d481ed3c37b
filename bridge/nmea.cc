#include "bridge/nmea.h"

#include <arpa/inet.h>
#include <fmt/format.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <ctime>

#include "data/schema/errors.h"

namespace kelvin::bridge {

namespace {

constexpr double kDeg = M_PI / 180.0;

// A sentence being built in a fixed buffer.
class SentenceBuilder {
 public:
  explicit SentenceBuilder(std::span<char> out) : out_(out) {}

  void Append(const char* format, auto... args) {
    if (failed_) return;
    const std::size_t room = out_.size() > length_ ? out_.size() - length_ : 0;
    int n = 0;
    if constexpr (sizeof...(args) == 0) {
      n = std::snprintf(out_.data() + length_, room, "%s", format);
    } else {
      n = std::snprintf(out_.data() + length_, room, format, args...);
    }
    if (n < 0 || static_cast<std::size_t>(n) >= room) {
      failed_ = true;
      return;
    }
    length_ += static_cast<std::size_t>(n);
  }
  void Fail() { failed_ = true; }

  // Appends "*hh\r\n" and returns the length, or 0 on failure.
  std::size_t Finish() {
    if (failed_ || length_ < 1) return 0;
    const std::uint8_t sum = NmeaChecksum(std::string_view(out_.data() + 1, length_ - 1));
    Append("*%02X\r\n", static_cast<unsigned>(sum));
    if (failed_ || length_ > kNmeaMaxSentence) return 0;
    return length_;
  }

 private:
  std::span<char> out_;
  std::size_t length_ = 0;
  bool failed_ = false;
};

// hhmmss.ss and ddmmyy of a UNIX time, from its value rounded to 0.01 s.
bool AppendTime(SentenceBuilder& b, double utc_seconds) {
  if (!std::isfinite(utc_seconds) || utc_seconds < 0) return false;
  const long long centi = std::llround(utc_seconds * 100.0);
  const std::time_t secs = static_cast<std::time_t>(centi / 100);
  std::tm tm{};
  if (!gmtime_r(&secs, &tm)) return false;
  b.Append("%02d%02d%02d.%02lld", tm.tm_hour, tm.tm_min, tm.tm_sec, centi % 100);
  return true;
}

void AppendDate(SentenceBuilder& b, double utc_seconds) {
  const long long centi = std::llround(utc_seconds * 100.0);
  const std::time_t secs = static_cast<std::time_t>(centi / 100);
  std::tm tm{};
  gmtime_r(&secs, &tm);
  b.Append("%02d%02d%02d", tm.tm_mday, tm.tm_mon + 1, tm.tm_year % 100);
}

// ddmm.mmmmm,N (degree_digits 2) or dddmm.mmmmm,E (3), from the angle rounded
// to 1e-5 minute so that 59.999996' carries into the degrees.
bool AppendAngle(SentenceBuilder& b, double degrees, int degree_digits, char positive, char negative) {
  if (!std::isfinite(degrees)) return false;
  const long long units = std::llround(std::abs(degrees) * 60.0 * 1e5);  // 1e-5 minute
  const long long per_degree = 60LL * 100000LL;
  const long long whole = units / per_degree;
  const long long rem = units % per_degree;
  b.Append(degree_digits == 2 ? "%02lld%02lld.%05lld,%c" : "%03lld%02lld.%05lld,%c", whole, rem / 100000,
           rem % 100000, degrees < 0 && units > 0 ? negative : positive);
  return true;
}

// An angle in [0, 360) with two decimals, rounded before wrapping.
bool AppendBearing(SentenceBuilder& b, double radians) {
  if (!std::isfinite(radians)) return false;
  long long centi = std::llround(radians / kDeg * 100.0) % 36000;
  if (centi < 0) centi += 36000;
  b.Append("%lld.%02lld", centi / 100, centi % 100);
  return true;
}

bool Simulated(const NmeaFix& f) { return f.mode == NmeaFixMode::kSimulated; }

// The FAA mode indicator of RMC and VTG (NMEA 0183 2.3 and later).
const char* FaaMode(const NmeaFix& f) { return Simulated(f) ? "S" : "A"; }

// The talker of the heading sentences: a gyro, or the GNSS compass itself.
const char* HeadingTalker(const NmeaFix& f) { return Simulated(f) ? "HE" : "GP"; }

bool AppendFixed(SentenceBuilder& b, double value, int decimals) {
  if (!std::isfinite(value)) return false;
  b.Append("%.*f", decimals, value == 0.0 ? 0.0 : value);
  return true;
}

}  // namespace

std::string_view NmeaFixModeName(NmeaFixMode mode) {
  switch (mode) {
    case NmeaFixMode::kAutonomous: return "autonomous";
    case NmeaFixMode::kSimulated: return "simulated";
  }
  return "?";
}

NmeaFixMode ParseNmeaFixMode(std::string_view text, std::string_view what) {
  for (NmeaFixMode m : {NmeaFixMode::kAutonomous, NmeaFixMode::kSimulated}) {
    if (text == NmeaFixModeName(m)) return m;
  }
  throw ArgumentError(fmt::format("{} '{}': expected autonomous (FAA mode A, GGA quality 1: what chart plotters and gpsd "
                                  "display) or simulated (FAA mode S, GGA quality 8)",
                                  what, text));
}

std::uint8_t NmeaChecksum(std::string_view body) {
  std::uint8_t sum = 0;
  for (char c : body) sum ^= static_cast<std::uint8_t>(c);
  return sum;
}

std::size_t FormatRmc(const NmeaFix& f, std::span<char> out) {
  SentenceBuilder b(out);
  b.Append("$GPRMC,");
  if (!AppendTime(b, f.utc_seconds)) return 0;
  b.Append(",A,");
  if (!AppendAngle(b, f.position.latitude, 2, 'N', 'S')) return 0;
  b.Append(",");
  if (!AppendAngle(b, f.position.longitude, 3, 'E', 'W')) return 0;
  b.Append(",");
  if (!AppendFixed(b, f.speed_over_ground / kMetresPerSecondPerKnot, 2)) return 0;
  b.Append(",");
  if (!AppendBearing(b, f.course_over_ground)) return 0;
  b.Append(",");
  AppendDate(b, f.utc_seconds);
  b.Append(",,,%s", FaaMode(f));
  return b.Finish();
}

std::size_t FormatGga(const NmeaFix& f, std::span<char> out) {
  SentenceBuilder b(out);
  b.Append("$GPGGA,");
  if (!AppendTime(b, f.utc_seconds)) return 0;
  b.Append(",");
  if (!AppendAngle(b, f.position.latitude, 2, 'N', 'S')) return 0;
  b.Append(",");
  if (!AppendAngle(b, f.position.longitude, 3, 'E', 'W')) return 0;
  // Quality 1 (autonomous GNSS fix) with the satellites in use, or 8
  // (simulation mode) with none; HDOP 1.0, antenna at the waterline, no geoid
  // separation, no differential data.
  if (f.satellites < 0 || f.satellites > 99) return 0;
  if (Simulated(f)) {
    b.Append(",8,00");
  } else {
    b.Append(",1,%02d", f.satellites);
  }
  b.Append(",1.0,0.0,M,0.0,M,,");
  return b.Finish();
}

std::size_t FormatVtg(const NmeaFix& f, std::span<char> out) {
  SentenceBuilder b(out);
  b.Append("$GPVTG,");
  if (!AppendBearing(b, f.course_over_ground)) return 0;
  b.Append(",T,,M,");
  if (!AppendFixed(b, f.speed_over_ground / kMetresPerSecondPerKnot, 2)) return 0;
  b.Append(",N,");
  if (!AppendFixed(b, f.speed_over_ground * 3.6, 2)) return 0;
  b.Append(",K,%s", FaaMode(f));
  return b.Finish();
}

std::size_t FormatHdt(const NmeaFix& f, std::span<char> out) {
  SentenceBuilder b(out);
  b.Append("$%sHDT,", HeadingTalker(f));
  if (!AppendBearing(b, f.heading)) return 0;
  b.Append(",T");
  return b.Finish();
}

std::size_t FormatRot(const NmeaFix& f, std::span<char> out) {
  SentenceBuilder b(out);
  b.Append("$%sROT,", HeadingTalker(f));
  if (!AppendFixed(b, f.yaw_rate / kDeg * 60.0, 2)) return 0;
  b.Append(",A");
  return b.Finish();
}

std::size_t FormatRsa(const NmeaFix& f, std::span<char> out) {
  SentenceBuilder b(out);
  b.Append("$IIRSA,");
  if (!AppendFixed(b, f.rudder_angle / kDeg, 1)) return 0;
  b.Append(",A,,V");
  return b.Finish();
}

UdpEndpoint UdpEndpoint::Parse(std::string_view text, std::string_view what) {
  const auto fail = [&](std::string_view expected) -> UdpEndpoint {
    throw ArgumentError(fmt::format("{} '{}': {}", what, text, expected));
  };
  const std::size_t colon = text.rfind(':');
  if (colon == std::string_view::npos || colon == 0 || colon + 1 == text.size()) {
    return fail("expected host:port, e.g. 127.0.0.1:10110");
  }
  UdpEndpoint e;
  e.host = std::string(text.substr(0, colon));
  const std::string_view port = text.substr(colon + 1);
  int value = 0;
  const auto [ptr, ec] = std::from_chars(port.data(), port.data() + port.size(), value);
  if (ec != std::errc() || ptr != port.data() + port.size() || value < 1 || value > 65535) {
    return fail("expected a port between 1 and 65535 after the colon");
  }
  e.port = value;
  in_addr addr{};
  if (::inet_pton(AF_INET, e.host.c_str(), &addr) != 1) {
    return fail("expected a numeric IPv4 host such as 127.0.0.1");
  }
  return e;
}

std::string UdpEndpoint::ToString() const { return fmt::format("{}:{}", host, port); }

NmeaUdpSender::NmeaUdpSender(const UdpEndpoint& endpoint) {
  address_.sin_family = AF_INET;
  address_.sin_port = htons(static_cast<std::uint16_t>(endpoint.port));
  if (::inet_pton(AF_INET, endpoint.host.c_str(), &address_.sin_addr) != 1) {
    throw ArgumentError(fmt::format("NMEA host '{}': expected a numeric IPv4 address", endpoint.host));
  }
  fd_ = ::socket(AF_INET, SOCK_DGRAM | SOCK_NONBLOCK | SOCK_CLOEXEC, 0);
  if (fd_ < 0) {
    throw ArgumentError(fmt::format("NMEA output to {}: cannot create a UDP socket: {}", endpoint.ToString(),
                                    std::strerror(errno)));
  }
}

NmeaUdpSender::~NmeaUdpSender() {
  if (fd_ >= 0) ::close(fd_);
}

void NmeaUdpSender::SendOne(std::size_t length) {
  if (length == 0) {
    ++dropped_;
    return;
  }
  const ssize_t n = ::sendto(fd_, buffer_, length, MSG_DONTWAIT | MSG_NOSIGNAL,
                             reinterpret_cast<const sockaddr*>(&address_), sizeof(address_));
  if (n == static_cast<ssize_t>(length)) {
    ++sent_;
  } else {
    ++dropped_;
  }
}

void NmeaUdpSender::Send(const NmeaFix& fix) {
  const std::span<char> buf(buffer_, sizeof(buffer_));
  SendOne(FormatRmc(fix, buf));
  SendOne(FormatGga(fix, buf));
  SendOne(FormatVtg(fix, buf));
  SendOne(FormatHdt(fix, buf));
  SendOne(FormatRot(fix, buf));
  SendOne(FormatRsa(fix, buf));
}

}  // namespace kelvin::bridge
