// Shared helpers for kelvin tests: scratch directories, paths of the source
// and build trees, and running a program to check its exit code and output.
#pragma once

#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <string>

namespace kelvin::testing {

// A fresh directory under the system temp dir, removed on destruction.
class ScopedTempDir {
 public:
  ScopedTempDir() {
    std::random_device rd;
    path_ = std::filesystem::temp_directory_path() / ("kelvin_test_" + std::to_string(rd()) + std::to_string(rd()));
    std::filesystem::create_directories(path_);
  }
  ~ScopedTempDir() {
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
  }
  ScopedTempDir(const ScopedTempDir&) = delete;
  ScopedTempDir& operator=(const ScopedTempDir&) = delete;
  const std::filesystem::path& path() const { return path_; }
  std::filesystem::path operator/(const std::string& name) const { return path_ / name; }

 private:
  std::filesystem::path path_;
};

inline std::filesystem::path EnvPath(const char* var, const char* fallback) {
  const char* v = std::getenv(var);
  return v ? std::filesystem::path(v) : std::filesystem::path(fallback);
}

#ifndef KELVIN_DEFAULT_SOURCE_DIR
#define KELVIN_DEFAULT_SOURCE_DIR "."
#endif
#ifndef KELVIN_DEFAULT_TOOLS_DIR
#define KELVIN_DEFAULT_TOOLS_DIR "./tools"
#endif

// The repository root (set by ctest, or compiled in for direct runs).
inline std::filesystem::path SourceDir() { return EnvPath("KELVIN_SOURCE_DIR", KELVIN_DEFAULT_SOURCE_DIR); }
// The directory holding the built `kelvin` program.
inline std::filesystem::path ToolsDir() { return EnvPath("KELVIN_TOOLS_DIR", KELVIN_DEFAULT_TOOLS_DIR); }

// The whole content of a file (empty if it cannot be read).
inline std::string ReadText(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

struct CommandResult {
  int exit_code = -1;
  std::string output;  // stdout and stderr together
};

// Runs a shell command and captures its combined output.
inline CommandResult RunCommand(const std::string& command) {
  CommandResult result;
  FILE* pipe = ::popen((command + " 2>&1").c_str(), "r");
  if (!pipe) return result;
  std::array<char, 4096> buf{};
  std::size_t n = 0;
  while ((n = std::fread(buf.data(), 1, buf.size(), pipe)) > 0) result.output.append(buf.data(), n);
  const int status = ::pclose(pipe);
  result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return result;
}

inline bool HaveProgram(const std::string& name) {
  return RunCommand("command -v " + name + " >/dev/null").exit_code == 0;
}

}  // namespace kelvin::testing
