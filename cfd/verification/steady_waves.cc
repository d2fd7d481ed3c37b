#include "cfd/verification/steady_waves.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <unsupported/Eigen/FFT>

#include "data/schema/errors.h"

namespace kelvin::cfd {
namespace {

void RequirePositive(const char* what, double v, const char* name) {
  if (!(v > 0.0) || !std::isfinite(v)) {
    throw ConfigError(fmt::format("{}: {} = {}; expected a finite value > 0", what, name, v));
  }
}

}  // namespace

void GaussLegendre(int n, std::vector<double>& x, std::vector<double>& w) {
  x.assign(n, 0.0);
  w.assign(n, 0.0);
  for (int i = 0; i < n; ++i) {
    double t = std::cos(std::numbers::pi * (i + 0.75) / (n + 0.5)), dp = 0.0;
    for (int it = 0; it < 100; ++it) {
      double p0 = 1.0, p1 = t;
      for (int m = 2; m <= n; ++m) {
        const double p2 = ((2.0 * m - 1.0) * t * p1 - (m - 1.0) * p0) / m;
        p0 = p1;
        p1 = p2;
      }
      dp = n * (t * p1 - p0) / (t * t - 1.0);
      const double step = p1 / dp;
      t -= step;
      if (std::abs(step) < 1e-15) break;
    }
    x[i] = t;
    w[i] = 2.0 / ((1.0 - t * t) * dp * dp);
  }
}

SteadyWaveField::SteadyWaveField(const char* what, const WaveBoxOptions& box, double depth, double finest_length,
                                 const Forcing& forcing)
    : box_(box) {
  RequirePositive(what, box.g, "g");
  RequirePositive(what, box.speed, "speed");
  RequirePositive(what, box.spacing, "spacing");
  RequirePositive(what, box.box_length, "box_length");
  RequirePositive(what, box.box_width, "box_width");
  RequirePositive(what, box.damping_length, "damping_length");
  if (!std::isfinite(box.origin_x) || !std::isfinite(box.origin_y)) {
    throw ConfigError(fmt::format("{}: origin = ({}, {}); expected finite values", what, box.origin_x, box.origin_y));
  }
  // The grid must resolve the disturbance and the box must hold enough
  // decay before the waves wrap around.
  if (box.spacing > 0.25 * finest_length) {
    throw ConfigError(fmt::format("{}: spacing = {} m; expected at most {} m (a quarter of the disturbance's scale)",
                                  what, box.spacing, 0.25 * finest_length));
  }
  if (box.box_length < 5.0 * box.damping_length) {
    throw ConfigError(fmt::format("{}: box_length = {} m; expected at least 5 damping lengths ({} m)", what,
                                  box.box_length, 5.0 * box.damping_length));
  }
  nx_ = 2 * static_cast<int>(std::ceil(0.5 * box.box_length / box.spacing));
  ny_ = 2 * static_cast<int>(std::ceil(0.5 * box.box_width / box.spacing));
  const double lx = nx_ * box.spacing, ly = ny_ * box.spacing;
  constexpr double kTwoPi = 2.0 * std::numbers::pi;
  const double eps = box.speed / (2.0 * box.damping_length);
  auto wavenumber = [kTwoPi](int n, int count, double length) {
    return kTwoPi * (n < count / 2 ? n : n - count) / length;
  };

  // Spectrum, shifted so that node (0, 0) sits at the origin: eta(origin +
  // (i, j) h) = (1 / (Lx Ly)) sum eta^ exp(i (a origin_x + b origin_y))
  // exp(i (a i h + b j h)).
  std::vector<std::complex<double>> field(static_cast<std::size_t>(nx_) * ny_);
  for (int i = 0; i < nx_; ++i) {
    const double a = wavenumber(i, nx_, lx);
    for (int j = 0; j < ny_; ++j) {
      const double b = wavenumber(j, ny_, ly);
      const double k = std::hypot(a, b);
      std::complex<double> value = 0.0;
      if (k > 0.0) {
        const double kt = std::isinf(depth) ? k : k * std::tanh(k * depth);
        const std::complex<double> omega(a * box.speed, -eps);
        value = forcing(a, b, k) / (box.g * kt - omega * omega) *
                std::exp(std::complex<double>(0.0, a * box.origin_x + b * box.origin_y)) / (lx * ly);
      }
      field[static_cast<std::size_t>(i) * ny_ + j] = value;
    }
  }

  // Inverse 2D transform, unscaled (the 1 / (Lx Ly) is in the spectrum).
  Eigen::FFT<double> fft;
  fft.SetFlag(Eigen::FFT<double>::Unscaled);
  std::vector<std::complex<double>> in, out;
  for (int i = 0; i < nx_; ++i) {  // along y
    in.assign(field.begin() + static_cast<std::ptrdiff_t>(i) * ny_,
              field.begin() + static_cast<std::ptrdiff_t>(i + 1) * ny_);
    fft.inv(out, in);
    std::copy(out.begin(), out.end(), field.begin() + static_cast<std::ptrdiff_t>(i) * ny_);
  }
  eta_.assign(field.size(), 0.0);
  in.resize(nx_);
  for (int j = 0; j < ny_; ++j) {  // along x
    for (int i = 0; i < nx_; ++i) in[i] = field[static_cast<std::size_t>(i) * ny_ + j];
    fft.inv(out, in);
    for (int i = 0; i < nx_; ++i) eta_[static_cast<std::size_t>(i) * ny_ + j] = out[i].real();
  }
}

double SteadyWaveField::Node(int i, int j) const {
  i = ((i % nx_) + nx_) % nx_;
  j = ((j % ny_) + ny_) % ny_;
  return eta_[static_cast<std::size_t>(i) * ny_ + j];
}

double SteadyWaveField::Elevation(double x, double y) const {
  return Node(static_cast<int>(std::lround((x - box_.origin_x) / box_.spacing)),
              static_cast<int>(std::lround((y - box_.origin_y) / box_.spacing)));
}

double SteadyWaveField::Interpolate(double x, double y) const {
  const double u = (x - box_.origin_x) / box_.spacing, v = (y - box_.origin_y) / box_.spacing;
  const double fu = std::floor(u), fv = std::floor(v);
  const int i = static_cast<int>(fu), j = static_cast<int>(fv);
  const double s = u - fu, t = v - fv;
  return (1 - s) * (1 - t) * Node(i, j) + s * (1 - t) * Node(i + 1, j) + (1 - s) * t * Node(i, j + 1) +
         s * t * Node(i + 1, j + 1);
}

PressurePatchWaves::PressurePatchWaves(const PressurePatchWaveOptions& o)
    : SteadyWaveField(
          "pressure patch waves", o,
          [&o] {
            RequirePositive("pressure patch waves", o.depth, "depth");
            RequirePositive("pressure patch waves", o.radius, "radius");
            RequirePositive("pressure patch waves", o.head, "head");
            return o.depth;
          }(),
          o.radius, [&o](double, double, double k) -> std::complex<double> {
            const double r2 = o.radius * o.radius;
            const double pressure = o.g * o.head * std::numbers::pi * r2 * std::exp(-0.25 * k * k * r2);
            return -pressure * k * std::tanh(k * o.depth);
          }) {}

namespace {

// Checks the hull before the field is built; returns the finest scale the
// grid must resolve (a tenth of the length: spacing at most L / 40).
double CheckHull(const ThinShipWaveOptions& o) {
  RequirePositive("thin ship waves", o.length, "length");
  RequirePositive("thin ship waves", o.beam, "beam");
  RequirePositive("thin ship waves", o.draft, "draft");
  if (!(o.cutoff_wavelength >= 0.0) || !std::isfinite(o.cutoff_wavelength)) {
    throw ConfigError(
        fmt::format("thin ship waves: cutoff_wavelength = {}; expected a finite value >= 0", o.cutoff_wavelength));
  }
  if (!std::isfinite(o.centre_x)) {
    throw ConfigError(fmt::format("thin ship waves: centre_x = {}; expected a finite value", o.centre_x));
  }
  return 0.1 * o.length;
}

// The thin ship's forcing S(a, b, k), with the Gauss-Legendre nodes of the
// vertical integral computed once.
std::function<std::complex<double>(double, double, double)> ThinShipForcing(const ThinShipWaveOptions& o) {
  std::vector<double> xq, wq;
  GaussLegendre(32, xq, wq);
  return [&o, xq, wq](double a, double, double k) -> std::complex<double> {
    // x: integral over the hull of df/dx e^{-i a x} = 2 i B e^{-i a x_c}
    // (sin s - s cos s) / s^2 with s = a L / 2 (series near s = 0).
    const double s = 0.5 * a * o.length;
    const double shape = std::abs(s) < 1e-4 ? s / 3.0 : (std::sin(s) - s * std::cos(s)) / (s * s);
    const std::complex<double> x_part =
        std::complex<double>(0.0, 2.0 * o.beam * shape) * std::exp(std::complex<double>(0.0, -a * o.centre_x));
    // z: integral over [-T, 0] of (1 - (z/T)^2) e^{k z}.
    double z_part = 0.0;
    for (std::size_t q = 0; q < xq.size(); ++q) {
      const double z = -0.5 * o.draft * (xq[q] + 1.0);
      z_part += 0.5 * o.draft * wq[q] * (1.0 - (z / o.draft) * (z / o.draft)) * std::exp(k * z);
    }
    // m = 2 U df/dx; S = i a U M^, low-pass filtered.
    double filter = 1.0;
    if (o.cutoff_wavelength > 0.0) {
      const double r = k * o.cutoff_wavelength / (2.0 * std::numbers::pi);
      filter = std::exp(-r * r * r * r);
    }
    return std::complex<double>(0.0, a * o.speed) * 2.0 * o.speed * x_part * z_part * filter;
  };
}

}  // namespace

ThinShipWaves::ThinShipWaves(const ThinShipWaveOptions& o)
    : SteadyWaveField("thin ship waves", o, std::numeric_limits<double>::infinity(), CheckHull(o),
                      ThinShipForcing(o)) {}

}  // namespace kelvin::cfd
