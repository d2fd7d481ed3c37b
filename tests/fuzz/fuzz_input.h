// What every fuzz target shares: the input as text, a scratch file for the
// readers that only open files, and the rule that a kelvin::InputError is the
// reader's answer to bad input while anything else (another exception, a
// crash, a sanitizer report) is a defect.
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>

#include "data/schema/errors.h"

namespace kelvin::fuzz {

inline std::string Text(const std::uint8_t* data, std::size_t size) {
  return std::string(reinterpret_cast<const char*>(data), size);
}

// A per-process directory under the temporary directory, created once.
std::filesystem::path ScratchDirectory();

// Writes the input to ScratchDirectory() / name and returns the path.
std::filesystem::path ScratchFile(const std::string& name, const std::uint8_t* data, std::size_t size);

// Runs `read`; an InputError is expected, every other exception escapes.
template <typename Read>
void ExpectInputError(Read&& read) {
  try {
    read();
  } catch (const kelvin::InputError&) {
  }
}

}  // namespace kelvin::fuzz
