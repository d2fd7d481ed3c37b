#include "identification/joint_fit.h"

#include <gtest/gtest.h>

#include <cstdio>

#include "identification/virtual_captive.h"
#include "tests/test_utilities/test_utilities.h"

namespace kelvin::ident {
namespace {

sim::ShipParameters Kvlcc2() { return sim::LoadShip(testing::SourceDir() / "data/ships/kvlcc2.yaml"); }

TEST(JointFit, Explore) {
  const sim::ShipParameters ship = Kvlcc2();
  const sim::MmgModel<double> model(ship);
  for (bool combined : {true, false}) {
    for (double noise : {0.0, 0.05}) {
      CaptiveCampaign c = GenerateCampaign(model, StandardDesign(ship.approach_speed, combined), {});
      if (noise > 0) AddForceNoise(c, noise, 1);
      JointFitOptions o;
      o.fix_unidentifiable = false;
      const JointFitResult r = FitCampaign(c, o, "virtual");
      std::printf("combined %d noise %g conv %d %s\n", combined, noise, r.converged, r.solver_report.c_str());
      for (int i = 0; i < kCoefficientCount; ++i) {
        std::printf("%10s true %9.5f fit %9.5f relerr %9.2e se %9.2e status %s %s\n",
                    std::string(sim::HullCoefficients<double>::kNames[i]).c_str(), ship.hull[i], r.coefficients[i],
                    (r.coefficients[i] - ship.hull[i]) / ship.hull[i], r.std_error[i],
                    std::string(CoefficientStatusName(r.status[i])).c_str(), r.note[i].c_str());
      }
      for (const auto& w : r.warnings) std::printf("  W: %s\n", w.c_str());
    }
  }
}

}  // namespace
}  // namespace kelvin::ident
