// A square sparse matrix with the cell-to-cell sparsity of a mesh, set once
// (CSR, row-major); values are refilled in place from LDU coefficients.
#pragma once

#include <Eigen/SparseCore>

#include <span>
#include <vector>

#include "cfd/mesh/mesh.h"

namespace kelvin::cfd {

using CsrMatrix = Eigen::SparseMatrix<double, Eigen::RowMajor, int>;

class SparseSystem {
 public:
  explicit SparseSystem(const Mesh& mesh);
  // Overwrites the values: A(P,P) = diag, A(P,N) = upper, A(N,P) = lower.
  void Fill(std::span<const double> diag, std::span<const double> upper, std::span<const double> lower);
  // Overwrites the diagonal only.
  void FillDiagonal(std::span<const double> diag);
  const CsrMatrix& matrix() const { return a_; }
  CsrMatrix& matrix() { return a_; }
  int rows() const { return static_cast<int>(a_.rows()); }

 private:
  CsrMatrix a_;
  std::vector<int> diag_pos_;
  std::vector<int> upper_pos_;
  std::vector<int> lower_pos_;
};

}  // namespace kelvin::cfd
