// PMM Fourier analysis and classical derivative extraction. Truth: the
// KVLCC2 L7 set of Yasukawa & Yoshimura (2015), J. Mar. Sci. Technol.
// 20:37-52 (data/ships/kvlcc2.yaml).
#include "identification/pmm_analysis.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "identification/derivative_set_io.h"
#include "identification/virtual_captive.h"
#include "tests/test_utilities/test_utilities.h"
#include "tests/simulator/simulator_test_utilities.h"

namespace kelvin::ident {
namespace {

using sim::testing::Kvlcc2;

data::CaptiveShip UnitShip() {
  data::CaptiveShip s;
  s.name = "unit";
  s.Lpp = 2.0;
  s.d = 0.5;
  s.rho = 1000.0;
  s.mass = 100.0;
  s.I_zG = 25.0;
  return s;
}

// A signal with a known mean and first harmonic plus a third harmonic and
// garbage during the ramp-up: the analysis must return the first harmonic
// exactly, because it uses whole periods after t_ramp only.
TEST(PmmAnalysisTest, FirstHarmonicOverWholePeriodsAfterRamp) {
  const data::CaptiveShip ship = UnitShip();
  data::CaptiveRun run;
  run.name = "synthetic";
  run.motion.kind = data::MotionKind::kPureSway;
  run.motion.U = 1.0;
  run.motion.y_a = 0.1;
  run.motion.omega = 0.8;
  const double T = run.motion.Period();
  run.motion.t_ramp = 0.6 * T;  // the window starts at the next period boundary, t = T
  const int n = 4 * 64 + 13;    // a partial period at the end, dropped too
  for (int i = 0; i < n; ++i) {
    const double t = i * T / 64;
    const double w = run.motion.omega * t;
    run.time.push_back(t);
    const double garbage = t < T ? 50.0 * std::exp(-t) : 0.0;
    run.force[0].push_back(3.0 + 0.5 * std::cos(w) + 0.25 * std::sin(3 * w) + garbage);
    run.force[1].push_back(-2.0 * std::cos(w) + 1.5 * std::sin(w) + 0.7 * std::cos(3 * w) +
                           garbage);
    run.force[2].push_back(0.3 * std::sin(w) - 0.1 + garbage);
  }
  const RunAnalysis a = AnalyseRun(ship, run, "synthetic");
  EXPECT_EQ(a.window.periods, 3);
  EXPECT_EQ(a.window.begin, 64u);
  EXPECT_EQ(a.window.end, 4u * 64u);
  EXPECT_NEAR(a.force[0].mean, 3.0, 1e-12);
  EXPECT_NEAR(a.force[0].in_phase, 0.5, 1e-12);
  EXPECT_NEAR(a.force[0].quadrature, 0.0, 1e-12);
  EXPECT_NEAR(a.force[1].mean, 0.0, 1e-12);
  EXPECT_NEAR(a.force[1].in_phase, -2.0, 1e-12);
  EXPECT_NEAR(a.force[1].quadrature, 1.5, 1e-12);
  EXPECT_NEAR(a.force[1].Amplitude(), 2.5, 1e-12);
  EXPECT_NEAR(a.force[1].Phase(), std::atan2(1.5, -2.0), 1e-12);
  EXPECT_NEAR(a.force[2].mean, -0.1, 1e-12);
  EXPECT_NEAR(a.force[2].quadrature, 0.3, 1e-12);
  // Prime: X, Y by 0.5 rho L d U^2 = 500 N, N by 0.5 rho L^2 d U^2 = 1000 N m.
  EXPECT_NEAR(a.force_prime[1].in_phase, -2.0 / 500.0, 1e-15);
  EXPECT_NEAR(a.force_prime[2].quadrature, 0.3 / 1000.0, 1e-15);
}

TEST(PmmAnalysisTest, RigidBodyInertiaIsRemoved) {
  const sim::ShipParameters ship = Kvlcc2();
  const sim::MmgModel<double> model(ship);
  data::VirtualCaptiveOptions with, without;
  without.include_rigid_body_inertia = false;
  const data::CampaignDesign d = data::StandardDesign(ship.approach_speed, true);
  const PmmAnalysis a = AnalyseCampaign(GenerateCampaign(model, d, with), "with");
  const PmmAnalysis b = AnalyseCampaign(GenerateCampaign(model, d, without), "without");
  ASSERT_EQ(a.runs.size(), b.runs.size());
  for (std::size_t r = 0; r < a.runs.size(); ++r) {
    for (int c = 0; c < 3; ++c) {
      const double scale =
          1.0 + std::abs(b.runs[r].force[c].Amplitude()) + std::abs(b.runs[r].force[c].mean);
      EXPECT_NEAR(a.runs[r].force[c].mean, b.runs[r].force[c].mean, 1e-9 * scale);
      EXPECT_NEAR(a.runs[r].force[c].in_phase, b.runs[r].force[c].in_phase, 1e-9 * scale);
      EXPECT_NEAR(a.runs[r].force[c].quadrature, b.runs[r].force[c].quadrature, 1e-9 * scale);
    }
  }
}

const ClassicalEstimate* Find(const PmmAnalysis& a, const std::string& name,
                              const std::string& source) {
  for (const ClassicalEstimate& e : a.estimates) {
    if (e.name == name && e.source == source) return &e;
  }
  return nullptr;
}

// Static drift: X' = -R0' + X_vv v'^2 + X_vvvv v'^4 and Y' = Y_v v' + Y_vvv v'^3
// hold exactly in steady drift (v' = -sin beta, U constant), so the
// regression over six angles is exact to rounding.
TEST(PmmAnalysisTest, StaticDriftRegressionIsExact) {
  const sim::ShipParameters ship = Kvlcc2();
  const PmmAnalysis a =
      AnalyseCampaign(GenerateCampaign(sim::MmgModel<double>(ship),
                                       data::StandardDesign(ship.approach_speed, false), {}),
                      "kvlcc2");
  const std::string reg = "static drift regression";
  const sim::HullCoefficients<double>& h = ship.hull;
  for (auto [name, truth] : std::vector<std::pair<std::string, double>>{{"R0_prime", h.R0},
                                                                        {"X_vv", h.X_vv},
                                                                        {"X_vvvv", h.X_vvvv},
                                                                        {"Y_v", h.Y_v},
                                                                        {"Y_vvv", h.Y_vvv},
                                                                        {"N_v", h.N_v},
                                                                        {"N_vvv", h.N_vvv}}) {
    const ClassicalEstimate* e = Find(a, name, reg);
    ASSERT_NE(e, nullptr) << name;
    EXPECT_NEAR(e->value, truth, 1e-9) << name;
  }
}

// Pure sway and pure yaw: the classical derivatives against their MMG
// counterparts (pmm_analysis.h). Per run they carry the cubic terms
// (3/4 Y_vvv v'_a^2 ...) and the carriage-speed normalization; the
// extrapolation to zero amplitude removes the amplitude^2 part, leaving
// O(amplitude^4) (< 0.2^4 / 0.2^2 of the per-run bias).
TEST(PmmAnalysisTest, ClassicalDerivativesMatchTheMmgModel) {
  const sim::ShipParameters ship = Kvlcc2();
  const PmmAnalysis a =
      AnalyseCampaign(GenerateCampaign(sim::MmgModel<double>(ship),
                                       data::StandardDesign(ship.approach_speed, false), {}),
                      "kvlcc2");
  const std::string zero = "zero-amplitude extrapolation";
  for (const std::string name :
       {"Y_v", "N_v", "Y_vdot", "N_vdot", "Y_r", "N_r", "Y_rdot", "N_rdot"}) {
    const ClassicalEstimate* e = Find(a, name, zero);
    ASSERT_NE(e, nullptr) << name;
    double truth = 0;
    ASSERT_TRUE(ClassicalCounterpart(name, ship.hull, &truth));
    std::printf("%-7s classical %+.6f  MMG %+.6f\n", name.c_str(), e->value, truth);
    if (truth == 0) {
      EXPECT_NEAR(e->value, 0.0, 1e-4) << name;  // vs |Y'_vdot| = 0.223, |N'_rdot| = 0.011
    } else {
      EXPECT_NEAR(e->value, truth, 3e-3 * std::abs(truth)) << name;
    }
  }
  // Per run the amplitude terms are there: with v' = v / U (carriage speed)
  // the model force is Y_v v' (1 + v'^2)^(1/2) + Y_vvv v'^3 (1 + v'^2)^(-1/2),
  // whose first harmonic at v'_a = 0.2 is Y_v (1 + 3/8 a^2) + 3/4 Y_vvv a^2 +
  // O(a^4) (about 17% off Y_v); the extrapolation removes it.
  const ClassicalEstimate* big = nullptr;
  for (const ClassicalEstimate& e : a.estimates) {
    if (e.name == "Y_v" && std::abs(e.amplitude - 0.2) < 1e-9) big = &e;
  }
  ASSERT_NE(big, nullptr);
  EXPECT_NEAR(big->value, ship.hull.Y_v * (1 + 0.375 * 0.04) + 0.75 * ship.hull.Y_vvv * 0.04,
              0.005 * std::abs(ship.hull.Y_v));
}

}  // namespace
}  // namespace kelvin::ident
