// Typed exceptions for bad user input. Every message names the file (or the
// CLI argument / LCM field), the key, the offending value and what was
// expected; the program prints it once and exits non-zero.
#pragma once

#include <stdexcept>
#include <string>

namespace kelvin {

// Base of every error caused by what the user gave us (files, arguments,
// messages). Internal invariant violations use KELVIN_CHECK instead.
class InputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// A YAML case, ship or derivative file: unknown key, wrong type, bad value.
class ConfigError : public InputError {
 public:
  using InputError::InputError;
};

// A data file: HDF5, CSV, mesh, STL.
class DataFileError : public InputError {
 public:
  using InputError::InputError;
};

// A command-line argument.
class ArgumentError : public InputError {
 public:
  using InputError::InputError;
};

// A parameter set that is readable but not physical (negative mass, ...).
class ModelError : public InputError {
 public:
  using InputError::InputError;
};

[[noreturn]] void CheckFailed(const char* expr, const char* file, int line, const std::string& msg);

}  // namespace kelvin

// Always-on invariant check: aborts with file and line. For programming
// errors only, never for user input.
#define KELVIN_CHECK(cond, msg)                                 \
  do {                                                          \
    if (!(cond)) ::kelvin::CheckFailed(#cond, __FILE__, __LINE__, (msg)); \
  } while (false)
