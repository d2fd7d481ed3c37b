#include "bridge/lcm_url.h"

#include <charconv>
#include <cstdlib>

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

}  // namespace kelvin::bridge
