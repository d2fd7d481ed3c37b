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
// the maths: AddDdt, AddConvection, AddLaplacian, AddSource.
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

// Non-orthogonal correction vectors k_f = n_f - d_f / (n_f . d_f) and the
// matching delta coefficients 1 / (n_f . d_f), as OpenFOAM's "corrected".
struct NonOrthGeometry {
  explicit NonOrthGeometry(const Mesh& mesh);
  std::vector<double> delta_coeffs;    // internal faces
  std::vector<Vector3> correction;     // internal faces
  // Boundary faces: n - d_b / (n . d_b) with d_b = x_f - x_P, so that
  // snGrad = dc (phi_b - phi_P) + k_b . grad(phi)_P on skewed wall cells.
  std::vector<Vector3> boundary_correction;
  // False when every correction vector is zero (orthogonal mesh); the two
  // vectors above are then released and must not be read.
  bool any_correction = false;
};

}  // namespace kelvin::cfd
