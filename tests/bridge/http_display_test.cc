// The bridge's browser display over HTTP, read with cpp-httplib's client
// and Python's json module: the state stream carries the LCM states exactly;
// the page that holds the helm steers (through the same helm filter and
// statistics as LCM helm commands) and every other page is refused; malformed
// and oversized requests are dropped and counted; the server is bound to
// loopback by default; the page and its script are served by kelvin itself.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <fstream>
#include <lcm/lcm-cpp.hpp>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "bridge/bridge.h"
#include "bridge/display_feed.h"
#include "bridge/helm_holder.h"
#include "bridge/http_display.h"
#include "bridge/listener.h"
#include "data/schema/errors.h"
#include "simulator/mmg/ship_parameters.h"
#include "tests/bridge/running_bridge.h"
#include "tests/test_utilities/test_utilities.h"
// Last: httplib.h brings <resolv.h>, whose _res macro breaks Eigen's headers.
#include <httplib.h>

namespace kelvin::bridge {
namespace {

using testing::RunningBridge;

using ::testing::HasSubstr;
constexpr double kDeg = M_PI / 180.0;

BridgeOptions HelmOptions() {
  BridgeOptions o;
  o.rate = 20;
  o.speedup = 1;
  o.duration = 600;  // stopped by the test
  return o;
}

// Form fields as a body.
std::string Form(const std::string& token, const std::string& rudder, const std::string& rps) {
  return "token=" + token + "&rudder=" + rudder + "&rps=" + rps;
}

std::string Claim(httplib::Client& cli) {
  const auto r = cli.Post("/helm/claim", "", "application/x-www-form-urlencoded");
  if (!r || r->status != 200) return "";
  const std::string key = R"("token":")";
  const std::size_t at = r->body.find(key);
  if (at == std::string::npos) return "";
  return r->body.substr(at + key.size(), 32);
}

// A Python expression of the /state document `d`, read by Python's json module.
std::string StateField(httplib::Client& cli, const std::string& path) {
  const auto r = cli.Get("/state");
  if (!r || r->status != 200) return "";
  const testing::ScopedTempDir dir;
  std::ofstream(dir / "state.json") << r->body;
  const auto py = testing::RunCommand("/usr/bin/python3 -c 'import json,sys; d=json.load(open(sys.argv[1])); print(" +
                                      path + ")' " + (dir / "state.json").string());
  return py.exit_code == 0 ? py.output.substr(0, py.output.find('\n')) : "error: " + py.output;
}

TEST(HttpDisplay, TheStateStreamCarriesTheLcmStatesExactly) {
  BridgeOptions o;
  o.rate = 20;
  o.speedup = 10;
  o.duration = 30;  // 3 s of wall-clock time
  o.script = "zigzag:20/20:stbd";
  RunningBridge run(o);
  httplib::Client cli = run.Client();
  std::string stream;
  int events = 0;
  const auto r = cli.Get("/stream", [&](const char* data, std::size_t n) {
    stream.append(data, n);
    events = static_cast<int>(std::count(stream.begin(), stream.end(), '\n')) / 2;
    return events < 20;
  });
  run.Join();
  const auto& states = run.States();
  ASSERT_EQ(states.size(), 601u);

  const testing::ScopedTempDir dir;
  std::ofstream(dir / "stream.txt") << stream;
  const auto py = testing::RunCommand("/usr/bin/python3 " +
                                      (testing::SourceDir() / "tests/bridge/decode_state_stream.py").string() + " " +
                                      (dir / "stream.txt").string());
  ASSERT_EQ(py.exit_code, 0) << py.output;
  std::istringstream lines(py.output);
  int checked = 0;
  long seq = 0, last_seq = -1;
  double t, x, y, heading, rudder_angle, rudder_order, rps;
  std::string phase;
  while (lines >> seq >> t >> x >> y >> heading >> rudder_angle >> rudder_order >> rps >> phase) {
    ASSERT_GE(seq, 0);
    ASSERT_LT(static_cast<std::size_t>(seq), states.size());
    EXPECT_GE(seq, last_seq);  // never goes back
    last_seq = seq;
    const auto& st = states[static_cast<std::size_t>(seq)];
    EXPECT_EQ(t, st.t);
    EXPECT_EQ(x, st.x);
    EXPECT_EQ(y, st.y);
    EXPECT_EQ(heading, st.heading);
    EXPECT_EQ(rudder_angle, st.rudder_angle);
    EXPECT_EQ(rudder_order, st.rudder_order);
    EXPECT_EQ(rps, st.propeller_rps);
    const char* kPhases[] = {"approach", "execute", "steady", "finished", "free"};
    EXPECT_EQ(phase, kPhases[st.maneuver_phase]);
    ++checked;
  }
  EXPECT_GE(checked, 19);
  EXPECT_GT(last_seq, 0);
}

TEST(HttpDisplay, TheHelmHolderSteersOthersAreRefusedAndEverythingIsCounted) {
  RunningBridge run(HelmOptions());
  httplib::Client holder = run.Client(), other = run.Client();
  const std::string token = Claim(holder);
  ASSERT_EQ(token.size(), 32u);
  // One page holds the helm at a time.
  const auto second = other.Post("/helm/claim", "", "application/x-www-form-urlencoded");
  ASSERT_TRUE(second);
  EXPECT_EQ(second->status, 409);
  // A page without the token, or with a wrong one, is refused.
  for (const std::string& t : {std::string(""), std::string(32, '0')}) {
    const auto r = other.Post("/helm", Form(t, "-30", "1"), "application/x-www-form-urlencoded");
    ASSERT_TRUE(r);
    EXPECT_EQ(r->status, 403);
  }
  // Malformed fields: 422, counted, never queued.
  const auto bad = holder.Post("/helm", Form(token, "ten", "1"), "application/x-www-form-urlencoded");
  ASSERT_TRUE(bad);
  EXPECT_EQ(bad->status, 422);
  EXPECT_THAT(bad->body, HasSubstr("helm order: field 'rudder' is 'ten'; expected a number"));
  const auto missing = holder.Post("/helm", "token=" + token + "&rudder=5", "application/x-www-form-urlencoded");
  ASSERT_TRUE(missing);
  EXPECT_EQ(missing->status, 422);
  // Oversized body: 413 from httplib, counted.
  const auto big = holder.Post("/helm", Form(token, "5", std::string(4096, '1')), "application/x-www-form-urlencoded");
  ASSERT_TRUE(big);
  EXPECT_EQ(big->status, 413);
  // A NaN order is queued and rejected by the helm filter, as over LCM.
  const auto nan = holder.Post("/helm", Form(token, "nan", "1"), "application/x-www-form-urlencoded");
  ASSERT_TRUE(nan);
  EXPECT_EQ(nan->status, 200);

  // The holder's order: 10 deg to starboard at the current propeller order.
  // The first state may not be published yet: wait for it (bounded).
  std::string rps;
  for (int i = 0; i < 400 && (rps.empty() || rps[0] == 'e'); ++i) {
    rps = StateField(holder, "repr(d[\"state\"][\"propeller_rps_order\"])");
    if (rps.empty() || rps[0] == 'e') std::this_thread::sleep_for(std::chrono::milliseconds(25));
  }
  ASSERT_FALSE(rps.empty() || rps[0] == 'e') << rps;
  const auto ok = holder.Post("/helm", Form(token, "10", rps), "application/x-www-form-urlencoded");
  ASSERT_TRUE(ok);
  EXPECT_EQ(ok->status, 200) << ok->body;
  // Wait (bounded) until the order shows in the state, then stop the bridge.
  for (int i = 0; i < 400; ++i) {
    const std::string order = StateField(holder, "repr(d[\"state\"][\"rudder_order\"])");
    if (!order.empty() && order[0] != 'e' && std::abs(std::stod(order) - 10.0 * kDeg) < 1e-12) break;
    std::this_thread::sleep_for(std::chrono::milliseconds(25));
  }
  run.Stop();
  const auto& states = run.States();
  ASSERT_FALSE(states.empty());
  EXPECT_DOUBLE_EQ(states.back().rudder_order, 10.0 * kDeg);
  EXPECT_EQ(states.back().propeller_rps_order, std::stod(rps));

  const HelmCounters& h = run.summary().helm;
  EXPECT_EQ(h.received, 2);  // the NaN and the 10 deg order: nothing else reached the filter
  EXPECT_EQ(h.not_finite, 1);
  EXPECT_EQ(h.accepted, 1);
  const PageCounters p = run.display().counters();
  EXPECT_EQ(p.helm_queued, 2);
  EXPECT_EQ(p.not_holder, 2);
  EXPECT_EQ(p.malformed, 2);
  EXPECT_EQ(p.oversized, 1);
  EXPECT_EQ(p.streams_refused, 0);
}

// The local addresses (hex, as in /proc/net/tcp) listening on `port`.
std::vector<std::string> ListeningAddresses(int port) {
  std::vector<std::string> out;
  std::ifstream tcp("/proc/net/tcp");
  std::string line;
  std::getline(tcp, line);  // header
  char wanted[8];
  std::snprintf(wanted, sizeof(wanted), "%04X", port);
  while (std::getline(tcp, line)) {
    std::istringstream f(line);
    std::string slot, local, remote, state;
    f >> slot >> local >> remote >> state;
    if (state == "0A" && local.substr(local.find(':') + 1) == wanted) out.push_back(local.substr(0, local.find(':')));
  }
  return out;
}

TEST(HttpDisplay, BoundToLoopbackUnlessAnotherAddressIsNamed) {
  EXPECT_EQ(HttpDisplayOptions{}.host, "127.0.0.1");
  EXPECT_EQ(HttpDisplayOptions{}.port, 8080);
  EXPECT_EQ(HttpDisplayOptions::Parse("0.0.0.0:9000").host, "0.0.0.0");
  EXPECT_EQ(HttpDisplayOptions::Parse("0.0.0.0:9000").port, 9000);
  DisplayFeed feed;
  HttpDisplayOptions o;
  o.port = 0;
  const HttpDisplay display(feed, DisplayInfo{}, o);
  // The kernel's own table: one listening socket, on 127.0.0.1 (0100007F).
  EXPECT_EQ(ListeningAddresses(display.port()), std::vector<std::string>{"0100007F"});
  EXPECT_EQ(display.url(), "http://127.0.0.1:" + std::to_string(display.port()) + "/");
}

TEST(HttpDisplay, BadAddressesAndOptionsHaveOneClearMessage) {
  const auto message = [](auto make) -> std::string {
    try {
      make();
    } catch (const ArgumentError& e) {
      return e.what();
    }
    return "no error";
  };
  EXPECT_EQ(message([] { HttpDisplayOptions::Parse("localhost:8080"); }),
            "--http 'localhost:8080': expected a numeric IPv4 host such as 127.0.0.1");
  EXPECT_EQ(message([] { HttpDisplayOptions::Parse("127.0.0.1"); }),
            "--http '127.0.0.1': expected host:port, e.g. 127.0.0.1:10110");
  HttpDisplayOptions slow;
  slow.update_rate = 5;
  EXPECT_EQ(message([&] { slow.Validate(); }), "display update rate 5 Hz: expected 10 to 50 Hz");
  // An address that is not this machine's cannot be bound.
  DisplayFeed feed;
  HttpDisplayOptions remote;
  remote.host = "192.0.2.1";  // TEST-NET-1, never local
  remote.port = 8080;
  EXPECT_EQ(message([&] { HttpDisplay d(feed, DisplayInfo{}, remote); }),
            "--http 192.0.2.1:8080: cannot listen there (in use, or not an address of this machine)");
}

TEST(HttpDisplay, ServesItsOwnPageAndScriptWithoutOutsideResources) {
  DisplayFeed feed;
  HttpDisplayOptions o;
  o.port = 0;
  const HttpDisplay display(feed, DisplayInfo{}, o);
  httplib::Client cli("127.0.0.1", display.port());
  const auto page = cli.Get("/");
  ASSERT_TRUE(page);
  EXPECT_EQ(page->status, 200);
  EXPECT_EQ(page->get_header_value("Content-Type"), "text/html; charset=utf-8");
  EXPECT_THAT(page->body, HasSubstr(R"(<script src="/display.js"></script>)"));
  const auto script = cli.Get("/display.js");
  ASSERT_TRUE(script);
  EXPECT_EQ(script->status, 200);
  EXPECT_THAT(script->body, HasSubstr("new EventSource('/stream')"));
  for (const std::string& body : {page->body, script->body}) {
    EXPECT_EQ(body.find("http://"), std::string::npos);
    EXPECT_EQ(body.find("https://"), std::string::npos);
    EXPECT_EQ(body.find("//cdn"), std::string::npos);
  }
  // Before the first state: a document without one.
  const auto state = cli.Get("/state");
  ASSERT_TRUE(state);
  EXPECT_THAT(state->body, HasSubstr(R"("state":null)"));
}

TEST(HttpDisplay, PagesBeyondTheStreamLimitAndBadRequestsAreRefusedAndCounted) {
  DisplayFeed feed;
  HttpDisplayOptions o;
  o.port = 0;
  o.max_streams = 1;
  const HttpDisplay display(feed, DisplayInfo{}, o);
  std::atomic<bool> watching{false}, done{false};
  std::thread first([&] {
    httplib::Client cli("127.0.0.1", display.port());
    cli.Get("/stream", [&](const char*, std::size_t) {
      watching.store(true);
      return !done.load();
    });
  });
  while (!watching.load()) std::this_thread::sleep_for(std::chrono::milliseconds(5));
  httplib::Client cli("127.0.0.1", display.port());
  const auto second = cli.Get("/stream");
  ASSERT_TRUE(second);
  EXPECT_EQ(second->status, 503);
  done.store(true);
  first.join();
  // Headers beyond httplib's 8 KiB limit: 400, counted.
  const auto huge = cli.Get("/state", {{"X-Big", std::string(20000, 'a')}});
  ASSERT_TRUE(huge);
  EXPECT_EQ(huge->status, 400);
  const PageCounters p = display.counters();
  EXPECT_EQ(p.streams_refused, 1);
  EXPECT_EQ(p.bad_requests, 1);
}

TEST(HttpDisplay, AReleasedOrLapsedHelmCanBeTakenByAnotherPage) {
  DisplayFeed feed;
  HttpDisplayOptions o;
  o.port = 0;
  const HttpDisplay display(feed, DisplayInfo{}, o);
  httplib::Client a("127.0.0.1", display.port()), b("127.0.0.1", display.port());
  const std::string token = Claim(a);
  ASSERT_EQ(token.size(), 32u);
  EXPECT_EQ(Claim(b), "");
  const auto wrong = b.Post("/helm/release", "token=" + std::string(32, 'f'), "application/x-www-form-urlencoded");
  ASSERT_TRUE(wrong);
  EXPECT_EQ(wrong->status, 403);
  const auto released = a.Post("/helm/release", "token=" + token, "application/x-www-form-urlencoded");
  ASSERT_TRUE(released);
  EXPECT_EQ(released->status, 200);
  const std::string second = Claim(b);
  EXPECT_EQ(second.size(), 32u);
  EXPECT_NE(second, token);
  // The holder's lapse, on the holder's own clock.
  HelmHolder holder(10.0);
  const auto t = holder.Claim(0);
  ASSERT_TRUE(t);
  EXPECT_TRUE(holder.Holds(*t, 9'000'000'000));   // refreshed at 9 s
  EXPECT_FALSE(holder.Claim(18'000'000'000));      // 9 s after the last order
  EXPECT_TRUE(holder.Claim(19'000'000'001));       // lapsed: free again
  EXPECT_FALSE(holder.Holds(*t, 19'000'000'002));  // and the old token is void
}

}  // namespace
}  // namespace kelvin::bridge
