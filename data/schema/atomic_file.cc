#include "data/schema/atomic_file.h"

#include <fcntl.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstring>
#include <fstream>

#include "data/schema/errors.h"

namespace kelvin::data {

namespace fs = std::filesystem;

fs::path TemporaryPathFor(const fs::path& target) {
  static std::atomic<unsigned> counter{0};
  fs::path tmp = target;
  tmp += ".tmp." + std::to_string(::getpid()) + "." + std::to_string(counter++);
  return tmp;
}

void CommitFile(const fs::path& tmp, const fs::path& target) {
  std::error_code ec;
  if (target.has_parent_path()) fs::create_directories(target.parent_path(), ec);
  fs::rename(tmp, target, ec);
  if (ec) {
    fs::remove(tmp, ec);
    throw DataFileError("cannot write '" + target.string() + "': " + ec.message());
  }
}

void WriteFileAtomically(const fs::path& target, std::string_view content) {
  std::error_code ec;
  if (target.has_parent_path()) fs::create_directories(target.parent_path(), ec);
  const fs::path tmp = TemporaryPathFor(target);
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    if (!out) {
      throw DataFileError("cannot write '" + target.string() + "': cannot create temporary file '" +
                          tmp.string() + "': " + std::strerror(errno));
    }
    out.write(content.data(), static_cast<std::streamsize>(content.size()));
    out.flush();
    if (!out) {
      out.close();
      fs::remove(tmp, ec);
      throw DataFileError("cannot write '" + target.string() + "': write failed");
    }
  }
  const int fd = ::open(tmp.c_str(), O_RDONLY);
  if (fd >= 0) {
    ::fsync(fd);
    ::close(fd);
  }
  CommitFile(tmp, target);
}

}  // namespace kelvin::data
