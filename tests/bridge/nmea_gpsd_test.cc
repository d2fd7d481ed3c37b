// The bridge's NMEA stream read by real consumers from Debian: gpsd's decoder
// (gpsdecode, gpsd-clients) for position, course, speed and heading, and
// pynmea2 (python3-nmea2) for rate of turn and rudder angle, which gpsd does
// not decode. A scripted zig-zag streams in-process over memq:// while a
// thread collects the UDP datagrams; every decoded value is checked against
// the LCM state of the same instant. Acceptance 5 of issue 26.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <lcm/lcm-cpp.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "bridge/bridge.h"
#include "bridge/geo.h"
#include "bridge/listener.h"
#include "simulator/mmg/ship_parameters.h"
#include "tests/bridge/udp_collector.h"
#include "tests/test_utilities/test_utilities.h"

namespace kelvin::bridge {
namespace {

constexpr double kDeg = M_PI / 180.0;
constexpr double kKnot = 1852.0 / 3600.0;
constexpr double kEpoch = 1700000000.0;     // NMEA time of simulation time 0
constexpr double kRate = 20.0;               // states per simulation second
const GeoPoint kOrigin{50.9, -1.4};          // west of Greenwich: W longitudes

struct Tpv {
  double time, lat, lon, track, speed;
  int mode;
};
struct RotRudder {
  double time, rot, rudder;  // s, deg/min, deg
};
struct Decoded {
  std::vector<Tpv> tpv;            // gpsd
  std::vector<double> heading;     // gpsd ATT, deg, one per HDT
  std::vector<RotRudder> fixes;    // pynmea2, one per RMC
};

struct Stream {
  BridgeSummary summary;
  std::vector<kelvin::ship_state_t> states;  // index = seq
  std::vector<std::string> sentences;
};

Stream StreamZigZag(NmeaFixMode mode, double duration) {
  testing::UdpCollector udp;
  EXPECT_TRUE(udp.bound());
  const sim::ShipParameters ship = sim::LoadShip(testing::SourceDir() / "data/ships/kvlcc2.yaml");
  lcm::LCM lcm("memq://");
  BridgeOptions o;
  o.rate = kRate;
  o.speedup = 20;  // 400 states per wall second
  o.duration = duration;
  o.script = "zigzag:20/20:stbd";
  o.origin = kOrigin;
  o.nmea = UdpEndpoint::Parse("127.0.0.1:" + std::to_string(udp.port()), "--nmea");
  o.nmea_rate = 10;  // every 40th state: one fix per 2 s of simulation time
  o.nmea_epoch = kEpoch;
  o.nmea_fix = mode;
  Bridge bridge(ship, o, lcm);
  Listener listener(lcm, "KELVIN");
  Stream s;
  s.summary = bridge.Run();
  while (lcm.handleTimeout(0) > 0) {
  }
  s.states = listener.states();
  s.sentences = udp.Stop();
  return s;
}

// The next word as a number; strtod reads "nan", which operator>> does not.
double Next(std::istream& in) {
  std::string word;
  in >> word;
  return std::strtod(word.c_str(), nullptr);
}

Decoded Decode(const std::vector<std::string>& sentences) {
  const testing::ScopedTempDir dir;
  {
    std::ofstream out(dir / "stream.nmea", std::ios::binary);
    for (const auto& s : sentences) out << s;
  }
  const auto r = testing::RunCommand("/usr/bin/python3 " + (testing::SourceDir() / "tests/bridge/decode_nmea.py").string() +
                                     " " + (dir / "stream.nmea").string());
  EXPECT_EQ(r.exit_code, 0) << r.output;
  Decoded d;
  std::istringstream lines(r.output);
  std::string kind;
  while (lines >> kind) {
    if (kind == "TPV") {
      Tpv t{};
      t.time = Next(lines);
      t.mode = static_cast<int>(Next(lines));
      t.lat = Next(lines);
      t.lon = Next(lines);
      t.track = Next(lines);
      t.speed = Next(lines);
      d.tpv.push_back(t);
    } else if (kind == "ATT") {
      d.heading.push_back(Next(lines));
    } else if (kind == "FIX") {
      RotRudder f{};
      f.time = Next(lines);
      f.rot = Next(lines);
      f.rudder = Next(lines);
      d.fixes.push_back(f);
    } else {
      ADD_FAILURE() << "unexpected decoder output: " << r.output;
      break;
    }
  }
  return d;
}

// The state published at NMEA time `time`, or nullptr if none is.
const kelvin::ship_state_t* StateAt(const Stream& s, double time) {
  const double t = time - kEpoch;
  const long k = std::lround(t * kRate);
  if (k < 0 || static_cast<std::size_t>(k) >= s.states.size() || std::abs(k / kRate - t) > 1e-3) return nullptr;
  return &s.states[static_cast<std::size_t>(k)];
}

double AngleDiffDeg(double a, double b) { return std::remainder(a - b, 360.0); }

void RequireDecoders() {
  ASSERT_TRUE(testing::HaveProgram("gpsdecode")) << "gpsdecode is missing: install gpsd-clients (tools/setup)";
  ASSERT_EQ(testing::RunCommand("/usr/bin/python3 -c 'import pynmea2'").exit_code, 0)
      << "pynmea2 is missing: install python3-nmea2 (tools/setup)";
}

TEST(NmeaGpsd, AutonomousFixesAreDecodedByGpsdAndMatchTheLcmState) {
  RequireDecoders();
  if (HasFatalFailure()) return;
  const Stream s = StreamZigZag(NmeaFixMode::kAutonomous, 0.0);  // until the zig-zag ends
  ASSERT_EQ(s.summary.status, BridgeStatus::kCompleted);
  ASSERT_EQ(s.summary.nmea_sentences_dropped, 0);
  ASSERT_EQ(static_cast<long>(s.sentences.size()), s.summary.nmea_sentences_sent);
  for (std::size_t k = 0; k < s.states.size(); ++k) ASSERT_EQ(s.states[k].seq, static_cast<std::int64_t>(k));
  const std::size_t n_fixes = s.sentences.size() / 6;
  ASSERT_GE(n_fixes, 50u);  // 106.45 s of zig-zag, one fix per 2 s
  const Decoded d = Decode(s.sentences);

  // gpsd reports every fix but the first (it learns the reporting cycle
  // from it) as a 3D fix.
  ASSERT_GE(d.tpv.size(), n_fixes - 1);
  const LocalOrigin origin(kOrigin);
  double max_position_error = 0;
  for (const Tpv& t : d.tpv) {
    SCOPED_TRACE(::testing::Message() << "gpsd TPV at t = " << t.time - kEpoch << " s");
    EXPECT_EQ(t.mode, 3);
    const kelvin::ship_state_t* st = StateAt(s, t.time);
    ASSERT_NE(st, nullptr);
    double x = 0, y = 0;
    origin.ToLocal({t.lat, t.lon}, &x, &y);
    const double error = std::hypot(x - st->x, y - st->y);
    max_position_error = std::max(max_position_error, error);
    EXPECT_LT(error, 1.0);
    // Sentence precision 1e-5 minute (half a unit), gpsd prints 1e-9 deg.
    EXPECT_NEAR(t.lat, st->latitude, 0.5e-5 / 60.0 + 1e-9);
    EXPECT_NEAR(t.lon, st->longitude, 0.5e-5 / 60.0 + 1e-9);
    // 0.01 deg in the sentences, gpsd prints 1e-4 deg.
    EXPECT_NEAR(AngleDiffDeg(t.track, st->course_over_ground / kDeg), 0.0, 0.005 + 0.5e-4);
    // 0.01 kn in the sentences, gpsd prints 1e-3 m/s.
    EXPECT_NEAR(t.speed, st->speed_over_ground, 0.005 * kKnot + 0.5e-3);
  }
  std::printf("gpsd: %zu of %zu fixes as 3D fixes; largest position error %.4f m\n", d.tpv.size(), n_fixes,
              max_position_error);

  // One heading per HDT, in order: fix k is state 40 k.
  ASSERT_EQ(d.heading.size(), n_fixes);
  for (std::size_t k = 0; k < n_fixes; ++k) {
    const auto& st = s.states.at(40 * k);
    EXPECT_NEAR(AngleDiffDeg(d.heading[k], st.heading / kDeg), 0.0, 0.005 + 0.5e-3) << "fix " << k;
  }

  ASSERT_EQ(d.fixes.size(), n_fixes);
  double max_rudder = 0;
  for (const RotRudder& f : d.fixes) {
    SCOPED_TRACE(::testing::Message() << "pynmea2 fix at t = " << f.time - kEpoch << " s");
    const kelvin::ship_state_t* st = StateAt(s, f.time);
    ASSERT_NE(st, nullptr);
    EXPECT_NEAR(f.rot, st->r / kDeg * 60.0, 0.005 + 1e-9);
    EXPECT_NEAR(f.rudder, st->rudder_angle / kDeg, 0.05 + 1e-9);
    max_rudder = std::max(max_rudder, std::abs(f.rudder));
  }
  EXPECT_GT(max_rudder, 19.9);  // the stream covers the zig-zag's rudder swings
}

TEST(NmeaGpsd, SimulatedFixesAreFlaggedSoGpsdReportsNoPosition) {
  RequireDecoders();
  if (HasFatalFailure()) return;
  const Stream s = StreamZigZag(NmeaFixMode::kSimulated, 10.0);
  ASSERT_EQ(s.summary.nmea_sentences_dropped, 0);
  ASSERT_EQ(s.sentences.size(), 36u);  // six fixes (t = 0, 2, ..., 10 s)
  const Decoded d = Decode(s.sentences);
  ASSERT_FALSE(d.tpv.empty());
  for (const Tpv& t : d.tpv) {
    EXPECT_LT(t.mode, 2) << "gpsd took a simulated fix for a position";
    EXPECT_TRUE(std::isnan(t.lat)) << t.lat;
  }
  // pynmea2 still reads every fix.
  EXPECT_EQ(d.fixes.size(), 6u);
}

}  // namespace
}  // namespace kelvin::bridge
