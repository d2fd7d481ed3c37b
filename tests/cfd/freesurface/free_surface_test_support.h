// Helpers of the free-surface tests: a box mesh with its surface on zmax, a
// box of water under a linearized free surface (zmax) with slip walls, Prony's fit of a sampled damped
// oscillation, and the angular spread of a steady Kelvin pattern.
#pragma once

#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <cmath>
#include <complex>
#include <memory>
#include <numbers>
#include <span>
#include <utility>
#include <vector>

#include "cfd/freesurface/linearized_free_surface.h"
#include "cfd/mesh/box_mesh.h"
#include "tests/cfd/cfd_test_support.h"

namespace kelvin::cfd::testing {

// A box mesh of `cells` between min and max (z = 0 on top: the free surface
// on zmax), its x sides plain patches.
inline Mesh Box(std::array<int, 3> cells, bool polyhedral = false, Vector3 min = Vector3(0, 0, -1),
                Vector3 max = Vector3(1, 1, 0)) {
  BoxMeshOptions mo;
  mo.min = min;
  mo.max = max;
  mo.cells = cells;
  mo.polyhedral = polyhedral;
  mo.kinds[0] = mo.kinds[1] = PatchKind::kPatch;
  return MakeBoxMesh(mo);
}

// PIMPLE solver on `mesh` with the linearized free surface on zmax, slip
// walls everywhere else (empty patches stay empty); *surface is set to the
// free-surface condition owned by the solver's pressure field.
inline std::unique_ptr<PimpleSolver> MakeWaterBox(const Mesh& mesh, LinearizedFreeSurfaceOptions fs,
                                                  TimeScheme time, LinearizedFreeSurface** surface,
                                                  int n_correctors = 2, double tolerance = 1e-12) {
  auto U = MakeField<Vector3>("U", mesh,
                              [](const Patch& p) -> std::unique_ptr<BoundaryCondition<Vector3>> {
                                if (p.kind == PatchKind::kEmpty)
                                  return std::make_unique<Empty<Vector3>>();
                                if (p.name == "zmax")
                                  return std::make_unique<ZeroGradient<Vector3>>();
                                return std::make_unique<Slip>();
                              });
  LinearizedFreeSurface* lfs = nullptr;
  auto p = MakeField<double>(
      "p", mesh, [&](const Patch& patch) -> std::unique_ptr<BoundaryCondition<double>> {
        if (patch.kind == PatchKind::kEmpty) return std::make_unique<Empty<double>>();
        if (patch.name == "zmax") {
          auto bc = std::make_unique<LinearizedFreeSurface>(mesh, mesh.FindPatch("zmax"), fs);
          lfs = bc.get();
          return bc;
        }
        return std::make_unique<ZeroGradient<double>>();
      });
  *surface = lfs;
  PhysicsOptions physics;
  physics.nu = 1e-6;
  SchemeOptions schemes;
  schemes.time = time;
  schemes.convection = ConvectionScheme::kLinearUpwind;
  PimpleOptions pimple;
  pimple.n_correctors = n_correctors;
  pimple.momentum_solver.relative_tolerance = tolerance;
  pimple.pressure_solver.relative_tolerance = tolerance;
  pimple.pressure_final_relative_tolerance = tolerance;
  return std::make_unique<PimpleSolver>(mesh, physics, schemes, pimple, std::move(U), std::move(p));
}

// A 2 cm Gaussian hump off the centre of the 1 m x 0.6 m water box: it
// sloshes in x and y and has a non-zero mean level.
inline std::vector<double> OffCentreHump(const PatchSurface& surface) {
  std::vector<double> eta(surface.size());
  for (int i = 0; i < surface.size(); ++i) {
    const Vector3& x = surface.centres()[i];
    eta[i] = 0.02 * std::exp(-(std::pow(x.x() - 0.3, 2) + std::pow(x.y() - 0.2, 2)) / 0.02);
  }
  return eta;
}

// Net volume flux out through a patch (m^3/s).
inline double PatchFlux(const PimpleSolver& solver, const Patch& patch) {
  double sum = 0.0;
  for (int f = patch.start; f < patch.start + patch.size; ++f) sum += solver.flux()[f];
  return sum;
}

// Least-squares fit of x_{n+1} = c1 x_n + c2 x_{n-1} over samples [first,
// end): a single damped mode x_n = Re(A G^n) satisfies it exactly, with G a
// root of G^2 - c1 G - c2 = 0. Returns G with Im(G) >= 0.
inline std::complex<double> PronyRoot(const std::vector<double>& x, std::size_t first) {
  const auto rows = static_cast<Eigen::Index>(x.size() - first - 1);
  Eigen::MatrixXd a(rows, 2);
  Eigen::VectorXd b(rows);
  for (Eigen::Index r = 0; r < rows; ++r) {
    const std::size_t n = first + static_cast<std::size_t>(r);
    a(r, 0) = x[n];
    a(r, 1) = x[n - 1];
    b(r) = x[n + 1];
  }
  const Eigen::Vector2d c = a.colPivHouseholderQr().solve(b);
  const std::complex<double> disc = std::sqrt(std::complex<double>(c[0] * c[0] + 4.0 * c[1], 0.0));
  const std::complex<double> g = 0.5 * (c[0] + disc);
  return g.imag() >= 0.0 ? g : std::conj(g);
}

// The angular spread of a steady wave pattern (the Kelvin wedge), by the
// distribution of wave energy eta^2 dA over the angle from the track as seen
// from the disturbance: face i lies along[i] downstream of it and across[i]
// to the side. Only faces between r_min and r_max from it and outside the
// beaches (damping 0) count.
struct WedgeSpread {
  double angle95 = 0.0;          // deg, the angle holding 95% of the energy
  double beyond_wedge = 0.0;     // fraction of the energy beyond 19.47 deg
  double beyond_wedge_10 = 0.0;  // ... beyond 29.47 deg
};

inline WedgeSpread MeasureWedgeSpread(const std::vector<double>& along, const std::vector<double>& across,
                                      std::span<const double> area, std::span<const double> damping,
                                      std::span<const double> eta, double r_min, double r_max) {
  std::vector<std::pair<double, double>> energy;  // (angle deg, eta^2 dA)
  double total = 0.0;
  for (std::size_t i = 0; i < along.size(); ++i) {
    const double r = std::hypot(along[i], across[i]);
    if (r < r_min || r > r_max || damping[i] > 0.0) continue;
    energy.emplace_back(std::atan2(std::abs(across[i]), along[i]) * 180.0 / std::numbers::pi,
                        eta[i] * eta[i] * area[i]);
    total += energy.back().second;
  }
  std::sort(energy.begin(), energy.end());
  WedgeSpread w;
  double sum = 0.0;
  for (const auto& [angle, e] : energy) {
    sum += e;
    if (sum < 0.95 * total) w.angle95 = angle;
    if (angle > 19.47) w.beyond_wedge += e / total;
    if (angle > 29.47) w.beyond_wedge_10 += e / total;
  }
  return w;
}

}  // namespace kelvin::cfd::testing
