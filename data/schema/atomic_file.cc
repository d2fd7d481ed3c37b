#include "data/schema/atomic_file.h"

#include <fcntl.h>
#include <signal.h>
#include <unistd.h>

#include <atomic>
#include <cctype>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <string>

#include "data/schema/errors.h"

namespace kelvin::data {

namespace fs = std::filesystem;

fs::path TemporaryPathFor(const fs::path& target) {
  static std::atomic<unsigned> counter{0};
  fs::path tmp = target;
  tmp += ".tmp." + std::to_string(::getpid()) + "." + std::to_string(counter++);
  return tmp;
}

namespace {

// The writer's pid of a TemporaryPathFor name "<target>.tmp.<pid>.<n>", or -1.
long TemporaryOwner(const std::string& name) {
  const std::size_t at = name.rfind(".tmp.");
  if (at == std::string::npos) return -1;
  const std::string tail = name.substr(at + 5);
  const std::size_t dot = tail.find('.');
  if (dot == 0 || dot == std::string::npos || dot + 1 == tail.size()) return -1;
  for (std::size_t i = 0; i < tail.size(); ++i) {
    if (i != dot && !std::isdigit(static_cast<unsigned char>(tail[i]))) return -1;
  }
  return std::stol(tail.substr(0, dot));
}

}  // namespace

int RemoveStaleTemporaries(const fs::path& dir) {
  std::error_code ec;
  int removed = 0;
  for (const fs::directory_entry& e : fs::directory_iterator(dir, ec)) {
    if (!e.is_regular_file(ec)) continue;
    const long pid = TemporaryOwner(e.path().filename().string());
    if (pid <= 0 || pid == ::getpid()) continue;
    if (::kill(static_cast<pid_t>(pid), 0) == 0 || errno != ESRCH) continue;  // alive (or not ours to judge)
    if (fs::remove(e.path(), ec)) ++removed;
  }
  return removed;
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
