// The kelvin program's command-line contract: --version, help, and exit code
// 2 with one clear line on bad arguments.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "tests/test_utilities/test_utilities.h"

namespace {

using kelvin::testing::RunCommand;
using ::testing::HasSubstr;

std::string Kelvin() { return (kelvin::testing::ToolsDir() / "kelvin").string(); }

int CountLines(const std::string& s) {
  int n = 0;
  for (char c : s) n += c == '\n';
  return n;
}

TEST(KelvinCliTest, Version) {
  const auto r = RunCommand(Kelvin() + " --version");
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_THAT(r.output, HasSubstr("kelvin 0."));
}

TEST(KelvinCliTest, UnknownOptionExitsTwoWithOneLine) {
  const auto r = RunCommand(Kelvin() + " --no-such-flag");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(CountLines(r.output), 1) << r.output;
  EXPECT_THAT(r.output, HasSubstr("kelvin: error:"));
  EXPECT_THAT(r.output, HasSubstr("--no-such-flag"));
}

TEST(KelvinCliTest, UnknownSubcommandExitsTwo) {
  const auto r = RunCommand(Kelvin() + " frobnicate");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(CountLines(r.output), 1) << r.output;
  EXPECT_THAT(r.output, HasSubstr("frobnicate"));
}

TEST(KelvinCliTest, HelpForUnknownCommandExitsTwo) {
  const auto r = RunCommand(Kelvin() + " help frobnicate");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.output, HasSubstr("unknown command 'frobnicate'"));
}

TEST(KelvinCliTest, HelpListsCommands) {
  const auto r = RunCommand(Kelvin() + " help");
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_THAT(r.output, HasSubstr("help"));
}

}  // namespace
