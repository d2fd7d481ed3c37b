// CG preconditioned by hypre BoomerAMG through the IJ/ParCSR interface.
// The sparsity is given once; each solve copies the new values into the
// existing ParCSR matrix and reuses the AMG hierarchy until the iteration
// count grows or a setup is requested. Runs serially as an MPI singleton; the
// row partition (ilower..iupper) is where a domain decomposition plugs in.
#pragma once

#include <map>

#include "cfd/linalg/linear_solver.h"

namespace kelvin::cfd {

// Initializes MPI once per process (singleton when not under mpirun) and
// finalizes it at exit.
void EnsureMpi();

class HypreAmgSolver : public LinearSolver {
 public:
  explicit HypreAmgSolver(const LinearSolverOptions& options);
  ~HypreAmgSolver() override;
  HypreAmgSolver(const HypreAmgSolver&) = delete;
  HypreAmgSolver& operator=(const HypreAmgSolver&) = delete;
  SolverSummary Solve(const CsrMatrix& a, std::span<const double> b, std::span<double> x) override;
  void RequestSetup() override { need_setup_ = true; }
  void SetRelativeTolerance(double relative) override;
  int setups() const { return setups_; }

 private:
  void Create(const CsrMatrix& a);
  void Destroy();

  LinearSolverOptions options_;
  struct Impl;
  std::unique_ptr<Impl> impl_;
  bool need_setup_ = true;
  std::map<double, int> reference_iterations_;  // per relative tolerance
  int setups_ = 0;
};

}  // namespace kelvin::cfd
