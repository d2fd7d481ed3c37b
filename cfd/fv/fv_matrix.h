// Finite-volume matrix in OpenFOAM's LDU form: one diagonal coefficient per
// cell, one upper (owner row, neighbour column) and one lower (neighbour row,
// owner column) coefficient per internal face, a source per cell, and the
// boundary contributions kept per boundary face (component-wise for vectors)
// so that each velocity component can have its own diagonal (slip walls).
//
//   (diag_P + sum_b internal_coeffs_b) phi_P + sum_N a_PN phi_N
//       = source_P + sum_b boundary_coeffs_b
//
// The operators below add terms to a matrix so that an equation reads like
// the maths: AddDdt, AddConvection, AddLaplacian, AddDivDev2Transpose,
// AddDivergence, AddSource.
// Free functions on spans (below the matrix operators) give the face fluxes
// of a Laplacian, for the conservative flux of the pressure equation
// (docs/formulation.md sections 4.4 and 10).
#pragma once

#include <span>
#include <vector>

#include "cfd/field/field.h"
#include "cfd/fv/gradient.h"
#include "cfd/fv/schemes.h"

namespace kelvin::cfd {

template <typename T>
class FvMatrix {
 public:
  explicit FvMatrix(const Mesh& mesh) : mesh_(&mesh) { Reset(); }
  void Reset() {
    diag.assign(mesh_->n_cells(), 0.0);
    upper.assign(mesh_->n_internal_faces(), 0.0);
    lower.assign(mesh_->n_internal_faces(), 0.0);
    source.assign(mesh_->n_cells(), Traits<T>::Zero());
    internal_coeffs.assign(mesh_->n_boundary_faces(), Traits<T>::Zero());
    boundary_coeffs.assign(mesh_->n_boundary_faces(), Traits<T>::Zero());
  }
  const Mesh& mesh() const { return *mesh_; }

  // Central coefficient per unit volume, with the component average of the
  // boundary diagonal (OpenFOAM's A()).
  std::vector<double> A() const;
  // H(psi) per unit volume: source minus the neighbour contributions, with
  // the boundary sources and the component part of the boundary diagonal.
  std::vector<T> H(std::span<const T> psi) const;
  // Implicit under-relaxation: diag /= alpha, source += (1 - alpha)/alpha
  // diag psi_prev (only the interior diagonal is scaled).
  void Relax(std::span<const T> psi, double alpha);
  // Diagonal and source of component k with the boundary parts folded in.
  void ComponentSystem(int k, std::vector<double>& diag_k, std::vector<double>& source_k) const;

  std::vector<double> diag;
  std::vector<double> upper;
  std::vector<double> lower;
  std::vector<T> source;
  std::vector<T> internal_coeffs;
  std::vector<T> boundary_coeffs;

 private:
  const Mesh* mesh_;
};

// d/dt (V phi): Euler or backward (backward falls back to Euler when only one
// old level exists).
template <typename T>
void AddDdt(FvMatrix<T>& m, const CellField<T>& field, double dt, TimeScheme scheme);

// sum_f F_f phi_f with F the relative flux: implicit upwind plus a deferred
// correction to the chosen face value. `grad` is the cell gradient of field.
template <typename T>
void AddConvection(FvMatrix<T>& m, const CellField<T>& field, std::span<const double> flux,
                   ConvectionScheme scheme, const std::vector<GradType<T>>& grad);

// -div(gamma grad phi) with constant gamma: orthogonal part implicit, the
// non-orthogonal correction explicit from `grad` (null: no correction).
struct NonOrthGeometry;
template <typename T>
void AddLaplacian(FvMatrix<T>& m, const CellField<T>& field, double gamma, const NonOrthGeometry& geo,
                  const std::vector<GradType<T>>* grad);

// The same with one diffusivity per face (all faces, boundary ones included:
// wall functions put the wall eddy viscosity there).
template <typename T>
void AddLaplacian(FvMatrix<T>& m, const CellField<T>& field, std::span<const double> gamma_faces,
                  const NonOrthGeometry& geo, const std::vector<GradType<T>>* grad);

// Explicit -div(gamma dev2(grad(U)^T)) on the left-hand side (the
// transposed-gradient part of the viscous stress): with J(i, j) = du_i/dx_j
// the face flux gamma_f (J_f^T - 2/3 tr(J_f) I) S_f goes to the source, J_f
// interpolated linearly on internal faces and the owner value on boundary
// faces. `gamma_faces` on every face, `grad` the cell gradient of U.
void AddDivDev2Transpose(FvMatrix<Vector3>& m, std::span<const double> gamma_faces, const std::vector<Matrix3>& grad);

// Explicit div(F) = sum_f F_f (F_f out of the owner) on the left-hand side:
// internal faces go to the source, boundary faces to boundary_coeffs. With
// AddLaplacian it makes the pressure equation laplacian(rAU, p) == div(F).
void AddDivergence(FvMatrix<double>& m, std::span<const double> face_flux);

// Implicit linear source: + coeff * phi per unit volume on the left-hand side
// (coeff >= 0 keeps the matrix diagonally dominant: destruction terms).
void AddImplicitSource(FvMatrix<double>& m, std::span<const double> coeff_per_volume);

// Fixes the solution in `cells` to `values` (OpenFOAM's setValues): the rows
// keep their diagonal and lose their couplings, and the neighbours see the
// fixed values as known sources. Used for omega in wall cells.
void SetCellValues(FvMatrix<double>& m, std::span<const int> cells, std::span<const double> values);

// Explicit source per unit volume (moved to the right-hand side times V).
template <typename T>
void AddSource(FvMatrix<T>& m, std::span<const T> per_volume);

// A system that no boundary condition ties to a value (gradient_internal
// zero on every face of `field`) has the constants as null space.
bool NeedsReference(const CellField<double>& field);

// Fixes the level of such a system in `cell` (OpenFOAM's setReference):
// source_c += diag_c value, diag_c doubles. Applied to the assembled system,
// after ComponentSystem has folded in the boundary parts.
void SetReference(std::vector<double>& diag, std::vector<double>& source, int cell, double value);

// Face fluxes of a corrected Laplacian, gamma_f |S_f| snGrad(phi)_f with
// snGrad = dc_f (phi_N - phi_P) + k_f . grad(phi)_f on internal faces, split
// as the matrix splits it:
//   LaplacianFlux: the implicit part, gamma_f |S_f| dc_f (phi_N - phi_P) on
//     internal faces and gamma_f |S_f| (gi phi_P + gb) from the conditions
//     on boundary faces (every face);
//   NonOrthogonalFlux: the explicit part gamma_f |S_f| k_f . grad(phi)_f with
//     the linearly interpolated cell gradient (internal faces; zeros when
//     the mesh is orthogonal).
void LaplacianFlux(const CellField<double>& field, std::span<const double> gamma_faces, const NonOrthGeometry& geo,
                   std::vector<double>& flux);
void NonOrthogonalFlux(const Mesh& mesh, std::span<const double> gamma_faces, std::span<const Vector3> grad,
                       const NonOrthGeometry& geo, std::vector<double>& flux);

// Where the explicit part of the corrected face-normal gradient takes the
// cell gradients (docs/formulation.md section 4.4):
//   kInterpolated: k_f . (w grad_P + (1 - w) grad_N), the gradient
//     interpolated to where the owner-neighbour line meets the face
//     (OpenFOAM's "corrected");
//   kFaceCentre: dc_f (grad_N . t_N - grad_P . t_P), with t the part of
//     (x_f - x_cell) along the face: each cell's value is carried to the
//     normal through the face centre. The same for a linear field; on the
//     2:1 split faces of refinement interfaces it keeps the manufactured
//     solution's velocity at second order (mms_order_test).
enum class NonOrthogonalForm { kInterpolated, kFaceCentre };

// Non-orthogonal correction vectors k_f = n_f - d_f / (n_f . d_f) and the
// matching delta coefficients 1 / (n_f . d_f), as OpenFOAM's "corrected".
struct NonOrthGeometry {
  explicit NonOrthGeometry(const Mesh& mesh, NonOrthogonalForm form = NonOrthogonalForm::kInterpolated);
  std::vector<double> delta_coeffs;    // internal faces
  std::vector<Vector3> correction;     // internal faces
  // kFaceCentre only (empty otherwise): dc_f t_P and dc_f t_N per internal face.
  std::vector<Vector3> owner_tangent;
  std::vector<Vector3> neighbour_tangent;
  // Boundary faces: n - d_b / (n . d_b) with d_b = x_f - x_P, so that
  // snGrad = dc (phi_b - phi_P) + k_b . grad(phi)_P on skewed wall cells.
  std::vector<Vector3> boundary_correction;
  // False when every correction vector is zero (orthogonal mesh); the two
  // vectors above are then released and must not be read.
  bool any_correction = false;
};

}  // namespace kelvin::cfd
