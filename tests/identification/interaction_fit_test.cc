// The interaction fit (identification/interaction_fit.h) against runs made by
// the MMG model itself: the model's own rudder inflow, normal force, thrust,
// advance speed and total loads at held motions, with interaction
// coefficients unlike the ship file's. Every equation of the fit is the
// model's equation, so the coefficients come back to round-off; what the
// runs do not excite stays at the ship file's value with a warning.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <numbers>

#include "data/schema/appendage_runs.h"
#include "data/schema/errors.h"
#include "data/schema/h5_file.h"
#include "identification/interaction_fit.h"
#include "simulator/mmg/derivative_set.h"
#include "simulator/mmg/mmg_model.h"
#include "simulator/mmg/ship_parameters.h"
#include "tests/test_utilities/test_utilities.h"

namespace kelvin::ident {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

sim::ShipParameters Wigley() { return sim::LoadShip(testing::SourceDir() / "data/ships/wigley.yaml"); }

// The ship with the coefficients the runs are made with.
sim::ShipParameters Truth() {
  sim::ShipParameters s = Wigley();
  s.propeller.t_P = 0.21;
  s.propeller.w_P0 = 0.31;
  s.rudder.epsilon = 0.93;
  s.rudder.kappa = 0.81;
  s.rudder.gamma_R_minus = 0.27;
  s.rudder.gamma_R_plus = 0.33;
  s.rudder.l_R_prime = -1.1;
  s.rudder.t_R = 0.15;
  s.rudder.a_H = 0.22;
  s.rudder.x_H_prime = -0.41;
  s.rudder.f_alpha = 2.96;
  return s;
}

data::AppendageRun Run(const sim::MmgModel<double>& m, const data::AppendageTest& t) {
  const sim::MmgForces<double> f = m.Forces(t.u, t.v, t.r, t.delta, t.n);
  data::AppendageRun r;
  r.name = t.name;
  r.u = t.u, r.v = t.v, r.r = t.r, r.delta = t.delta, r.n = t.n;
  r.X = f.total.X, r.Y = f.total.Y, r.N = f.total.N;
  r.T = f.thrust;
  r.U_A = t.u * (1.0 - f.w_P);
  r.J = f.J_P, r.K_T = f.K_T;
  r.F_N = f.F_N, r.u_R = f.u_R, r.v_R = f.v_R;
  return r;
}

data::AppendageCampaign Campaign(const sim::ShipParameters& s, const data::AppendageDesign& d) {
  const sim::MmgModel<double> model(s);
  data::AppendageCampaign c;
  c.geometry = {s.principal.Lpp, s.propeller.D_p, s.rudder.A_R, s.rudder.H_R, s.rudder.x_R_prime,
                s.propeller.x_P_prime, s.principal.rho, "wigley.yaml"};
  for (const data::AppendageTest& t : data::PlanAppendageTests(d, 1.0, s.principal.Lpp)) c.runs.push_back(Run(model, t));
  return c;
}

data::AppendageDesign FullDesign() {
  data::AppendageDesign d;
  d.propeller_rate = 59.79;
  d.rate_factors = {0.8, 1.25};
  d.rudder_angles = {-35 * kDeg, -20 * kDeg, -10 * kDeg, 10 * kDeg, 20 * kDeg, 35 * kDeg};
  d.drift_angles = {-6 * kDeg, 6 * kDeg};
  d.circular = {{0.0, 0.3}, {0.0, -0.3}, {0.0, 0.6}, {6 * kDeg, 0.6}, {-6 * kDeg, -0.6}, {6 * kDeg, 0.6, 1.5}};
  return d;
}

InteractionFitOptions ShipFileOptions(const sim::ShipParameters& truth) {
  const sim::ShipParameters file = Wigley();
  InteractionFitOptions o;
  o.propeller = file.propeller;
  o.rudder = file.rudder;
  o.bare_X = sim::MmgModel<double>(truth).HullForces(1.0, 0.0, 0.0).X;
  return o;
}

TEST(InteractionFit, RecoversTheModelsOwnCoefficients) {
  const sim::ShipParameters truth = Truth();
  const data::AppendageCampaign c = Campaign(truth, FullDesign());
  const InteractionFitResult r = FitInteraction(c, ShipFileOptions(truth), "synthetic");
  const std::map<std::string, double> want = {
      {"t_P", 0.21}, {"w_P0", 0.31}, {"epsilon", 0.93}, {"kappa", 0.81}, {"gamma_R_minus", 0.27},
      {"gamma_R_plus", 0.33}, {"l_R_prime", -1.1}, {"t_R", 0.15}, {"a_H", 0.22}, {"x_H_prime", -0.41},
      {"f_alpha", 2.96}};
  for (const auto& [name, value] : want) {
    const InteractionCoefficient& k = r.Get(name);
    EXPECT_TRUE(k.identified) << name;
    EXPECT_NEAR(k.value, value, 1e-6 * std::abs(value)) << name;
  }
  EXPECT_TRUE(r.warnings.empty()) << r.warnings.front();
  // Applied to the ship file, the surrogate's rudder then gives the runs' own force.
  sim::ShipParameters applied = Wigley();
  sim::ApplyInteraction(r.Identified(), applied);
  const auto f = sim::MmgModel<double>(applied).Forces(0.44, -0.047, 0.287, 35 * kDeg, 59.79);
  const auto g = sim::MmgModel<double>(truth).Forces(0.44, -0.047, 0.287, 35 * kDeg, 59.79);
  EXPECT_NEAR(f.F_N, g.F_N, 1e-6 * std::abs(g.F_N));
}

TEST(InteractionFit, WhatTheRunsDoNotExciteKeepsTheShipFilesValue) {
  const sim::ShipParameters truth = Truth();
  data::AppendageDesign d = FullDesign();
  d.rate_factors.clear();  // one propeller loading: kappa cannot be told from epsilon
  d.circular.clear();      // no yawing run: no l_R
  d.drift_angles = {6 * kDeg};  // beta_R > 0 only
  const data::AppendageCampaign c = Campaign(truth, d);
  InteractionFitOptions o = ShipFileOptions(truth);
  o.bare_X.reset();  // no bare-hull straight run: no t_P
  const InteractionFitResult r = FitInteraction(c, o, "synthetic");
  for (const char* name : {"kappa", "l_R_prime", "gamma_R_minus", "t_P"}) {
    EXPECT_FALSE(r.Get(name).identified) << name;
    EXPECT_EQ(r.Get(name).value, r.Get(name).ship) << name;
  }
  EXPECT_EQ(r.warnings.size(), 4u);
  EXPECT_NEAR(r.Get("gamma_R_plus").value, 0.33, 1e-6);
  EXPECT_NEAR(r.Get("w_P0").value, 0.31, 1e-9);
  EXPECT_EQ(r.Identified().count("kappa"), 0u);
}

TEST(InteractionFit, NeedsAStraightRunAtRudderAmidships) {
  const sim::ShipParameters truth = Truth();
  data::AppendageCampaign c = Campaign(truth, FullDesign());
  c.runs.erase(c.runs.begin(), c.runs.begin() + 3);  // the delta = 0 straight runs
  EXPECT_THROW(FitInteraction(c, ShipFileOptions(truth), "synthetic"), InputError);
  data::AppendageCampaign astern = Campaign(truth, FullDesign());
  astern.runs.back().u = -0.1;
  EXPECT_THROW(FitInteraction(astern, ShipFileOptions(truth), "synthetic"), InputError);
}

TEST(AppendageRuns, RoundTripAndMalformedFiles) {
  const data::AppendageCampaign c = Campaign(Truth(), FullDesign());
  const auto dir = std::filesystem::temp_directory_path() / "kelvin_appendage_runs_test";
  std::filesystem::create_directories(dir);
  const auto path = dir / "campaign.h5";
  {
    data::H5Writer w(path);
    data::WriteAppendageRuns(c, w);
    w.Commit();
  }
  ASSERT_TRUE(data::HasAppendageRuns(path));
  const data::AppendageCampaign back = data::ReadAppendageRuns(path);
  ASSERT_EQ(back.runs.size(), c.runs.size());
  EXPECT_EQ(back.runs[5].name, c.runs[5].name);
  EXPECT_EQ(back.runs[5].F_N, c.runs[5].F_N);
  EXPECT_EQ(back.geometry.A_R, c.geometry.A_R);
  // A zero rudder span, and a non-finite value: one clear error each.
  for (int bad = 0; bad < 2; ++bad) {
    data::AppendageCampaign b = c;
    if (bad == 0) b.geometry.H_R = 0.0;
    if (bad == 1) b.runs[2].u_R = std::nan("");
    {
      data::H5Writer w(path);
      data::WriteAppendageRuns(b, w);
      w.Commit();
    }
    try {
      data::ReadAppendageRuns(path);
      ADD_FAILURE() << "no error for defect " << bad;
    } catch (const DataFileError& e) {
      EXPECT_NE(std::string(e.what()).find(bad == 0 ? "H_R" : "u_R"), std::string::npos) << e.what();
    }
  }
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace kelvin::ident
