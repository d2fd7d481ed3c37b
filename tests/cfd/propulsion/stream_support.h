// The body-force tests in a stream: tensor-product boxes with a uniform core
// and cells growing geometrically to the far boundaries, and the laminar
// stream solver through them.
#pragma once

#include <array>
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "cfd/mesh/box_mesh.h"
#include "cfd/mesh/mesh.h"
#include "cfd/solver/pimple_solver.h"
#include "tests/cfd/cfd_test_support.h"

namespace kelvin::cfd::testing {

// Node coordinates: uniform cells of size h on [a, b], growing by `ratio`
// per cell outward to lo and hi (the outermost stretched run scaled to end
// exactly there).
inline std::vector<double> StretchedCoordinates(double lo, double a, double b, double hi, double h, double ratio) {
  auto run = [&](double length) {
    std::vector<double> sizes;
    double sum = 0.0, s = h;
    while (sum < length - 1e-12) {
      s *= ratio;
      sizes.push_back(s);
      sum += s;
    }
    for (double& v : sizes) v *= length / sum;
    return sizes;
  };
  std::vector<double> x = {a};
  const int n_core = static_cast<int>(std::lround((b - a) / h));
  for (int i = 1; i <= n_core; ++i) x.push_back(a + (b - a) * i / n_core);
  for (double s : run(hi - b)) x.push_back(x.back() + s);
  x.back() = hi;
  std::vector<double> left = {a};
  for (double s : run(a - lo)) left.push_back(left.back() - s);
  if (left.size() > 1) left.back() = lo;
  std::vector<double> out(left.rbegin(), left.rend() - 1);
  out.insert(out.end(), x.begin(), x.end());
  return out;
}

// A box mesh with the given node coordinates per axis (the built-in
// generator on the index lattice, its points then mapped).
inline Mesh TensorMesh(const std::array<std::vector<double>, 3>& coords, const std::array<PatchKind, 6>& kinds) {
  BoxMeshOptions mo;
  for (int d = 0; d < 3; ++d) {
    mo.cells[d] = static_cast<int>(coords[d].size()) - 1;
    mo.max[d] = mo.cells[d];
  }
  mo.kinds = kinds;
  const Mesh lattice = MakeBoxMesh(mo);
  std::vector<Vector3> points;
  for (const Vector3& p : lattice.points()) {
    Vector3 q;
    for (int d = 0; d < 3; ++d) q[d] = coords[d][static_cast<std::size_t>(std::lround(p[d]))];
    points.push_back(q);
  }
  std::vector<std::vector<int>> faces;
  for (auto f : lattice.faces()) faces.emplace_back(f.begin(), f.end());
  return Mesh(std::move(points), std::move(faces), {lattice.owner().begin(), lattice.owner().end()},
              {lattice.neighbour().begin(), lattice.neighbour().end()}, lattice.patches(), "stretched box");
}

// A uniform stream `stream` (m/s) in at patch `inlet`, a fixed-pressure
// outflow at `outlet`, slip on the other sides; laminar, nu = 1e-4 (Re 1e4 at
// 1 m/s over 1 m), Euler steps, the field started at the stream.
inline std::unique_ptr<PimpleSolver> StreamSolver(const Mesh& mesh, const Vector3& stream, const std::string& inlet,
                                                  const std::string& outlet) {
  auto U = MakeField<Vector3>("U", mesh, [&](const Patch& p) -> std::unique_ptr<BoundaryCondition<Vector3>> {
    if (p.name == inlet) return std::make_unique<FixedValue<Vector3>>(stream);
    if (p.name == outlet) return std::make_unique<InletOutlet<Vector3>>(Vector3(0, 0, 0));
    return std::make_unique<Slip>();
  });
  auto p = MakeField<double>("p", mesh, [&](const Patch& patch) -> std::unique_ptr<BoundaryCondition<double>> {
    if (patch.name == outlet) return std::make_unique<FixedValue<double>>(0.0);
    return std::make_unique<ZeroGradient<double>>();
  });
  PhysicsOptions physics;
  physics.nu = 1e-4;
  SchemeOptions schemes;
  schemes.time = TimeScheme::kEuler;
  PimpleOptions pimple;
  pimple.n_outer = 2;
  pimple.relax_U = 0.8;
  pimple.relax_p = 0.5;
  pimple.momentum_solver.relative_tolerance = 1e-6;
  pimple.pressure_solver.relative_tolerance = 1e-4;
  pimple.pressure_final_relative_tolerance = 1e-6;
  auto solver = std::make_unique<PimpleSolver>(mesh, physics, schemes, pimple, std::move(U), std::move(p));
  for (Vector3& u : solver->U().values()) u = stream;
  return solver;
}

}  // namespace kelvin::cfd::testing
