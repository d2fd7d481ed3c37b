// Steady linear waves of disturbances moving at constant speed over calm
// water: exact solutions of the linearized free-surface problem that the
// LinearizedFreeSurface condition discretizes, used to validate computed
// Kelvin patterns.
//
// Frame moving with the disturbance; the stream runs along +x at speed U, so
// the waves trail at x > 0. With eta^ the Fourier transform of the elevation
// over (x, y) -> (a, b), k = |(a, b)| and water of depth h,
//
//   eta^(a, b) = S(a, b) / (g k tanh(k h) - (a U - i eps)^2),
//
// where S is the forcing of the disturbance and the vanishing Rayleigh
// damping eps > 0 selects the radiation condition (no waves ahead). Two
// forcings:
// - PressurePatchWaves: a Gaussian surface pressure p_a = p0 exp(-(x^2 +
//   y^2) / r^2) (a Havelock pressure distribution), S = -P^ k tanh(k h) with
//   P^ = (p0 / rho) pi r^2 exp(-k^2 r^2 / 4), from the kinematic (U eta_x =
//   phi_z) and dynamic (U phi_x + g eta + p_a / rho = 0) conditions;
// - ThinShipWaves: Michell's thin ship, deep water: the Wigley hull y =
//   +-f(x, z), f = (B/2)(1 - xi^2)(1 - (z/T)^2), xi = 2 (x - x_c) / L,
//   replaced by sources of density m = 2 U df/dx on the centreplane. A
//   source Q at depth zeta gives eta^ = i a U Q e^{k zeta} / (g k - (a U)^2)
//   (source, image and the free-surface condition U^2 phi_xx + g phi_z = 0),
//   so S = i a U M^(a, k), M^ = integral of m e^{k z} e^{-i a x}: the x
//   integral in closed form, the z integral by Gauss-Legendre quadrature.
//   The bow is at x_c - L/2 (upstream).
//
// The inverse transform is taken by FFT on a periodic box much larger than
// the region of interest, with eps small enough that the waves decay only
// slightly across that region but die out before they wrap around the box.
// With eps = U / (2 L_d) a free transverse wave's amplitude falls as
// exp(-x / (2 L_d (1 - c_g / c))): as exp(-x / L_d) in deep water, where its
// energy moves downstream at U / 2 in this frame. The box is at least 5 L_d
// long. The box mean of eta is zero (no k = 0 mode).
#pragma once

#include <complex>
#include <functional>
#include <vector>

namespace kelvin::cfd {

// Gauss-Legendre nodes and weights of n points on [-1, 1] (Newton on the
// Legendre recurrence; exact for polynomials of degree 2n - 1).
void GaussLegendre(int n, std::vector<double>& nodes, std::vector<double>& weights);

// The periodic grid the waves are computed on.
struct WaveBoxOptions {
  double g = 9.81;               // m/s^2
  double speed = 0.0;            // U, m/s
  double spacing = 0.0;          // grid spacing, m (same in x and y)
  double origin_x = 0.0;         // position of grid node (0, 0) relative to the
  double origin_y = 0.0;         //   disturbance's origin, m; nodes at origin + (i, j) spacing
  double box_length = 200.0;     // periodic box along x, m (>= 5 damping lengths)
  double box_width = 60.0;       // periodic box along y, m
  double damping_length = 40.0;  // L_d, m
};

// The elevation on the periodic grid, from the forcing S(a, b) and the depth
// (infinity: deep water).
class SteadyWaveField {
 public:
  // Elevation eta (m) at the grid node nearest to (x, y); exact at the nodes
  // origin + (i, j) spacing. The box is periodic.
  double Elevation(double x, double y) const;
  // Bilinear interpolation between the four surrounding nodes.
  double Interpolate(double x, double y) const;
  int nx() const { return nx_; }
  int ny() const { return ny_; }

 protected:
  using Forcing = std::function<std::complex<double>(double a, double b, double k)>;
  // Validates the box (ConfigError naming the field, `what` first).
  SteadyWaveField(const char* what, const WaveBoxOptions& box, double depth, double finest_length,
                  const Forcing& forcing);

 private:
  double Node(int i, int j) const;
  WaveBoxOptions box_;
  int nx_ = 0, ny_ = 0;
  std::vector<double> eta_;  // row-major in x: eta_[i * ny_ + j]
};

struct PressurePatchWaveOptions : WaveBoxOptions {
  double depth = 0.0;   // h, m (> 0)
  double radius = 0.0;  // r of the Gaussian, m
  double head = 0.0;    // p0 / (rho g), m
};

class PressurePatchWaves : public SteadyWaveField {
 public:
  explicit PressurePatchWaves(const PressurePatchWaveOptions& options);
};

struct ThinShipWaveOptions : WaveBoxOptions {
  double length = 0.0;    // L, m
  double beam = 0.0;      // B, m
  double draft = 0.0;     // T, m
  double centre_x = 0.0;  // x_c, midship relative to the disturbance origin, m
  // Shortest waves kept, m (0: all): the forcing is filtered by
  // exp(-(k / k_c)^4), k_c = 2 pi / cutoff_wavelength. The sharp ends of the
  // Wigley (df/dx jumps at bow and stern, up to z = 0) excite divergent
  // waves of every length; those shorter than a few grid spacings alias
  // into spurious short waves everywhere, ahead of the bow included. A grid
  // that computes the flow resolves none of them either.
  double cutoff_wavelength = 0.0;
};

class ThinShipWaves : public SteadyWaveField {
 public:
  explicit ThinShipWaves(const ThinShipWaveOptions& options);
};

}  // namespace kelvin::cfd
