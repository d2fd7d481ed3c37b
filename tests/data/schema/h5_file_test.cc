#include "data/schema/h5_file.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fstream>
#include <stdexcept>
#include <string>

#include "data/schema/errors.h"
#include "tests/test_utilities/test_utilities.h"

namespace kelvin::data {
namespace {

using kelvin::testing::ScopedTempDir;
using ::testing::HasSubstr;

TEST(H5FileTest, RoundTripValuesAndAttributes) {
  ScopedTempDir dir;
  const auto path = dir / "run.h5";
  {
    H5Writer w(path);
    w.DeclareSeries("time", "s", "simulation time");
    w.DeclareSeries("forces/hull", "N", "X, Y, N of the hull", 3);
    for (int i = 0; i < 5000; ++i) {  // more than one chunk
      const double t = 0.01 * i;
      w.Append("time", std::span<const double>(&t, 1));
      const double f[3] = {-t, 2 * t, 3 * t};
      w.Append("forces/hull", f);
    }
    w.SetAttribute("/", "ship", "KVLCC2");
    w.SetAttribute("/forces", "rho", 1025.0);
    w.WriteArray("grid/xy", std::vector<double>{1, 2, 3, 4, 5, 6}, {2, 3}, "m", "points");
    w.WriteStrings("names", {"a", "bb"}, "labels");
    w.Commit();
  }
  H5Reader r(path);
  const Series t = r.Read("time");
  ASSERT_EQ(t.rows, 5000u);
  EXPECT_EQ(t.cols, 1u);
  EXPECT_EQ(t.units, "s");
  EXPECT_EQ(t.description, "simulation time");
  EXPECT_DOUBLE_EQ(t.at(4321), 43.21);
  const Series f = r.Read("forces/hull");
  ASSERT_EQ(f.rows, 5000u);
  ASSERT_EQ(f.cols, 3u);
  EXPECT_DOUBLE_EQ(f.at(10, 2), 0.3);
  EXPECT_EQ(f.units, "N");
  EXPECT_EQ(r.StringAttribute("/", "ship"), "KVLCC2");
  EXPECT_DOUBLE_EQ(r.NumberAttribute("/forces", "rho"), 1025.0);
  EXPECT_EQ(r.Read("grid/xy").cols, 3u);
  EXPECT_EQ(r.ReadStrings("names"), (std::vector<std::string>{"a", "bb"}));
  EXPECT_EQ(r.List("/"), (std::vector<std::string>{"time", "forces", "grid", "names"}));
  EXPECT_FALSE(r.Has("forces/propeller"));
  EXPECT_FALSE(r.Has("nothing/here"));
}

TEST(H5FileTest, AppendModeExtendsExistingFile) {
  ScopedTempDir dir;
  const auto path = dir / "series.h5";
  {
    H5Writer w(path);
    w.DeclareSeries("x", "m", "position");
    w.Append("x", std::vector<double>{1, 2, 3});
    w.Commit();
  }
  {
    H5Writer w(path, H5Writer::Mode::kAppend);
    w.DeclareSeries("x", "m", "position");  // same width: accepted
    w.Append("x", std::vector<double>{4, 5});
    w.Commit();
  }
  const Series x = H5Reader(path).Read("x");
  EXPECT_EQ(x.values, (std::vector<double>{1, 2, 3, 4, 5}));
}

TEST(H5FileTest, ExceptionBeforeCommitLeavesOldFileIntact) {
  ScopedTempDir dir;
  const auto path = dir / "result.h5";
  {
    H5Writer w(path);
    w.DeclareSeries("x", "m", "position");
    w.Append("x", std::vector<double>{1, 2, 3});
    w.Commit();
  }
  // A writer killed mid-write (here: by an exception) must not touch the
  // committed file, nor leave its temporary behind.
  try {
    H5Writer w(path, H5Writer::Mode::kAppend);
    w.DeclareSeries("x", "m", "position");
    w.Append("x", std::vector<double>{99, 98});
    w.Flush();
    H5Writer w2(path);
    w2.DeclareSeries("y", "m", "other");
    throw std::runtime_error("killed");
  } catch (const std::runtime_error&) {
  }
  const Series x = H5Reader(path).Read("x");
  EXPECT_EQ(x.values, (std::vector<double>{1, 2, 3}));
  EXPECT_FALSE(H5Reader(path).Has("y"));
  int files = 0;
  for (const auto& e : std::filesystem::directory_iterator(dir.path())) {
    (void)e;
    ++files;
  }
  EXPECT_EQ(files, 1) << "a temporary file was left behind";
}

TEST(H5FileTest, WidthMismatchIsAnError) {
  ScopedTempDir dir;
  H5Writer w(dir / "a.h5");
  w.DeclareSeries("f", "N", "force", 3);
  EXPECT_THROW(w.DeclareSeries("f", "N", "force", 2), DataFileError);
  EXPECT_THROW(w.Append("g", std::vector<double>{1.0}), DataFileError);
}

TEST(H5FileTest, ReadingMissingOrBadFilesNamesThem) {
  ScopedTempDir dir;
  try {
    H5Reader r(dir / "missing.h5");
    FAIL();
  } catch (const DataFileError& e) {
    EXPECT_THAT(e.what(), HasSubstr("missing.h5: file not found"));
  }
  const auto bogus = dir / "bogus.h5";
  std::ofstream(bogus) << "not hdf5";
  try {
    H5Reader r(bogus);
    FAIL();
  } catch (const DataFileError& e) {
    EXPECT_THAT(e.what(), HasSubstr("bogus.h5: not an HDF5 file"));
  }
  {
    H5Writer w(dir / "ok.h5");
    w.Commit();
  }
  try {
    H5Reader(dir / "ok.h5").Read("forces/X");
    FAIL();
  } catch (const DataFileError& e) {
    EXPECT_THAT(e.what(), HasSubstr("'forces/X': dataset missing"));
  }
}

TEST(H5FileTest, H5dumpReadsWrittenFile) {
  if (!kelvin::testing::HaveProgram("h5dump")) GTEST_SKIP() << "h5dump not installed (package hdf5-tools)";
  ScopedTempDir dir;
  const auto path = dir / "dump.h5";
  {
    H5Writer w(path);
    w.DeclareSeries("speed", "m/s", "ship speed");
    w.Append("speed", std::vector<double>{1.25, 2.5});
    w.Commit();
  }
  const auto res = kelvin::testing::RunCommand("h5dump " + path.string());
  ASSERT_EQ(res.exit_code, 0) << res.output;
  EXPECT_THAT(res.output, HasSubstr("DATASET \"speed\""));
  EXPECT_THAT(res.output, HasSubstr("\"m/s\""));
  EXPECT_THAT(res.output, HasSubstr("1.25, 2.5"));
}

// The DataFileError a read of a fuzzer's regression input throws ("no error"
// if none).
template <typename Read>
std::string ErrorOfRegression(const std::string& input, Read&& read) {
  const H5Reader r(kelvin::testing::SourceDir() / "tests/fuzz/regressions/captive_h5" / input);
  try {
    read(r);
  } catch (const DataFileError& e) {
    return e.what();
  }
  return "no error";
}

// A captive campaign file whose chunk of 'runs/drift/time' has a corrupt
// filter mask (the deflate filter marked skipped) and 188 stored bytes: the
// reader refuses it with one error instead of letting libhdf5 copy the whole
// 32 kB chunk out of those 188 bytes (found by the captive_h5 fuzzer).
TEST(H5Reader, CorruptUnfilteredChunkIsAnError) {
  EXPECT_THAT(ErrorOfRegression("h5dread_heap_overflow", [](const H5Reader& r) { r.Read("runs/drift/time"); }),
              HasSubstr("'runs/drift/time': corrupt chunk 0: 188 bytes stored unfiltered where the chunk needs 32768"));
  EXPECT_EQ(ErrorOfRegression("h5dread_heap_overflow",
                              [](const H5Reader& r) { EXPECT_EQ(r.Read("runs/drift/X").values.size(), 40u); }),
            "no error");  // its intact neighbour
}

// A campaign file whose dataspace for one channel declares 53 TB of values
// where the dataset stores 71 compressed bytes (deflate expands at most
// 1032-fold): the reader refuses it by name before allocating (it asked for
// the terabytes, and ASan's allocator gave up; found by the captive_h5 fuzzer).
TEST(H5Reader, DataspaceLargerThanItsStorageIsAnError) {
  EXPECT_THAT(ErrorOfRegression("read_huge_dataspace_22250dbc", [](const H5Reader& r) { r.Read("runs/drift/Y"); }),
              HasSubstr("'runs/drift/Y': corrupt dataspace: 5.28e+13 bytes of values declared where the dataset "
                        "stores 71 bytes, compressed"));
}

// A group whose link information is corrupt: its link count was garbage
// (billions) and the reader tried every index, one failed lookup at a time
// (a time-out found by the captive_h5 fuzzer); the failed query is an error
// now.
TEST(H5Reader, CorruptLinkCountIsAnError) {
  EXPECT_THAT(ErrorOfRegression("list_corrupt_link_count_0bb195ce", [](const H5Reader& r) { r.List("/runs"); }),
              HasSubstr("'/runs': corrupt group: its link count cannot be read"));
}

}  // namespace
}  // namespace kelvin::data
