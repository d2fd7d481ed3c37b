// The fv operators of the pressure equation and of the viscous stress
// against their definitions, and the pressure equation they assemble against
// the hand-written loops it replaced (bit for bit).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "cfd/bc/boundary_condition.h"
#include "cfd/fv/fv_matrix.h"
#include "cfd/mesh/box_mesh.h"
#include "tests/cfd/cfd_test_support.h"

namespace kelvin::cfd {
namespace {

using testing::MakeField;

Mesh SkewedBox() {
  BoxMeshOptions o;
  o.cells = {5, 4, 3};
  o.max = Vector3(1.0, 0.8, 0.6);
  o.perturbation = 0.2;
  o.seed = 5;
  return MakeBoxMesh(o);
}

std::vector<double> Random(int n, unsigned seed, double lo = -1.0, double hi = 1.0) {
  std::mt19937 gen(seed);
  std::uniform_real_distribution<double> u(lo, hi);
  std::vector<double> v(n);
  for (double& x : v) x = u(gen);
  return v;
}

// p with a fixed value on xmax, a Robin condition on ymin and zero gradient
// elsewhere, updated from random cell values.
std::unique_ptr<ScalarField> Pressure(const Mesh& mesh, bool fixed) {
  auto p = MakeField<double>("p", mesh, [fixed](const Patch& patch) -> std::unique_ptr<BoundaryCondition<double>> {
    if (fixed && patch.name == "xmax") return std::make_unique<FixedValue<double>>(0.5);
    if (fixed && patch.name == "ymin") return std::make_unique<Mixed<double>>(0.2, 0.3, 0.4);
    if (patch.name == "zmin") return std::make_unique<Mixed<double>>(0.0, 0.7, 0.0);  // gradient only
    return std::make_unique<ZeroGradient<double>>();
  });
  p->values() = Random(mesh.n_cells(), 11);
  p->CorrectBoundary(0.0, {});
  return p;
}

TEST(FvOperators, AddDivergenceSumsTheOutwardFluxes) {
  const Mesh mesh = SkewedBox();
  const std::vector<double> flux = Random(mesh.n_faces(), 3);
  FvMatrix<double> m(mesh);
  AddDivergence(m, flux);
  std::vector<double> diag, rhs;
  m.ComponentSystem(0, diag, rhs);
  std::vector<double> div(mesh.n_cells(), 0.0);
  for (int f = 0; f < mesh.n_faces(); ++f) {
    div[mesh.owner()[f]] += flux[f];
    if (f < mesh.n_internal_faces()) div[mesh.neighbour()[f]] -= flux[f];
  }
  for (int c = 0; c < mesh.n_cells(); ++c) {
    EXPECT_NEAR(rhs[c], -div[c], 1e-14) << c;  // + div(F) on the left-hand side
    EXPECT_EQ(diag[c], 0.0);
  }
}

TEST(FvOperators, CorrectedLaplacianFluxOfALinearFieldIsExact) {
  // snGrad = dc (phi_N - phi_P) + k . grad(phi) is exact for a linear field
  // with its exact gradient: the two face fluxes add up to gamma S_f . g.
  const Mesh mesh = SkewedBox();
  const Vector3 g(0.3, -1.2, 0.7);
  auto phi = MakeField<double>("phi", mesh, [&](const Patch&) -> std::unique_ptr<BoundaryCondition<double>> {
    return std::make_unique<FixedValue<double>>(ValueFunction<double>([g](const Vector3& x, double) { return g.dot(x); }));
  });
  for (int c = 0; c < mesh.n_cells(); ++c) (*phi)[c] = g.dot(mesh.cell_centres()[c]);
  phi->CorrectBoundary(0.0, {});
  const NonOrthGeometry geo(mesh);
  ASSERT_TRUE(geo.any_correction);
  const std::vector<double> gamma = Random(mesh.n_faces(), 4, 0.5, 2.0);
  std::vector<double> implicit, explicit_part;
  LaplacianFlux(*phi, gamma, geo, implicit);
  NonOrthogonalFlux(mesh, gamma, std::vector<Vector3>(mesh.n_cells(), g), geo, explicit_part);
  ASSERT_EQ(static_cast<int>(explicit_part.size()), mesh.n_internal_faces());
  for (int f = 0; f < mesh.n_internal_faces(); ++f) {
    EXPECT_NEAR(implicit[f] + explicit_part[f], gamma[f] * mesh.face_areas()[f].dot(g), 1e-12) << f;
  }
  // Boundary faces: gamma |S| (phi_b - phi_P) dc from the conditions.
  for (int f = mesh.n_internal_faces(); f < mesh.n_faces(); ++f) {
    const Vector3 n = mesh.face_areas()[f] / mesh.face_area_magnitudes()[f];
    const double dc = 1.0 / n.dot(mesh.deltas()[f]);
    const double phi_b = g.dot(mesh.face_centres()[f]);
    const double phi_P = (*phi)[mesh.owner()[f]];
    EXPECT_NEAR(implicit[f], gamma[f] * mesh.face_area_magnitudes()[f] * dc * (phi_b - phi_P), 1e-12) << f;
  }
}

TEST(FvOperators, FaceCentreCorrectionOfALinearFieldIsExact) {
  // The face-centre form carries each cell's value along the face to the
  // normal through the face centre: exact for a linear field too, on skewed
  // hexahedra and on the 2:1 split faces of a refinement interface.
  BoxMeshOptions split;
  split.cells = {4, 4, 2};
  split.polyhedral = true;
  const Vector3 g(0.3, -1.2, 0.7);
  for (const Mesh& mesh : {SkewedBox(), MakeBoxMesh(split)}) {
    auto phi = MakeField<double>("phi", mesh, [&](const Patch&) -> std::unique_ptr<BoundaryCondition<double>> {
      return std::make_unique<FixedValue<double>>(ValueFunction<double>([g](const Vector3& x, double) { return g.dot(x); }));
    });
    for (int c = 0; c < mesh.n_cells(); ++c) (*phi)[c] = g.dot(mesh.cell_centres()[c]);
    phi->CorrectBoundary(0.0, {});
    const NonOrthGeometry geo(mesh, NonOrthogonalForm::kFaceCentre);
    ASSERT_TRUE(geo.any_correction);
    const std::vector<double> gamma = Random(mesh.n_faces(), 5, 0.5, 2.0);
    std::vector<double> implicit, explicit_part;
    LaplacianFlux(*phi, gamma, geo, implicit);
    NonOrthogonalFlux(mesh, gamma, std::vector<Vector3>(mesh.n_cells(), g), geo, explicit_part);
    for (int f = 0; f < mesh.n_internal_faces(); ++f) {
      EXPECT_NEAR(implicit[f] + explicit_part[f], gamma[f] * mesh.face_areas()[f].dot(g), 1e-12) << f;
    }
  }
}

// sum_f F_f phi_f of AddConvection applied to a linear field with its exact
// gradient, per cell, against the sum with the exact face-centre values:
// LUST (3/4 central from both sides' gradients, 1/4 linear upwind) and linear
// upwind carry each value to the face centre, so both are exact on skewed
// hexahedra and on 2:1 split faces; the weighted linear interpolation is not
// (the owner-neighbour line misses the face centre).
double ConvectionErrorOfALinearField(const Mesh& mesh, ConvectionScheme scheme) {
  const Vector3 g(0.3, -1.2, 0.7);
  auto phi = MakeField<double>("phi", mesh, [&](const Patch&) -> std::unique_ptr<BoundaryCondition<double>> {
    return std::make_unique<FixedValue<double>>(ValueFunction<double>([g](const Vector3& x, double) { return g.dot(x); }));
  });
  for (int c = 0; c < mesh.n_cells(); ++c) (*phi)[c] = g.dot(mesh.cell_centres()[c]);
  phi->CorrectBoundary(0.0, {});
  const std::vector<double> flux = Random(mesh.n_faces(), 9);
  FvMatrix<double> m(mesh);
  AddConvection(m, *phi, flux, scheme, std::vector<Vector3>(mesh.n_cells(), g));
  const std::vector<double> A = m.A();
  const std::vector<double> H = m.H(std::span<const double>(phi->values()));
  std::vector<double> exact(mesh.n_cells(), 0.0);
  for (int f = 0; f < mesh.n_faces(); ++f) {
    const double face = flux[f] * g.dot(mesh.face_centres()[f]);
    exact[mesh.owner()[f]] += face;
    if (f < mesh.n_internal_faces()) exact[mesh.neighbour()[f]] -= face;
  }
  double worst = 0.0;
  // A and H are per unit volume.
  for (int c = 0; c < mesh.n_cells(); ++c) {
    worst = std::max(worst, std::abs((A[c] * (*phi)[c] - H[c]) * mesh.cell_volumes()[c] - exact[c]));
  }
  return worst;
}

TEST(FvOperators, LustAndLinearUpwindConvectALinearFieldExactly) {
  BoxMeshOptions split;
  split.cells = {4, 4, 2};
  split.polyhedral = true;
  for (const Mesh& mesh : {SkewedBox(), MakeBoxMesh(split)}) {
    EXPECT_LT(ConvectionErrorOfALinearField(mesh, ConvectionScheme::kLust), 1e-12);
    EXPECT_LT(ConvectionErrorOfALinearField(mesh, ConvectionScheme::kLinearUpwind), 1e-12);
    EXPECT_GT(ConvectionErrorOfALinearField(mesh, ConvectionScheme::kLinear), 1e-3);
  }
}

TEST(FvOperators, NonOrthogonalFluxIsZeroOnOrthogonalMeshes) {
  BoxMeshOptions o;
  o.cells = {3, 3, 3};
  const Mesh mesh = MakeBoxMesh(o);
  const NonOrthGeometry geo(mesh);
  ASSERT_FALSE(geo.any_correction);
  std::vector<double> flux;
  NonOrthogonalFlux(mesh, std::vector<double>(mesh.n_faces(), 1.0),
                    std::vector<Vector3>(mesh.n_cells(), Vector3(1, 2, 3)), geo, flux);
  EXPECT_EQ(flux, std::vector<double>(mesh.n_internal_faces(), 0.0));
}

TEST(FvOperators, ReferenceOnlyWithoutAFixedLevel) {
  const Mesh mesh = SkewedBox();
  EXPECT_FALSE(NeedsReference(*Pressure(mesh, true)));
  EXPECT_TRUE(NeedsReference(*Pressure(mesh, false)));
  std::vector<double> diag = {2.0, 3.0}, source = {1.0, 1.0};
  SetReference(diag, source, 1, 0.5);
  EXPECT_EQ(diag, (std::vector<double>{2.0, 6.0}));
  EXPECT_EQ(source, (std::vector<double>{1.0, 2.5}));
}

// The pressure equation as PimpleSolver assembled it by hand before it used
// the operators (the diagonal, off-diagonal and right-hand side, and the
// conservative flux from the solution).
struct HandPressure {
  std::vector<double> diag, off, rhs, face_corr, flux;
};
HandPressure HandAssembly(const ScalarField& p, std::span<const double> rAUf, std::span<const double> phi_HbyA,
                          const std::vector<Vector3>& grad_p, const NonOrthGeometry& geo, int ref_cell,
                          double ref_value) {
  const Mesh& mesh = p.mesh();
  const int nc = mesh.n_cells(), ni = mesh.n_internal_faces();
  const auto owner = mesh.owner();
  const auto neighbour = mesh.neighbour();
  const auto w = mesh.weights();
  const auto mag = mesh.face_area_magnitudes();
  bool fixed_level = false;
  for (int k = 0; k < p.n_patches(); ++k) {
    for (double g : p.bc(k).gradient_internal()) fixed_level = fixed_level || g != 0.0;
  }
  HandPressure h{std::vector<double>(nc, 0.0), std::vector<double>(ni), std::vector<double>(nc, 0.0),
                 std::vector<double>(ni, 0.0), std::vector<double>(mesh.n_faces())};
  for (int f = 0; f < ni; ++f) {
    const int P = owner[f], N = neighbour[f];
    const double a = rAUf[f] * mag[f] * geo.delta_coeffs[f];
    h.diag[P] += a;
    h.diag[N] += a;
    h.off[f] = -a;
    const Vector3 g = w[f] * grad_p[P] + (1.0 - w[f]) * grad_p[N];
    h.face_corr[f] = rAUf[f] * mag[f] * g.dot(geo.correction[f]);
    const double known = phi_HbyA[f] - h.face_corr[f];
    h.rhs[P] -= known;
    h.rhs[N] += known;
  }
  for (int k = 0; k < p.n_patches(); ++k) {
    const Patch& patch = mesh.patches()[k];
    const auto& bc = p.bc(k);
    for (int i = 0; i < patch.size; ++i) {
      const int f = patch.start + i;
      const double a = rAUf[f] * mag[f];
      h.diag[owner[f]] -= a * bc.gradient_internal()[i];
      h.rhs[owner[f]] += a * bc.gradient_boundary()[i] - phi_HbyA[f];
    }
  }
  if (!fixed_level) {
    h.rhs[ref_cell] += h.diag[ref_cell] * ref_value;
    h.diag[ref_cell] += h.diag[ref_cell];
  }
  for (int f = 0; f < ni; ++f) {
    const double a = rAUf[f] * mag[f] * geo.delta_coeffs[f];
    h.flux[f] = phi_HbyA[f] - a * (p[neighbour[f]] - p[owner[f]]) - h.face_corr[f];
  }
  for (int k = 0; k < p.n_patches(); ++k) {
    const Patch& patch = mesh.patches()[k];
    const auto& bc = p.bc(k);
    for (int i = 0; i < patch.size; ++i) {
      const int f = patch.start + i;
      const double sn_grad = bc.gradient_internal()[i] * p[owner[f]] + bc.gradient_boundary()[i];
      h.flux[f] = phi_HbyA[f] - rAUf[f] * mag[f] * sn_grad;
    }
  }
  return h;
}

class PressureEquation : public ::testing::TestWithParam<bool> {};

TEST_P(PressureEquation, OperatorsGiveTheHandAssemblyBitForBit) {
  const Mesh mesh = SkewedBox();
  const auto p = Pressure(mesh, GetParam());
  const NonOrthGeometry geo(mesh);
  const std::vector<double> rAUf = Random(mesh.n_faces(), 7, 0.1, 1.0);
  const std::vector<double> phi_HbyA = Random(mesh.n_faces(), 8);
  std::vector<Vector3> grad_p(mesh.n_cells());
  const std::vector<double> r = Random(3 * mesh.n_cells(), 9);
  for (int c = 0; c < mesh.n_cells(); ++c) grad_p[c] = Vector3(r[3 * c], r[3 * c + 1], r[3 * c + 2]);
  const int ref_cell = 7;
  const double ref_value = 1.25;
  const HandPressure h = HandAssembly(*p, rAUf, phi_HbyA, grad_p, geo, ref_cell, ref_value);

  std::vector<double> face_corr;
  NonOrthogonalFlux(mesh, rAUf, grad_p, geo, face_corr);
  std::vector<double> known(phi_HbyA);
  for (int f = 0; f < mesh.n_internal_faces(); ++f) known[f] = phi_HbyA[f] - face_corr[f];
  FvMatrix<double> pEqn(mesh);
  AddLaplacian(pEqn, *p, std::span<const double>(rAUf), geo, nullptr);
  AddDivergence(pEqn, known);
  std::vector<double> diag, rhs;
  pEqn.ComponentSystem(0, diag, rhs);
  if (NeedsReference(*p)) SetReference(diag, rhs, ref_cell, ref_value);
  EXPECT_EQ(diag, h.diag);
  EXPECT_EQ(rhs, h.rhs);
  EXPECT_EQ(pEqn.upper, h.off);
  EXPECT_EQ(pEqn.lower, h.off);
  EXPECT_EQ(face_corr, h.face_corr);

  std::vector<double> laplacian_flux;
  LaplacianFlux(*p, rAUf, geo, laplacian_flux);
  for (int f = 0; f < mesh.n_faces(); ++f) {
    const double corr = f < mesh.n_internal_faces() ? face_corr[f] : 0.0;
    const double flux = f < mesh.n_internal_faces() ? phi_HbyA[f] - laplacian_flux[f] - corr
                                                    : phi_HbyA[f] - laplacian_flux[f];
    EXPECT_EQ(flux, h.flux[f]) << f;
  }
}

INSTANTIATE_TEST_SUITE_P(FixedLevelOrReference, PressureEquation, ::testing::Bool());

TEST(FvOperators, DivDev2TransposeOfAUniformGradientVanishes) {
  // A constant J and gamma: each closed cell sums gamma (J^T - 2/3 tr J I) S_f
  // over faces whose S_f add up to zero.
  const Mesh mesh = SkewedBox();
  Matrix3 J;
  J << 1.0, 2.0, -0.5, 0.3, -1.0, 0.7, 0.2, 0.4, 0.6;
  FvMatrix<Vector3> m(mesh);
  AddDivDev2Transpose(m, std::vector<double>(mesh.n_faces(), 1.5), std::vector<Matrix3>(mesh.n_cells(), J));
  for (const Vector3& s : m.source) EXPECT_LT(s.norm(), 1e-13);
}

TEST(FvOperators, DivDev2TransposeFaceFlux) {
  // Two cells, one internal face along x: only that face has gamma != 0.
  BoxMeshOptions o;
  o.cells = {2, 1, 1};
  o.max = Vector3(2.0, 1.0, 1.0);
  const Mesh mesh = MakeBoxMesh(o);
  ASSERT_EQ(mesh.n_internal_faces(), 1);
  std::vector<double> gamma;
  for (int f = 0; f < mesh.n_faces(); ++f) gamma.push_back(f == 0 ? 2.0 : 0.0);
  Matrix3 J0 = Matrix3::Zero(), J1 = Matrix3::Zero();
  J0(1, 0) = 1.0;  // dv/dx in cell 0
  J1(0, 0) = 3.0;  // du/dx in cell 1
  FvMatrix<Vector3> m(mesh);
  AddDivDev2Transpose(m, gamma, {J0, J1});
  const Matrix3 Jf = 0.5 * (J0 + J1);
  const Vector3 S = mesh.face_areas()[0];
  const Vector3 t = 2.0 * (Jf.transpose() * S - (2.0 / 3.0) * Jf.trace() * S);
  const int P = mesh.owner()[0], N = mesh.neighbour()[0];
  EXPECT_TRUE(m.source[P].isApprox(t));
  EXPECT_TRUE(m.source[N].isApprox(-t));
}

}  // namespace
}  // namespace kelvin::cfd
