// YAML configuration access with precise errors. Every lookup knows the file,
// the line and the dotted key path, so a mistake in a case or ship file is
// reported as e.g.
//   ship.yaml:14: unknown key 'hull.Y_vv'; valid keys: R0_prime, X_vv, ... (did you mean 'X_vv'?)
#pragma once

#include <yaml-cpp/yaml.h>

#include <filesystem>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "data/schema/errors.h"

namespace kelvin::data {

class ConfigNode {
 public:
  // Loads a YAML file; a missing file or a syntax error is a ConfigError.
  static ConfigNode LoadFile(const std::filesystem::path& path);
  // Parses YAML text; `source` names it in messages (a file name or "<cli>").
  static ConfigNode LoadString(const std::string& text, const std::string& source);

  // The child map or value at `key`; a ConfigError if it is absent.
  ConfigNode operator[](std::string_view key) const;
  // The child at `key`, or nullopt if absent.
  std::optional<ConfigNode> Find(std::string_view key) const;
  bool Has(std::string_view key) const;

  // Required scalar at `key`.
  template <typename T>
  T Get(std::string_view key) const {
    return (*this)[key].As<T>();
  }
  // Optional scalar at `key` with a default.
  template <typename T>
  T Get(std::string_view key, const T& fallback) const {
    auto child = Find(key);
    return child ? child->As<T>() : fallback;
  }
  // Required number at `key` that must be > 0 (or >= 0 when allow_zero).
  double GetPositive(std::string_view key, bool allow_zero = false) const;

  // This node converted to T; a ConfigError naming the key and the value if
  // the conversion fails (e.g. "abc" where a number is expected).
  template <typename T>
  T As() const;

  // Fails with "unknown key" if the map has any key outside `valid`.
  void ExpectKeys(std::initializer_list<std::string_view> valid) const;
  void ExpectKeys(std::span<const std::string> valid) const;

  bool IsMap() const { return node_.IsMap(); }
  bool IsSequence() const { return node_.IsSequence(); }
  bool IsScalar() const { return node_.IsScalar(); }
  std::size_t size() const { return node_.size(); }
  // Elements of a sequence (a ConfigError if this is not a sequence).
  std::vector<ConfigNode> Items() const;
  // Keys of a map in file order.
  std::vector<std::string> Keys() const;

  // "file:line" of this node, for messages.
  std::string Where() const;
  const std::string& path() const { return path_; }
  const std::string& source() const { return source_; }
  std::string ScalarText() const;
  const YAML::Node& yaml() const { return node_; }

  // Throws a ConfigError "<file>:<line>: key '<path>' = <value>: <expected>".
  [[noreturn]] void Fail(const std::string& expected) const;

 private:
  ConfigNode(YAML::Node node, std::string source, std::string path)
      : node_(std::move(node)), source_(std::move(source)), path_(std::move(path)) {}
  std::string ChildPath(std::string_view key) const;

  YAML::Node node_;
  std::string source_;
  std::string path_;
};

// The closest candidate by edit distance, if it is close enough to suggest.
std::optional<std::string> ClosestMatch(std::string_view word, std::span<const std::string> candidates);

template <>
double ConfigNode::As<double>() const;
template <>
int ConfigNode::As<int>() const;
template <>
bool ConfigNode::As<bool>() const;
template <>
std::string ConfigNode::As<std::string>() const;
template <>
std::vector<double> ConfigNode::As<std::vector<double>>() const;

}  // namespace kelvin::data
