// The exact linear steady waves of a moving Gaussian pressure patch
// (cfd/verification/steady_waves.h), checked against the limits the
// Fourier solution must reproduce before it can serve as the reference of
// the Kelvin-pattern validation.
#include "cfd/verification/steady_waves.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>

#include "data/schema/errors.h"

namespace kelvin::cfd {
namespace {

constexpr double kG = 9.81;

// Wavelength on y = 0 between x = from and to, from the mean spacing of the
// zero crossings (linear interpolation between nodes); 0 with fewer than
// `min_crossings`.
double CentrelineWavelength(const SteadyWaveField& waves, double from, double to, double step,
                            std::size_t min_crossings) {
  std::vector<double> crossings;
  double last_x = 0.0, last_eta = 0.0;
  for (double x = from; x <= to; x += step) {
    const double eta = waves.Elevation(x, 0.0);
    if (x > from && eta * last_eta < 0.0) crossings.push_back(last_x + (x - last_x) * last_eta / (last_eta - eta));
    last_x = x;
    last_eta = eta;
  }
  if (crossings.size() < min_crossings) return 0.0;
  return 2.0 * (crossings.back() - crossings.front()) / static_cast<double>(crossings.size() - 1);
}

PressurePatchWaveOptions Patch(double speed, double depth) {
  PressurePatchWaveOptions o;
  o.g = kG;
  o.speed = speed;
  o.depth = depth;
  o.radius = 0.25;
  o.head = 0.005;
  o.spacing = 1.0 / 16.0;
  return o;  // box 200 x 60 m, damping length 40 m (the defaults)
}

// Creeping speed: every free wave is far shorter than the patch (2 pi U^2 / g
// = 0.6 um against r = 0.25 m), so the surface takes the hydrostatic
// depression eta = -p_a / (rho g); the first correction is of the order of
// the squared depth Froude number U^2 / (g h) = 2e-7. This checks the
// transform's normalization and the node offsets.
TEST(PressurePatchWaves, HydrostaticDepressionAtCreepingSpeed) {
  PressurePatchWaveOptions o = Patch(0.001, 0.5);
  o.origin_x = 0.03;  // nodes off the patch centre
  o.origin_y = -0.02;
  const PressurePatchWaves waves(o);
  double worst = 0.0;
  for (int i = -10; i <= 10; ++i) {
    for (int j = -10; j <= 10; ++j) {
      const double x = o.origin_x + i * o.spacing, y = o.origin_y + j * o.spacing;
      // The box mean of eta is zero (no k = 0 mode): the depression's volume
      // pi r^2 head is spread as a rise over the periodic box.
      const double mean = std::numbers::pi * o.radius * o.radius * o.head /
                          ((waves.nx() * o.spacing) * (waves.ny() * o.spacing));
      const double hydrostatic = mean - o.head * std::exp(-(x * x + y * y) / (o.radius * o.radius));
      worst = std::max(worst, std::abs(waves.Elevation(x, y) - hydrostatic));
    }
  }
  std::printf("creeping patch: max |eta - hydrostatic| = %.2e of the head\n", worst / o.head);
  EXPECT_LT(worst, 1e-5 * o.head) << "max deviation from -p_a/(rho g): " << worst << " m";
}

// At speed: the centreline far behind the patch carries the transverse wave
// of the finite-depth dispersion relation k tanh(k h) = g / U^2, nothing
// travels upstream, and the result does not depend on the (vanishing)
// damping once its length is large.
TEST(PressurePatchWaves, TransverseWavelengthAndRadiationCondition) {
  const double lambda0 = 1.0;
  const double U = std::sqrt(kG * lambda0 / (2.0 * std::numbers::pi));
  const double h = 0.25;  // k0 h = pi / 2: a clearly finite-depth wavelength
  PressurePatchWaveOptions o = Patch(U, h);
  const PressurePatchWaves waves(o);
  // Steady transverse wave, phase speed U: k U^2 = g tanh(k h), by
  // fixed-point iteration on k = k0 tanh(k h) from k0 = g / U^2.
  const double k0 = kG / (U * U);
  double k = k0;
  for (int it = 0; it < 200; ++it) k = k0 * std::tanh(k * h);
  const double expected = 2.0 * std::numbers::pi / k;
  // Zero crossings between 6 and 12 wavelengths behind, on y = 0.
  const double measured = CentrelineWavelength(waves, 6.0, 12.0, o.spacing, 8);
  ASSERT_GT(measured, 0.0) << "fewer than 8 crossings";
  // Linear interpolation of crossings on a 16-point-per-wavelength grid: the
  // error is O(spacing^2 / lambda^2) of the crossing position, well under 1%.
  EXPECT_NEAR(measured / expected, 1.0, 0.01) << "measured " << measured << " m, dispersion " << expected << " m";
  EXPECT_GT(expected / lambda0, 1.05);  // the depth matters at this h

  // Upstream: from 2 to 5 wavelengths ahead, |eta| is a small fraction of the
  // wave behind (no waves ahead of the patch; what remains is the tail of the
  // local disturbance and the waves that wrapped around the periodic box
  // after decaying by about exp(-4)).
  double peak_behind = 0.0, max_ahead = 0.0;
  for (double x = 2.0; x <= 5.0; x += o.spacing) {
    peak_behind = std::max(peak_behind, std::abs(waves.Elevation(x, 0.0)));
    max_ahead = std::max(max_ahead, std::abs(waves.Elevation(-x, 0.0)));
  }
  EXPECT_LT(max_ahead, 0.02 * peak_behind);

  // Damping length doubled: the wave 3 wavelengths behind changes as the
  // damped free wave decays, exp(-x / (2 L_d (1 - c_g / c))) with the group
  // to phase speed ratio of the finite-depth wave (0.67 here; 1/2 in deep
  // water): 6% between L_d 40 and 80, so the solution converges as L_d
  // grows, at the predicted rate.
  PressurePatchWaveOptions longer = o;
  longer.damping_length = 80.0;
  longer.box_length = 400.0;
  const PressurePatchWaves waves_longer(longer);
  double peak40 = 0.0, peak80 = 0.0;
  for (double x = 2.5; x <= 3.5; x += o.spacing) {
    peak40 = std::max(peak40, std::abs(waves.Elevation(x, 0.0)));
    peak80 = std::max(peak80, std::abs(waves_longer.Elevation(x, 0.0)));
  }
  const double kh = k * h;
  const double group_ratio = 0.5 * (1.0 + 2.0 * kh / std::sinh(2.0 * kh));
  const double rate = 1.0 / (2.0 * (1.0 - group_ratio));  // per damping length
  std::printf(
      "h = %.2f m: centreline wavelength %.4f m against %.4f m from the dispersion relation; upstream "
      "max |eta| %.4f of the wave behind; L_d 40 / 80 wave ratio %.4f against %.4f predicted\n",
      h, measured, expected, max_ahead / peak_behind, peak40 / peak80,
      std::exp(-3.0 * rate * (1.0 / 40.0 - 1.0 / 80.0)));
  EXPECT_NEAR(peak40 / peak80, std::exp(-3.0 * rate * (1.0 / 40.0 - 1.0 / 80.0)), 0.01);
}

// Michell's thin ship (a 6 m Wigley, L/B 10, B/T 1.6). At Fn 0.005 the free
// waves are far too short to be excited, and the surface follows the
// double-body (rigid-lid) flow of the centreplane sources: eta = -(U/g)
// phi_x with phi = -(1/(2 pi)) integral m / R (source and image), m = 2 U
// df/dx. That integral by Gauss quadrature, at points off the hull, checks
// the source density, its transform and the shift to midship.
// The 6 m Wigley of the resistance cases (L/B 10, B/T 1.6) at Froude number fn.
ThinShipWaveOptions Wigley(double fn) {
  ThinShipWaveOptions o;
  o.length = 6.0;
  o.beam = 0.6;
  o.draft = 0.375;
  o.speed = fn * std::sqrt(kG * o.length);
  return o;
}

TEST(ThinShipWaves, RigidLidLimitAtCreepingSpeed) {
  ThinShipWaveOptions o = Wigley(0.005);
  o.centre_x = 1.0;
  o.spacing = 0.04;
  o.box_length = 60.0;
  o.box_width = 24.0;
  o.damping_length = 6.0;
  const ThinShipWaves waves(o);
  std::vector<double> gx, gw;
  GaussLegendre(64, gx, gw);
  auto rigid_lid = [&](double x, double y) {
    double sum = 0.0;  // integral of f_x (x - xi) / R^3 over the centreplane
    for (std::size_t a = 0; a < gx.size(); ++a) {
      const double xi = o.centre_x + 0.5 * o.length * gx[a];
      const double fx = -(2.0 * o.beam / o.length) * gx[a];  // df/dx at depth 0, bow upstream
      for (std::size_t b = 0; b < gx.size(); ++b) {
        const double z = -0.5 * o.draft * (gx[b] + 1.0);
        const double r2 = (x - xi) * (x - xi) + y * y + z * z;
        sum += 0.25 * o.length * o.draft * gw[a] * gw[b] * fx * (1.0 - (z / o.draft) * (z / o.draft)) * (x - xi) /
               (r2 * std::sqrt(r2));
      }
    }
    return -o.speed * o.speed / (std::numbers::pi * kG) * sum;
  };
  double worst = 0.0, scale = 0.0;
  for (double fx : {-0.8, -0.5, -0.2, 0.0, 0.2, 0.5, 0.8}) {
    for (double fy : {0.2, 0.4}) {
      const double x = o.centre_x + fx * o.length, y = fy * o.length;
      const double exact = rigid_lid(x, y);
      scale = std::max(scale, std::abs(exact));
      worst = std::max(worst, std::abs(waves.Interpolate(x, y) - exact));
    }
  }
  std::printf("thin ship at Fn 0.005: max |eta - rigid-lid eta| = %.2e of the largest (%.3e m)\n", worst / scale,
              scale);
  // The bilinear interpolation between nodes 4 cm apart (1e-4 here) and
  // the neglected O(Fn^2 L k) wave correction at the resolved wavenumbers.
  EXPECT_LT(worst, 0.01 * scale);
}

// At speed: the transverse waves behind the hull have the deep-water length
// 2 pi U^2 / g, and nothing travels ahead of the bow: from one wavelength
// ahead on, what is left is the decaying rise of the bow's stagnation and
// the waves that wrapped around the periodic box (measured: 4% of the waves
// behind in this 400 x 120 m box, 9% in a 200 x 60 m one).
TEST(ThinShipWaves, TransverseWavelengthBehindAndCalmAhead) {
  ThinShipWaveOptions o = Wigley(0.316);
  o.spacing = 0.1;
  o.cutoff_wavelength = 0.4;
  o.box_length = 400.0;
  o.box_width = 120.0;
  const ThinShipWaves waves(o);
  const double lambda = 2.0 * std::numbers::pi * o.speed * o.speed / kG;
  const double from = 0.5 * o.length + 4.0 * lambda, to = from + 6.0 * lambda;
  const double measured = CentrelineWavelength(waves, from, to, o.spacing, 6);
  ASSERT_GT(measured, 0.0) << "fewer than 6 crossings";
  double behind = 0.0, ahead = 0.0;
  for (double x = from; x <= to; x += o.spacing) behind = std::max(behind, std::abs(waves.Elevation(x, 0.0)));
  for (double x = -0.5 * o.length - lambda; x >= -0.5 * o.length - 4.0 * lambda; x -= o.spacing) {
    ahead = std::max(ahead, std::abs(waves.Elevation(x, 0.0)));
  }
  std::printf("thin ship at Fn 0.316: transverse wavelength %.4f m against 2 pi U^2/g = %.4f m; ahead of the bow "
              "max |eta| %.4f of the waves behind (from one wavelength on)\n",
              measured, lambda, ahead / behind);
  EXPECT_NEAR(measured / lambda, 1.0, 0.01);
  EXPECT_LT(ahead, 0.1 * behind);
}

// The quadrature of the thin-ship sources: n points integrate x^(2n - 2)
// exactly (2 / (2n - 1) on [-1, 1]) and the weights sum to 2.
TEST(GaussLegendre, ExactForPolynomialsOfDegree2nMinus1) {
  for (int n : {1, 4, 32}) {
    std::vector<double> x, w;
    GaussLegendre(n, x, w);
    double sum = 0.0, moment = 0.0;
    for (int i = 0; i < n; ++i) {
      sum += w[i];
      moment += w[i] * std::pow(x[i], 2 * n - 2);
    }
    EXPECT_NEAR(sum, 2.0, 1e-13) << n;
    EXPECT_NEAR(moment, 2.0 / (2 * n - 1), 1e-13) << n;
  }
}

std::string Message(const PressurePatchWaveOptions& o) {
  try {
    PressurePatchWaves waves(o);
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "no error";
}

TEST(PressurePatchWaves, BadOptionsNameTheField) {
  using ::testing::HasSubstr;
  PressurePatchWaveOptions o = Patch(1.0, 0.5);
  o.depth = -1.0;
  EXPECT_THAT(Message(o), HasSubstr("depth = -1; expected a finite value > 0"));
  o = Patch(1.0, 0.5);
  o.spacing = 0.2;
  EXPECT_THAT(Message(o), HasSubstr("spacing = 0.2 m; expected at most 0.0625 m"));
  o = Patch(1.0, 0.5);
  o.box_length = 190.0;
  EXPECT_THAT(Message(o), HasSubstr("box_length = 190 m; expected at least 5 damping lengths"));
}

}  // namespace
}  // namespace kelvin::cfd
