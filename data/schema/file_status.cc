#include "data/schema/file_status.h"

#include <system_error>

namespace kelvin::data {

bool PathExists(const std::filesystem::path& path) {
  std::error_code ec;
  return std::filesystem::exists(path, ec) && !ec;
}

bool IsExistingDirectory(const std::filesystem::path& path) {
  std::error_code ec;
  return std::filesystem::is_directory(path, ec) && !ec;
}

}  // namespace kelvin::data
