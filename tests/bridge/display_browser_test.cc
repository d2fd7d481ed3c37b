// The browser display in Debian's headless Chromium (acceptance 1 of issue
// 26): a bridge plays a zig-zag, Chromium loads the page, watches a few
// updates and dumps its DOM; Python's html.parser reads the displayed
// heading and rudder angle, which must be those of the LCM state the page
// shows (its seq), and a screenshot is saved. A second page, started with
// ?helm=10, takes the helm through its own script and orders 10 deg of
// rudder, which must appear in the LCM state.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <fmt/format.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <map>
#include <sstream>
#include <string>
#include <thread>

#include "tests/bridge/running_bridge.h"
#include "tests/test_utilities/test_utilities.h"

namespace kelvin::bridge {
namespace {

using testing::RunningBridge;
constexpr double kDeg = M_PI / 180.0;

// Headless Chromium on `url` with `what` (--dump-dom, --screenshot=...).
// The page closes its stream after ?updates=N, so the virtual-time budget
// can run out and Chromium returns.
testing::CommandResult Chromium(const std::string& url, const std::string& what) {
  return testing::RunCommand("timeout 120 chromium --headless --no-sandbox --disable-gpu --no-first-run "
                             "--window-size=1400,900 --virtual-time-budget=5000 " +
                             what + " '" + url + "' 2>/dev/null");
}

struct Shown {
  std::string value, text;
};

// The elements with a data-value, by id, read by Python's html.parser.
std::map<std::string, Shown> ReadDom(const std::string& dom) {
  const testing::ScopedTempDir dir;
  std::ofstream(dir / "dom.html") << dom;
  const auto py = testing::RunCommand("/usr/bin/python3 " +
                                      (testing::SourceDir() / "tests/bridge/read_display_dom.py").string() + " " +
                                      (dir / "dom.html").string());
  EXPECT_EQ(py.exit_code, 0) << py.output;
  std::map<std::string, Shown> out;
  std::istringstream lines(py.output);
  std::string id, value, text;
  while (lines >> id >> value >> text) out[id] = {value, text};
  return out;
}

void RequireChromium() {
  ASSERT_TRUE(testing::HaveProgram("chromium")) << "chromium is missing: install it (tools/setup)";
}

BridgeOptions ZigZag() {
  BridgeOptions o;
  o.rate = 20;
  o.speedup = 1;
  o.duration = 600;  // stopped by the test
  o.script = "zigzag:20/20:stbd";
  return o;
}

TEST(DisplayBrowser, ChromiumShowsTheHeadingAndRudderAngleOfTheLcmState) {
  RequireChromium();
  if (HasFatalFailure()) return;
  RunningBridge run(ZigZag());
  const auto dump = Chromium(run.Url("?updates=30"), "--dump-dom");
  const std::filesystem::path shot =
      testing::EnvPath("KELVIN_BINARY_DIR", ".") / "tests/bridge/display_browser_test.png";
  const auto screenshot = Chromium(run.Url("?updates=60"), "--screenshot=" + shot.string());
  run.Stop();
  ASSERT_EQ(dump.exit_code, 0) << dump.output.substr(0, 2000);
  const auto shown = ReadDom(dump.output);
  ASSERT_TRUE(shown.count("seq") && shown.count("heading") && shown.count("rudder-angle")) << dump.output;
  const auto& states = run.States();
  const long seq = std::stol(shown.at("seq").value);
  ASSERT_GE(seq, 1);
  ASSERT_LT(static_cast<std::size_t>(seq), states.size());
  const auto& st = states[static_cast<std::size_t>(seq)];
  // The values the page computed, and the text it shows (one decimal).
  const double heading = std::stod(shown.at("heading").value);
  const double rudder = std::stod(shown.at("rudder-angle").value);
  EXPECT_NEAR(heading, st.heading / kDeg, 1e-9);
  EXPECT_NEAR(rudder, st.rudder_angle / kDeg, 1e-9);
  EXPECT_EQ(shown.at("heading").text, fmt::format("{:.1f}", heading));
  EXPECT_EQ(shown.at("rudder-angle").text, fmt::format("{:.1f}", rudder));
  std::printf("chromium showed state %ld: heading %s deg (LCM %.4f), rudder %s deg (LCM %.4f)\n", seq,
              shown.at("heading").text.c_str(), st.heading / kDeg, shown.at("rudder-angle").text.c_str(),
              st.rudder_angle / kDeg);
  EXPECT_EQ(screenshot.exit_code, 0);
  EXPECT_TRUE(std::filesystem::exists(shot)) << shot;
  EXPECT_GT(std::filesystem::file_size(shot), 10000u) << shot;
}

TEST(DisplayBrowser, AHelmOrderFromThePageReachesTheLcmState) {
  RequireChromium();
  if (HasFatalFailure()) return;
  BridgeOptions o = ZigZag();
  o.script.clear();  // helm mode
  RunningBridge run(o);
  const auto dump = Chromium(run.Url("?updates=20&helm=10"), "--dump-dom");
  // The page has sent its order by the time Chromium returns; wait
  // (bounded, nothing timed is asserted) until the loop has taken it.
  for (int i = 0; i < 1000; ++i) {
    const DisplaySnapshot snapshot = run.feed().Snapshot();
    if (snapshot.has_state && snapshot.state.rudder_order == 10.0 * kDeg) break;
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  run.Stop();
  ASSERT_EQ(dump.exit_code, 0);
  EXPECT_THAT(dump.output, ::testing::HasSubstr("this page holds the helm; order 10 deg taken"));
  const auto& states = run.States();
  ASSERT_FALSE(states.empty());
  EXPECT_DOUBLE_EQ(states.back().rudder_order, 10.0 * kDeg);
  EXPECT_GE(run.summary().helm.accepted, 1);
  EXPECT_EQ(run.summary().helm.rejected(), 0);
  EXPECT_GE(run.display().counters().helm_queued, 1);
}

}  // namespace
}  // namespace kelvin::bridge
