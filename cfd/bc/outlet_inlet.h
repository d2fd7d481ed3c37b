// The pressure partner of InletOutlet at far-field boundaries whose role is
// decided by the relative flux F - F_mesh (a drifting or yawing hull sees
// inflow on its sides): the value is fixed where the flow leaves (F > 0) and
// the normal gradient is zero where it enters, so each face has one Dirichlet
// and one Neumann condition between U (InletOutlet) and p (OpenFOAM's
// outletInlet).
#pragma once

#include <algorithm>

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
  PatchRole role() const override { return PatchRole::kOutflow; }

 private:
  T outflow_;
};

}  // namespace kelvin::cfd

namespace kelvin::cfd {

// Far field of a body moving through still water, with the inflow/outflow
// switch of InletOutlet + OutletInlet made continuous: with the relative
// normal velocity u_n = (F - F_mesh) / |S| (positive out of the domain), the
// inflow weight is w = 1 for u_n <= -band, 0 for u_n >= band and a cubic
// smoothstep between. The velocity condition is w Dirichlet (inflow value) +
// (1 - w) zero gradient; the pressure condition the reverse (fixed where the
// flow leaves). A hard switch lets faces flip every step where the side
// boundaries of a swaying or yawing domain change from inflow to outflow,
// which makes PMM force histories noisy; the band removes the flips.
template <typename T>
class FarField : public BoundaryCondition<T> {
 public:
  // `inflow_fixed`: true for the velocity (fixed on inflow), false for the
  // pressure (fixed on outflow). band > 0 in m/s.
  FarField(const T& value, bool inflow_fixed, double band)
      : value_(value), inflow_fixed_(inflow_fixed), band_(band) {
    KELVIN_CHECK(band > 0.0, "positive far-field band");
  }
  void Update(const BcContext& ctx, std::span<const T>) override {
    this->Resize(ctx.patch.size);
    for (int i = 0; i < ctx.patch.size; ++i) {
      const int f = ctx.patch.start + i;
      const double un =
          ctx.face_flux.empty() ? 0.0 : ctx.face_flux[f] / ctx.mesh.face_area_magnitudes()[f];
      const double x = std::clamp(0.5 * (1.0 - un / band_), 0.0, 1.0);  // 1 = inflow
      const double inflow = x * x * (3.0 - 2.0 * x);
      const double w = inflow_fixed_ ? inflow : 1.0 - inflow;  // weight of the fixed value
      const double dc = this->DeltaCoeff(ctx.mesh, f);
      this->vi_[i] = (1.0 - w) * Traits<T>::One();
      this->vb_[i] = w * value_;
      this->gi_[i] = -w * dc * Traits<T>::One();
      this->gb_[i] = w * dc * value_;
    }
  }
  std::string type() const override { return "farField"; }
  PatchRole role() const override { return PatchRole::kOutflow; }

 private:
  T value_;
  bool inflow_fixed_;
  double band_;
};

}  // namespace kelvin::cfd
