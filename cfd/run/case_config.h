// Small readers shared by the case-file loaders of cfd/run.
#pragma once

#include <initializer_list>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "cfd/mesh/mesh.h"
#include "data/schema/config.h"
#include "data/schema/errors.h"

namespace kelvin::cfd {

using data::ConfigNode;

inline Vector3 GetVector(const ConfigNode& node, std::string_view key) {
  const std::vector<double> v = node[key].As<std::vector<double>>();
  if (v.size() != 3) node[key].Fail("a list of 3 numbers");
  return Vector3(v[0], v[1], v[2]);
}

// The enum value whose name the key holds (fallback when absent).
template <typename E>
E GetEnum(const ConfigNode& node, std::string_view key, E fallback,
          std::initializer_list<std::pair<const char*, E>> choices) {
  if (!node.Has(key)) return fallback;
  const std::string text = node.Get<std::string>(key);
  std::string names;
  for (const auto& [name, value] : choices) {
    if (text == name) return value;
    names += (names.empty() ? "" : ", ") + std::string(name);
  }
  node[key].Fail("one of " + names);
}

// Calls `validate` and turns its ConfigError into one naming `node`.
template <typename F>
void ValidateAt(const ConfigNode& node, F&& validate) {
  try {
    validate();
  } catch (const ConfigError& e) {
    node.Fail(e.what());
  }
}

}  // namespace kelvin::cfd
