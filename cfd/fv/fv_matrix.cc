#include "cfd/fv/fv_matrix.h"

#include <algorithm>
#include <cmath>

#include "data/schema/errors.h"

namespace kelvin::cfd {

template <typename T>
std::vector<double> FvMatrix<T>::A() const {
  const Mesh& mesh = *mesh_;
  std::vector<double> a(diag);
  const int ni = mesh.n_internal_faces();
  for (int f = ni; f < mesh.n_faces(); ++f) a[mesh.owner()[f]] += Traits<T>::CmptAv(internal_coeffs[f - ni]);
  const auto vol = mesh.cell_volumes();
  for (int c = 0; c < mesh.n_cells(); ++c) a[c] /= vol[c];
  return a;
}

template <typename T>
std::vector<T> FvMatrix<T>::H(std::span<const T> psi) const {
  const Mesh& mesh = *mesh_;
  const int ni = mesh.n_internal_faces();
  const auto owner = mesh.owner();
  const auto neighbour = mesh.neighbour();
  std::vector<T> h(source);
  for (int f = 0; f < ni; ++f) {
    h[owner[f]] -= upper[f] * psi[neighbour[f]];
    h[neighbour[f]] -= lower[f] * psi[owner[f]];
  }
  for (int f = ni; f < mesh.n_faces(); ++f) {
    const int c = owner[f];
    const T& ic = internal_coeffs[f - ni];
    // Component part of the boundary diagonal that A() averaged away.
    h[c] += Traits<T>::Mul(Traits<T>::CmptAv(ic) * Traits<T>::One() - ic, psi[c]);
    h[c] += boundary_coeffs[f - ni];
  }
  const auto vol = mesh.cell_volumes();
  for (int c = 0; c < mesh.n_cells(); ++c) h[c] /= vol[c];
  return h;
}

template <typename T>
void FvMatrix<T>::Relax(std::span<const T> psi, double alpha) {
  if (alpha >= 1.0) return;
  for (std::size_t c = 0; c < diag.size(); ++c) {
    const double d = diag[c] / alpha;
    source[c] += (d - diag[c]) * psi[c];
    diag[c] = d;
  }
}

template <typename T>
void FvMatrix<T>::ComponentSystem(int k, std::vector<double>& diag_k, std::vector<double>& source_k) const {
  const Mesh& mesh = *mesh_;
  const int ni = mesh.n_internal_faces();
  diag_k = diag;
  source_k.resize(source.size());
  for (std::size_t c = 0; c < source.size(); ++c) source_k[c] = Traits<T>::Component(source[c], k);
  for (int f = ni; f < mesh.n_faces(); ++f) {
    diag_k[mesh.owner()[f]] += Traits<T>::Component(internal_coeffs[f - ni], k);
    source_k[mesh.owner()[f]] += Traits<T>::Component(boundary_coeffs[f - ni], k);
  }
}

NonOrthGeometry::NonOrthGeometry(const Mesh& mesh, NonOrthogonalForm form) {
  const int ni = mesh.n_internal_faces();
  delta_coeffs.resize(ni);
  correction.resize(ni);
  for (int f = 0; f < ni; ++f) {
    const Vector3 n = mesh.face_areas()[f] / mesh.face_area_magnitudes()[f];
    const Vector3& d = mesh.deltas()[f];
    delta_coeffs[f] = 1.0 / std::max(n.dot(d), 0.05 * d.norm());
    correction[f] = n - d * delta_coeffs[f];
  }
  if (form == NonOrthogonalForm::kFaceCentre) {
    owner_tangent.resize(ni);
    neighbour_tangent.resize(ni);
    for (int f = 0; f < ni; ++f) {
      const Vector3 n = mesh.face_areas()[f] / mesh.face_area_magnitudes()[f];
      auto along_face = [&n](const Vector3& r) -> Vector3 { return r - r.dot(n) * n; };
      owner_tangent[f] = delta_coeffs[f] * along_face(mesh.face_centres()[f] - mesh.cell_centres()[mesh.owner()[f]]);
      neighbour_tangent[f] =
          delta_coeffs[f] * along_face(mesh.face_centres()[f] - mesh.cell_centres()[mesh.neighbour()[f]]);
    }
  }
  boundary_correction.resize(mesh.n_boundary_faces());
  for (int f = ni; f < mesh.n_faces(); ++f) {
    const Vector3 n = mesh.face_areas()[f] / mesh.face_area_magnitudes()[f];
    const Vector3& d = mesh.deltas()[f];
    boundary_correction[f - ni] = n - d / std::max(n.dot(d), 0.05 * d.norm());
  }
  for (const Vector3& k : correction) any_correction = any_correction || k.norm() > 1e-12;
  for (const Vector3& k : boundary_correction) any_correction = any_correction || k.norm() > 1e-12;
  if (!any_correction) {
    // Orthogonal mesh: the vectors are all zero and never read.
    correction = std::vector<Vector3>();
    boundary_correction = std::vector<Vector3>();
    owner_tangent = std::vector<Vector3>();
    neighbour_tangent = std::vector<Vector3>();
  }
}

template <typename T>
void AddDdt(FvMatrix<T>& m, const CellField<T>& field, double dt, TimeScheme scheme) {
  const auto vol = m.mesh().cell_volumes();
  const bool backward = scheme == TimeScheme::kBackward && field.n_old() >= 2;
  const auto& old0 = field.old(0);
  for (int c = 0; c < m.mesh().n_cells(); ++c) {
    const double r = vol[c] / dt;
    if (backward) {
      m.diag[c] += 1.5 * r;
      m.source[c] += r * (2.0 * old0[c] - 0.5 * field.old(1)[c]);
    } else {
      m.diag[c] += r;
      m.source[c] += r * old0[c];
    }
  }
}

namespace {

inline double Dot(const Vector3& g, const Vector3& d) { return g.dot(d); }
inline Vector3 Dot(const Matrix3& g, const Vector3& d) { return g * d; }

// The explicit non-orthogonal part of the face-normal gradient of face f
// (NonOrthogonalForm), from the owner and neighbour cell gradients.
template <typename G>
auto NonOrthogonalPart(const NonOrthGeometry& geo, int f, const G& grad_owner, const G& grad_neighbour, double w)
    -> decltype(Dot(grad_owner, geo.correction[f])) {
  if (!geo.owner_tangent.empty()) {
    return Dot(grad_neighbour, geo.neighbour_tangent[f]) - Dot(grad_owner, geo.owner_tangent[f]);
  }
  return Dot(G(w * grad_owner + (1.0 - w) * grad_neighbour), geo.correction[f]);
}

inline double VanLeer(double r) { return (r + std::abs(r)) / (1.0 + std::abs(r)); }

// Bounded face value, limited per component.
inline double LimitedFace(double up, double down, double grad_dot_d, double frac) {
  const double diff = down - up;
  if (std::abs(diff) < 1e-300) return up;
  const double r = 2.0 * grad_dot_d / diff - 1.0;
  return up + VanLeer(r) * frac * diff;
}
inline Vector3 LimitedFace(const Vector3& up, const Vector3& down, const Vector3& grad_dot_d, double frac) {
  Vector3 out;
  for (int k = 0; k < 3; ++k) out[k] = LimitedFace(up[k], down[k], grad_dot_d[k], frac);
  return out;
}

}  // namespace

template <typename T>
void AddConvection(FvMatrix<T>& m, const CellField<T>& field, std::span<const double> flux, ConvectionScheme scheme,
                   const std::vector<GradType<T>>& grad) {
  const Mesh& mesh = m.mesh();
  const int ni = mesh.n_internal_faces();
  const auto owner = mesh.owner();
  const auto neighbour = mesh.neighbour();
  const auto xf = mesh.face_centres();
  const auto xc = mesh.cell_centres();
  const auto w = mesh.weights();
  const auto& phi = field.values();
  for (int f = 0; f < ni; ++f) {
    const double F = flux[f];
    const int P = owner[f];
    const int N = neighbour[f];
    m.diag[P] += std::max(F, 0.0);
    m.upper[f] += std::min(F, 0.0);
    m.diag[N] += std::max(-F, 0.0);
    m.lower[f] -= std::max(F, 0.0);
    if (scheme == ConvectionScheme::kUpwind) continue;
    const bool from_owner = F >= 0.0;
    const int U = from_owner ? P : N;
    const int D = from_owner ? N : P;
    // A cell's value carried to the face centre by its gradient.
    auto at_face = [&](int c) -> T { return phi[c] + Dot(grad[c], Vector3(xf[f] - xc[c])); };
    T face;
    switch (scheme) {
      case ConvectionScheme::kLinearUpwind:
        face = at_face(U);
        break;
      case ConvectionScheme::kLust:
        // 3/4 central from both sides (second order on skewed faces too) and
        // 1/4 linear upwind.
        face = 0.75 * (0.5 * (at_face(P) + at_face(N))) + 0.25 * at_face(U);
        break;
      case ConvectionScheme::kLimited: {
        const double frac = from_owner ? 1.0 - w[f] : w[f];
        face = LimitedFace(phi[U], phi[D], Dot(grad[U], Vector3(xc[D] - xc[U])), frac);
        break;
      }
      case ConvectionScheme::kLinear:
      default:
        face = w[f] * phi[P] + (1.0 - w[f]) * phi[N];
        break;
    }
    const T correction = F * (face - phi[U]);
    m.source[P] -= correction;
    m.source[N] += correction;
  }
  for (const Patch& patch : mesh.patches()) {
    const auto& bc = field.bc(mesh.FindPatch(patch.name));
    for (int i = 0; i < patch.size; ++i) {
      const int f = patch.start + i;
      m.internal_coeffs[f - ni] += flux[f] * bc.value_internal()[i];
      m.boundary_coeffs[f - ni] -= flux[f] * bc.value_boundary()[i];
    }
  }
}

namespace {

// -div(gamma_f grad phi) with the face diffusivity from `gamma(f)`.
template <typename T, typename Gamma>
void LaplacianImpl(FvMatrix<T>& m, const CellField<T>& field, const Gamma& gamma, const NonOrthGeometry& geo,
                   const std::vector<GradType<T>>* grad) {
  const Mesh& mesh = m.mesh();
  const int ni = mesh.n_internal_faces();
  const auto owner = mesh.owner();
  const auto neighbour = mesh.neighbour();
  const auto mag = mesh.face_area_magnitudes();
  const auto w = mesh.weights();
  if (!geo.any_correction) grad = nullptr;
  for (int f = 0; f < ni; ++f) {
    const double gf = gamma(f);
    const double a = gf * mag[f] * geo.delta_coeffs[f];
    m.diag[owner[f]] += a;
    m.diag[neighbour[f]] += a;
    m.upper[f] -= a;
    m.lower[f] -= a;
    if (grad) {
      const T corr = gf * mag[f] * T(NonOrthogonalPart(geo, f, (*grad)[owner[f]], (*grad)[neighbour[f]], w[f]));
      m.source[owner[f]] += corr;
      m.source[neighbour[f]] -= corr;
    }
  }
  for (int p = 0; p < field.n_patches(); ++p) {
    const Patch& patch = mesh.patches()[p];
    const auto& bc = field.bc(p);
    for (int i = 0; i < patch.size; ++i) {
      const int f = patch.start + i;
      const double gf = gamma(f);
      m.internal_coeffs[f - ni] -= gf * mag[f] * bc.gradient_internal()[i];
      m.boundary_coeffs[f - ni] += gf * mag[f] * bc.gradient_boundary()[i];
      if (grad) {
        // Skewed wall cell: the part of dc (phi_b - phi_P) along the face,
        // weighted by how much the condition fixes the value (-gi / dc).
        const double n_dot_d = mesh.face_areas()[f].dot(mesh.deltas()[f]) / mag[f];
        const double dc = 1.0 / std::max(n_dot_d, 0.05 * mesh.deltas()[f].norm());
        const T fraction = -bc.gradient_internal()[i] / dc;
        const T tangential = Dot((*grad)[owner[f]], geo.boundary_correction[f - ni]);
        m.source[owner[f]] += gf * mag[f] * Traits<T>::Mul(fraction, tangential);
      }
    }
  }
}

}  // namespace

template <typename T>
void AddLaplacian(FvMatrix<T>& m, const CellField<T>& field, double gamma, const NonOrthGeometry& geo,
                  const std::vector<GradType<T>>* grad) {
  LaplacianImpl(m, field, [gamma](int) { return gamma; }, geo, grad);
}

template <typename T>
void AddLaplacian(FvMatrix<T>& m, const CellField<T>& field, std::span<const double> gamma_faces,
                  const NonOrthGeometry& geo, const std::vector<GradType<T>>* grad) {
  KELVIN_CHECK(static_cast<int>(gamma_faces.size()) == m.mesh().n_faces(), "one diffusivity per face");
  LaplacianImpl(m, field, [gamma_faces](int f) { return gamma_faces[f]; }, geo, grad);
}

void AddDivDev2Transpose(FvMatrix<Vector3>& m, std::span<const double> gamma_faces, const std::vector<Matrix3>& grad) {
  const Mesh& mesh = m.mesh();
  const int ni = mesh.n_internal_faces();
  const auto owner = mesh.owner();
  const auto neighbour = mesh.neighbour();
  const auto w = mesh.weights();
  const auto sf = mesh.face_areas();
  auto face_flux = [&](const Matrix3& J, int f) -> Vector3 {
    return gamma_faces[f] * (J.transpose() * sf[f] - (2.0 / 3.0) * J.trace() * sf[f]);
  };
  for (int f = 0; f < ni; ++f) {
    const int P = owner[f], N = neighbour[f];
    const Vector3 t = face_flux(w[f] * grad[P] + (1.0 - w[f]) * grad[N], f);
    m.source[P] += t;
    m.source[N] -= t;
  }
  for (int f = ni; f < mesh.n_faces(); ++f) m.source[owner[f]] += face_flux(grad[owner[f]], f);
}

void AddDivergence(FvMatrix<double>& m, std::span<const double> face_flux) {
  const Mesh& mesh = m.mesh();
  const int ni = mesh.n_internal_faces();
  KELVIN_CHECK(static_cast<int>(face_flux.size()) == mesh.n_faces(), "one flux per face");
  for (int f = 0; f < ni; ++f) {
    m.source[mesh.owner()[f]] -= face_flux[f];
    m.source[mesh.neighbour()[f]] += face_flux[f];
  }
  for (int f = ni; f < mesh.n_faces(); ++f) m.boundary_coeffs[f - ni] -= face_flux[f];
}

void AddImplicitSource(FvMatrix<double>& m, std::span<const double> coeff_per_volume) {
  const auto vol = m.mesh().cell_volumes();
  for (int c = 0; c < m.mesh().n_cells(); ++c) m.diag[c] += vol[c] * coeff_per_volume[c];
}

void SetCellValues(FvMatrix<double>& m, std::span<const int> cells, std::span<const double> values) {
  const Mesh& mesh = m.mesh();
  const int ni = mesh.n_internal_faces();
  std::vector<char> fixed(mesh.n_cells(), 0);
  std::vector<double> value(mesh.n_cells(), 0.0);
  for (std::size_t i = 0; i < cells.size(); ++i) {
    fixed[cells[i]] = 1;
    value[cells[i]] = values[i];
  }
  for (int f = 0; f < ni; ++f) {
    const int P = mesh.owner()[f], N = mesh.neighbour()[f];
    if (fixed[P]) {
      // Row P loses its coupling; row N sees a known value.
      if (!fixed[N]) m.source[N] -= m.lower[f] * value[P];
      m.upper[f] = 0.0;
      m.lower[f] = 0.0;
    }
    if (fixed[N]) {
      if (!fixed[P]) m.source[P] -= m.upper[f] * value[N];
      m.upper[f] = 0.0;
      m.lower[f] = 0.0;
    }
  }
  for (int f = ni; f < mesh.n_faces(); ++f) {
    if (fixed[mesh.owner()[f]]) {
      m.internal_coeffs[f - ni] = 0.0;
      m.boundary_coeffs[f - ni] = 0.0;
    }
  }
  for (int c = 0; c < mesh.n_cells(); ++c) {
    if (!fixed[c]) continue;
    if (!(m.diag[c] > 0.0)) m.diag[c] = 1.0;
    m.source[c] = m.diag[c] * value[c];
  }
}

template <typename T>
void AddSource(FvMatrix<T>& m, std::span<const T> per_volume) {
  const auto vol = m.mesh().cell_volumes();
  for (int c = 0; c < m.mesh().n_cells(); ++c) m.source[c] += vol[c] * per_volume[c];
}

bool NeedsReference(const CellField<double>& field) {
  for (int p = 0; p < field.n_patches(); ++p) {
    for (double g : field.bc(p).gradient_internal()) {
      if (g != 0.0) return false;
    }
  }
  return true;
}

void SetReference(std::vector<double>& diag, std::vector<double>& source, int cell, double value) {
  source[cell] += diag[cell] * value;
  diag[cell] += diag[cell];
}

void LaplacianFlux(const CellField<double>& field, std::span<const double> gamma_faces, const NonOrthGeometry& geo,
                   std::vector<double>& flux) {
  const Mesh& mesh = field.mesh();
  const auto owner = mesh.owner();
  const auto neighbour = mesh.neighbour();
  const auto mag = mesh.face_area_magnitudes();
  flux.resize(mesh.n_faces());
  for (int f = 0; f < mesh.n_internal_faces(); ++f) {
    const double a = gamma_faces[f] * mag[f] * geo.delta_coeffs[f];
    flux[f] = a * (field[neighbour[f]] - field[owner[f]]);
  }
  for (int p = 0; p < field.n_patches(); ++p) {
    const Patch& patch = mesh.patches()[p];
    const auto& bc = field.bc(p);
    for (int i = 0; i < patch.size; ++i) {
      const int f = patch.start + i;
      const double sn_grad = bc.gradient_internal()[i] * field[owner[f]] + bc.gradient_boundary()[i];
      flux[f] = gamma_faces[f] * mag[f] * sn_grad;
    }
  }
}

void NonOrthogonalFlux(const Mesh& mesh, std::span<const double> gamma_faces, std::span<const Vector3> grad,
                       const NonOrthGeometry& geo, std::vector<double>& flux) {
  const int ni = mesh.n_internal_faces();
  if (!geo.any_correction) {
    flux.assign(ni, 0.0);
    return;
  }
  flux.resize(ni);
  const auto owner = mesh.owner();
  const auto neighbour = mesh.neighbour();
  const auto w = mesh.weights();
  const auto mag = mesh.face_area_magnitudes();
  for (int f = 0; f < ni; ++f) {
    flux[f] = gamma_faces[f] * mag[f] * NonOrthogonalPart(geo, f, grad[owner[f]], grad[neighbour[f]], w[f]);
  }
}

template class FvMatrix<double>;
template class FvMatrix<Vector3>;
template void AddDdt(FvMatrix<double>&, const CellField<double>&, double, TimeScheme);
template void AddDdt(FvMatrix<Vector3>&, const CellField<Vector3>&, double, TimeScheme);
template void AddConvection(FvMatrix<double>&, const CellField<double>&, std::span<const double>, ConvectionScheme,
                            const std::vector<Vector3>&);
template void AddConvection(FvMatrix<Vector3>&, const CellField<Vector3>&, std::span<const double>,
                            ConvectionScheme, const std::vector<Matrix3>&);
template void AddLaplacian(FvMatrix<double>&, const CellField<double>&, double, const NonOrthGeometry&,
                           const std::vector<Vector3>*);
template void AddLaplacian(FvMatrix<Vector3>&, const CellField<Vector3>&, double, const NonOrthGeometry&,
                           const std::vector<Matrix3>*);
template void AddLaplacian(FvMatrix<double>&, const CellField<double>&, std::span<const double>,
                           const NonOrthGeometry&, const std::vector<Vector3>*);
template void AddLaplacian(FvMatrix<Vector3>&, const CellField<Vector3>&, std::span<const double>,
                           const NonOrthGeometry&, const std::vector<Matrix3>*);
template void AddSource(FvMatrix<double>&, std::span<const double>);
template void AddSource(FvMatrix<Vector3>&, std::span<const Vector3>);

}  // namespace kelvin::cfd
