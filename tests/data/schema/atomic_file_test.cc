#include "data/schema/atomic_file.h"

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "data/schema/errors.h"

#include "tests/test_utilities/test_utilities.h"

namespace kelvin::data {
namespace {

std::string Slurp(const std::filesystem::path& p) {
  std::ifstream in(p);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

TEST(AtomicFileTest, ReplacesContentAndLeavesNoTemporary) {
  kelvin::testing::ScopedTempDir dir;
  const auto target = dir / "sub/out.yaml";
  WriteFileAtomically(target, "first\n");
  WriteFileAtomically(target, "second\n");
  EXPECT_EQ(Slurp(target), "second\n");
  int files = 0;
  for (const auto& e : std::filesystem::directory_iterator(target.parent_path())) {
    (void)e;
    ++files;
  }
  EXPECT_EQ(files, 1);
}

// The temporaries a killed writer left are removed; those of live writers
// (this process, its parent), the targets and look-alike names stay.
TEST(AtomicFileTest, StaleTemporariesOfDeadWritersAreRemoved) {
  kelvin::testing::ScopedTempDir dir;
  const pid_t child = ::fork();
  if (child == 0) ::_exit(0);
  ASSERT_GT(child, 0);
  int status = 0;
  ASSERT_EQ(::waitpid(child, &status, 0), child);  // reaped: the pid names no process now
  auto touch = [&](const std::string& name) { std::ofstream(dir / name) << "x"; };
  const std::string dead = std::to_string(child), self = std::to_string(::getpid()),
                    parent = std::to_string(::getppid());
  touch("checkpoint.h5");
  touch("checkpoint.h5.tmp." + dead + ".0");
  touch("result.h5.tmp." + dead + ".12");
  touch("checkpoint.h5.tmp." + self + ".3");
  touch("checkpoint.h5.tmp." + parent + ".1");
  touch("notes.tmp." + dead + ".x");   // not a TemporaryPathFor name
  touch("notes.tmp." + dead);          // nor this
  std::filesystem::create_directory(dir / "sub");
  touch("sub/samples.h5.tmp." + dead + ".0");  // subdirectories are not searched
  EXPECT_EQ(RemoveStaleTemporaries(dir.path()), 2);
  std::vector<std::string> left;
  for (const auto& e : std::filesystem::directory_iterator(dir.path())) {
    if (e.is_regular_file()) left.push_back(e.path().filename().string());
  }
  std::sort(left.begin(), left.end());
  std::vector<std::string> expected = {"checkpoint.h5", "checkpoint.h5.tmp." + self + ".3",
                                       "checkpoint.h5.tmp." + parent + ".1", "notes.tmp." + dead,
                                       "notes.tmp." + dead + ".x"};
  std::sort(expected.begin(), expected.end());
  EXPECT_EQ(left, expected);
  EXPECT_TRUE(std::filesystem::exists(dir / "sub" / ("samples.h5.tmp." + dead + ".0")));
  EXPECT_EQ(RemoveStaleTemporaries(dir / "missing"), 0);
}

TEST(AtomicFileTest, UnwritableDirectoryIsAnInputError) {
  EXPECT_THROW(WriteFileAtomically("/proc/kelvin_cannot_write/x.txt", "x"), InputError);
}

}  // namespace
}  // namespace kelvin::data
