// Helpers of the free-surface tests: a box of water under a linearized free
// surface (zmax) with slip walls, and Prony's fit of a sampled damped
// oscillation.
#pragma once

#include <Eigen/Dense>
#include <cmath>
#include <complex>
#include <memory>
#include <vector>

#include "cfd/freesurface/linearized_free_surface.h"
#include "cfd/mesh/box_mesh.h"
#include "tests/cfd/cfd_test_support.h"

namespace kelvin::cfd::testing {

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

}  // namespace kelvin::cfd::testing
