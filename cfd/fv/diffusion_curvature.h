// Second-order diffusive fluxes on skewed and kinked faces
// (docs/formulation.md section 10, "Curvature correction").
//
// The two-point flux of a Laplacian, |S| (dc (phi_N - phi_P) + k . grad(phi)_f'),
// is the face's flux only where its parts are evaluated at the face centre:
// the difference phi_N - phi_P is exact to second order at the midpoint x_m of
// PN, the interpolated gradient at the weighting point x_f' on PN, and a kinked
// (non-planar) face is not one plane. On refinement interfaces (a face centre
// a quarter cell off the PN line) and on polyhedral cells with kinked faces
// the leftover is O(h |S|) per face: an O(1) truncation error of the Laplacian
// in every cell such a face bounds. The velocity converges regardless, but the
// pressure takes up the gradient part of the viscous truncation error, and
// its error then falls no faster than O(1) (measured by
// tests/cfd/solver/mms_order_test.cc, MmsTruncation).
//
// With the cell Hessians H = grad(grad(phi)) (the gradient of the gradient),
// the exact flux of a quadratic phi is recovered by the per-face tensor
//   C_f = |S| [dc (x_c - x_m) (x) d + (x_c - x_f') (x) k] + sum_t (x_t - x_c) (x) S_t
// (x_c the face centre, t the triangles of the face fanned about it):
//   flux_f += gamma_f H_f : C_f,  H_f = w H_P + (1 - w) H_N.
// The correction is explicit (it goes to the source) and vanishes on
// orthogonal meshes with planar faces through the PN midpoint.
#pragma once

#include <array>
#include <span>
#include <vector>

#include "cfd/fv/fv_matrix.h"
#include "cfd/fv/gradient.h"

namespace kelvin::cfd {

// M_f = sum_t (x_t - x_c) (x) S_t of every internal face: zero on a planar
// face, O(h |S|) on a kinked one, where the flux of a field v is
// v(x_c) . S_f + grad(v) : M_f^T to second order (J(i, j) = dv_i/dx_j).
std::vector<Matrix3> FaceFirstMoments(const Mesh& mesh);

// C_f of every internal face for the non-orthogonal form of `geo`, from the
// faces' first moments (FaceFirstMoments). In the face-centre form the cell
// values are carried along the face to P' and N' on the normal through x_c,
// and C_f = |S| [(x_c - x_m') (x) n + dc (t_N (x) t_N - t_P (x) t_P) / 2] + M_f,
// x_m' the midpoint of P'N'.
std::vector<Matrix3> DiffusionCurvatureTensors(const Mesh& mesh, const NonOrthGeometry& geo,
                                               std::span<const Matrix3> moments);

// The symmetric Hessian of each component of a vector field from its cell
// gradient J (J(i, j) = du_i/dx_j): the gradient of row i, with the owner
// cell's gradient on boundary faces.
std::array<std::vector<Matrix3>, 3> ComponentHessians(const Gradient& gradient, const std::vector<Matrix3>& grad);

// flux_f += gamma H_f : C_f on every internal face of -div(gamma grad U).
void AddDiffusionCurvature(FvMatrix<Vector3>& m, double gamma, std::span<const Matrix3> tensors,
                           const std::array<std::vector<Matrix3>, 3>& hessians);
// The same with one diffusivity per face (every face; the internal ones are read).
void AddDiffusionCurvature(FvMatrix<Vector3>& m, std::span<const double> gamma_faces, std::span<const Matrix3> tensors,
                           const std::array<std::vector<Matrix3>, 3>& hessians);

}  // namespace kelvin::cfd
