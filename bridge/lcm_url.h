// The LCM URL of `kelvin bridge` and `kelvin listen` and what it exposes:
// without --lcm-url, LCM_DEFAULT_URL if it is set (LCM's own convention),
// else udpm:// with TTL 0, so that nothing the bridge sends leaves this
// machine. What it receives is another matter: LCM joins the multicast group
// on the interface the route names, so where multicast routes to a network
// interface, other machines there can send to the bridge.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace kelvin::bridge {

constexpr const char* kLoopbackLcmUrl = "udpm://239.255.76.67:7667?ttl=0";

// `given` if not empty, else $LCM_DEFAULT_URL if set and not empty, else kLoopbackLcmUrl.
std::string ResolveLcmUrl(const std::string& given);
// The multicast TTL of a udpm:// URL (LCM's 0 without ttl=); nullopt for
// other providers or a ttl that is not a number.
std::optional<int> UdpmTtl(std::string_view url);
// The multicast group of a udpm:// URL ("239.255.76.67"); nullopt for other providers.
std::optional<std::string> UdpmGroup(std::string_view url);
// The interfaces that have joined the IPv4 multicast `group`, from text in
// the format of /proc/net/igmp.
std::vector<std::string> MulticastMembers(std::string_view igmp, std::string_view group);

}  // namespace kelvin::bridge
