// Steady linear waves of a Gaussian pressure patch moving at constant speed
// over water of uniform depth: the exact solution of the linearized
// free-surface problem that the LinearizedFreeSurface condition discretizes
// (a Havelock pressure distribution), used to validate computed Kelvin
// patterns.
//
// Frame moving with the patch; the stream runs along +x at speed U, so the
// waves trail at x > 0. Surface pressure p_a = p0 exp(-(x^2 + y^2) / r^2).
// With eta = Fourier transform of the elevation and k = |(a, b)|, the
// linearized kinematic (U eta_x = phi_z) and dynamic (U phi_x + g eta +
// p_a / rho = 0) conditions over depth h give
//
//   eta^(a, b) = -P^(k) k tanh(k h) / (g k tanh(k h) - (a U - i eps)^2),
//   P^(k) = (p0 / rho) pi r^2 exp(-k^2 r^2 / 4),
//
// where the vanishing Rayleigh damping eps > 0 selects the radiation
// condition (no waves ahead of the patch). The inverse transform is taken by
// FFT on a periodic box much larger than the region of interest, with eps
// small enough that the waves decay only slightly across that region but
// die out before they wrap around the box. With eps = U / (2 L_d) a free
// transverse wave's amplitude falls as exp(-x / (2 L_d (1 - c_g / c))): as
// exp(-x / L_d) in deep water, where its energy moves downstream at U / 2 in
// this frame. The box is at least 5 L_d long.
#pragma once

#include <vector>

namespace kelvin::cfd {

struct PressurePatchWaveOptions {
  double g = 9.81;            // m/s^2
  double speed = 0.0;         // U, m/s
  double depth = 0.0;         // h, m (> 0)
  double radius = 0.0;        // r of the Gaussian, m
  double head = 0.0;          // p0 / (rho g), m
  double spacing = 0.0;       // grid spacing, m (same in x and y)
  double origin_x = 0.0;      // position of grid node (0, 0) relative to the patch
  double origin_y = 0.0;      //   centre, m; nodes at origin + (i, j) spacing
  double box_length = 200.0;  // periodic box along x, m (>= 5 damping lengths)
  double box_width = 60.0;    // periodic box along y, m
  double damping_length = 40.0;  // L_d, m
  void Validate() const;         // ConfigError naming the field
};

class PressurePatchWaves {
 public:
  explicit PressurePatchWaves(const PressurePatchWaveOptions& options);

  // Elevation eta (m) at the grid node nearest to (x, y), relative to the
  // patch centre; exact at the nodes origin + (i, j) spacing. Points farther
  // than half the box from the patch wrap around (the box is periodic).
  double Elevation(double x, double y) const;

  int nx() const { return nx_; }
  int ny() const { return ny_; }

 private:
  PressurePatchWaveOptions options_;
  int nx_ = 0, ny_ = 0;
  std::vector<double> eta_;  // row-major in x: eta_[i * ny_ + j]
};

}  // namespace kelvin::cfd
