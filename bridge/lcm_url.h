// The LCM URL of `kelvin bridge` and `kelvin listen`: without --lcm-url,
// LCM_DEFAULT_URL if it is set (LCM's own convention), else udpm:// with
// TTL 0, so that nothing leaves this machine unless the user asks for it.
#pragma once

#include <optional>
#include <string>
#include <string_view>

namespace kelvin::bridge {

constexpr const char* kLoopbackLcmUrl = "udpm://239.255.76.67:7667?ttl=0";

// `given` if not empty, else $LCM_DEFAULT_URL if set and not empty, else kLoopbackLcmUrl.
std::string ResolveLcmUrl(const std::string& given);
// The multicast TTL of a udpm:// URL (LCM's 0 without ttl=); nullopt for
// other providers or a ttl that is not a number.
std::optional<int> UdpmTtl(std::string_view url);

}  // namespace kelvin::bridge
