// Free-running runs of the 1 m Wigley on the quickstart's captive grid (k-omega
// SST, linearized free surface, data/cases/free_running/), through `kelvin
// run`'s driver and the free-running coupler (issue #20):
// - acceptance 2, free surge decay: towed at 1 m/s, released at 4 s with the
//   propeller off; the speed follows (m + m_x) du/dt = -R(u) within 2% over
//   two ship lengths, R(u) from towed runs of the same case at four speeds
//   (the carriage force averaged over 4-8 s, two periods of the start-up
//   oscillation of X) and m_x from the ship file (kelvin identify on this
//   grid's captive campaign);
// - acceptance 3, coupling stability: released in sway from a towed drift,
//   with a sway added mass 2.13 times the mass; the stabilised coupling runs
//   at the captive campaign's time step and decays like (m + m_y) dv/dt = Y(v)
//   of the ship file's derivatives, the explicit staggered scheme stops as
//   diverged within a second of the release;
// - a restart from a checkpoint after the release continues bit for bit;
// - acceptance 4 (the Wigley part), self-propulsion: towed at 1 m/s with the
//   body-force propeller of data/ships/wigley.yaml, the rate controller
//   reaches the point where the carriage force vanishes; the thrust
//   deduction and the wake come out of the flow (the working propeller
//   raises the hull's resistance above the towed one; the disk's inflow is
//   slower than the ship); a restart of the run continues bit for bit;
// - bad input around the free body and the propeller is one clear error.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>
#include <vector>

#include "cfd/run/run_case.h"
#include "data/schema/errors.h"
#include "data/schema/h5_file.h"
#include "tests/cfd/run/wigley_free_running_fixture.h"
#include "tests/test_utilities/test_utilities.h"

namespace kelvin::cfd {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;
using testing::FreeRunning;
using testing::History;

// The Wigley's ship file (data/ships/wigley.yaml): mass, added masses and
// the linear and cubic sway derivatives identified on this grid.
constexpr double kMass = 1000.0 * 0.0027777778;
constexpr double kPrimeMass = 0.5 * 1000.0 * 1.0 * 1.0 * 0.0625;  // 0.5 rho L^2 d
constexpr double kMx = 0.01057 * kPrimeMass, kMy = 0.1893 * kPrimeMass;

// Integrates dy/dt = f(y) with RK4 from (t0, y0) and returns y at the times `at`.
template <typename F>
std::vector<double> Integrate(F f, double t0, double y0, const std::vector<double>& at) {
  std::vector<double> out;
  double t = t0, y = y0;
  const double h = 1e-3;
  for (double target : at) {
    while (t < target - 1e-12) {
      const double s = std::min(h, target - t);
      const double k1 = f(y), k2 = f(y + 0.5 * s * k1), k3 = f(y + 0.5 * s * k2), k4 = f(y + s * k3);
      y += s / 6.0 * (k1 + 2 * k2 + 2 * k3 + k4);
      t += s;
    }
    out.push_back(y);
  }
  return out;
}

TEST_F(FreeRunning, SurgeDecayFollowsTheTowedResistanceCurve) {
  // R(u) from the same case towed at four speeds (no degree of freedom free).
  const std::vector<double> speeds = {0.7, 0.8, 0.9, 1.0};
  std::vector<double> r_over_u2;
  for (double u : speeds) {
    std::string text = CaseText("wigley_surge_decay");
    Replace(text, "free: [surge]", "free: []");
    Replace(text, "initial: {u: 1.0,", "initial: {u: " + std::to_string(u) + ",");
    Replace(text, "end: 6.4", "end: 8.0");
    const std::string name = "tow_" + std::to_string(u);
    ASSERT_EQ(Run(name, text).status, RunSummary::Status::kCompleted);
    const History h = Read(name);
    double sum = 0.0;
    int n = 0;
    for (std::size_t i = 0; i < h.t.size(); ++i) {
      if (h.t[i] > 4.0 + 1e-9) {
        sum += h.constraint_x[i];
        ++n;
      }
    }
    r_over_u2.push_back(sum / n / (u * u));
    std::printf("towed at %.2f m/s: R = %.4f N (mean over 4-8 s)\n", u, sum / n);
  }
  auto resistance = [&](double u) {
    const double c = u <= speeds.front() ? r_over_u2.front()
                     : u >= speeds.back() ? r_over_u2.back()
                                          : [&] {
                                              std::size_t k = 1;
                                              while (speeds[k] < u) ++k;
                                              const double w = (u - speeds[k - 1]) / (speeds[k] - speeds[k - 1]);
                                              return (1 - w) * r_over_u2[k - 1] + w * r_over_u2[k];
                                            }();
    return c * u * u;
  };

  ASSERT_EQ(Run("decay", CaseText("wigley_surge_decay")).status, RunSummary::Status::kCompleted);
  const History h = Read("decay");
  std::size_t i0 = 0;
  while (h.t[i0] < 4.0 - 1e-9) ++i0;
  const std::vector<double> times(h.t.begin() + i0, h.t.end());
  const std::vector<double> ode =
      Integrate([&](double u) { return -resistance(u) / (kMass + kMx); }, h.t[i0], h.u[i0], times);
  double worst = 0.0, distance = 0.0;
  for (std::size_t k = 0; k < times.size(); ++k) {
    distance = h.x0[i0 + k] - h.x0[i0];
    if (distance > 2.0) break;
    const double err = (h.u[i0 + k] - ode[k]) / ode[k];
    worst = std::max(worst, std::abs(err));
    if (k % 10 == 0) std::printf("t %.2f s  %.3f L  u %.4f  ODE %.4f  %+.2f%%\n", times[k], distance, h.u[i0 + k], ode[k], 100 * err);
  }
  std::printf("surge decay: largest speed difference %.2f%% over %.2f ship lengths (m_x / m = %.3f)\n", 100 * worst,
              distance, kMx / kMass);
  EXPECT_GT(distance, 1.9);
  EXPECT_LT(worst, 0.02);
  EXPECT_LT(h.u.back(), 0.8);  // it did slow down by a fifth
}

TEST_F(FreeRunning, SwayReleaseIsStableWithAnAddedMassTwiceTheMassWhereExplicitCouplingFails) {
  std::printf("sway added mass / mass = %.3f\n", kMy / kMass);
  ASSERT_GT(kMy / kMass, 1.0);
  const RunSummary ok = Run("sway", CaseText("wigley_sway_release"));
  ASSERT_EQ(ok.status, RunSummary::Status::kCompleted) << ok.message;
  const History h = Read("sway");
  std::size_t i0 = 0;
  while (h.t[i0] < 4.0 - 1e-9) ++i0;
  // The decay of the ship file's sway model, Y' = Y_v v' + Y_vvv v'^3, surge held at 1 m/s.
  auto y_model = [](double v) {
    const double U2 = 1.0 + v * v, vp = v / std::sqrt(U2);
    return 0.5 * 1000.0 * 1.0 * 0.0625 * U2 * (-0.3142 * vp - 10.27 * vp * vp * vp);
  };
  const std::vector<double> times(h.t.begin() + i0, h.t.end());
  const std::vector<double> mmg = Integrate([&](double v) { return y_model(v) / (kMass + kMy); }, h.t[i0], h.v[i0], times);
  auto halving = [&](auto value) {
    for (std::size_t k = 0; k < times.size(); ++k) {
      if (std::abs(value(k)) < 0.5 * std::abs(h.v[i0])) return times[k] - times[0];
    }
    return 1e9;
  };
  const double t_cfd = halving([&](std::size_t k) { return h.v[i0 + k]; });
  const double t_mmg = halving([&](std::size_t k) { return mmg[k]; });
  std::printf("sway release: |v| halves in %.3f s (CFD) and %.3f s (the ship file's derivatives)\n", t_cfd, t_mmg);
  for (std::size_t k = 1; k < times.size(); ++k) EXPECT_LE(std::abs(h.v[i0 + k]), std::abs(h.v[i0 + k - 1]) + 1e-6);
  // Both from this grid: the CFD's lift builds with some lag, so the free
  // decay is a little slower than the quasi-steady derivatives say.
  EXPECT_NEAR(t_cfd, t_mmg, 0.15 * t_mmg);

  std::string text = CaseText("wigley_sway_release");
  Replace(text, "scheme: stabilised", "scheme: explicit");
  const RunSummary bad = Run("sway_explicit", text);
  EXPECT_EQ(bad.status, RunSummary::Status::kDiverged);
  EXPECT_THAT(bad.message, HasSubstr("the body speed"));
  EXPECT_THAT(bad.message, HasSubstr("last good checkpoint"));
  EXPECT_LT(bad.time, 5.0);
}

TEST_F(FreeRunning, RestartAfterTheReleaseContinuesBitForBit) {
  ASSERT_EQ(Run("whole", CaseText("wigley_surge_decay")).status, RunSummary::Status::kCompleted);
  std::string half = CaseText("wigley_surge_decay");
  Replace(half, "end: 6.4", "end: 4.4");
  ASSERT_EQ(Run("half", half).status, RunSummary::Status::kCompleted);
  const RunSummary rest = Run("rest", CaseText("wigley_surge_decay"), tmp_->path() / "half/out/checkpoint.h5");
  ASSERT_EQ(rest.status, RunSummary::Status::kCompleted) << rest.message;
  const History whole = Read("whole"), tail = Read("rest");
  ASSERT_EQ(tail.t.size(), 50u);
  for (std::size_t i = 0; i < tail.t.size(); ++i) {
    EXPECT_EQ(tail.u[i], whole.u[110 + i]) << "step " << 111 + i;
    EXPECT_EQ(tail.x0[i], whole.x0[110 + i]) << "step " << 111 + i;
  }
}

TEST_F(FreeRunning, WigleySelfPropulsionFindsThePointAndItsThrustDeductionAndWake) {
  const RunSummary run = Run("sp", CaseText("wigley_self_propulsion"));
  ASSERT_EQ(run.status, RunSummary::Status::kCompleted) << run.message;
  std::printf("%s\n", run.message.c_str());
  // The report test (tools/plot_self_propulsion.py) draws this run.
  if (const char* dir = std::getenv("KELVIN_REPORT_DIR")) {
    fs::create_directories(dir);
    fs::copy_file(tmp_->path() / "sp/out/history.h5", fs::path(dir) / "history.h5", fs::copy_options::overwrite_existing);
  }
  const data::H5Reader h(tmp_->path() / "sp/out/history.h5");
  const double T = h.Read("self_propulsion/thrust").at(0), n = h.Read("self_propulsion/n").at(0);
  const double t = h.Read("self_propulsion/thrust_deduction").at(0), w = h.Read("self_propulsion/wake_fraction").at(0);
  const double X_c = h.Read("self_propulsion/carriage_force").at(0);
  EXPECT_EQ(h.Read("self_propulsion/thrust").units, "N");
  // At the point: the carriage supplies under 1% of the thrust.
  EXPECT_LT(std::abs(X_c), 0.01 * T);
  // The hull's own resistance with the propeller working, over the last 4 s,
  // exceeds the towed 0.3827 N: the suction of the disk on the stern is the
  // thrust deduction, computed by the flow.
  const auto time = h.Read("time").values, hull = h.Read("body/hull_load").values;
  const auto inflow = h.Read("propeller/inflow").values;
  double r_hull = 0.0, u_disk = 0.0, u_a = 0.0;
  int k = 0;
  for (std::size_t i = 0; i < time.size(); ++i) {
    if (time[i] <= time.back() - 4.0 + 1e-9) continue;
    r_hull -= hull[3 * i];
    u_disk += inflow[5 * i];
    u_a += inflow[5 * i + 1];
    ++k;
  }
  r_hull /= k;
  u_disk /= k;
  u_a /= k;
  std::printf("Wigley self-propulsion: n %.3f 1/s, T %.4f N, t %.4f, w_T %.4f; hull resistance %.4f N (towed 0.3827 N); "
              "U_disk %.4f m/s, U_A %.4f m/s\n", n, T, t, w, r_hull, u_disk, u_a);
  EXPECT_GT(r_hull, 0.3827 * 1.02);
  EXPECT_NEAR(r_hull, T, 0.01 * T);  // no carriage force: the hull's drag is the thrust
  EXPECT_GT(t, 0.0);
  EXPECT_LT(t, 0.3);
  // The disk accelerates the flow through it (U_disk > U_A), and the hull's
  // wake slows the inflow below the ship's speed (U_A < 1 m/s, w_T > 0).
  EXPECT_GT(u_disk, u_a);
  EXPECT_LT(u_a, 1.0);
  EXPECT_GT(w, 0.0);
  EXPECT_LT(w, 0.6);
}

TEST_F(FreeRunning, SelfPropulsionRestartContinuesBitForBit) {
  std::string whole = CaseText("wigley_self_propulsion");
  Replace(whole, "end: 12.0", "end: 6.0");
  ASSERT_EQ(Run("sp_whole", whole).status, RunSummary::Status::kCompleted);
  std::string half = CaseText("wigley_self_propulsion");
  Replace(half, "end: 12.0", "end: 4.0");
  ASSERT_EQ(Run("sp_half", half).status, RunSummary::Status::kCompleted);
  ASSERT_EQ(Run("sp_rest", whole, tmp_->path() / "sp_half/out/checkpoint.h5").status, RunSummary::Status::kCompleted);
  const data::H5Reader a(tmp_->path() / "sp_whole/out/history.h5"), b(tmp_->path() / "sp_rest/out/history.h5");
  for (const char* name : {"propeller/state", "propeller/inflow", "body/hull_load", "body/constraint_load"}) {
    const auto x = a.Read(name).values, y = b.Read(name).values;
    ASSERT_EQ(y.size() * 3, x.size()) << name;  // 50 of 150 steps
    for (std::size_t i = 0; i < y.size(); ++i) EXPECT_EQ(y[i], x[x.size() - y.size() + i]) << name << " " << i;
  }
  EXPECT_EQ(a.Read("self_propulsion/n").at(0), b.Read("self_propulsion/n").at(0));
}

TEST_F(FreeRunning, BadPropellerInputIsOneClearError) {
  struct Bad {
    std::string from, to, message;
  };
  // Ship files with the propeller moved or its table broken.
  const std::vector<Bad> ships = {
      {"z_P: 0.035", "z_P: 5.0", "contains no cell"},                      // below the domain
      {"x_P_prime: -0.52", "x_P_prime: -0.48", "touches wall patch 'hull'"},  // cutting the stern
      {"K_Q_coefficients: [0.07557, -0.05194, -0.00940]", "K_Q_coefficients: [0.07557, 0.05194, -0.00940]",
       "K_Q"},  // K_Q rising with J
  };
  for (const Bad& b : ships) {
    std::string ship = kelvin::testing::ReadText(ship_);
    Replace(ship, b.from, b.to);
    const fs::path file = tmp_->path() / "bad_ship.yaml";
    std::ofstream(file) << ship;
    std::string text = CaseText("wigley_self_propulsion");
    Replace(text, "ship: " + ship_.string(), "ship: " + file.string());
    try {
      Run("bad_prop", text);
      ADD_FAILURE() << b.to << " was accepted";
    } catch (const InputError& e) {
      EXPECT_THAT(e.what(), HasSubstr(b.message)) << b.to;
    }
  }
  // An open-water table that does not reach the operating J (about 0.41):
  // one error after the start-up, naming the J and the table's range.
  std::string ship = kelvin::testing::ReadText(ship_);
  Replace(ship, "K_Q_coefficients: [0.07557, -0.05194, -0.00940]",
          "open_water: {J: [0.0, 0.1, 0.2, 0.3], K_T: [0.2931, 0.2664, 0.2370, 0.2049], K_Q: [0.0756, 0.0703, 0.0648, 0.0591]}");
  const fs::path file = tmp_->path() / "short_table.yaml";
  std::ofstream(file) << ship;
  std::string text = CaseText("wigley_self_propulsion");
  Replace(text, "ship: " + ship_.string(), "ship: " + file.string());
  try {
    Run("short_table", text);
    ADD_FAILURE() << "a table ending at J = 0.3 was accepted";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("outside the table's range [0, 0.3]"));
    EXPECT_THAT(e.what(), HasSubstr("open_water"));
  }
  // A propeller section without a free body.
  std::string fixed = kelvin::testing::ReadText(kelvin::testing::SourceDir() / "data/cases/captive_cfd/wigley_quick_case.yaml");
  Replace(fixed, "time: {dt: 0.04}", "time: {dt: 0.04, end: 1.0}");
  fixed += "motion: {kind: static_drift, speed: 1.0, centre: [0.5, 0, 0]}\npropeller: {rate: {n: 10}}\n";
  try {
    Run("prop_fixed", fixed);
    ADD_FAILURE() << "a propeller without a free body was accepted";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("motion: {kind: free}"));
  }
}

TEST_F(FreeRunning, BadFreeBodyInputIsOneClearError) {
  // A ship file with no displaced volume: no mass.
  std::string ship = kelvin::testing::ReadText(ship_);
  Replace(ship, "displacement: 0.0027777778", "displacement: 0.0");
  const fs::path bad_ship = tmp_->path() / "massless.yaml";
  std::ofstream(bad_ship) << ship;
  struct Bad {
    std::string from, to, message;
  };
  const std::vector<Bad> cases = {
      {"ship: " + ship_.string(), "ship: " + bad_ship.string(), "principal.displacement"},
      {"free: [surge]", "free: [heave]", "surge, sway, yaw (got 'heave')"},
      {"release_time: 4.0", "release_time: 0.5", "release_time"},
      {"added_mass: ship}", "added_mass: [1, 2]}", "[m_x, m_y, J_z]"},
      {"scheme: stabilised", "scheme: implicit", "stabilised, explicit"},
  };
  for (const Bad& b : cases) {
    std::string text = CaseText("wigley_surge_decay");
    Replace(text, b.from, b.to);
    try {
      Run("bad", text);
      ADD_FAILURE() << b.to << " was accepted";
    } catch (const InputError& e) {
      EXPECT_THAT(e.what(), HasSubstr(b.message)) << b.to;
      EXPECT_THAT(e.what(), HasSubstr("case.yaml")) << b.to;
    }
  }
}

}  // namespace
}  // namespace kelvin::cfd
