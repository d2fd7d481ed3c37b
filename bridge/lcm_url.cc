#include "bridge/lcm_url.h"

#include <arpa/inet.h>
#include <fmt/format.h>

#include <charconv>
#include <cstdlib>
#include <sstream>

namespace kelvin::bridge {

std::string ResolveLcmUrl(const std::string& given) {
  if (!given.empty()) return given;
  const char* env = std::getenv("LCM_DEFAULT_URL");
  return env && *env ? std::string(env) : std::string(kLoopbackLcmUrl);
}

std::optional<int> UdpmTtl(std::string_view url) {
  if (url.substr(0, 7) != "udpm://") return std::nullopt;
  const std::size_t query = url.find('?');
  if (query == std::string_view::npos) return 0;
  std::string_view rest = url.substr(query + 1);
  while (!rest.empty()) {
    const std::size_t amp = rest.find('&');
    const std::string_view arg = rest.substr(0, amp);
    if (arg.substr(0, 4) == "ttl=") {
      int ttl = -1;
      const std::string_view v = arg.substr(4);
      const auto [end, ec] = std::from_chars(v.data(), v.data() + v.size(), ttl);
      if (ec != std::errc() || end != v.data() + v.size() || ttl < 0) return std::nullopt;
      return ttl;
    }
    rest = amp == std::string_view::npos ? std::string_view() : rest.substr(amp + 1);
  }
  return 0;
}

std::optional<std::string> UdpmGroup(std::string_view url) {
  if (url.substr(0, 7) != "udpm://") return std::nullopt;
  const std::string_view target = url.substr(7, url.find_first_of(":?", 7) - 7);
  return std::string(target.empty() ? "239.255.76.67" : target);
}

std::vector<std::string> MulticastMembers(std::string_view igmp, std::string_view group) {
  in_addr a{};
  if (inet_pton(AF_INET, std::string(group).c_str(), &a) != 1) return {};
  // The kernel prints the group's 32 bits as they lie in memory.
  const std::string wanted = fmt::format("{:08X}", a.s_addr);
  std::vector<std::string> members;
  std::istringstream in{std::string(igmp)};
  std::string line, device;
  while (std::getline(in, line)) {
    if (line.empty()) continue;
    std::istringstream f(line);
    if (line[0] != '\t') {  // "<index>\t<device> : <count> <querier>"
      std::string index;
      f >> index >> device;
      continue;
    }
    std::string hex;
    f >> hex;
    if (hex == wanted && (members.empty() || members.back() != device)) members.push_back(device);
  }
  return members;
}

}  // namespace kelvin::bridge
