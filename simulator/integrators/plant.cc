#include "simulator/integrators/plant.h"

#include <ceres/jet.h>

namespace kelvin::sim {

LinearPlant LinearPlant::Linearize(const MmgModel<double>& model, const StateVec& y0, double delta0, double n0) {
  // Differentiate with respect to the 6 states and the 2 inputs at once.
  using Jet = ceres::Jet<double, kStateSize + 2>;
  const MmgModel<Jet> jet_model(model.ship(), model.hull().Cast<Jet>());
  Jet y[kStateSize], ydot[kStateSize];
  for (int i = 0; i < kStateSize; ++i) y[i] = Jet(y0[i], i);
  const Jet delta(delta0, kStateSize), n(n0, kStateSize + 1);
  jet_model.Derivative(y, delta, n, ydot);
  LinearPlant p;
  p.ship_ = model.ship();
  p.y0_ = y0;
  p.delta0_ = delta0;
  p.n0_ = n0;
  for (int i = 0; i < kStateSize; ++i) {
    p.f0_[i] = ydot[i].a;
    for (int j = 0; j < kStateSize; ++j) p.A_(i, j) = ydot[i].v[j];
    p.B_(i, 0) = ydot[i].v[kStateSize];
    p.B_(i, 1) = ydot[i].v[kStateSize + 1];
  }
  return p;
}

void LinearPlant::Derivative(const double* y, double delta, double n, double* ydot) const {
  const Eigen::Map<const StateVec> yv(y);
  Eigen::Map<StateVec> out(ydot);
  out = f0_ + A_ * (yv - y0_) + B_ * Eigen::Vector2d(delta - delta0_, n - n0_);
}

}  // namespace kelvin::sim
