// Writing the `check` section of a derivative set (the layout is in
// simulator/mmg/derivative_set.h). kelvin check writes it after comparing
// the set's surrogate with reference runs; the bridge reads it
// (bridge/derivative_set.h).
#pragma once

#include <filesystem>
#include <string>

#include "simulator/mmg/derivative_set.h"

namespace kelvin::sim {

// The section as YAML text ("check:\n  passed: ...\n"); a multi-line
// summary is a literal block, one line per maneuver.
std::string FormatDerivativeCheck(const DerivativeCheck& check);

// `text` (a derivative file named `source`) with its top-level `check`
// section replaced by `check`, or with the section appended if it has none.
// Every other line, comments included, is kept as it was. The result is
// parsed back as a derivative set; a kelvin::ConfigError names `source` if it
// does not load or does not carry `check`.
std::string WithDerivativeCheck(const std::string& text, const DerivativeCheck& check, const std::string& source);

// Replaces (or adds) the check section of the derivative file at `path`,
// atomically: a crash leaves the old file. A missing or invalid file is a
// kelvin::ConfigError naming it.
void WriteDerivativeCheck(const std::filesystem::path& path, const DerivativeCheck& check);

}  // namespace kelvin::sim
