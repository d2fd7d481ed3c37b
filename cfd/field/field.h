// Fields on the cells of a mesh: values, old time levels and boundary face
// values, with one boundary condition per patch. T is double (p) or Vector3
// (U). Component-wise helpers let one code path serve both.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "cfd/bc/boundary_condition.h"
#include "cfd/mesh/mesh.h"

namespace kelvin::cfd {

template <typename T>
class CellField {
 public:
  // `bcs` holds one condition per patch, in the mesh's patch order.
  CellField(std::string name, const Mesh& mesh, std::vector<std::unique_ptr<BoundaryCondition<T>>> bcs)
      : name_(std::move(name)),
        mesh_(&mesh),
        values_(mesh.n_cells(), Traits<T>::Zero()),
        boundary_(mesh.n_boundary_faces(), Traits<T>::Zero()),
        bcs_(std::move(bcs)) {
    KELVIN_CHECK(bcs_.size() == mesh.patches().size(), "one boundary condition per patch");
  }

  const std::string& name() const { return name_; }
  const Mesh& mesh() const { return *mesh_; }
  std::vector<T>& values() { return values_; }
  const std::vector<T>& values() const { return values_; }
  // Boundary face values, indexed by face - n_internal_faces.
  std::vector<T>& boundary() { return boundary_; }
  const std::vector<T>& boundary() const { return boundary_; }
  T& operator[](int cell) { return values_[cell]; }
  const T& operator[](int cell) const { return values_[cell]; }

  BoundaryCondition<T>& bc(int patch) { return *bcs_[patch]; }
  const BoundaryCondition<T>& bc(int patch) const { return *bcs_[patch]; }
  int n_patches() const { return static_cast<int>(bcs_.size()); }

  // Old time levels: old(0) is t^n, old(1) is t^{n-1}.
  const std::vector<T>& old(int level) const { return old_[level]; }
  int n_old() const { return static_cast<int>(old_.size()); }
  // Shifts the time levels before a new step (keeps at most `levels`).
  void StoreOldTime(int levels) {
    if (static_cast<int>(old_.size()) < levels) old_.emplace_back();
    for (std::size_t i = old_.size() - 1; i > 0; --i) old_[i].swap(old_[i - 1]);
    old_[0] = values_;
  }
  void SetOld(std::vector<std::vector<T>> old) { old_ = std::move(old); }

  // Refreshes the boundary coefficients of every patch and the boundary
  // values from them (value = internal_coeff * phi_P + boundary_coeff).
  void CorrectBoundary(double time, std::span<const double> face_flux) {
    const int ni = mesh_->n_internal_faces();
    for (int p = 0; p < n_patches(); ++p) {
      const Patch& patch = mesh_->patches()[p];
      BcContext ctx{*mesh_, patch, time, face_flux};
      bcs_[p]->Update(ctx, values_);
      for (int i = 0; i < patch.size; ++i) {
        const int f = patch.start + i;
        boundary_[f - ni] = Traits<T>::Mul(bcs_[p]->value_internal()[i], values_[mesh_->owner()[f]]) +
                            bcs_[p]->value_boundary()[i];
      }
    }
  }

 private:
  std::string name_;
  const Mesh* mesh_;
  std::vector<T> values_;
  std::vector<T> boundary_;
  std::vector<std::vector<T>> old_;
  std::vector<std::unique_ptr<BoundaryCondition<T>>> bcs_;
};

using ScalarField = CellField<double>;
using VectorField = CellField<Vector3>;

}  // namespace kelvin::cfd
