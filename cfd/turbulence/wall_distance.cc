#include "cfd/turbulence/wall_distance.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>

#include "cfd/field/field.h"
#include "cfd/fv/fv_matrix.h"
#include "cfd/linalg/linear_solver.h"
#include "data/schema/errors.h"

namespace kelvin::cfd {

std::vector<double> WallDistance(const Mesh& mesh, const std::vector<int>& wall_patches, const DomainPart* part) {
  if (wall_patches.empty()) throw ConfigError("wall distance: no wall patch (the turbulence model needs one)");
  std::vector<bool> is_wall(mesh.patches().size(), false);
  for (int p : wall_patches) {
    KELVIN_CHECK(p >= 0 && p < static_cast<int>(mesh.patches().size()), "wall patch index in range");
    is_wall[p] = true;
  }
  std::vector<std::unique_ptr<BoundaryCondition<double>>> bcs;
  for (std::size_t p = 0; p < mesh.patches().size(); ++p) {
    if (is_wall[p]) {
      bcs.push_back(std::make_unique<FixedValue<double>>(0.0));
    } else if (mesh.patches()[p].kind == PatchKind::kEmpty) {
      bcs.push_back(std::make_unique<Empty<double>>());
    } else {
      bcs.push_back(std::make_unique<ZeroGradient<double>>());
    }
  }
  ScalarField phi("wallDistancePotential", mesh, std::move(bcs));
  const NonOrthGeometry geo(mesh);
  Gradient grad(mesh, GradientOptions{});
  std::vector<Vector3> g;
  LinearSolverOptions options;
  options.type = LinearSolverOptions::Type::kPcgAmg;
  options.relative_tolerance = 1e-8;
  options.amg.strong_threshold = 0.5;
  auto solver = LinearSolver::Create(options, part);
  SparseSystem system(mesh);
  const std::vector<double> ones(mesh.n_cells(), 1.0);
  std::vector<double> diag, source;
  // The non-orthogonal correction is explicit: a few passes converge it.
  const int passes = geo.any_correction ? 3 : 1;
  for (int pass = 0; pass < passes; ++pass) {
    phi.CorrectBoundary(0.0, {});
    grad.Compute(std::span<const double>(phi.values()), std::span<const double>(phi.boundary()), g);
    UpdateGhosts(part, g);
    FvMatrix<double> m(mesh);
    AddLaplacian(m, phi, 1.0, geo, geo.any_correction ? &g : nullptr);
    AddSource(m, std::span<const double>(ones));
    m.ComponentSystem(0, diag, source);
    system.Fill(diag, m.upper, m.lower);
    solver->Solve(system.matrix(), source, phi.values());
    UpdateGhosts(part, phi.values());
  }
  phi.CorrectBoundary(0.0, {});
  grad.Compute(std::span<const double>(phi.values()), std::span<const double>(phi.boundary()), g);
  UpdateGhosts(part, g);
  std::vector<double> d(mesh.n_cells());
  for (int c = 0; c < mesh.n_cells(); ++c) {
    const double gn = g[c].norm();
    d[c] = std::sqrt(gn * gn + 2.0 * std::max(phi[c], 0.0)) - gn;
  }
  // Wall cells: exact normal distance to the (nearest) wall face.
  std::vector<double> exact(mesh.n_cells(), std::numeric_limits<double>::infinity());
  for (int p : wall_patches) {
    const Patch& patch = mesh.patches()[p];
    for (int f = patch.start; f < patch.start + patch.size; ++f) {
      const Vector3 n = mesh.face_areas()[f] / mesh.face_area_magnitudes()[f];
      const int c = mesh.owner()[f];
      exact[c] = std::min(exact[c], std::abs(n.dot(mesh.face_centres()[f] - mesh.cell_centres()[c])));
    }
  }
  for (int c = 0; c < mesh.n_cells(); ++c) {
    if (std::isfinite(exact[c])) d[c] = exact[c];
    d[c] = std::max(d[c], 1e-300);
  }
  UpdateGhosts(part, d);  // a ghost next to its owner's wall
  return d;
}

}  // namespace kelvin::cfd
