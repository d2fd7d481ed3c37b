#include "data/schema/atomic_file.h"

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

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

TEST(AtomicFileTest, UnwritableDirectoryIsAnInputError) {
  EXPECT_THROW(WriteFileAtomically("/proc/kelvin_cannot_write/x.txt", "x"), InputError);
}

}  // namespace
}  // namespace kelvin::data
