#include "data/report/progress.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cstdio>
#include <string>

namespace kelvin {
namespace {

std::string ReadAll(std::FILE* f) {
  std::rewind(f);
  std::string s;
  char buf[512];
  std::size_t n;
  while ((n = std::fread(buf, 1, sizeof buf, f)) > 0) s.append(buf, n);
  return s;
}

TEST(ProgressTest, ARunThatEndsEarlyReportsWhatItDid) {
  std::FILE* f = std::tmpfile();
  ASSERT_NE(f, nullptr);
  Progress p(2000, {.label = "kelvin run", .unit = "steps", .delay_seconds = 0.0, .stream = f});
  for (int i = 1; i <= 994; ++i) p.Update(i);  // a maneuver finished at step 994 of 2000
  p.Finish("done");
  const std::string out = ReadAll(f);
  std::fclose(f);
  EXPECT_THAT(out, ::testing::HasSubstr("kelvin run: done 994 steps"));
  EXPECT_THAT(out, ::testing::Not(::testing::HasSubstr("done 2000 steps")));
}

TEST(ProgressTest, PlainModePrintsOneLinePerTenthWhenNotATerminal) {
  std::FILE* f = std::tmpfile();
  ASSERT_NE(f, nullptr);
  Progress p(1000, {.label = "sim", .unit = "steps", .plain_every = 0.1, .delay_seconds = 0.0, .stream = f});
  EXPECT_FALSE(p.is_terminal());
  for (int i = 1; i <= 1000; ++i) p.Update(i);
  p.Finish("ok");
  const std::string out = ReadAll(f);
  std::fclose(f);
  int lines = 0;
  for (char c : out) lines += c == '\n';
  EXPECT_EQ(lines, 11);  // 10%, 20%, ... 100% and the final line
  EXPECT_THAT(out, ::testing::HasSubstr("sim:  10.0%  100/1000 steps"));
  EXPECT_THAT(out, ::testing::HasSubstr("ETA"));
  EXPECT_THAT(out, ::testing::HasSubstr("sim: done 1000 steps"));
  EXPECT_EQ(out.find('\r'), std::string::npos);
}

TEST(ProgressTest, ShortRunsStayQuiet) {
  std::FILE* f = std::tmpfile();
  ASSERT_NE(f, nullptr);
  Progress p(10, {.label = "quick", .delay_seconds = 30.0, .stream = f});
  for (int i = 1; i <= 10; ++i) p.Update(i);
  p.Finish();
  EXPECT_EQ(ReadAll(f), "");
  std::fclose(f);
}

TEST(ProgressTest, FormatDuration) {
  EXPECT_EQ(FormatDuration(12.34), "12.3s");
  EXPECT_EQ(FormatDuration(185), "3m05s");
  EXPECT_EQ(FormatDuration(3720), "1h02m");
  EXPECT_EQ(FormatDuration(-1), "--");
}

}  // namespace
}  // namespace kelvin
