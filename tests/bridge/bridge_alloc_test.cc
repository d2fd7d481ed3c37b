// "No allocation inside the real-time step or the LCM callbacks": every
// operator new in this test program is counted, and a bridge run that is ten
// times longer (ten times the steps, publications, helm callbacks) must
// allocate exactly as often as a short one, i.e. only in its set-up.
#include <gtest/gtest.h>

#include <atomic>
#include <cstdlib>
#include <lcm/lcm-cpp.hpp>
#include <new>

#include "bridge/bridge.h"
#include "bridge/pacer.h"
#include "simulator/mmg/ship_parameters.h"
#include "tests/test_utilities/test_utilities.h"

namespace {
std::atomic<long> g_allocations{0};
}  // namespace

void* operator new(std::size_t size) {
  g_allocations.fetch_add(1, std::memory_order_relaxed);
  if (void* p = std::malloc(size ? size : 1)) return p;
  throw std::bad_alloc();
}
void operator delete(void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }

namespace kelvin::bridge {
namespace {

// Operator-new calls made by Run() for `duration` s of simulation with
// `helm_messages` helm orders queued up front (drained 256 per state).
// With `display`, the states, events and helm statistics also go to a
// DisplayFeed (the browser display's side of the loop) holding `page_orders`
// queued page helm orders.
long AllocationsOfRun(const std::string& script, double duration, int helm_messages, const std::string& prefix,
                      bool display = false, int page_orders = 0) {
  const sim::ShipParameters ship = sim::LoadShip(testing::SourceDir() / "data/ships/kvlcc2.yaml");
  lcm::LCM lcm("memq://");
  BridgeOptions o;
  o.rate = 20;
  o.speedup = 1000;
  o.duration = duration;
  o.script = script;
  o.channel_prefix = prefix;
  o.helm.stale_timeout = 60;
  Bridge bridge(ship, o, lcm);
  DisplayFeed feed;
  if (display) bridge.SetDisplay(&feed);
  kelvin::helm_command_t cmd{};
  cmd.utime = RealtimeMicroseconds();
  cmd.rps_order = bridge.approach_rps();
  for (int i = 0; i < helm_messages; ++i) {
    cmd.rudder_order = (i % 2 ? 1 : -1) * 0.1;
    lcm.publish(bridge.helm_channel(), &cmd);
  }
  for (int i = 0; i < page_orders; ++i) EXPECT_TRUE(feed.QueueHelm(cmd));
  const long before = g_allocations.load();
  const BridgeSummary s = bridge.Run();
  const long after = g_allocations.load();
  EXPECT_EQ(s.helm.accepted, helm_messages + page_orders);
  return after - before;
}

TEST(BridgeAllocations, HelmModeAllocatesNothingPerStep) {
  // A long prefix: LCM's C++ wrapper would allocate its channel string.
  const long short_run = AllocationsOfRun("", 5, 100, "A_LONG_CHANNEL_PREFIX");
  const long long_run = AllocationsOfRun("", 50, 1000, "A_LONG_CHANNEL_PREFIX");
  EXPECT_EQ(long_run, short_run);
}

TEST(BridgeAllocations, ScriptedZigZagAllocatesNothingPerStep) {
  // Both runs cover at least one rudder reversal (the first is at ~12 s).
  const long short_run = AllocationsOfRun("zigzag:20/20:stbd", 20, 0, "KELVIN");
  const long long_run = AllocationsOfRun("zigzag:20/20:stbd", 100, 0, "KELVIN");
  EXPECT_EQ(long_run, short_run);
}

TEST(BridgeAllocations, TheDisplayFeedAllocatesNothingPerStep) {
  const long short_run = AllocationsOfRun("zigzag:20/20:stbd", 20, 0, "KELVIN", true, 16);
  const long long_run = AllocationsOfRun("zigzag:20/20:stbd", 100, 0, "KELVIN", true, 16);
  EXPECT_EQ(long_run, short_run);
}

}  // namespace
}  // namespace kelvin::bridge
