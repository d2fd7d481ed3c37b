#include "cfd/fv/diffusion_curvature.h"

#include "data/schema/errors.h"

namespace kelvin::cfd {

namespace {

// sum_t (x_t - x_c) (x) S_t over the triangles of face f fanned about its centre.
Matrix3 FaceFirstMoment(const Mesh& mesh, int f) {
  const Vector3& xc = mesh.face_centres()[f];
  const auto pts = mesh.face(f);
  Matrix3 m = Matrix3::Zero();
  for (std::size_t i = 0; i < pts.size(); ++i) {
    const Vector3& a = mesh.points()[pts[i]];
    const Vector3& b = mesh.points()[pts[(i + 1) % pts.size()]];
    const Vector3 s = 0.5 * (a - xc).cross(b - xc);
    const Vector3 xt = (xc + a + b) / 3.0;
    m += (xt - xc) * s.transpose();
  }
  return m;
}

}  // namespace

std::vector<Matrix3> FaceFirstMoments(const Mesh& mesh) {
  std::vector<Matrix3> m(mesh.n_internal_faces());
  for (int f = 0; f < mesh.n_internal_faces(); ++f) m[f] = FaceFirstMoment(mesh, f);
  return m;
}

std::vector<Matrix3> DiffusionCurvatureTensors(const Mesh& mesh, const NonOrthGeometry& geo,
                                               std::span<const Matrix3> moments) {
  const int ni = mesh.n_internal_faces();
  KELVIN_CHECK(static_cast<int>(moments.size()) == ni, "one first moment per internal face");
  const auto owner = mesh.owner();
  const auto neighbour = mesh.neighbour();
  const auto w = mesh.weights();
  const bool face_centre_form = !geo.owner_tangent.empty();
  std::vector<Matrix3> c(ni);
  for (int f = 0; f < ni; ++f) {
    const Vector3& xp = mesh.cell_centres()[owner[f]];
    const Vector3& xn = mesh.cell_centres()[neighbour[f]];
    const Vector3& xc = mesh.face_centres()[f];
    const double mag = mesh.face_area_magnitudes()[f];
    const double dc = geo.delta_coeffs[f];
    c[f] = moments[f];
    if (face_centre_form) {
      // The values carried along the face to the normal through x_c, at
      // P' = x_P + t_P and N' = x_N + t_N: their difference is the normal
      // derivative at the midpoint of P'N', each carried value misses
      // t^T H t / 2.
      const Vector3 tp = geo.owner_tangent[f] / dc, tn = geo.neighbour_tangent[f] / dc;
      const Vector3 n = mesh.face_areas()[f] / mag;
      const Vector3 xm = 0.5 * (xp + tp + xn + tn);
      c[f] += mag * ((xc - xm) * n.transpose() + 0.5 * dc * (tn * tn.transpose() - tp * tp.transpose()));
    } else {
      const Vector3 xm = 0.5 * (xp + xn);
      const Vector3 xw = w[f] * xp + (1.0 - w[f]) * xn;
      const Vector3 k = geo.correction.empty() ? Vector3::Zero() : geo.correction[f];
      c[f] += mag * (dc * (xc - xm) * mesh.deltas()[f].transpose() + (xc - xw) * k.transpose());
    }
  }
  return c;
}

std::array<std::vector<Matrix3>, 3> ComponentHessians(const Gradient& gradient, const std::vector<Matrix3>& grad) {
  const Mesh& mesh = gradient.mesh();
  const int ni = mesh.n_internal_faces();
  std::array<std::vector<Matrix3>, 3> h;
  std::vector<Vector3> rows(grad.size()), boundary(mesh.n_faces() - ni);
  for (int i = 0; i < 3; ++i) {
    for (std::size_t c = 0; c < grad.size(); ++c) rows[c] = grad[c].row(i).transpose();
    for (int f = ni; f < mesh.n_faces(); ++f) boundary[f - ni] = rows[mesh.owner()[f]];
    gradient.Compute(std::span<const Vector3>(rows), std::span<const Vector3>(boundary), h[i]);
    for (Matrix3& m : h[i]) m = 0.5 * (m + m.transpose()).eval();
  }
  return h;
}

namespace {

template <typename Gamma>
void AddCurvatureFluxes(FvMatrix<Vector3>& m, const Gamma& gamma, std::span<const Matrix3> tensors,
                        const std::array<std::vector<Matrix3>, 3>& hessians) {
  const Mesh& mesh = m.mesh();
  const auto owner = mesh.owner();
  const auto neighbour = mesh.neighbour();
  const auto w = mesh.weights();
  KELVIN_CHECK(static_cast<int>(tensors.size()) == mesh.n_internal_faces(), "one curvature tensor per internal face");
  for (int f = 0; f < mesh.n_internal_faces(); ++f) {
    const int P = owner[f], N = neighbour[f];
    Vector3 flux;
    for (int i = 0; i < 3; ++i) {
      const Matrix3 hf = w[f] * hessians[i][P] + (1.0 - w[f]) * hessians[i][N];
      flux[i] = gamma(f) * hf.cwiseProduct(tensors[f]).sum();
    }
    m.source[P] += flux;
    m.source[N] -= flux;
  }
}

}  // namespace

void AddDiffusionCurvature(FvMatrix<Vector3>& m, double gamma, std::span<const Matrix3> tensors,
                           const std::array<std::vector<Matrix3>, 3>& hessians) {
  AddCurvatureFluxes(m, [gamma](int) { return gamma; }, tensors, hessians);
}

void AddDiffusionCurvature(FvMatrix<Vector3>& m, std::span<const double> gamma_faces, std::span<const Matrix3> tensors,
                           const std::array<std::vector<Matrix3>, 3>& hessians) {
  KELVIN_CHECK(static_cast<int>(gamma_faces.size()) == m.mesh().n_faces(), "one diffusivity per face");
  AddCurvatureFluxes(m, [gamma_faces](int f) { return gamma_faces[f]; }, tensors, hessians);
}

}  // namespace kelvin::cfd
