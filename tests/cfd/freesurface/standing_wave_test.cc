// Acceptance 2 of issue 6: a small-amplitude standing wave in a closed box
// (linearized free surface on top, slip walls, nu = 1e-6) oscillates at the
// linear dispersion frequency omega^2 = g k tanh(k h), with the damping of the
// time scheme only, and stays stable far beyond the explicit gravity-wave
// time-step limit.
//
// The box is 2D (x-z, one cell in y): L = 1 m, h = 0.5 m, 40 x 20 cells; the
// mode eta = a cos(k x), k = pi / L, is an exact discrete eigenvector in x on
// the uniform grid with slip walls, so the computed modal amplitude is one
// damped oscillation and Prony's two-term fit recovers its per-step
// amplification G exactly. From G the time scheme can be inverted: Euler
// has G = 1 / (1 - i omega_h dt), BDF2 (3/2 - i omega_h dt) G^2 - 2 G + 1/2 = 0,
// which gives the frequency omega_h of the space-discrete system and tells
// the error of the spatial discretization apart from that of the time step.
//
// Explicit limit. With the dynamic condition explicit (p_f = g eta^n) the
// scheme is symplectic Euler on d eta/dt = w, dw/dt = -g Lambda eta, where
// Lambda is the discrete Dirichlet-to-Neumann operator of the pressure
// equation (surface flux per unit surface pressure, times 1/rAU = 1/dt); it is
// stable for dt^2 g Lambda_max < 4, i.e. dt < dt_expl = 2 / sqrt(g Lambda_max).
// Lambda_max belongs to the shortest x mode of the grid and is computed below
// exactly for this grid (a tridiagonal solve down the column).
#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <cstdio>
#include <numbers>

#include "tests/cfd/freesurface/free_surface_test_support.h"

namespace kelvin::cfd {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kG = 9.81;
constexpr double kL = 1.0;
constexpr double kDepth = 0.5;
constexpr int kNx = 40;
constexpr int kNz = 20;
constexpr double kAmplitude = 1e-3;

Mesh StandingWaveMesh() {
  BoxMeshOptions mo;
  mo.min = Vector3(0.0, 0.0, -kDepth);
  mo.max = Vector3(kL, 0.05, 0.0);
  mo.cells = {kNx, 1, kNz};
  mo.kinds[2] = mo.kinds[3] = PatchKind::kEmpty;
  return MakeBoxMesh(mo);
}

// Lambda of x mode k on the uniform nx x nz grid: solve the discrete Laplace
// equation in the column with a unit surface pressure (half-cell distance to
// the face, Neumann bottom) and return the surface flux per unit area.
double DiscreteDtN(double k, double dx, double dz, int nz) {
  const double lx = (2.0 - 2.0 * std::cos(k * dx)) / (dx * dx);
  // Rows j = 0 (bottom) ... nz-1 (top), each multiplied by dz^2.
  std::vector<double> lo(nz, -1.0), di(nz), up(nz, -1.0), rhs(nz, 0.0);
  for (int j = 0; j < nz; ++j) di[j] = 2.0 + lx * dz * dz;
  di[0] = 1.0 + lx * dz * dz;       // Neumann bottom
  di[nz - 1] = 3.0 + lx * dz * dz;  // face at dz/2: 2 (p - p_f) + (p - p_below)
  rhs[nz - 1] = 2.0;                // p_f = 1
  for (int j = 1; j < nz; ++j) {    // Thomas algorithm
    const double m = lo[j] / di[j - 1];
    di[j] -= m * up[j - 1];
    rhs[j] -= m * rhs[j - 1];
  }
  std::vector<double> p(nz);
  p[nz - 1] = rhs[nz - 1] / di[nz - 1];
  for (int j = nz - 2; j >= 0; --j) p[j] = (rhs[j] - up[j] * p[j + 1]) / di[j];
  return (1.0 - p[nz - 1]) / (0.5 * dz);
}

double ExplicitLimit() {
  const double dx = kL / kNx, dz = kDepth / kNz;
  const double lambda_max = DiscreteDtN((kNx - 1) * kPi / kL, dx, dz, kNz);
  return 2.0 / std::sqrt(kG * lambda_max);
}

double ExactOmega() {
  const double k = kPi / kL;
  return std::sqrt(kG * k * std::tanh(k * kDepth));
}

// Runs `steps` steps of size dt from eta = a cos(k x), u = 0, and returns the
// modal amplitude after each step (index 0: the initial value).
std::vector<double> ModalAmplitude(TimeScheme scheme, double dt, int steps) {
  const Mesh mesh = StandingWaveMesh();
  LinearizedFreeSurface* fs = nullptr;
  LinearizedFreeSurfaceOptions o;
  o.g = kG;
  auto solver = testing::MakeWaterBox(mesh, o, scheme, &fs);
  const double k = kPi / kL;
  const auto x = fs->surface().centres();
  const auto area = fs->surface().areas();
  std::vector<double> eta(x.size());
  double norm = 0.0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    eta[i] = kAmplitude * std::cos(k * x[i].x());
    norm += std::pow(std::cos(k * x[i].x()), 2) * area[i];
  }
  fs->SetEta(eta);
  auto project = [&]() {
    double s = 0.0;
    for (std::size_t i = 0; i < x.size(); ++i) s += fs->eta()[i] * std::cos(k * x[i].x()) * area[i];
    return s / norm;
  };
  std::vector<double> a = {project()};
  for (int n = 0; n < steps; ++n) {
    const StepSummary s = solver->Step(dt);
    EXPECT_TRUE(s.finite) << "step " << n;
    if (!s.finite) break;
    a.push_back(project());
  }
  return a;
}

TEST(StandingWave, DispersionFrequencyWithinOnePercentAtSmallStep) {
  const double omega = ExactOmega();
  const double period = 2.0 * kPi / omega;
  const double dt = period / 100.0;
  const std::vector<double> a = ModalAmplitude(TimeScheme::kBackward, dt, 300);
  ASSERT_EQ(a.size(), 301u);
  // Skip the start, where BDF2's parasitic root (about 1/3 per step) and the
  // Euler first step still show.
  const std::complex<double> G = testing::PronyRoot(a, 20);
  const double omega_measured = std::arg(G) / dt;
  const double damping_per_period = 1.0 - std::pow(std::abs(G), 2.0 * kPi / std::arg(G));
  // Space-discrete system from the BDF2 amplification factor.
  const std::complex<double> z = 1.5 - 2.0 / G + 0.5 / (G * G);
  const double omega_h = z.imag() / dt;
  const double sigma_h = -z.real() / dt;
  std::printf(
      "standing wave (BDF2, dt = T/100 = %.5f s): omega exact %.6f rad/s, measured %.6f (error "
      "%+.3f%%), "
      "space-discrete %.6f (error %+.3f%%); damping %.4f%% per period (space-discrete rate %.2e "
      "1/s)\n",
      dt, omega, omega_measured, 100.0 * (omega_measured / omega - 1.0), omega_h,
      100.0 * (omega_h / omega - 1.0), 100.0 * damping_per_period, sigma_h);
  EXPECT_NEAR(omega_measured / omega, 1.0, 0.01);
  EXPECT_NEAR(omega_h / omega, 1.0, 0.01);
  // BDF2 alone damps 0.04% per period at this step; allow a few times that.
  EXPECT_GT(damping_per_period, 0.0);
  EXPECT_LT(damping_per_period, 0.002);
  // Amplitude check independent of the fit: after three periods the signal
  // still has 99% of its amplitude.
  double late_max = 0.0;
  for (std::size_t n = 200; n < a.size(); ++n) late_max = std::max(late_max, std::abs(a[n]));
  EXPECT_GT(late_max, 0.99 * kAmplitude);
  EXPECT_LT(late_max, kAmplitude * (1.0 + 1e-9));
}

// Euler at 10x, 30x and 100x the explicit limit. Implicit Euler from rest
// (w = 0) gives eta^1 = eta^0 / (1 + (omega dt)^2) exactly, and later steps
// follow G = 1 / (1 - i omega dt): |G| = 1 / sqrt(1 + (omega dt)^2), observed
// frequency atan(omega dt) / dt. The run must stay stable, and inverting
// Euler from the computed amplitudes must recover the physical omega (1% at
// 10x and 30x; 2% at 100x, where the viscous part of the momentum diagonal,
// nu dt / dx^2 = 0.014, already shifts 1/rAU by a few percent). The raw
// observed frequency is far from omega at these steps (omega dt = 4.5, 13.5,
// 45: a few steps per period or fewer), exactly as the time scheme dictates;
// that is the justified wider tolerance on the frequency itself. The Prony
// fit needs a few samples above the solver noise (1e-7 of the start), so it
// runs at 10x and 30x only.
TEST(StandingWave, StableAndOnTheImplicitEulerCurveFarBeyondTheExplicitLimit) {
  const double omega = ExactOmega();
  const double dt_expl = ExplicitLimit();
  std::printf("explicit gravity-wave limit dt_expl = %.5f s (T = %.4f s)\n", dt_expl,
              2.0 * kPi / omega);
  for (double ratio : {10.0, 30.0, 100.0}) {
    const double dt = ratio * dt_expl;
    const double theta = omega * dt;
    const std::vector<double> a = ModalAmplitude(TimeScheme::kEuler, dt, 8);
    ASSERT_EQ(a.size(), 9u);
    // Stable: never above the start and decayed by orders of magnitude.
    for (std::size_t n = 1; n < a.size(); ++n)
      EXPECT_LT(std::abs(a[n]), std::abs(a[0])) << "step " << n;
    EXPECT_LT(std::abs(a.back()), 1e-3 * std::abs(a[0]));
    const double omega_first = std::sqrt(a[0] / a[1] - 1.0) / dt;
    std::printf(
        "dt = %.0f x dt_expl = %.4f s (omega dt = %.1f): first-step factor %.4e (Euler %.4e), "
        "recovered "
        "omega %.5f (error %+.3f%%)\n",
        ratio, dt, theta, a[1] / a[0], 1.0 / (1.0 + theta * theta), omega_first,
        100.0 * (omega_first / omega - 1.0));
    EXPECT_NEAR(omega_first / omega, 1.0, ratio < 50.0 ? 0.01 : 0.02);
    if (ratio > 50.0) continue;
    const std::complex<double> G = testing::PronyRoot(a, 1);
    const std::complex<double> inv = 1.0 / G;  // = 1 - i omega_h dt for implicit Euler
    const double omega_h = -inv.imag() / dt;
    std::printf(
        "  Prony: |G| = %.5f (Euler %.5f), observed omega %.4f (Euler %.4f, exact %.4f), recovered "
        "omega "
        "%.5f (error %+.3f%%)\n",
        std::abs(G), 1.0 / std::sqrt(1.0 + theta * theta), std::arg(G) / dt, std::atan(theta) / dt,
        omega, omega_h, 100.0 * (omega_h / omega - 1.0));
    EXPECT_LT(std::abs(G), 1.0);
    EXPECT_NEAR(std::abs(G) * std::sqrt(1.0 + theta * theta), 1.0, 0.01);
    EXPECT_NEAR(std::arg(G) / std::atan(theta), 1.0, 0.01);
    EXPECT_NEAR(omega_h / omega, 1.0, 0.01);
  }
}

}  // namespace
}  // namespace kelvin::cfd
