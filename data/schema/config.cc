#include "data/schema/config.h"

#include "data/schema/file_status.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <ios>

namespace kelvin::data {

namespace {

// The edit distance of a and b if it is below `bound`, else `bound` (or more):
// a candidate that cannot beat the best so far is given up early. `prev` and
// `cur` are scratch rows, kept across candidates.
std::size_t EditDistance(std::string_view a, std::string_view b, std::size_t bound, std::vector<std::size_t>& prev,
                         std::vector<std::size_t>& cur) {
  // The distance is at least the difference of the lengths.
  if ((a.size() > b.size() ? a.size() - b.size() : b.size() - a.size()) >= bound) return bound;
  prev.resize(b.size() + 1);
  cur.resize(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) prev[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    cur[0] = i;
    std::size_t row_min = cur[0];
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t sub = prev[j - 1] + (a[i - 1] == b[j - 1] ? 0 : 1);
      cur[j] = std::min({prev[j] + 1, cur[j - 1] + 1, sub});
      row_min = std::min(row_min, cur[j]);
    }
    // No entry of a later row is below this row's minimum.
    if (row_min >= bound) return bound;
    std::swap(prev, cur);
  }
  return prev[b.size()];
}

// The text of a map key of `map_path`; a ConfigError if the key is a list or
// a map (YAML allows both, kelvin's files use names).
std::string KeyName(const YAML::Node& key, const std::string& source, const std::string& map_path) {
  if (!key.IsScalar()) {
    throw ConfigError(fmt::format("{}:{}: a {} is used as a key in {}; expected a key name", source,
                                  key.Mark().line + 1, key.IsMap() ? "map" : "list",
                                  map_path.empty() ? "the top level" : "'" + map_path + "'"));
  }
  return key.Scalar();
}

}  // namespace

std::optional<std::string> ClosestMatch(std::string_view word, std::span<const std::string> candidates) {
  std::optional<std::string> best;
  std::size_t best_d = std::max<std::size_t>(2, word.size() / 3) + 1;
  std::vector<std::size_t> prev, cur;
  for (const auto& c : candidates) {
    const std::size_t d = EditDistance(word, c, best_d, prev, cur);
    if (d < best_d) {
      best_d = d;
      best = c;
    }
  }
  return best;
}

ConfigNode ConfigNode::LoadFile(const std::filesystem::path& path) {
  if (!data::PathExists(path)) {
    throw ConfigError(fmt::format("{}: file not found", path.string()));
  }
  if (data::IsExistingDirectory(path)) {
    throw ConfigError(fmt::format("{}: is a directory; expected a YAML file", path.string()));
  }
  try {
    return ConfigNode(YAML::LoadFile(path.string()), path.string(), "");
  } catch (const YAML::Exception& e) {
    throw ConfigError(fmt::format("{}:{}: YAML syntax error: {}", path.string(), e.mark.line + 1, e.msg));
  } catch (const std::ios_base::failure& e) {
    // A read error of the stream (a special file, an I/O error) escapes yaml-cpp as the stream's own exception.
    throw ConfigError(fmt::format("{}: cannot be read ({}); expected a YAML file", path.string(), e.what()));
  }
}

ConfigNode ConfigNode::LoadString(const std::string& text, const std::string& source) {
  try {
    return ConfigNode(YAML::Load(text), source, "");
  } catch (const YAML::Exception& e) {
    throw ConfigError(fmt::format("{}:{}: YAML syntax error: {}", source, e.mark.line + 1, e.msg));
  }
}

std::string ConfigNode::ChildPath(std::string_view key) const {
  return path_.empty() ? std::string(key) : path_ + "." + std::string(key);
}

std::string ConfigNode::Where() const {
  const auto mark = node_.Mark();
  if (mark.line < 0) return source_;
  return fmt::format("{}:{}", source_, mark.line + 1);
}

std::string ConfigNode::ScalarText() const {
  if (!node_.IsDefined() || node_.IsNull()) return "(empty)";
  if (node_.IsScalar()) return "'" + node_.Scalar() + "'";
  if (node_.IsMap()) return "(a map)";
  return "(a list)";
}

void ConfigNode::Fail(const std::string& expected) const {
  throw ConfigError(fmt::format("{}: key '{}' = {}: expected {}", Where(), path_.empty() ? "(top level)" : path_,
                                ScalarText(), expected));
}

std::optional<ConfigNode> ConfigNode::Find(std::string_view key) const {
  if (!node_.IsMap()) return std::nullopt;
  const std::string k(key);
  YAML::Node child = node_[k];
  if (!child.IsDefined()) return std::nullopt;
  return ConfigNode(child, source_, ChildPath(key));
}

bool ConfigNode::Has(std::string_view key) const { return Find(key).has_value(); }

ConfigNode ConfigNode::operator[](std::string_view key) const {
  if (!node_.IsMap()) {
    Fail(fmt::format("a map containing key '{}'", key));
  }
  auto child = Find(key);
  if (!child) {
    throw ConfigError(fmt::format("{}: missing required key '{}'", Where(), ChildPath(key)));
  }
  return *child;
}

double ConfigNode::GetPositive(std::string_view key, bool allow_zero) const {
  const ConfigNode child = (*this)[key];
  const double v = child.As<double>();
  if (allow_zero ? !(v >= 0.0) : !(v > 0.0)) {
    child.Fail(allow_zero ? "a non-negative number" : "a positive number");
  }
  return v;
}

template <>
double ConfigNode::As<double>() const {
  if (!node_.IsScalar()) Fail("a number");
  try {
    const double v = node_.as<double>();
    if (!std::isfinite(v)) Fail("a finite number");
    return v;
  } catch (const YAML::Exception&) {
    Fail("a number");
  }
}

template <>
int ConfigNode::As<int>() const {
  if (!node_.IsScalar()) Fail("an integer");
  try {
    return node_.as<int>();
  } catch (const YAML::Exception&) {
    Fail("an integer");
  }
}

template <>
bool ConfigNode::As<bool>() const {
  if (!node_.IsScalar()) Fail("true or false");
  try {
    return node_.as<bool>();
  } catch (const YAML::Exception&) {
    Fail("true or false");
  }
}

template <>
std::string ConfigNode::As<std::string>() const {
  if (!node_.IsScalar()) Fail("a string");
  return node_.Scalar();
}

template <>
std::vector<double> ConfigNode::As<std::vector<double>>() const {
  if (!node_.IsSequence()) Fail("a list of numbers");
  std::vector<double> out;
  for (const auto& item : Items()) out.push_back(item.As<double>());
  return out;
}

std::vector<ConfigNode> ConfigNode::Items() const {
  if (!node_.IsSequence()) Fail("a list");
  std::vector<ConfigNode> out;
  for (std::size_t i = 0; i < node_.size(); ++i) {
    out.push_back(ConfigNode(node_[i], source_, fmt::format("{}[{}]", path_, i)));
  }
  return out;
}

std::vector<std::string> ConfigNode::Keys() const {
  std::vector<std::string> keys;
  if (!node_.IsMap()) return keys;
  for (const auto& kv : node_) keys.push_back(KeyName(kv.first, source_, path_));
  return keys;
}

void ConfigNode::ExpectKeys(std::initializer_list<std::string_view> valid) const {
  // The list as strings only when a key is outside it (the error names them).
  if (node_.IsMap()) {
    bool all_valid = true;
    for (const auto& kv : node_) {
      if (std::find(valid.begin(), valid.end(), KeyName(kv.first, source_, path_)) == valid.end()) {
        all_valid = false;
        break;
      }
    }
    if (all_valid) return;
  }
  std::vector<std::string> v(valid.begin(), valid.end());
  ExpectKeys(std::span<const std::string>(v));
}

void ConfigNode::ExpectKeys(std::span<const std::string> valid) const {
  if (!node_.IsMap()) {
    if (node_.IsNull() || !node_.IsDefined()) return;
    Fail("a map");
  }
  for (const auto& kv : node_) {
    const std::string key = KeyName(kv.first, source_, path_);
    if (std::find(valid.begin(), valid.end(), key) != valid.end()) continue;
    const auto mark = kv.first.Mark();
    std::string msg = fmt::format("{}:{}: unknown key '{}'; valid keys: {}", source_, mark.line + 1,
                                  ChildPath(key), fmt::join(valid, ", "));
    if (auto guess = ClosestMatch(key, valid)) msg += fmt::format(" (did you mean '{}'?)", *guess);
    throw ConfigError(msg);
  }
}

}  // namespace kelvin::data
