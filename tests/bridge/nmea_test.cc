// NMEA 0183 output checked by an independent parser written here: framing,
// checksum, field counts per sentence, and the values read back within the
// precision of each field; the UDP sender on loopback; the bridge's NMEA
// stream against its LCM state messages.
#include <arpa/inet.h>
#include <gtest/gtest.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <lcm/lcm-cpp.hpp>
#include <random>
#include <string>
#include <vector>

#include "bridge/bridge.h"
#include "bridge/geo.h"
#include "bridge/listener.h"
#include "bridge/nmea.h"
#include "data/schema/errors.h"
#include "simulator/mmg/ship_parameters.h"
#include "tests/test_utilities/test_utilities.h"

namespace kelvin::bridge {
namespace {

constexpr double kDeg = M_PI / 180.0;
constexpr double kKnot = 1852.0 / 3600.0;

// --- An independent NMEA 0183 parser ------------------------------------

struct Sentence {
  std::string address;              // "GPRMC"
  std::vector<std::string> fields;  // after the address
};

int HexDigit(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  return -1;
}

// Parses "$<address>,<f1>,...*<hh>\r\n"; fails the test on any framing or
// checksum error.
Sentence Parse(const std::string& text) {
  Sentence s;
  EXPECT_LE(text.size(), 82u) << text;
  EXPECT_GE(text.size(), 11u) << text;
  if (text.size() < 11) return s;
  EXPECT_EQ(text[0], '$') << text;
  EXPECT_EQ(text.substr(text.size() - 2), "\r\n") << text;
  const std::size_t star = text.size() - 5;
  EXPECT_EQ(text[star], '*') << text;
  int sum = 0;
  for (std::size_t i = 1; i < star; ++i) {
    const unsigned char c = static_cast<unsigned char>(text[i]);
    EXPECT_TRUE(c >= 0x20 && c < 0x7F && c != '$' && c != '*' && c != '!') << text;
    sum ^= c;
  }
  const int hi = HexDigit(text[star + 1]), lo = HexDigit(text[star + 2]);
  EXPECT_TRUE(hi >= 0 && lo >= 0) << "checksum digits must be upper-case hex: " << text;
  EXPECT_EQ(hi * 16 + lo, sum) << "checksum of " << text;
  std::string body = text.substr(1, star - 1);
  std::size_t start = 0;
  std::vector<std::string> parts;
  while (true) {
    const std::size_t comma = body.find(',', start);
    parts.push_back(body.substr(start, comma == std::string::npos ? std::string::npos : comma - start));
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  s.address = parts[0];
  s.fields.assign(parts.begin() + 1, parts.end());
  return s;
}

double Number(const std::string& f) {
  char* end = nullptr;
  const double v = std::strtod(f.c_str(), &end);
  EXPECT_TRUE(!f.empty() && *end == '\0') << "not a number: '" << f << "'";
  return v;
}

// ddmm.mmmmm / dddmm.mmmmm with its hemisphere letter to signed degrees.
double LatLon(const std::string& f, const std::string& hemi, int degree_digits) {
  EXPECT_EQ(f.find('.'), static_cast<std::size_t>(degree_digits + 2)) << f;
  const double deg = Number(f.substr(0, static_cast<std::size_t>(degree_digits)));
  const double min = Number(f.substr(static_cast<std::size_t>(degree_digits)));
  EXPECT_LT(min, 60.0) << f;
  const double v = deg + min / 60.0;
  return hemi == "S" || hemi == "W" ? -v : v;
}

// Seconds of the day from hhmmss.ss.
double TimeOfDay(const std::string& f) {
  EXPECT_EQ(f.size(), 9u) << f;
  return Number(f.substr(0, 2)) * 3600 + Number(f.substr(2, 2)) * 60 + Number(f.substr(4));
}

double AngleDiffDeg(double a, double b) { return std::remainder(a - b, 360.0); }

std::string Format(std::size_t (*format)(const NmeaFix&, std::span<char>), const NmeaFix& fix) {
  char buf[128];
  const std::size_t n = format(fix, std::span<char>(buf, sizeof(buf)));
  return std::string(buf, n);
}

// Checks the six sentences of `fix` and reads every value back.
void CheckRoundTrip(const NmeaFix& fix) {
  SCOPED_TRACE(::testing::Message() << "lat " << fix.position.latitude << " lon " << fix.position.longitude);
  const double lat = fix.position.latitude, lon = fix.position.longitude;
  const double tod = std::fmod(fix.utc_seconds, 86400.0);
  const double pos_tol = 0.5e-5 / 60.0 + 1e-12;  // half a unit of 1e-5 minute, in deg
  const double sog_kn = fix.speed_over_ground / kKnot;
  const bool simulated = fix.mode == NmeaFixMode::kSimulated;
  const std::string faa = simulated ? "S" : "A";  // FAA mode: simulator or autonomous
  const std::string heading_talker = simulated ? "HE" : "GP";

  const Sentence rmc = Parse(Format(FormatRmc, fix));
  EXPECT_EQ(rmc.address, "GPRMC");
  ASSERT_EQ(rmc.fields.size(), 12u);
  EXPECT_NEAR(std::remainder(TimeOfDay(rmc.fields[0]) - tod, 86400.0), 0.0, 0.005 + 1e-6);
  EXPECT_EQ(rmc.fields[1], "A");
  EXPECT_NEAR(LatLon(rmc.fields[2], rmc.fields[3], 2), lat, pos_tol);
  EXPECT_NEAR(LatLon(rmc.fields[4], rmc.fields[5], 3), lon, pos_tol);
  EXPECT_NEAR(Number(rmc.fields[6]), sog_kn, 0.005 + 1e-9);
  EXPECT_NEAR(AngleDiffDeg(Number(rmc.fields[7]), fix.course_over_ground / kDeg), 0.0, 0.005 + 1e-9);
  EXPECT_EQ(rmc.fields[8].size(), 6u);
  EXPECT_EQ(rmc.fields[9], "");
  EXPECT_EQ(rmc.fields[10], "");
  EXPECT_EQ(rmc.fields[11], faa);

  const Sentence gga = Parse(Format(FormatGga, fix));
  EXPECT_EQ(gga.address, "GPGGA");
  ASSERT_EQ(gga.fields.size(), 14u);
  EXPECT_NEAR(std::remainder(TimeOfDay(gga.fields[0]) - tod, 86400.0), 0.0, 0.005 + 1e-6);
  EXPECT_NEAR(LatLon(gga.fields[1], gga.fields[2], 2), lat, pos_tol);
  EXPECT_NEAR(LatLon(gga.fields[3], gga.fields[4], 3), lon, pos_tol);
  EXPECT_EQ(gga.fields[5], simulated ? "8" : "1");  // simulation mode or autonomous GNSS fix
  EXPECT_EQ(Number(gga.fields[6]), simulated ? 0 : fix.satellites);
  EXPECT_EQ(gga.fields[6].size(), 2u);
  EXPECT_EQ(gga.fields[8], "0.0");
  EXPECT_EQ(gga.fields[9], "M");
  EXPECT_EQ(gga.fields[11], "M");

  const Sentence vtg = Parse(Format(FormatVtg, fix));
  EXPECT_EQ(vtg.address, "GPVTG");
  ASSERT_EQ(vtg.fields.size(), 9u);
  EXPECT_NEAR(AngleDiffDeg(Number(vtg.fields[0]), fix.course_over_ground / kDeg), 0.0, 0.005 + 1e-9);
  EXPECT_EQ(vtg.fields[1], "T");
  EXPECT_EQ(vtg.fields[3], "M");
  EXPECT_NEAR(Number(vtg.fields[4]), sog_kn, 0.005 + 1e-9);
  EXPECT_EQ(vtg.fields[5], "N");
  EXPECT_NEAR(Number(vtg.fields[6]), fix.speed_over_ground * 3.6, 0.005 + 1e-9);
  EXPECT_EQ(vtg.fields[7], "K");
  EXPECT_EQ(vtg.fields[8], faa);

  const Sentence hdt = Parse(Format(FormatHdt, fix));
  EXPECT_EQ(hdt.address, heading_talker + "HDT");
  ASSERT_EQ(hdt.fields.size(), 2u);
  const double heading = Number(hdt.fields[0]);
  EXPECT_GE(heading, 0.0);
  EXPECT_LT(heading, 360.0);
  EXPECT_NEAR(AngleDiffDeg(heading, fix.heading / kDeg), 0.0, 0.005 + 1e-9);
  EXPECT_EQ(hdt.fields[1], "T");

  const Sentence rot = Parse(Format(FormatRot, fix));
  EXPECT_EQ(rot.address, heading_talker + "ROT");
  ASSERT_EQ(rot.fields.size(), 2u);
  EXPECT_NEAR(Number(rot.fields[0]), fix.yaw_rate / kDeg * 60.0, 0.005 + 1e-9);
  EXPECT_EQ(rot.fields[1], "A");

  const Sentence rsa = Parse(Format(FormatRsa, fix));
  EXPECT_EQ(rsa.address, "IIRSA");
  ASSERT_EQ(rsa.fields.size(), 4u);
  EXPECT_NEAR(Number(rsa.fields[0]), fix.rudder_angle / kDeg, 0.05 + 1e-9);
  EXPECT_EQ(rsa.fields[1], "A");
  EXPECT_EQ(rsa.fields[2], "");
  EXPECT_EQ(rsa.fields[3], "V");
}

NmeaFix ExampleFix() {
  NmeaFix f;
  f.utc_seconds = 1700000000.0 + 0.256;  // 2023-11-14 22:13:20.256 UTC
  f.position = {53.5123456, 3.0456789};
  f.speed_over_ground = 1.179;
  f.course_over_ground = 12.345 * kDeg;
  f.heading = 10.0 * kDeg;
  f.yaw_rate = -0.5 * kDeg;
  f.rudder_angle = 20.0 * kDeg;
  return f;
}

TEST(Nmea, ChecksumOfAKnownSentence) {
  // The classic example from the NMEA 0183 literature.
  EXPECT_EQ(NmeaChecksum("GPGGA,123519,4807.038,N,01131.000,E,1,08,0.9,545.4,M,46.9,M,,"), 0x47);
}

TEST(Nmea, ExactTextOfEachSentenceOfASimulatedFix) {
  NmeaFix f = ExampleFix();
  f.mode = NmeaFixMode::kSimulated;
  // Checksums computed independently (Python: functools.reduce of XOR).
  EXPECT_EQ(Format(FormatRmc, f), "$GPRMC,221320.26,A,5330.74074,N,00302.74073,E,2.29,12.35,141123,,,S*73\r\n");
  EXPECT_EQ(Format(FormatGga, f), "$GPGGA,221320.26,5330.74074,N,00302.74073,E,8,00,1.0,0.0,M,0.0,M,,*53\r\n");
  EXPECT_EQ(Format(FormatVtg, f), "$GPVTG,12.35,T,,M,2.29,N,4.24,K,S*11\r\n");
  EXPECT_EQ(Format(FormatHdt, f), "$HEHDT,10.00,T*2E\r\n");
  EXPECT_EQ(Format(FormatRot, f), "$HEROT,-30.00,A*05\r\n");
  EXPECT_EQ(Format(FormatRsa, f), "$IIRSA,20.0,A,,V*4B\r\n");
  CheckRoundTrip(f);
}

TEST(Nmea, ExactTextOfEachSentenceOfAnAutonomousFixTheDefault) {
  const NmeaFix f = ExampleFix();
  ASSERT_EQ(f.mode, NmeaFixMode::kAutonomous);
  EXPECT_EQ(Format(FormatRmc, f), "$GPRMC,221320.26,A,5330.74074,N,00302.74073,E,2.29,12.35,141123,,,A*61\r\n");
  EXPECT_EQ(Format(FormatGga, f), "$GPGGA,221320.26,5330.74074,N,00302.74073,E,1,12,1.0,0.0,M,0.0,M,,*59\r\n");
  EXPECT_EQ(Format(FormatVtg, f), "$GPVTG,12.35,T,,M,2.29,N,4.24,K,A*03\r\n");
  EXPECT_EQ(Format(FormatHdt, f), "$GPHDT,10.00,T*34\r\n");
  EXPECT_EQ(Format(FormatRot, f), "$GPROT,-30.00,A*1F\r\n");
  EXPECT_EQ(Format(FormatRsa, f), "$IIRSA,20.0,A,,V*4B\r\n");
  CheckRoundTrip(f);
}

TEST(Nmea, FixModeNamesAndTheirOneError) {
  EXPECT_EQ(ParseNmeaFixMode("autonomous", "--nmea-fix"), NmeaFixMode::kAutonomous);
  EXPECT_EQ(ParseNmeaFixMode("simulated", "--nmea-fix"), NmeaFixMode::kSimulated);
  EXPECT_EQ(NmeaFixModeName(NmeaFixMode::kAutonomous), "autonomous");
  EXPECT_EQ(NmeaFixModeName(NmeaFixMode::kSimulated), "simulated");
  try {
    ParseNmeaFixMode("S", "--nmea-fix");
    ADD_FAILURE() << "no error";
  } catch (const ArgumentError& e) {
    EXPECT_STREQ(e.what(), "--nmea-fix 'S': expected autonomous (FAA mode A, GGA quality 1: what chart plotters and "
                           "gpsd display) or simulated (FAA mode S, GGA quality 8)");
  }
}

TEST(Nmea, SatelliteCountOutsideTwoDigitsGivesNoGga) {
  NmeaFix f = ExampleFix();
  char buf[128];
  f.satellites = 100;
  EXPECT_EQ(FormatGga(f, std::span<char>(buf, sizeof(buf))), 0u);
  f.satellites = -1;
  EXPECT_EQ(FormatGga(f, std::span<char>(buf, sizeof(buf))), 0u);
  f.satellites = 7;
  EXPECT_EQ(Parse(Format(FormatGga, f)).fields[6], "07");
}

TEST(Nmea, RoundTripOfRandomFixes) {
  std::mt19937_64 rng(42);
  std::uniform_real_distribution<double> lat(-89.0, 89.0), lon(-180.0, 180.0), ang(-10.0, 10.0), speed(0.0, 15.0),
      rate(-0.05, 0.05), rudder(-35.0, 35.0), day(0.0, 3e9);
  for (int i = 0; i < 2000; ++i) {
    NmeaFix f;
    f.utc_seconds = day(rng);
    f.position = {lat(rng), lon(rng)};
    f.speed_over_ground = speed(rng);
    f.course_over_ground = ang(rng);
    f.heading = ang(rng);
    f.yaw_rate = rate(rng);
    f.rudder_angle = rudder(rng) * kDeg;
    f.mode = i % 2 ? NmeaFixMode::kSimulated : NmeaFixMode::kAutonomous;
    CheckRoundTrip(f);
    if (HasFailure()) return;
  }
}

TEST(Nmea, RoundingCarriesIntoDegreesAndWrapsBearings) {
  NmeaFix f = ExampleFix();
  f.position = {53.0 + 59.9999996 / 60.0, -(3.0 + 59.9999996 / 60.0)};
  f.heading = 359.996 * kDeg;
  f.course_over_ground = -0.001 * kDeg;
  const Sentence gga = Parse(Format(FormatGga, f));
  EXPECT_EQ(gga.fields[1], "5400.00000");
  EXPECT_EQ(gga.fields[3], "00400.00000");
  EXPECT_EQ(gga.fields[4], "W");
  EXPECT_EQ(Parse(Format(FormatHdt, f)).fields[0], "0.00");
  EXPECT_EQ(Parse(Format(FormatVtg, f)).fields[0], "0.00");
  CheckRoundTrip(f);
}

TEST(Nmea, NonFiniteValuesOrSmallBuffersGiveNoSentence) {
  NmeaFix f = ExampleFix();
  char small[20];
  EXPECT_EQ(FormatRmc(f, std::span<char>(small, sizeof(small))), 0u);
  f.position.latitude = std::nan("");
  char buf[128];
  EXPECT_EQ(FormatRmc(f, std::span<char>(buf, sizeof(buf))), 0u);
  EXPECT_EQ(FormatGga(f, std::span<char>(buf, sizeof(buf))), 0u);
  f = ExampleFix();
  f.heading = INFINITY;
  EXPECT_EQ(FormatHdt(f, std::span<char>(buf, sizeof(buf))), 0u);
}

TEST(Geo, LocalPlaneRoundTripAndScale) {
  const LocalOrigin o({53.5, 3.0});
  const GeoPoint p = o.ToGeodetic(1000.0, -2000.0);
  double x = 0, y = 0;
  o.ToLocal(p, &x, &y);
  EXPECT_NEAR(x, 1000.0, 1e-9);
  EXPECT_NEAR(y, -2000.0, 1e-9);
  // One minute of latitude is about one nautical mile (1852 m): 1855 m at 53.5 N.
  EXPECT_NEAR(o.meridian_radius() * kDeg / 60.0, 1855.1, 0.5);
  // Crossing the antimeridian wraps the longitude.
  const LocalOrigin d({0.0, 179.999});
  EXPECT_NEAR(d.ToGeodetic(0.0, 1000.0).longitude, -179.99202, 1e-5);
}

TEST(UdpEndpoint, ParsesHostAndPort) {
  const UdpEndpoint e = UdpEndpoint::Parse("127.0.0.1:10110", "--nmea");
  EXPECT_EQ(e.host, "127.0.0.1");
  EXPECT_EQ(e.port, 10110);
  EXPECT_EQ(e.ToString(), "127.0.0.1:10110");
}

TEST(UdpEndpoint, EachBadEndpointHasOneClearMessage) {
  auto message = [](const char* text) -> std::string {
    try {
      UdpEndpoint::Parse(text, "--nmea");
    } catch (const ArgumentError& e) {
      return e.what();
    }
    return "no error";
  };
  EXPECT_EQ(message("127.0.0.1"), "--nmea '127.0.0.1': expected host:port, e.g. 127.0.0.1:10110");
  EXPECT_EQ(message("127.0.0.1:"), "--nmea '127.0.0.1:': expected host:port, e.g. 127.0.0.1:10110");
  EXPECT_EQ(message("127.0.0.1:70000"), "--nmea '127.0.0.1:70000': expected a port between 1 and 65535 after the colon");
  EXPECT_EQ(message("127.0.0.1:10x"), "--nmea '127.0.0.1:10x': expected a port between 1 and 65535 after the colon");
  EXPECT_EQ(message("localhost:10110"), "--nmea 'localhost:10110': expected a numeric IPv4 host such as 127.0.0.1");
}

// A UDP socket bound to an ephemeral loopback port.
class UdpReceiver {
 public:
  UdpReceiver() {
    fd_ = ::socket(AF_INET, SOCK_DGRAM, 0);
    sockaddr_in a{};
    a.sin_family = AF_INET;
    a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    a.sin_port = 0;
    EXPECT_EQ(::bind(fd_, reinterpret_cast<sockaddr*>(&a), sizeof(a)), 0);
    socklen_t len = sizeof(a);
    ::getsockname(fd_, reinterpret_cast<sockaddr*>(&a), &len);
    port_ = ntohs(a.sin_port);
    int size = 1 << 22;
    ::setsockopt(fd_, SOL_SOCKET, SO_RCVBUF, &size, sizeof(size));
  }
  ~UdpReceiver() { ::close(fd_); }
  int port() const { return port_; }
  // Every datagram that arrives until none has come for `quiet_ms`.
  std::vector<std::string> ReceiveAll(int quiet_ms) {
    std::vector<std::string> out;
    char buf[2048];
    pollfd p{fd_, POLLIN, 0};
    while (::poll(&p, 1, quiet_ms) > 0) {
      const ssize_t n = ::recv(fd_, buf, sizeof(buf), 0);
      if (n < 0) break;
      out.emplace_back(buf, static_cast<std::size_t>(n));
    }
    return out;
  }

 private:
  int fd_ = -1;
  int port_ = 0;
};

TEST(NmeaUdpSender, SendsTheSixSentencesOnLoopback) {
  UdpReceiver rx;
  NmeaUdpSender tx(UdpEndpoint::Parse("127.0.0.1:" + std::to_string(rx.port()), "--nmea"));
  tx.Send(ExampleFix());
  const auto got = rx.ReceiveAll(1000);
  ASSERT_EQ(got.size(), 6u);
  const char* kOrder[] = {"GPRMC", "GPGGA", "GPVTG", "GPHDT", "GPROT", "IIRSA"};
  for (std::size_t i = 0; i < 6; ++i) EXPECT_EQ(Parse(got[i]).address, kOrder[i]);
  EXPECT_EQ(tx.sentences_sent(), 6);
  EXPECT_EQ(tx.sentences_dropped(), 0);
}

TEST(NmeaUdpSender, TheBridgeStreamMatchesItsStateMessages) {
  UdpReceiver rx;
  const sim::ShipParameters ship = sim::LoadShip(testing::SourceDir() / "data/ships/kvlcc2.yaml");
  lcm::LCM lcm("memq://");
  BridgeOptions o;
  o.rate = 20;
  o.speedup = 100;       // 2000 states per wall second
  o.duration = 60;       // 0.6 s of wall time
  o.script = "turning:35:stbd";
  o.nmea = UdpEndpoint::Parse("127.0.0.1:" + std::to_string(rx.port()), "--nmea");
  o.nmea_rate = 10;      // every 200th state
  o.nmea_epoch = 1700000000.0;
  Bridge bridge(ship, o, lcm);
  Listener listener(lcm, "KELVIN");
  const BridgeSummary s = bridge.Run();
  while (lcm.handleTimeout(0) > 0) {
  }
  const auto got = rx.ReceiveAll(500);
  // States 0, 200, 400, ..., 1200: seven fixes of six sentences.
  ASSERT_EQ(s.nmea_sentences_sent, 42);
  ASSERT_EQ(got.size(), 42u);
  for (std::size_t k = 0; k < 7; ++k) {
    const auto& st = listener.states().at(200 * k);
    NmeaFix f;
    f.utc_seconds = 1700000000.0 + st.t;
    f.position = {st.latitude, st.longitude};
    f.speed_over_ground = st.speed_over_ground;
    f.course_over_ground = st.course_over_ground;
    f.heading = st.heading;
    f.yaw_rate = st.r;
    f.rudder_angle = st.rudder_angle;
    for (std::size_t j = 0; j < 6; ++j) {
      char buf[128];
      std::size_t (*fmt[])(const NmeaFix&, std::span<char>) = {FormatRmc, FormatGga, FormatVtg,
                                                                FormatHdt, FormatRot, FormatRsa};
      const std::size_t n = fmt[j](f, std::span<char>(buf, sizeof(buf)));
      EXPECT_EQ(got[6 * k + j], std::string(buf, n));
    }
    CheckRoundTrip(f);
  }
}

}  // namespace
}  // namespace kelvin::bridge
