// The bridge's defaults expose nothing beyond this machine: without
// --lcm-url, `kelvin bridge` sends its LCM packets with multicast TTL 0
// (read off the packets themselves with a raw socket, as root); NMEA and the
// display are off unless asked for, and when asked for without an address
// they go to 127.0.0.1 (the display's listening socket is checked in the
// kernel's table by http_display_test; NMEA's default by bridge_cli_test).
// What the bridge receives follows the multicast route: where the group is
// joined on a network interface, the bridge says so.
#include <arpa/inet.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <netinet/ip.h>
#include <poll.h>
#include <stdlib.h>
#include <sys/socket.h>
#include <unistd.h>

#include <atomic>
#include <cstring>
#include <mutex>
#include <set>
#include <string>
#include <thread>
#include <vector>

#include "bridge/bridge.h"
#include "bridge/http_display.h"
#include "bridge/lcm_url.h"
#include "bridge/nmea.h"
#include "tests/bridge/udp_collector.h"
#include "tests/bridge/udpm_loopback.h"
#include "tests/test_utilities/test_utilities.h"

namespace kelvin::bridge {
namespace {

using ::testing::HasSubstr;

// The IP TTL of every UDP datagram to `port` whose payload contains `marker`
// (an LCM channel name), read by a raw socket on a background thread.
class TtlCapture {
 public:
  TtlCapture(int port, std::string marker) : port_(port), marker_(std::move(marker)) {
    fd_ = ::socket(AF_INET, SOCK_RAW, IPPROTO_UDP);
    if (fd_ >= 0) reader_ = std::thread([this] { Read(); });
  }
  ~TtlCapture() {
    Stop();
    if (fd_ >= 0) ::close(fd_);
  }
  bool open() const { return fd_ >= 0; }
  std::set<int> Stop() {
    stop_.store(true);
    if (reader_.joinable()) reader_.join();
    std::lock_guard<std::mutex> lock(mutex_);
    return ttls_;
  }
  long packets() {
    std::lock_guard<std::mutex> lock(mutex_);
    return packets_;
  }

 private:
  void Read() {
    unsigned char buf[65536];
    pollfd p{fd_, POLLIN, 0};
    while (!stop_.load()) {
      if (::poll(&p, 1, 20) <= 0) continue;
      const ssize_t n = ::recv(fd_, buf, sizeof(buf), 0);
      if (n < static_cast<ssize_t>(sizeof(iphdr))) continue;
      const auto* ip = reinterpret_cast<const iphdr*>(buf);
      const std::size_t udp = static_cast<std::size_t>(ip->ihl) * 4;
      if (static_cast<std::size_t>(n) < udp + 8) continue;
      const int dport = (buf[udp + 2] << 8) | buf[udp + 3];
      const std::string payload(reinterpret_cast<const char*>(buf) + udp + 8, static_cast<std::size_t>(n) - udp - 8);
      if (dport != port_ || payload.find(marker_) == std::string::npos) continue;
      std::lock_guard<std::mutex> lock(mutex_);
      ttls_.insert(ip->ttl);
      ++packets_;
    }
  }

  int port_;
  std::string marker_;
  int fd_ = -1;
  std::atomic<bool> stop_{false};
  std::mutex mutex_;
  std::set<int> ttls_;
  long packets_ = 0;
  std::thread reader_;
};

std::string Bridge(const std::string& args) {
  return (testing::ToolsDir() / "kelvin").string() + " bridge " +
         (testing::SourceDir() / "data/ships/kvlcc2.yaml").string() + " " + args + " 2>&1";
}

TEST(BridgeLoopback, TheCaptureReadsTheTtlOfEachPacket) {
  testing::UdpCollector rx;
  ASSERT_TRUE(rx.bound());
  TtlCapture seven(rx.port(), "TTL-PROBE");
  if (!seven.open()) GTEST_SKIP() << "a raw socket needs root (CAP_NET_RAW): " << std::strerror(errno);
  // A unicast datagram to loopback with TTL 7: the capture must see 7.
  const int fd = ::socket(AF_INET, SOCK_DGRAM, 0);
  const int ttl = 7;
  ASSERT_EQ(::setsockopt(fd, IPPROTO_IP, IP_TTL, &ttl, sizeof(ttl)), 0);
  sockaddr_in to{};
  to.sin_family = AF_INET;
  to.sin_port = htons(static_cast<std::uint16_t>(rx.port()));
  to.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  for (int i = 0; i < 20 && seven.packets() == 0; ++i) {
    ::sendto(fd, "TTL-PROBE", 9, 0, reinterpret_cast<const sockaddr*>(&to), sizeof(to));
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  ::close(fd);
  EXPECT_EQ(seven.Stop(), std::set<int>{7});
}

TEST(BridgeLoopback, WithoutAnLcmUrlThePacketsHaveTtlZero) {
  if (const std::string why = testing::MulticastProblem(); !why.empty()) GTEST_SKIP() << why;
  TtlCapture capture(7667, "KELVIN_TTLCHECK_STATE");
  if (!capture.open()) GTEST_SKIP() << "a raw socket needs root (CAP_NET_RAW): " << std::strerror(errno);
  const auto r = testing::RunCommand("env -u LCM_DEFAULT_URL " +
                                     Bridge("--channel-prefix KELVIN_TTLCHECK --duration 2 --speedup 4"));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_THAT(r.output, HasSubstr("LCM udpm://239.255.76.67:7667?ttl=0, channels KELVIN_TTLCHECK_STATE"));
  EXPECT_THAT(r.output, ::testing::Not(HasSubstr("multicast TTL")));
  std::this_thread::sleep_for(std::chrono::milliseconds(100));
  const long packets = capture.packets();
  EXPECT_EQ(capture.Stop(), std::set<int>{0});
  EXPECT_GE(packets, 41);  // 2 s at 20 Hz: 41 states, each one datagram
}

TEST(BridgeLoopback, ANonZeroTtlIsWarnedAbout) {
  // The display's address is refused after the warning and before any
  // publication: no packet with TTL 1 leaves.
  const std::string url = testing::UniqueUdpmUrl();
  const std::string ttl1 = url.substr(0, url.find('?')) + "?ttl=1";
  const auto r = testing::RunCommand(Bridge("--lcm-url '" + ttl1 + "' --http 192.0.2.1:8080 --duration 1"));
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_THAT(r.output, HasSubstr("LCM " + ttl1 + ": multicast TTL 1 sends the states beyond this machine (ttl=0 "
                                  "keeps them on it)"));
  EXPECT_EQ(UdpmTtl("udpm://239.255.76.67:7667?ttl=1"), 1);
  EXPECT_EQ(UdpmTtl("udpm://239.255.76.67:7667?recv_buf_size=4096&ttl=3"), 3);
  EXPECT_EQ(UdpmTtl("udpm://239.255.76.67:7667?ttl=0"), 0);
  EXPECT_EQ(UdpmTtl("udpm://239.255.76.67:7667"), 0);  // LCM's own default
  EXPECT_EQ(UdpmTtl("udpm://239.255.76.67:7667?ttl=x"), std::nullopt);
  EXPECT_EQ(UdpmTtl("memq://"), std::nullopt);
  EXPECT_EQ(UdpmTtl("file:///tmp/log?mode=w"), std::nullopt);
}

TEST(BridgeLoopback, TheInterfacesThatJoinedAGroupAreReadFromTheKernelsTable) {
  const std::string igmp =
      "Idx\tDevice    : Count Querier\tGroup    Users Timer\tReporter\n"
      "1\tlo        :     1      V3\n"
      "\t\t\t\t010000E0     1 0:00000000\t\t0\n"
      "4\teth0      :     2      V3\n"
      "\t\t\t\t434CFFEF     7 0:00000000\t\t0\n"
      "\t\t\t\t010000E0     1 0:00000000\t\t0\n";
  EXPECT_EQ(MulticastMembers(igmp, "239.255.76.67"), std::vector<std::string>{"eth0"});
  EXPECT_EQ(MulticastMembers(igmp, "224.0.0.1"), (std::vector<std::string>{"lo", "eth0"}));
  EXPECT_TRUE(MulticastMembers(igmp, "239.255.76.68").empty());
  EXPECT_TRUE(MulticastMembers(igmp, "not an address").empty());
  EXPECT_EQ(UdpmGroup("udpm://239.255.76.67:7667?ttl=0"), "239.255.76.67");
  EXPECT_EQ(UdpmGroup("udpm://239.255.0.9"), "239.255.0.9");
  EXPECT_EQ(UdpmGroup("memq://"), std::nullopt);
}

// Whether other machines can send to the bridge follows the multicast route:
// warned about unless it is loopback.
TEST(BridgeLoopback, AGroupJoinedOnANetworkInterfaceIsWarnedAbout) {
  if (const std::string why = testing::MulticastProblem(); !why.empty()) GTEST_SKIP() << why;
  const std::string route = testing::RunCommand(std::string("ip route get ") + testing::kLcmGroup).output;
  const std::size_t dev = route.find(" dev ");
  ASSERT_NE(dev, std::string::npos) << route;
  const std::string device = route.substr(dev + 5, route.find(' ', dev + 5) - dev - 5);
  const std::string url = testing::UniqueUdpmUrl();
  const auto r = testing::RunCommand(Bridge("--lcm-url '" + url + "' --duration 0.2 --speedup 10"));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const std::string warning = "LCM " + url + ": the multicast group 239.255.76.67 is joined on " + device +
                              ": other machines on that network can send to KELVIN_HELM";
  if (device == "lo") {
    EXPECT_THAT(r.output, ::testing::Not(HasSubstr("is joined on"))) << r.output;
  } else {
    EXPECT_THAT(r.output, HasSubstr(warning)) << r.output;
  }
}

TEST(BridgeLoopback, TheDefaultUrlIsLoopbackUnlessLcmDefaultUrlSaysOtherwise) {
  EXPECT_EQ(std::string(kLoopbackLcmUrl), "udpm://239.255.76.67:7667?ttl=0");
  EXPECT_EQ(ResolveLcmUrl("memq://"), "memq://");
  const char* saved = std::getenv("LCM_DEFAULT_URL");
  const std::string keep = saved ? saved : "";
  ::unsetenv("LCM_DEFAULT_URL");
  EXPECT_EQ(ResolveLcmUrl(""), kLoopbackLcmUrl);
  ::setenv("LCM_DEFAULT_URL", "", 1);
  EXPECT_EQ(ResolveLcmUrl(""), kLoopbackLcmUrl);
  ::setenv("LCM_DEFAULT_URL", "udpm://239.255.76.67:7700?ttl=1", 1);
  EXPECT_EQ(ResolveLcmUrl(""), "udpm://239.255.76.67:7700?ttl=1");
  if (saved) {
    ::setenv("LCM_DEFAULT_URL", keep.c_str(), 1);
  } else {
    ::unsetenv("LCM_DEFAULT_URL");
  }
}

TEST(BridgeLoopback, NmeaAndTheDisplayAreOffByDefaultAndLoopbackWhenAskedFor) {
  EXPECT_FALSE(BridgeOptions{}.nmea.has_value());
  EXPECT_EQ(UdpEndpoint{}.host, "127.0.0.1");
  EXPECT_EQ(HttpDisplayOptions{}.host, "127.0.0.1");
  // --http without a value: 127.0.0.1:8080 (served, or refused if another
  // program holds the port; either way the address is loopback).
  const auto r = testing::RunCommand(Bridge("--lcm-url memq:// --http --duration 1 --speedup 100"));
  EXPECT_THAT(r.output, ::testing::AnyOf(HasSubstr("display: open http://127.0.0.1:8080/"),
                                         HasSubstr("--http 127.0.0.1:8080: cannot listen there")))
      << r.output;
}

}  // namespace
}  // namespace kelvin::bridge
