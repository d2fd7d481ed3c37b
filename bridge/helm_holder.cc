#include "bridge/helm_holder.h"

#include <fmt/format.h>

#include <cmath>

#include "data/schema/errors.h"

namespace kelvin::bridge {

namespace {

// Compares in time independent of where the texts differ.
bool SameToken(std::string_view a, std::string_view b) {
  if (a.size() != b.size() || a.empty()) return false;
  unsigned char diff = 0;
  for (std::size_t i = 0; i < a.size(); ++i) diff |= static_cast<unsigned char>(a[i] ^ b[i]);
  return diff == 0;
}

}  // namespace

HelmHolder::HelmHolder(double lapse) : lapse_ns_(std::llround(lapse * 1e9)) {
  KELVIN_CHECK(lapse > 0, "the helm lapse must be positive");
}

bool HelmHolder::HeldLocked(std::int64_t now_ns) const {
  return !token_.empty() && now_ns - last_ns_ < lapse_ns_;
}

std::optional<std::string> HelmHolder::Claim(std::int64_t now_ns) {
  std::lock_guard<std::mutex> lock(mutex_);
  if (HeldLocked(now_ns)) return std::nullopt;
  token_.clear();
  for (int i = 0; i < 4; ++i) token_ += fmt::format("{:08x}", random_());  // 128 bits
  last_ns_ = now_ns;
  return token_;
}

bool HelmHolder::Holds(std::string_view token, std::int64_t now_ns) {
  std::lock_guard<std::mutex> lock(mutex_);
  if (!HeldLocked(now_ns) || !SameToken(token, token_)) return false;
  last_ns_ = now_ns;
  return true;
}

bool HelmHolder::Release(std::string_view token, std::int64_t now_ns) {
  std::lock_guard<std::mutex> lock(mutex_);
  if (!HeldLocked(now_ns) || !SameToken(token, token_)) return false;
  token_.clear();
  return true;
}

bool HelmHolder::held(std::int64_t now_ns) const {
  std::lock_guard<std::mutex> lock(mutex_);
  return HeldLocked(now_ns);
}

}  // namespace kelvin::bridge
