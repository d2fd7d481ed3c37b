// Cell gradients: Gauss linear or weighted least squares, optionally with a
// cell limiter (Barth-Jespersen: the reconstructed face values stay within
// the range of the cell and its neighbours). For vectors the result is the
// Jacobian J(i, j) = d u_i / d x_j.
#pragma once

#include <Eigen/Core>

#include <span>
#include <type_traits>
#include <vector>

#include "cfd/mesh/mesh.h"

namespace kelvin::cfd {

using Matrix3 = Eigen::Matrix3d;

enum class GradientScheme { kGaussLinear, kLeastSquares };
enum class GradientLimiter { kNone, kCellLimited };

struct GradientOptions {
  GradientScheme scheme = GradientScheme::kGaussLinear;
  GradientLimiter limiter = GradientLimiter::kNone;
  void Validate() const {}
};

template <typename T>
using GradType = std::conditional_t<std::is_same_v<T, double>, Vector3, Matrix3>;

class Gradient {
 public:
  Gradient(const Mesh& mesh, GradientOptions options);
  // `boundary` holds the boundary face values (face - n_internal_faces).
  void Compute(std::span<const double> cells, std::span<const double> boundary, std::vector<Vector3>& out) const;
  void Compute(std::span<const Vector3> cells, std::span<const Vector3> boundary, std::vector<Matrix3>& out) const;
  const GradientOptions& options() const { return options_; }
  const Mesh& mesh() const { return mesh_; }
  // Recomputes the cached least-squares vectors from the mesh geometry (after
  // the mesh moved; a no-op for Gauss linear).
  void UpdateGeometry();

 private:
  template <typename T>
  void ComputeImpl(std::span<const T> cells, std::span<const T> boundary, std::vector<GradType<T>>& out) const;
  template <typename T>
  void Limit(std::span<const T> cells, std::span<const T> boundary, std::vector<GradType<T>>& out) const;

  const Mesh& mesh_;
  GradientOptions options_;
  // Least squares: per face, the vectors multiplying (phi_other - phi_self)
  // for the owner and the neighbour.
  std::vector<Vector3> lsq_owner_;
  std::vector<Vector3> lsq_neighbour_;
};

}  // namespace kelvin::cfd
