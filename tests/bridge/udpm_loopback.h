// LCM's udpm:// provider on loopback for the inter-process and flood tests:
// whether this machine can carry it, and a URL of its own per test (a
// random port, TTL 0 so nothing leaves the machine).
#pragma once

#include <random>
#include <string>

#include "tests/test_utilities/test_utilities.h"

namespace kelvin::testing {

constexpr const char* kLcmGroup = "239.255.76.67";

// Empty when multicast to kLcmGroup has a route; otherwise why not.
inline std::string MulticastProblem() {
  const std::string check = std::string("ip route get ") + kLcmGroup + " >/dev/null 2>&1";
  if (RunCommand(check).exit_code == 0) return "";
  // Root may add the route for the test (CI containers often have none).
  RunCommand("ip route add 224.0.0.0/4 dev lo");
  if (RunCommand(check).exit_code == 0) return "";
  return "no multicast route on this machine; add one with 'ip route add 224.0.0.0/4 dev lo' (as root)";
}

inline std::string UniqueUdpmUrl() {
  std::random_device rd;
  const int port = 20000 + static_cast<int>(rd() % 20000);
  return "udpm://" + std::string(kLcmGroup) + ":" + std::to_string(port) + "?ttl=0";
}

}  // namespace kelvin::testing
