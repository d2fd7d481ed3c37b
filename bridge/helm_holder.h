// Who holds the helm of the browser display: one page at a time, known by
// an unguessable token that the page got when it claimed the helm. A holder
// that sends nothing for `lapse` seconds loses the helm, so a closed page
// does not keep it. Thread-safe (the HTTP threads share it).
#pragma once

#include <cstdint>
#include <mutex>
#include <optional>
#include <random>
#include <string>
#include <string_view>

namespace kelvin::bridge {

class HelmHolder {
 public:
  explicit HelmHolder(double lapse = 10.0);  // s

  // A new token if the helm is free (or its holder lapsed), else nullopt.
  std::optional<std::string> Claim(std::int64_t now_ns);
  // True if `token` holds the helm at `now_ns`; refreshes the holder.
  bool Holds(std::string_view token, std::int64_t now_ns);
  // Frees the helm if `token` holds it.
  bool Release(std::string_view token, std::int64_t now_ns);
  bool held(std::int64_t now_ns) const;

 private:
  bool HeldLocked(std::int64_t now_ns) const;
  std::int64_t lapse_ns_;
  mutable std::mutex mutex_;
  std::random_device random_;
  std::string token_;  // empty: free
  std::int64_t last_ns_ = 0;
};

}  // namespace kelvin::bridge
