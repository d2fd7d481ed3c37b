// Logging setup shared by every kelvin program: spdlog to stderr, with the
// level from --verbose/--quiet.
#pragma once

namespace kelvin {

enum class Verbosity { kQuiet, kNormal, kVerbose };

void InitLogging(Verbosity verbosity);

}  // namespace kelvin
