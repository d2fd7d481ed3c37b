// The one steady criterion (cfd/run/steady_criterion.h) against closed
// forms: on an exponentially settling force and elevation it stops at the
// step the closed form predicts; a window counted in steps alone holds
// exactly window_steps + 1 samples; several groups are each measured by
// their own scale.
#include "cfd/run/steady_criterion.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "data/schema/errors.h"

namespace kelvin::cfd {
namespace {

TEST(SteadyCriterion, StopsWhereTheClosedFormSays) {
  // R(t) = R0 (1 + A e^{-t/tau}); eta(t) = eta0 (1 + B e^{-t/tau2}). Over a
  // window W ending at t the largest change is against the oldest sample:
  // force: R0 A e^{-t/tau} (e^{W/tau} - 1) / R(t); eta: B e^{-t/tau2}
  // (e^{W/tau2} - 1) / (1 + B e^{-t/tau2}).
  const double R0 = 40.0, A = 0.5, tau = 3.0, B = 0.3, tau2 = 5.0, W = 4.0, tol = 1e-3, dt = 0.25;
  SteadyCriterion c({W, 1, tol});
  const std::vector<double> eta0 = {0.01, -0.02, 0.005};
  int stop = -1;
  for (int n = 1; n <= 400 && stop < 0; ++n) {
    const double t = n * dt;
    const double r = R0 * (1 + A * std::exp(-t / tau));
    const SteadyGroup drag[1] = {{{r, 0.3 * r, 0.7 * r}, r}};
    std::vector<double> eta(eta0);
    for (double& e : eta) e *= 1 + B * std::exp(-t / tau2);
    c.Add(t, drag, eta);
    if (t < W + dt - 1e-12) {  // the first sample is at t = dt
      EXPECT_TRUE(std::isnan(c.force_change()));
      EXPECT_FALSE(c.Settled());
      continue;
    }
    const double fc = R0 * A * std::exp(-t / tau) * std::expm1(W / tau) / r;
    const double ec = B * std::exp(-t / tau2) * std::expm1(W / tau2) / (1 + B * std::exp(-t / tau2));
    EXPECT_NEAR(c.force_change(), fc, 1e-12);
    EXPECT_NEAR(c.eta_change(), ec, 1e-12);
    if (c.Settled()) stop = n;
  }
  // The eta criterion is the slower one: first t with ec < tol.
  int expected = -1;
  for (int n = 1; n <= 400; ++n) {
    const double t = n * dt;
    const double ec = B * std::exp(-t / tau2) * std::expm1(W / tau2) / (1 + B * std::exp(-t / tau2));
    const double fc = A * std::exp(-t / tau) * std::expm1(W / tau) / (1 + A * std::exp(-t / tau));
    if (t >= W + dt - 1e-12 && ec < tol && fc < tol) {
      expected = n;
      break;
    }
  }
  ASSERT_GT(expected, 0);
  EXPECT_EQ(stop, expected);
  EXPECT_THROW(SteadyCriterion({-1.0, 1, tol}), ConfigError);
  EXPECT_THROW(SteadyCriterion({W, 1, 1.5}), ConfigError);
  EXPECT_THROW(SteadyCriterion({W, 0, tol}), ConfigError);
}

TEST(SteadyCriterion, AStepWindowAndTwoGroups) {
  // Window of 3 steps only (no pseudo-time span): the change is measured
  // against the sample 3 steps back. Group 1 drifts linearly by 1 per step
  // (scale 100), group 2 is constant: change = 3 / 100.
  SteadyCriterion c({0.0, 3, 0.05});
  for (int n = 0; n < 3; ++n) {
    const SteadyGroup g[2] = {{{100.0 + n}, 100.0 + n}, {{-5.0}, 5.0}};
    c.Add(n, g, {});
    EXPECT_TRUE(std::isnan(c.force_change()));
  }
  const SteadyGroup g[2] = {{{103.0}, 103.0}, {{-5.0}, 5.0}};
  c.Add(3, g, {});
  EXPECT_DOUBLE_EQ(c.force_change(), 3.0 / 103.0);
  EXPECT_EQ(c.eta_change(), 0.0);  // eta not monitored
  EXPECT_TRUE(c.Settled());
  // The constant group with a zero scale and a change is never settled.
  const SteadyGroup h[2] = {{{103.0}, 103.0}, {{1.0}, 0.0}};
  c.Add(4, h, {});
  EXPECT_TRUE(std::isinf(c.force_change()));
  EXPECT_FALSE(c.Settled());
}

// Save and Load carry the window over a checkpoint: a criterion loaded
// halfway measures every later step as the one that never stopped, eta
// included; a truncated, padded or inconsistent array is a DataFileError.
TEST(SteadyCriterion, SavedWindowResumesBitForBit) {
  const SteadyCriterionOptions o{0.25, 4, 1e-3};
  SteadyCriterion whole(o), resumed(o);
  auto sample = [](int n) {
    const double f = 10.0 + std::exp(-0.3 * n);
    return std::vector<SteadyGroup>{{{f, 0.1 * f}, f}};
  };
  auto eta = [](int n) { return std::vector<double>{std::sin(0.1 * n), 1.0 + std::exp(-0.2 * n)}; };
  for (int n = 0; n < 9; ++n) whole.Add(0.1 * n, sample(n), eta(n));
  resumed.Load(whole.Save());
  EXPECT_EQ(resumed.Save(), whole.Save());
  EXPECT_EQ(resumed.force_change(), whole.force_change());
  for (int n = 9; n < 30; ++n) {
    whole.Add(0.1 * n, sample(n), eta(n));
    resumed.Add(0.1 * n, sample(n), eta(n));
    EXPECT_EQ(resumed.force_change(), whole.force_change()) << n;
    EXPECT_EQ(resumed.eta_change(), whole.eta_change()) << n;
    EXPECT_EQ(resumed.Settled(), whole.Settled()) << n;
  }
  SteadyCriterion fresh(o);
  fresh.Load(SteadyCriterion(o).Save());  // an empty window
  EXPECT_TRUE(std::isnan(fresh.force_change()));
  std::vector<double> saved = whole.Save();
  EXPECT_THROW(fresh.Load(std::vector<double>(saved.begin(), saved.end() - 1)), DataFileError);
  saved.push_back(0.0);
  EXPECT_THROW(fresh.Load(saved), DataFileError);
  saved.pop_back();
  saved[0] = 1e12;  // more samples than numbers
  EXPECT_THROW(fresh.Load(saved), DataFileError);
  saved[0] = 2.5;
  EXPECT_THROW(fresh.Load(saved), DataFileError);
}

}  // namespace
}  // namespace kelvin::cfd
