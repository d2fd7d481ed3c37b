// The pressure partner of InletOutlet at far-field boundaries whose role is
// decided by the relative flux F - F_mesh (a drifting or yawing hull sees
// inflow on its sides): the value is fixed where the flow leaves (F > 0) and
// the normal gradient is zero where it enters, so each face has one Dirichlet
// and one Neumann condition between U (InletOutlet) and p (OpenFOAM's
// outletInlet).
#pragma once

#include "cfd/bc/boundary_condition.h"

namespace kelvin::cfd {

template <typename T>
class OutletInlet : public BoundaryCondition<T> {
 public:
  explicit OutletInlet(const T& outflow) : outflow_(outflow) {}
  void Update(const BcContext& ctx, std::span<const T>) override {
    this->Resize(ctx.patch.size);
    for (int i = 0; i < ctx.patch.size; ++i) {
      const int f = ctx.patch.start + i;
      const double flux = ctx.face_flux.empty() ? 0.0 : ctx.face_flux[f];
      if (flux > 0.0) {
        this->SetFixed(i, this->DeltaCoeff(ctx.mesh, f), outflow_);
      } else {
        this->SetZeroGradient(i);
      }
    }
  }
  std::string type() const override { return "outletInlet"; }

 private:
  T outflow_;
};

}  // namespace kelvin::cfd
