// Every force component of the MMG model against reference numbers computed
// by an independent implementation of the paper's equations
// (tests/simulator/mmg_reference.py, Yasukawa & Yoshimura 2015 eqs. 4-25,
// KVLCC2 L7 model). The states cover straight running, a starboard turn with
// drift and starboard rudder, and a port turn with port rudder at reduced
// rps, so both branches of gamma_R and C2 are exercised.
#include "simulator/mmg/mmg_model.h"

#include <ceres/jet.h>
#include <gtest/gtest.h>

#include <cmath>

#include "simulator/maneuvers/maneuver.h"
#include "tests/simulator/simulator_test_utilities.h"

namespace kelvin::sim {
namespace {

struct Reference {
  const char* name;
  double u, v, r, delta_deg, n;
  double XH, YH, NH, XP, T, wP, J, KT, uR, vR, aR, FN, XR, YR, NR;
};

// Printed by tests/simulator/mmg_reference.py.
const Reference kReferences[] = {
    {"straight", 1.179, 0.0, 0.0, 0.0, 11.85, -5.046613352550e+01, 0.0, 0.0, 5.044940195214e+01,
     6.467872045146e+01, 4.000000000000e-01, 2.763713080169e-01, 2.064361965675e-01, 1.253567164580e+00, 0.0, 0.0,
     0.0, 0.0, 0.0, 0.0},
    {"drift_turn_stbd_rudder", 1.10, -0.08, 0.05, 15.0, 11.85, -4.241033255729e+01, 1.074868046888e+02,
     -9.708378987238e+01, 4.717465403543e+01, 6.048032568645e+01, 2.695808377575e-01, 3.139010308121e-01,
     1.930361070028e-01, 1.308946219769e+00, 2.102850041471e-01, 1.025083338136e-01, 1.364739520543e+01,
     -2.165242152462e+00, -1.729527139554e+01, 5.949699910832e+01},
    {"port_turn_port_rudder", 0.90, 0.06, -0.07, -35.0, 10.0, -2.549408281836e+01, -1.025568093553e+02,
     2.008196887575e+02, 3.680134268144e+01, 4.718120856595e+01, 3.711775782978e-01, 2.620093423759e-01,
     2.114609560182e-01, 1.040612311394e+00, -1.611380127691e-01, -4.572361764036e-01, -3.714591338932e+01,
     -1.306059064426e+01, 3.992173396748e+01, -1.373336859506e+02},
};

void ExpectNear(double actual, double expected, const char* what, const char* state) {
  // 12 printed digits: relative 1e-10, with an absolute floor for zeros.
  EXPECT_NEAR(actual, expected, 1e-10 * std::abs(expected) + 1e-11) << what << " at state " << state;
}

TEST(MmgModelTest, ForceComponentsMatchIndependentEvaluation) {
  const MmgModel<double> model(testing::Kvlcc2());
  for (const Reference& ref : kReferences) {
    const auto f = model.Forces(ref.u, ref.v, ref.r, ref.delta_deg * M_PI / 180.0, ref.n);
    ExpectNear(f.hull.X, ref.XH, "X_H", ref.name);
    ExpectNear(f.hull.Y, ref.YH, "Y_H", ref.name);
    ExpectNear(f.hull.N, ref.NH, "N_H", ref.name);
    ExpectNear(f.propeller.X, ref.XP, "X_P", ref.name);
    ExpectNear(f.thrust, ref.T, "T", ref.name);
    ExpectNear(f.w_P, ref.wP, "w_P", ref.name);
    ExpectNear(f.J_P, ref.J, "J_P", ref.name);
    ExpectNear(f.K_T, ref.KT, "K_T", ref.name);
    ExpectNear(f.u_R, ref.uR, "u_R", ref.name);
    ExpectNear(f.v_R, ref.vR, "v_R", ref.name);
    ExpectNear(f.alpha_R, ref.aR, "alpha_R", ref.name);
    ExpectNear(f.F_N, ref.FN, "F_N", ref.name);
    ExpectNear(f.rudder.X, ref.XR, "X_R", ref.name);
    ExpectNear(f.rudder.Y, ref.YR, "Y_R", ref.name);
    ExpectNear(f.rudder.N, ref.NR, "N_R", ref.name);
    ExpectNear(f.total.X, ref.XH + ref.XP + ref.XR, "X", ref.name);
    ExpectNear(f.total.Y, ref.YH + ref.YR, "Y", ref.name);
    ExpectNear(f.total.N, ref.NH + ref.NR, "N", ref.name);
  }
}

TEST(MmgModelTest, SelfPropulsionBalancesResistance) {
  const MmgModel<double> model(testing::Kvlcc2());
  const double U0 = 1.179;
  const double n = SelfPropulsionRps(model, U0);
  // The reference file notes about 11.8 rps for these coefficients.
  EXPECT_NEAR(n, 11.85, 0.01);
  const auto f = model.Forces(U0, 0.0, 0.0, 0.0, n);
  EXPECT_NEAR(f.total.X, 0.0, 1e-9 * std::abs(f.hull.X));
}

TEST(MmgModelTest, AccelerationsSatisfyTheMotionEquations) {
  // Substitute the accelerations back into Yasukawa & Yoshimura eq. 4.
  const ShipParameters ship = testing::Kvlcc2();
  const MmgModel<double> model(ship);
  const double u = 1.1, v = -0.08, r = 0.05;
  const auto f = model.Forces(u, v, r, 0.2, 11.0).total;
  const auto a = model.Accelerations(u, v, r, f);
  const double m = ship.mass(), xG = ship.principal.x_G;
  const double mx = model.AddedMassX(), my = model.AddedMassY(), Jz = model.AddedInertiaZ();
  EXPECT_NEAR((m + mx) * a[0] - (m + my) * v * r - xG * m * r * r, f.X, 1e-9 * std::abs(f.X));
  EXPECT_NEAR((m + my) * a[1] + (m + mx) * u * r + xG * m * a[2], f.Y, 1e-9 * std::abs(f.Y));
  EXPECT_NEAR((ship.I_zG() + xG * xG * m + Jz) * a[2] + xG * m * (a[1] + u * r), f.N, 1e-9 * std::abs(f.N));
  // Prime-system scaling of the added masses: m'_y = 0.223 of 0.5 rho L^2 d.
  EXPECT_NEAR(my, 0.223 * 0.5 * 1025.0 * 49.0 * 0.46, 1e-9);
}

TEST(MmgModelTest, JetEvaluationGivesExactCoefficientDerivatives) {
  // dY_H/dY_v = 0.5 rho L d U^2 v' (the polynomial is linear in Y_v): the
  // model runs with ceres::Jet coefficients, as identification uses it.
  using Jet = ceres::Jet<double, HullCoefficients<double>::kCount>;
  const ShipParameters ship = testing::Kvlcc2();
  HullCoefficients<Jet> hull = ship.hull.Cast<Jet>();
  for (int i = 0; i < HullCoefficients<double>::kCount; ++i) hull[i].v[i] = 1.0;
  const MmgModel<Jet> model(ship, hull);
  const double u = 1.0, v = -0.1, r = 0.03;
  const auto f = model.HullForces(Jet(u), Jet(v), Jet(r));
  const double U2 = u * u + v * v, q = 0.5 * 1025.0 * 7.0 * 0.46;
  const double vp = v / std::sqrt(U2), rp = r * 7.0 / std::sqrt(U2);
  EXPECT_NEAR(f.Y.v[5], q * U2 * vp, 1e-12);             // Y_v
  EXPECT_NEAR(f.Y.v[9], q * U2 * vp * rp * rp, 1e-12);   // Y_vrr
  EXPECT_NEAR(f.N.v[12], q * 7.0 * U2 * rp, 1e-12);      // N_r
  EXPECT_NEAR(f.X.v[0], -q * U2, 1e-12);                 // R0'
  EXPECT_NEAR(f.Y.a, model.HullForces(Jet(u), Jet(v), Jet(r)).Y.a, 0.0);
  const MmgModel<double> plain(ship);
  EXPECT_NEAR(f.Y.a, plain.HullForces(u, v, r).Y, 1e-12);
}

TEST(MmgModelTest, HullForcesVanishAtRest) {
  const MmgModel<double> model(testing::Kvlcc2());
  const auto f = model.HullForces(0.0, 0.0, 0.0);
  EXPECT_EQ(f.X, 0.0);
  EXPECT_EQ(f.Y, 0.0);
  EXPECT_EQ(f.N, 0.0);
  const auto all = model.Forces(0.0, 0.0, 0.0, 0.3, 5.0);  // bollard pull, rudder in the race
  EXPECT_TRUE(std::isfinite(all.total.X) && std::isfinite(all.total.Y) && std::isfinite(all.total.N));
  EXPECT_GT(all.thrust, 0.0);
  EXPECT_GT(all.rudder.N, 0.0);  // positive rudder turns to starboard
}

}  // namespace
}  // namespace kelvin::sim
