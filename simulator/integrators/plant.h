// What the integrators integrate: a right-hand side y' = f(y, delta, n) of the
// 6-state planar motion, and the ship whose actuator limits apply. The MMG
// model is the plant used everywhere; its linearization about a steady state
// (LinearPlant) is the exactly solvable special case the integrator tests use,
// and gives course-stability figures.
#pragma once

#include <Eigen/Core>
#include <memory>

#include "simulator/mmg/mmg_model.h"

namespace kelvin::sim {

class Plant {
 public:
  virtual ~Plant() = default;
  virtual void Derivative(const double* y, double delta, double n, double* ydot) const = 0;
  virtual const ShipParameters& ship() const = 0;
};

// The MMG model as a plant, by reference: `model` (which owns the ship
// parameters) must outlive the plant.
class MmgPlant final : public Plant {
 public:
  explicit MmgPlant(const MmgModel<double>& model) : model_(&model) {}
  explicit MmgPlant(const MmgModel<double>&& model) = delete;  // would dangle
  void Derivative(const double* y, double delta, double n, double* ydot) const override {
    model_->Derivative(y, delta, n, ydot);
  }
  const ShipParameters& ship() const override { return model_->ship(); }
  const MmgModel<double>& model() const { return *model_; }

 private:
  const MmgModel<double>* model_;
};

using StateMatrix = Eigen::Matrix<double, kStateSize, kStateSize>;
using InputMatrix = Eigen::Matrix<double, kStateSize, 2>;
using StateVec = Eigen::Matrix<double, kStateSize, 1>;

// y' = f0 + A (y - y0) + B [delta - delta0; n - n0]: the first-order Taylor
// expansion of the MMG model at (y0, delta0, n0), derived exactly with
// automatic differentiation (ceres::Jet) of MmgModel.
class LinearPlant final : public Plant {
 public:
  static LinearPlant Linearize(const MmgModel<double>& model, const StateVec& y0, double delta0, double n0);

  void Derivative(const double* y, double delta, double n, double* ydot) const override;
  const ShipParameters& ship() const override { return ship_; }

  const StateMatrix& A() const { return A_; }
  const InputMatrix& B() const { return B_; }
  const StateVec& f0() const { return f0_; }
  const StateVec& y0() const { return y0_; }
  double delta0() const { return delta0_; }
  double n0() const { return n0_; }

 private:
  ShipParameters ship_;  // a copy: the linearization is a value that outlives the model it came from
  StateMatrix A_ = StateMatrix::Zero();
  InputMatrix B_ = InputMatrix::Zero();
  StateVec f0_ = StateVec::Zero();
  StateVec y0_ = StateVec::Zero();
  double delta0_ = 0, n0_ = 0;
};

}  // namespace kelvin::sim
