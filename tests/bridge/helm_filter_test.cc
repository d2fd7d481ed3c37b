// Helm input safety: every verdict of the filter with its message, and a fuzz
// of 10,000 random, malformed and out-of-range commands through the running
// bridge on memq://, which must not crash, must keep the state finite and
// within the actuator limits, and must count every command in its class.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <lcm/lcm-cpp.hpp>
#include <random>
#include <vector>

#include "bridge/bridge.h"
#include "bridge/helm_abuse.h"
#include "bridge/helm_filter.h"
#include "bridge/listener.h"
#include "bridge/pacer.h"
#include "data/schema/errors.h"
#include "simulator/mmg/ship_parameters.h"
#include "tests/test_utilities/test_utilities.h"

#include <spdlog/sinks/ostream_sink.h>
#include <spdlog/spdlog.h>

#include <sstream>

namespace kelvin::bridge {
namespace {

constexpr double kDeg = M_PI / 180.0;
constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr std::int64_t kNow = 1700000000000000;  // us

HelmFilterOptions Limits() {
  HelmFilterOptions o;
  o.rudder_max = 35 * kDeg;
  o.rudder_reject = 90 * kDeg;
  o.rps_min = 0;
  o.rps_max = 10;
  o.rps_reject = 20;
  o.stale_timeout = 1.0;
  o.future_tolerance = 0.5;
  o.sources = {1, 2};
  return o;
}

kelvin::helm_command_t Command(double rudder, double rps, std::int64_t utime = kNow, int source = 1) {
  kelvin::helm_command_t c{};
  c.utime = utime;
  c.source_id = source;
  c.rudder_order = rudder;
  c.rps_order = rps;
  return c;
}

std::vector<std::uint8_t> Encode(const kelvin::helm_command_t& c) {
  std::vector<std::uint8_t> buf(static_cast<std::size_t>(c.getEncodedSize()));
  c.encode(buf.data(), 0, static_cast<int>(buf.size()));
  return buf;
}

TEST(HelmFilter, AcceptsAnOrderWithinTheLimits) {
  HelmFilter f(Limits());
  const auto buf = Encode(Command(10 * kDeg, 5.0));
  EXPECT_EQ(f.Receive(buf.data(), buf.size(), kNow), HelmVerdict::kAccepted);
  double rudder = 0, rps = 0;
  ASSERT_TRUE(f.TakeOrder(&rudder, &rps));
  EXPECT_EQ(rudder, 10 * kDeg);
  EXPECT_EQ(rps, 5.0);
  EXPECT_FALSE(f.TakeOrder(&rudder, &rps));  // taken once
  EXPECT_EQ(f.counters().accepted, 1);
  EXPECT_EQ(f.counters().received, 1);
  EXPECT_EQ(f.last_problem(), "");
}

TEST(HelmFilter, ClampsOrdersBeyondTheShipsLimits) {
  HelmFilter f(Limits());
  EXPECT_EQ(f.Check(Command(40 * kDeg, 12.0), kNow), HelmVerdict::kClamped);
  EXPECT_EQ(f.last_problem(),
            "helm command from source 1 clamped to the ship's limits: rudder_order 40 -> 35 deg, rps_order 12 -> 10 1/s");
  double rudder = 0, rps = 0;
  ASSERT_TRUE(f.TakeOrder(&rudder, &rps));
  EXPECT_EQ(rudder, 35 * kDeg);
  EXPECT_EQ(rps, 10.0);
  EXPECT_EQ(f.Check(Command(-36 * kDeg, -1.0), kNow), HelmVerdict::kClamped);
  ASSERT_TRUE(f.TakeOrder(&rudder, &rps));
  EXPECT_EQ(rudder, -35 * kDeg);
  EXPECT_EQ(rps, 0.0);
  EXPECT_EQ(f.counters().clamped, 2);
  EXPECT_EQ(f.counters().accepted, 2);
}

struct RejectCase {
  kelvin::helm_command_t command;
  HelmVerdict verdict;
  const char* message;
};

TEST(HelmFilter, EachRejectionHasOneClearMessage) {
  const RejectCase cases[] = {
      {Command(kNaN, 5), HelmVerdict::kNotFinite,
       "helm command from source 1 rejected (not finite): rudder_order is not finite (rudder_order nan rad, "
       "rps_order 5 1/s, utime 1700000000000000 us)"},
      {Command(0.1, -kInf), HelmVerdict::kNotFinite,
       "helm command from source 1 rejected (not finite): rps_order is not finite (rudder_order 0.1 rad, rps_order "
       "-inf 1/s, utime 1700000000000000 us)"},
      {Command(2.0, 5), HelmVerdict::kOutOfRange,
       "helm command from source 1 rejected (out of range): |rudder_order| exceeds the plausible range (rudder_order "
       "2 rad, rps_order 5 1/s, utime 1700000000000000 us)"},
      {Command(0.1, -25), HelmVerdict::kOutOfRange,
       "helm command from source 1 rejected (out of range): |rps_order| exceeds the plausible range (rudder_order 0.1 "
       "rad, rps_order -25 1/s, utime 1700000000000000 us)"},
      {Command(0.1, 5, kNow - 1000001), HelmVerdict::kStale,
       "helm command from source 1 rejected (stale): utime is older than the stale timeout (rudder_order 0.1 rad, "
       "rps_order 5 1/s, utime 1699999998999999 us)"},
      {Command(0.1, 5, kNow + 500001), HelmVerdict::kFuture,
       "helm command from source 1 rejected (from the future): utime lies ahead of the clock (rudder_order 0.1 rad, "
       "rps_order 5 1/s, utime 1700000000500001 us)"},
      {Command(0.1, 5, kNow, 3), HelmVerdict::kUnknownSource,
       "helm command from source 3 rejected (unknown source): source_id is not in the accepted sources (rudder_order "
       "0.1 rad, rps_order 5 1/s, utime 1700000000000000 us)"},
  };
  for (const auto& c : cases) {
    HelmFilter f(Limits());
    EXPECT_EQ(f.Check(c.command, kNow), c.verdict) << c.message;
    EXPECT_EQ(f.last_problem(), c.message);
    double rudder = 0, rps = 0;
    EXPECT_FALSE(f.TakeOrder(&rudder, &rps));
    EXPECT_EQ(f.counters().rejected(), 1);
    EXPECT_EQ(f.counters().accepted, 0);
  }
}

TEST(HelmFilter, AgesAtTheLimitsAreAccepted) {
  HelmFilter f(Limits());
  EXPECT_EQ(f.Check(Command(0.1, 5, kNow - 1000000), kNow), HelmVerdict::kAccepted);
  EXPECT_EQ(f.Check(Command(0.1, 5, kNow + 500000), kNow), HelmVerdict::kAccepted);
  // Extreme utimes do not overflow the age.
  EXPECT_EQ(f.Check(Command(0.1, 5, std::numeric_limits<std::int64_t>::min()), kNow), HelmVerdict::kStale);
  EXPECT_EQ(f.Check(Command(0.1, 5, std::numeric_limits<std::int64_t>::max()), kNow), HelmVerdict::kFuture);
}

TEST(HelmFilter, AnySourceWhenNoneAreListed) {
  HelmFilterOptions o = Limits();
  o.sources.clear();
  HelmFilter f(o);
  EXPECT_EQ(f.Check(Command(0.1, 5, kNow, -12345), kNow), HelmVerdict::kAccepted);
}

TEST(HelmFilter, MalformedMessagesAreRejected) {
  HelmFilter f(Limits());
  const auto good = Encode(Command(0.1, 5));
  // Truncated.
  EXPECT_EQ(f.Receive(good.data(), good.size() - 1, kNow), HelmVerdict::kMalformed);
  EXPECT_EQ(f.last_problem(),
            "helm command from source 0 rejected (malformed): 35 bytes do not decode as kelvin.helm_command_t (36 bytes "
            "expected) (rudder_order 0 rad, rps_order 0 1/s, utime 0 us)");
  // Trailing bytes.
  auto longer = good;
  longer.push_back(0);
  EXPECT_EQ(f.Receive(longer.data(), longer.size(), kNow), HelmVerdict::kMalformed);
  // Another type on the channel.
  kelvin::ship_state_t state{};
  std::vector<std::uint8_t> other(static_cast<std::size_t>(state.getEncodedSize()));
  state.encode(other.data(), 0, static_cast<int>(other.size()));
  EXPECT_EQ(f.Receive(other.data(), other.size(), kNow), HelmVerdict::kMalformed);
  // Empty and null.
  EXPECT_EQ(f.Receive(good.data(), 0, kNow), HelmVerdict::kMalformed);
  EXPECT_EQ(f.Receive(nullptr, 36, kNow), HelmVerdict::kMalformed);
  EXPECT_EQ(f.counters().malformed, 5);
  EXPECT_EQ(f.counters().received, 5);
}

TEST(HelmFilter, BadOptionsHaveOneClearMessage) {
  auto message = [](HelmFilterOptions o) -> std::string {
    try {
      o.Validate();
    } catch (const ArgumentError& e) {
      return e.what();
    }
    return "no error";
  };
  HelmFilterOptions o = Limits();
  EXPECT_EQ(message(o), "no error");
  o.rudder_max = -1;
  EXPECT_EQ(message(o), "helm option rudder_max = -1: expected a positive angle in rad");
  o = Limits();
  o.rudder_reject = 0.1;
  EXPECT_EQ(message(o), "helm option rudder_reject = 0.1: expected an angle in rad not below rudder_max");
  o = Limits();
  o.rps_max = 0;
  EXPECT_EQ(message(o), "helm option rps_max = 0: expected a positive propeller speed in 1/s");
  o = Limits();
  o.rps_min = 11;
  EXPECT_EQ(message(o), "helm option rps_min = 11: expected a propeller speed not above rps_max");
  o = Limits();
  o.rps_reject = 5;
  EXPECT_EQ(message(o), "helm option rps_reject = 5: expected a propeller speed not below |rps_min| and rps_max");
  o = Limits();
  o.stale_timeout = kNaN;
  EXPECT_EQ(message(o), "helm option stale_timeout = nan: expected a positive time in s");
  o = Limits();
  o.future_tolerance = -1;
  EXPECT_EQ(message(o), "helm option future_tolerance = -1: expected a non-negative time in s");
}

// --- The abusive messages of the fuzz and flood tests ---------------------

TEST(HelmAbuse, EveryKindGetsItsOwnVerdictFromTheFilter) {
  HelmFilterOptions reverse = Limits();  // reverse thrust, any source
  reverse.rps_min = -reverse.rps_max;
  reverse.sources.clear();
  for (const HelmFilterOptions& limits : {Limits(), reverse}) {
    HelmAbuseMaker maker(limits, 7);
    const std::vector<HelmAbuse> kinds = HelmAbuseKinds(limits);
    EXPECT_EQ(kinds.size(), limits.sources.empty() ? 13u : 14u);
    for (HelmAbuse kind : kinds) {
      for (int i = 0; i < 1000; ++i) {
        HelmFilter filter(limits);
        const auto bytes = maker.Make(kind, kNow);
        const HelmVerdict verdict = filter.Receive(bytes.data(), bytes.size(), kNow);
        ASSERT_EQ(verdict, ExpectedVerdict(kind)) << HelmAbuseName(kind) << " #" << i;
        double rudder = 0, rps = 0;
        const bool steers = filter.TakeOrder(&rudder, &rps);
        ASSERT_EQ(steers, verdict == HelmVerdict::kAccepted || verdict == HelmVerdict::kClamped);
        if (steers) {
          ASSERT_EQ(rudder, maker.order_rudder());
          ASSERT_EQ(rps, maker.order_rps());
        }
      }
    }
  }
}

// --- Fuzz through the running bridge -------------------------------------

// Random kinds of bridge/helm_abuse.h, `per_state` of them after each state.
class Fuzzer {
 public:
  Fuzzer(lcm::LCM& lcm, const Bridge& bridge, int total, int per_state)
      : lcm_(lcm),
        bridge_(bridge),
        total_(total),
        per_state_(per_state),
        kinds_(HelmAbuseKinds(bridge.helm_filter().options())),
        maker_(bridge.helm_filter().options(), 20261122),
        rng_(20261122) {
    lcm_.subscribe(bridge.state_channel(), &Fuzzer::OnState, this);
  }
  HelmCounters expected;
  double last_rudder = kNaN, last_rps = kNaN;  // the last accepted order after clamping
  int sent = 0;

 private:
  void OnState(const lcm::ReceiveBuffer* /*rbuf*/, const std::string&) {
    for (int i = 0; i < per_state_ && sent < total_; ++i) SendOne();
  }

  void SendOne() {
    const auto pick = std::uniform_int_distribution<std::size_t>(0, kinds_.size() - 1)(rng_);
    const auto bytes = maker_.Make(kinds_[pick], RealtimeMicroseconds());
    const HelmVerdict verdict = ExpectedVerdict(kinds_[pick]);
    ++sent;
    expected.Count(verdict);
    if (verdict == HelmVerdict::kAccepted || verdict == HelmVerdict::kClamped) {
      last_rudder = maker_.order_rudder();
      last_rps = maker_.order_rps();
    }
    lcm_.publish(bridge_.helm_channel(), bytes.data(), static_cast<unsigned>(bytes.size()));
  }

  lcm::LCM& lcm_;
  const Bridge& bridge_;
  int total_;
  int per_state_;
  std::vector<HelmAbuse> kinds_;
  HelmAbuseMaker maker_;
  std::mt19937_64 rng_;
};

TEST(HelmFuzz, TenThousandCommandsThroughTheBridge) {
  const sim::ShipParameters ship = sim::LoadShip(testing::SourceDir() / "data/ships/kvlcc2.yaml");
  lcm::LCM lcm("memq://");
  BridgeOptions o;
  o.rate = 20;
  o.speedup = 100;
  o.duration = 15;  // 300 states; the fuzz needs 200
  o.helm.sources = {1, 2};
  // Generous clock windows, so that a loaded machine cannot turn a fresh
  // command stale; the stale and future ones are dated a minute or more away.
  o.helm.stale_timeout = 30;
  o.helm.future_tolerance = 30;
  Bridge bridge(ship, o, lcm);
  Listener listener(lcm, "KELVIN");
  Fuzzer fuzz(lcm, bridge, 10000, 50);
  const BridgeSummary s = bridge.Run();
  while (lcm.handleTimeout(0) > 0) {
  }
  ASSERT_EQ(s.status, BridgeStatus::kCompleted);
  ASSERT_EQ(fuzz.sent, 10000);
  EXPECT_EQ(s.helm, fuzz.expected);
  EXPECT_EQ(s.helm.received, 10000);
  EXPECT_EQ(s.helm.received, s.helm.accepted + s.helm.rejected());
  // Every class was exercised (each of the 14 kinds ~714 times).
  for (long n : {s.helm.clamped, s.helm.malformed, s.helm.not_finite, s.helm.out_of_range, s.helm.stale,
                 s.helm.future, s.helm.unknown_source}) {
    EXPECT_GT(n, 500);
  }
  const HelmFilterOptions& lim = bridge.helm_filter().options();
  ASSERT_EQ(listener.states().size(), 301u);
  for (const auto& st : listener.states()) {
    ASSERT_TRUE(AllFinite(st)) << "state " << st.seq;
    ASSERT_LE(std::abs(st.rudder_angle), lim.rudder_max);
    ASSERT_LE(std::abs(st.rudder_order), lim.rudder_max);
    ASSERT_GE(st.propeller_rps_order, lim.rps_min);
    ASSERT_LE(st.propeller_rps_order, lim.rps_max);
  }
  // The last accepted order is the one in force.
  EXPECT_EQ(listener.states().back().rudder_order, fuzz.last_rudder);
  EXPECT_EQ(listener.states().back().propeller_rps_order, fuzz.last_rps);
}

TEST(HelmLog, RejectionsAreSummarisedAtMostOncePerInterval) {
  std::ostringstream log;
  auto previous = spdlog::default_logger();
  spdlog::set_default_logger(
      std::make_shared<spdlog::logger>("test", std::make_shared<spdlog::sinks::ostream_sink_mt>(log)));
  spdlog::set_pattern("%v");
  const sim::ShipParameters ship = sim::LoadShip(testing::SourceDir() / "data/ships/kvlcc2.yaml");
  lcm::LCM lcm("memq://");
  BridgeOptions o;
  o.speedup = 100;
  o.duration = 1;
  o.log_interval = 60;  // longer than the run: only the final summary line
  o.helm.sources = {1};
  Bridge bridge(ship, o, lcm);
  for (int i = 0; i < 100; ++i) {
    kelvin::helm_command_t c = Command(kNaN, 5, RealtimeMicroseconds(), 1);
    lcm.publish(bridge.helm_channel(), &c);
  }
  kelvin::helm_command_t c = Command(0.1, 5, RealtimeMicroseconds(), 9);
  lcm.publish(bridge.helm_channel(), &c);
  const BridgeSummary s = bridge.Run();
  spdlog::set_default_logger(previous);
  EXPECT_EQ(s.helm.not_finite, 100);
  EXPECT_EQ(s.helm.unknown_source, 1);
  EXPECT_EQ(log.str(),
            "helm: 101 rejected (0 malformed, 100 not finite, 0 out of range, 0 stale, 0 from the future, 1 unknown "
            "source) and 0 clamped since the last report; latest: helm command from source 9 rejected (unknown "
            "source): source_id is not in the accepted sources (rudder_order 0.1 rad, rps_order 5 1/s, utime " +
            std::to_string(c.utime) + " us)\n");
}

}  // namespace
}  // namespace kelvin::bridge
