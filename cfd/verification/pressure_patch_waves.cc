#include "cfd/verification/pressure_patch_waves.h"

#include <fmt/format.h>

#include <cmath>
#include <complex>
#include <numbers>
#include <unsupported/Eigen/FFT>

#include "data/schema/errors.h"

namespace kelvin::cfd {

void PressurePatchWaveOptions::Validate() const {
  auto positive = [](double v, const char* name) {
    if (!(v > 0.0) || !std::isfinite(v)) {
      throw ConfigError(fmt::format("pressure patch waves: {} = {}; expected a finite value > 0", name, v));
    }
  };
  positive(g, "g");
  positive(speed, "speed");
  positive(depth, "depth");
  positive(radius, "radius");
  positive(head, "head");
  positive(spacing, "spacing");
  positive(box_length, "box_length");
  positive(box_width, "box_width");
  positive(damping_length, "damping_length");
  if (!std::isfinite(origin_x) || !std::isfinite(origin_y)) {
    throw ConfigError(fmt::format("pressure patch waves: origin = ({}, {}); expected finite values",
                                  origin_x, origin_y));
  }
  // The grid must resolve the patch and the box must hold many damping
  // lengths' worth of decay before the waves wrap around.
  if (spacing > 0.25 * radius) {
    throw ConfigError(fmt::format(
        "pressure patch waves: spacing = {} m; expected at most radius / 4 = {} m", spacing, 0.25 * radius));
  }
  if (box_length < 5.0 * damping_length) {
    throw ConfigError(fmt::format(
        "pressure patch waves: box_length = {} m; expected at least 5 damping lengths ({} m)", box_length,
        5.0 * damping_length));
  }
}

PressurePatchWaves::PressurePatchWaves(const PressurePatchWaveOptions& options) : options_(options) {
  options_.Validate();
  const auto& o = options_;
  nx_ = 2 * static_cast<int>(std::ceil(0.5 * o.box_length / o.spacing));
  ny_ = 2 * static_cast<int>(std::ceil(0.5 * o.box_width / o.spacing));
  const double lx = nx_ * o.spacing, ly = ny_ * o.spacing;
  constexpr double kTwoPi = 2.0 * std::numbers::pi;
  const double eps = o.speed / (2.0 * o.damping_length);
  const double p0 = o.g * o.head;
  const double r2 = o.radius * o.radius;
  // Signed FFT wavenumber of index n on a grid of N points over length L.
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
        const double kt = k * std::tanh(k * o.depth);
        const std::complex<double> omega(a * o.speed, -eps);
        const double pressure = p0 * std::numbers::pi * r2 * std::exp(-0.25 * k * k * r2);
        value = -pressure * kt / (o.g * kt - omega * omega) *
                std::exp(std::complex<double>(0.0, a * o.origin_x + b * o.origin_y)) / (lx * ly);
      }
      field[static_cast<std::size_t>(i) * ny_ + j] = value;
    }
  }

  // Inverse 2D transform, unscaled (the 1 / (Lx Ly) is in the spectrum).
  Eigen::FFT<double> fft;
  fft.SetFlag(Eigen::FFT<double>::Unscaled);
  std::vector<std::complex<double>> in(std::max(nx_, ny_)), out;
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

double PressurePatchWaves::Elevation(double x, double y) const {
  auto index = [](double s, int count) {
    const long n = std::lround(s);
    return static_cast<int>(((n % count) + count) % count);
  };
  const int i = index((x - options_.origin_x) / options_.spacing, nx_);
  const int j = index((y - options_.origin_y) / options_.spacing, ny_);
  return eta_[static_cast<std::size_t>(i) * ny_ + j];
}

}  // namespace kelvin::cfd
