// The samples file of a captive CFD run (what a resumed campaign reads back):
// every channel round-trips, and a file whose channels have different
// lengths is one clear error naming the channel, not a read past the end.
#include <gtest/gtest.h>

#include "cfd/campaign/run_samples.h"
#include "data/schema/errors.h"
#include "tests/test_utilities/test_utilities.h"

namespace kelvin::cfd {
namespace {

RigidMotion Towed() {
  MotionOptions o;
  o.speed = 1.5;
  return RigidMotion(o);
}

std::vector<CaptiveSample> Samples() {
  std::vector<CaptiveSample> s(3);
  for (std::size_t i = 0; i < s.size(); ++i) {
    const double k = static_cast<double>(i + 1);
    s[i].time = 0.5 * k;
    s[i].loads.pressure = {-1.0 * k, 2.0 * k, 3.0 * k};
    s[i].loads.viscous = {-4.0 * k, 5.0 * k, 6.0 * k};
    s[i].prime = {-7e-3 * k, 8e-3 * k, 9e-3 * k};
  }
  return s;
}

TEST(RunSamples, EveryChannelRoundTrips) {
  kelvin::testing::ScopedTempDir tmp;
  const std::vector<CaptiveSample> written = Samples();
  WriteSamples(tmp / "samples.h5", written, 3, 10, RunCost{});
  const RigidMotion motion = Towed();
  const std::vector<CaptiveSample> read = ReadSamples(tmp / "samples.h5", motion);
  ASSERT_EQ(read.size(), written.size());
  for (std::size_t i = 0; i < read.size(); ++i) {
    EXPECT_EQ(read[i].time, written[i].time);
    EXPECT_EQ(read[i].loads.pressure.X, written[i].loads.pressure.X);
    EXPECT_EQ(read[i].loads.pressure.Y, written[i].loads.pressure.Y);
    EXPECT_EQ(read[i].loads.pressure.N, written[i].loads.pressure.N);
    EXPECT_EQ(read[i].loads.viscous.X, written[i].loads.viscous.X);
    EXPECT_EQ(read[i].loads.viscous.Y, written[i].loads.viscous.Y);
    EXPECT_EQ(read[i].loads.viscous.N, written[i].loads.viscous.N);
    EXPECT_EQ(read[i].prime.X, written[i].prime.X);
    EXPECT_EQ(read[i].prime.Y, written[i].prime.Y);
    EXPECT_EQ(read[i].prime.N, written[i].prime.N);
    EXPECT_EQ(read[i].pose.x0, motion.At(written[i].time).x0);
  }
}

TEST(RunSamples, ChannelOfAnotherLengthIsAnError) {
  kelvin::testing::ScopedTempDir tmp;
  {
    data::H5Writer w(tmp / "samples.h5");
    const std::vector<double> three = {0.5, 1.0, 1.5}, two = {1.0, 2.0};
    w.WriteArray("captive/time", three, {3}, "s", "time");
    for (const char* name : {"X_pressure", "Y_pressure", "N_pressure", "X_viscous", "Y_viscous", "N_viscous",
                             "X_prime", "Y_prime", "N_prime"}) {
      const std::vector<double>& v = std::string(name) == "Y_viscous" ? two : three;
      w.WriteArray(std::string("captive/") + name, v, {v.size()}, "N", "a channel");
    }
    w.Commit();
  }
  try {
    ReadSamples(tmp / "samples.h5", Towed());
    FAIL() << "a channel of 2 samples beside 3 times was read";
  } catch (const DataFileError& e) {
    EXPECT_NE(std::string(e.what()).find("captive/Y_viscous has 2 samples; expected 3"), std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace kelvin::cfd
