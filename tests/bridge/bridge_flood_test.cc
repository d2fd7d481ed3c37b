// The bridge under a helm flood over udpm:// on loopback (TTL 0): 2,000
// messages a second for 6 s of every kind the helm filter tells apart
// (bridge/helm_abuse.h: valid, clamped, wrong fingerprint, truncated,
// trailing bytes, garbage, rudder and rps out of range, stale, from the
// future, NaN, +inf, -inf, unknown source) from a second LCM instance while
// the bridge streams in real time. The bridge must keep running, every state
// must be finite and carry only orders that the filter had to accept, and
// every kind must be counted under its own reason: each count lies between
// what was sent less what loopback lost (sent minus received, measured) and
// what was sent. The pacing is reported, not asserted (tests make no timing
// assertions; the bridge flags overruns but does not treat them as errors):
// tools/bench/bridge_flood_bench checks it at the full rate.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <lcm/lcm-cpp.hpp>
#include <set>
#include <thread>
#include <utility>

#include "bridge/bridge.h"
#include "bridge/helm_abuse.h"
#include "bridge/helm_flood.h"
#include "bridge/listener.h"
#include "tests/bridge/running_bridge.h"
#include "tests/bridge/udpm_loopback.h"

namespace kelvin::bridge {
namespace {

using testing::RunningBridge;

constexpr HelmVerdict kVerdicts[] = {HelmVerdict::kAccepted,   HelmVerdict::kClamped, HelmVerdict::kMalformed,
                                     HelmVerdict::kNotFinite,  HelmVerdict::kOutOfRange, HelmVerdict::kStale,
                                     HelmVerdict::kFuture,     HelmVerdict::kUnknownSource};

TEST(BridgeFlood, EveryKindOfHelmMessageIsCountedUnderItsReasonAndNoneRejectedSteers) {
  if (const std::string why = testing::MulticastProblem(); !why.empty()) GTEST_SKIP() << why;
  const std::string url = testing::UniqueUdpmUrl();
  BridgeOptions o;
  o.rate = 20;
  o.speedup = 1;
  o.helm.sources = {1, 2};  // so that an unknown source is a reason of its own
  RunningBridge run(o, {}, url);
  lcm::LCM sender(url);
  ASSERT_TRUE(sender.good()) << url;

  HelmFloodOptions f;
  f.rate = 2000;
  f.duration = 6;
  f.record_orders = true;
  HelmFlood flood(sender.getUnderlyingLCM(), run.bridge().helm_channel(), run.bridge().helm_filter().options(), f);
  const HelmFloodReport sent = flood.Run();
  std::this_thread::sleep_for(std::chrono::milliseconds(500));  // what is still in flight
  run.Stop();
  const BridgeSummary& s = run.summary();
  const auto& states = run.States();

  // The flood ran and the bridge kept running throughout.
  ASSERT_EQ(sent.publish_failures, 0);
  ASSERT_EQ(sent.total(), 12000);
  EXPECT_EQ(s.status, BridgeStatus::kStopped);

  // Counts by reason: a kind can lose at most every lost message.
  const long lost = sent.total() - s.helm.received;
  EXPECT_EQ(s.helm.received, s.helm.accepted + s.helm.rejected());
  EXPECT_GE(lost, 0) << "the bridge counted more helm messages than were sent";
  for (HelmVerdict v : kVerdicts) {
    const long owed = sent.owed.Of(v), got = s.helm.Of(v);
    ASSERT_GT(owed, 0) << VerdictName(v) << ": the flood sent none";
    EXPECT_LE(got, owed) << VerdictName(v);
    EXPECT_GE(got, owed - lost) << VerdictName(v) << " (" << lost << " lost)";
    // Fewer lost than half of any kind: each kind is provably counted under its reason.
    EXPECT_LT(2 * lost, owed) << VerdictName(v) << ": loopback lost too much to attribute the counts";
  }

  // Every state finite, and every order in force one the filter had to accept.
  std::set<std::pair<double, double>> accepted(sent.orders.begin(), sent.orders.end());
  accepted.emplace(0.0, run.bridge().approach_rps());  // before the first accepted order
  ASSERT_GE(states.size(), 10u);
  std::set<std::pair<double, double>> in_force;
  for (const auto& st : states) {
    ASSERT_TRUE(AllFinite(st)) << "state " << st.seq;
    const std::pair<double, double> order{st.rudder_order, st.propeller_rps_order};
    ASSERT_TRUE(accepted.count(order)) << "state " << st.seq << " carries rudder_order " << st.rudder_order
                                       << " rad, rps_order " << st.propeller_rps_order
                                       << " 1/s, which no message the filter must accept gave";
    in_force.insert(order);
  }
  EXPECT_GT(in_force.size(), states.size() / 2) << "the valid orders did not steer";

  std::printf("flood: %ld messages in %.2f s (%.0f/s), %ld lost on loopback (%.3f%%)\n", sent.total(),
              sent.seconds, sent.rate(), lost, 100.0 * static_cast<double>(lost) / static_cast<double>(sent.total()));
  for (HelmVerdict v : kVerdicts) {
    std::printf("  %-16s sent %5ld counted %5ld\n", std::string(VerdictName(v)).c_str(), sent.owed.Of(v),
                s.helm.Of(v));
  }
  std::printf("bridge: %ld states published, %zu received; pacing: %ld late ticks, %ld resyncs, max lateness "
              "%.3f ms; %ld drains cut at their time budget\n",
              s.states_published, states.size(), s.late_ticks, s.resyncs, s.max_lateness * 1e3,
              s.helm_drains_cut);
}

}  // namespace
}  // namespace kelvin::bridge
