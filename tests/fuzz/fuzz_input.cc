#include "tests/fuzz/fuzz_input.h"

#include <unistd.h>

#include <cstdlib>
#include <fstream>
#include <system_error>

namespace kelvin::fuzz {
namespace {

const std::filesystem::path* scratch = nullptr;  // removed at exit

void RemoveScratch() {
  std::error_code ignored;
  std::filesystem::remove_all(*scratch, ignored);
}

}  // namespace

std::filesystem::path ScratchDirectory() {
  static const std::filesystem::path dir = [] {
    auto d = std::filesystem::temp_directory_path() / ("kelvin_fuzz_" + std::to_string(getpid()));
    std::filesystem::create_directories(d);
    scratch = new std::filesystem::path(d);
    std::atexit(RemoveScratch);
    return d;
  }();
  return dir;
}

std::filesystem::path ScratchFile(const std::string& name, const std::uint8_t* data, std::size_t size) {
  const std::filesystem::path path = ScratchDirectory() / name;
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  return path;
}

}  // namespace kelvin::fuzz
