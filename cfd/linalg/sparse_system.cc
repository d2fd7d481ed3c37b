#include "cfd/linalg/sparse_system.h"

#include "data/schema/errors.h"

namespace kelvin::cfd {

SparseSystem::SparseSystem(const Mesh& mesh) {
  const int n = mesh.n_cells();
  const int ni = mesh.n_internal_faces();
  std::vector<Eigen::Triplet<double, int>> t;
  t.reserve(n + 2 * ni);
  for (int c = 0; c < n; ++c) t.emplace_back(c, c, 1.0);
  for (int f = 0; f < ni; ++f) {
    t.emplace_back(mesh.owner()[f], mesh.neighbour()[f], 1.0);
    t.emplace_back(mesh.neighbour()[f], mesh.owner()[f], 1.0);
  }
  a_.resize(n, n);
  a_.setFromTriplets(t.begin(), t.end());
  a_.makeCompressed();
  auto position = [&](int row, int col) {
    const int* begin = a_.innerIndexPtr() + a_.outerIndexPtr()[row];
    const int* end = a_.innerIndexPtr() + a_.outerIndexPtr()[row + 1];
    const int* it = std::lower_bound(begin, end, col);
    KELVIN_CHECK(it != end && *it == col, "entry in the sparsity pattern");
    return static_cast<int>(it - a_.innerIndexPtr());
  };
  diag_pos_.resize(n);
  for (int c = 0; c < n; ++c) diag_pos_[c] = position(c, c);
  upper_pos_.resize(ni);
  lower_pos_.resize(ni);
  for (int f = 0; f < ni; ++f) {
    upper_pos_[f] = position(mesh.owner()[f], mesh.neighbour()[f]);
    lower_pos_[f] = position(mesh.neighbour()[f], mesh.owner()[f]);
  }
}

void SparseSystem::Fill(std::span<const double> diag, std::span<const double> upper, std::span<const double> lower) {
  double* v = a_.valuePtr();
  for (std::size_t c = 0; c < diag.size(); ++c) v[diag_pos_[c]] = diag[c];
  for (std::size_t f = 0; f < upper.size(); ++f) {
    v[upper_pos_[f]] = upper[f];
    v[lower_pos_[f]] = lower[f];
  }
}

}  // namespace kelvin::cfd

namespace kelvin::cfd {

void SparseSystem::FillDiagonal(std::span<const double> diag) {
  double* v = a_.valuePtr();
  for (std::size_t c = 0; c < diag.size(); ++c) v[diag_pos_[c]] = diag[c];
}

}  // namespace kelvin::cfd
