// `kelvin bridge` from the command line: every bad argument exits 2 with its
// one message, the derivative-set check warns or refuses, and a scripted run
// and an interrupted run end cleanly.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fstream>
#include <string>

#include "tests/test_utilities/test_utilities.h"

namespace kelvin::bridge {
namespace {

using ::testing::HasSubstr;
using ::testing::Not;

std::string Kelvin() { return (testing::ToolsDir() / "kelvin").string(); }
std::string Ship() { return (testing::SourceDir() / "data/ships/kvlcc2.yaml").string(); }

testing::CommandResult Bridge(const std::string& args) {
  return testing::RunCommand(Kelvin() + " bridge " + Ship() + " " + args);
}

// The last line of the output (the error message).
std::string LastLine(const std::string& output) {
  std::string s = output;
  while (!s.empty() && s.back() == '\n') s.pop_back();
  const std::size_t nl = s.rfind('\n');
  return nl == std::string::npos ? s : s.substr(nl + 1);
}

struct BadArgument {
  const char* args;
  const char* message;
};

TEST(BridgeCli, EachBadArgumentExitsTwoWithOneMessage) {
  const BadArgument cases[] = {
      {"--rate 0", "kelvin: error: --rate 0: expected a state rate between 0 and 1000 Hz"},
      {"--speedup 1e9", "kelvin: error: --speedup 1000000000: expected a factor between 0 and 10000 (1 = real time)"},
      {"--duration -1", "kelvin: error: --duration -1: expected a simulation time >= 0 s (0 = until the script ends)"},
      {"--step 0.03", "kelvin: error: --step 0.03 s: expected a step that divides the state period 1/rate = 0.05 s"},
      {"--speed -2", "kelvin: error: --speed -2: expected an approach speed >= 0 m/s (0 = the ship file's)"},
      {"--channel-prefix a.b",
       "kelvin: error: --channel-prefix 'a.b': expected an UPPER_SNAKE name such as KELVIN or SIM_2"},
      {"--nmea bogus", "kelvin: error: --nmea 'bogus': expected host:port, e.g. 127.0.0.1:10110"},
      {"--nmea 127.0.0.1:0", "kelvin: error: --nmea '127.0.0.1:0': expected a port between 1 and 65535 after the colon"},
      {"--nmea 127.0.0.1:10110 --nmea-rate 20", "kelvin: error: --nmea-rate 20: expected an NMEA rate between 1 and 10 Hz"},
      {"--nmea --nmea-fix sim",
       "kelvin: error: --nmea-fix 'sim': expected autonomous (FAA mode A, GGA quality 1: what chart plotters and gpsd "
       "display) or simulated (FAA mode S, GGA quality 8)"},
      {"--http localhost:8080", "kelvin: error: --http 'localhost:8080': expected a numeric IPv4 host such as 127.0.0.1"},
      {"--http 192.0.2.1:8080",
       "kelvin: error: --http 192.0.2.1:8080: cannot listen there (in use, or not an address of this machine)"},
      {"--origin x", "kelvin: error: --origin 'x': expected <latitude>,<longitude> in degrees, e.g. 53.5,3.0"},
      {"--origin 95,3", "kelvin: error: origin latitude 95 deg: expected a latitude between -89 and 89 deg"},
      {"--stale-timeout -1", "kelvin: error: --stale-timeout -1: expected a positive time in s"},
      {"--script zigzag:20",
       "kelvin: error: maneuver 'zigzag:20': zigzag needs <rudder>/<heading> and a side; expected "
       "turning:<deg>:stbd|port, zigzag:<rudder deg>/<heading deg>:stbd|port, spiral:<max deg>:<step deg>, or "
       "stopping"},
      {"--lcm-url bogus://x",
       "kelvin: error: --lcm-url 'bogus://x': LCM cannot open this URL (expected e.g. "
       "udpm://239.255.76.67:7667?ttl=0 or memq://)"},
      {"--require-checked",
       "kelvin: error: --require-checked: refusing to stream: streaming the hull derivatives of the ship file "
       "('KVLCC2', Yasukawa & Yoshimura (2015), J. Mar. Sci. Technol. 20:37-52): a published reference set, not "
       "checked against this project's CFD"},
  };
  for (const auto& c : cases) {
    // Defaults for a short in-process run, unless the case sets the option.
    std::string args = c.args;
    for (const char* base : {"--lcm-url memq://", "--duration 1", "--speedup 100"}) {
      const std::string opt = std::string(base).substr(0, std::string(base).find(' '));
      if (args.find(opt + " ") == std::string::npos) args += std::string(" ") + base;
    }
    const auto r = Bridge(args);
    EXPECT_EQ(r.exit_code, 2) << c.args << "\n" << r.output;
    EXPECT_EQ(LastLine(r.output), c.message) << c.args;
  }
}

TEST(BridgeCli, MissingShipFileIsAParseError) {
  const auto r = testing::RunCommand(Kelvin() + " bridge /nonexistent/ship.yaml");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.output, HasSubstr("/nonexistent/ship.yaml"));
}

void WriteSet(const std::filesystem::path& path, const std::string& check) {
  std::ofstream f(path);
  // The KVLCC2 values of the ship file (Yasukawa & Yoshimura 2015).
  f << "hull:\n  R0_prime: 0.022\n  X_vv: -0.040\n  X_vr: 0.002\n  X_rr: 0.011\n  X_vvvv: 0.771\n"
       "  Y_v: -0.315\n  Y_r: 0.083\n  Y_vvv: -1.607\n  Y_vvr: 0.379\n  Y_vrr: -0.391\n  Y_rrr: 0.008\n"
       "  N_v: -0.137\n  N_r: -0.049\n  N_vvv: -0.030\n  N_vvr: -0.294\n  N_vrr: 0.055\n  N_rrr: -0.013\n"
       "  m_x_prime: 0.022\n  m_y_prime: 0.223\n  J_z_prime: 0.011\n"
    << check;
}

TEST(BridgeCli, UncheckedDerivativeSetWarnsLoudlyAndRefusesWhenRequired) {
  const testing::ScopedTempDir dir;
  const auto path = dir / "unchecked.yaml";
  WriteSet(path, "");
  const auto warn = Bridge("--derivatives " + path.string() + " --lcm-url memq:// --duration 1 --speedup 100");
  EXPECT_EQ(warn.exit_code, 0) << warn.output;
  EXPECT_THAT(warn.output, HasSubstr("*** UNCHECKED HULL DERIVATIVES *** derivative set " + path.string() +
                                     " has no 'check' section: it was never checked against CFD"));
  const auto refuse =
      Bridge("--derivatives " + path.string() + " --require-checked --lcm-url memq:// --duration 1 --speedup 100");
  EXPECT_EQ(refuse.exit_code, 2);
  EXPECT_EQ(LastLine(refuse.output), "kelvin: error: --require-checked: refusing to stream: derivative set " +
                                         path.string() + " has no 'check' section: it was never checked against CFD");
}

TEST(BridgeCli, FailedCheckRefusesWhenRequired) {
  const testing::ScopedTempDir dir;
  const auto path = dir / "failed.yaml";
  WriteSet(path, "check:\n  passed: false\n  reference: CFD zig-zag 10/10\n");
  const auto r =
      Bridge("--derivatives " + path.string() + " --require-checked --lcm-url memq:// --duration 1 --speedup 100");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(LastLine(r.output), "kelvin: error: --require-checked: refusing to stream: derivative set " +
                                    path.string() + " FAILED its check against CFD (CFD zig-zag 10/10)");
}

TEST(BridgeCli, CheckedDerivativeSetStreamsWithoutWarning) {
  const testing::ScopedTempDir dir;
  const auto path = dir / "checked.yaml";
  WriteSet(path, "check:\n  passed: true\n  reference: CFD zig-zag 10/10\n");
  const auto r =
      Bridge("--derivatives " + path.string() + " --require-checked --lcm-url memq:// --duration 1 --speedup 100");
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_THAT(r.output, HasSubstr("passed its check against CFD zig-zag 10/10"));
  EXPECT_THAT(r.output, Not(HasSubstr("UNCHECKED")));
  EXPECT_THAT(r.output, HasSubstr("bridge completed: t = 1.000 s, 21 states"));
}

TEST(BridgeCli, BadDerivativeFileExitsOneNamingTheKey) {
  const testing::ScopedTempDir dir;
  const auto path = dir / "bad.yaml";
  WriteSet(path, "chek:\n  passed: true\n");
  const auto r = Bridge("--derivatives " + path.string() + " --lcm-url memq:// --duration 1");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_THAT(LastLine(r.output), HasSubstr("unknown key 'chek'"));
  EXPECT_THAT(LastLine(r.output), HasSubstr(path.string()));
}

TEST(BridgeCli, ScriptedZigZagRunsToItsEnd) {
  const auto r = Bridge("--lcm-url memq:// --script zigzag:20/20:stbd --speedup 500");
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_THAT(r.output, HasSubstr("*** UNCHECKED HULL DERIVATIVES *** streaming the hull derivatives of the ship file"));
  // 4 reversals of the 20/20 zig-zag: t = 106.45 s, 2130 states (0.05 s
  // apart), events START, 4 EXECUTE, 3 OVERSHOOT, STOP.
  EXPECT_THAT(r.output, HasSubstr("bridge completed: t = 106.450 s, 2130 states, 9 events published (0 failed)"));
}

TEST(BridgeCli, NmeaWithoutAValueGoesToTheUsualPort) {
  const auto r = Bridge("--nmea --lcm-url memq:// --duration 1 --speedup 100");
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_THAT(r.output, HasSubstr("NMEA 0183 to 127.0.0.1:10110 at 1 Hz (autonomous fixes)"));
  // 21 states at 2000 per wall-clock second; at 1 Hz a fix goes with every
  // 2000th state: only the one at t = 0, six sentences.
  EXPECT_THAT(r.output, HasSubstr("nmea: 6 sentences sent, 0 dropped"));
}

TEST(BridgeCli, NmeaFixModeIsChosenOnTheCommandLine) {
  const auto r = Bridge("--nmea --nmea-fix simulated --lcm-url memq:// --duration 1 --speedup 100");
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_THAT(r.output, HasSubstr("NMEA 0183 to 127.0.0.1:10110 at 1 Hz (simulated fixes)"));
}

TEST(ListenCli, EachBadArgumentExitsTwoWithOneMessage) {
  const BadArgument cases[] = {
      {"--count -1", "kelvin: error: --count -1: expected a number of states >= 0"},
      {"--idle-timeout 0", "kelvin: error: --idle-timeout 0: expected a positive time in s"},
      {"--timeout -1", "kelvin: error: --timeout -1: expected a time >= 0 s"},
      {"--lcm-url bogus://x", "kelvin: error: --lcm-url 'bogus://x': LCM cannot open this URL"},
  };
  for (const auto& c : cases) {
    const auto r = testing::RunCommand(Kelvin() + " listen " + c.args);
    EXPECT_EQ(r.exit_code, 2) << c.args << "\n" << r.output;
    EXPECT_EQ(LastLine(r.output), c.message) << c.args;
  }
}

TEST(ListenCli, StopsAtItsTimeoutWhenNothingArrives) {
  const auto r = testing::RunCommand(Kelvin() + " listen --lcm-url memq:// --timeout 0.2");
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_THAT(r.output, HasSubstr("listen: 0 states, 0 events, 0 out of sequence, 0 malformed"));
}

TEST(BridgeCli, InterruptStopsTheBridgeCleanly) {
  // Without a script or duration the bridge runs until interrupted.
  const auto r = testing::RunCommand("timeout --preserve-status -s INT 1 " + Kelvin() + " bridge " + Ship() +
                                     " --lcm-url memq:// --rate 20");
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_THAT(r.output, HasSubstr("bridge stopped: t = "));
}

}  // namespace
}  // namespace kelvin::bridge
