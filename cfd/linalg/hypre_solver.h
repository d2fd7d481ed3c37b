// Krylov solvers of hypre through the IJ/ParCSR interface:
// - kPcgAmg: CG preconditioned by BoomerAMG (pressure, wall distance). The
//   AMG hierarchy is reused until the iteration count grows or a setup is
//   requested.
// - kBiCgStabIlu: BiCGStab preconditioned by hypre's ILU(0) (transport
//   equations dominated by convection, such as k and omega at large time
//   steps). The factorization is redone at every solve (the values change
//   every step; ILU(0) costs a few matrix-vector products).
// (BiCGStab and CG with Jacobi are Eigen's serially and PETSc's on a shell
// matrix on ranks: linear_solver.h, petsc_shell_solver.h.)
// The sparsity is given once; each solve copies the new values into the
// existing ParCSR matrix. Serial runs are MPI singletons with the rows
// 0..n-1; on a decomposed mesh (cfd/parallel/domain_part.h) each rank gives
// the rows of its owned cells, with the columns in global row numbers.
#pragma once

#include <map>

#include "cfd/linalg/linear_solver.h"

namespace kelvin::cfd {

// Initializes MPI once per process (singleton when not under mpirun) and
// finalizes it at exit.
void EnsureMpi();

class HypreSolver : public LinearSolver {
 public:
  // `part` (null: serial) must outlive the solver. Types kPcgAmg and
  // kBiCgStabIlu.
  explicit HypreSolver(const LinearSolverOptions& options, const DomainPart* part = nullptr);
  ~HypreSolver() override;
  HypreSolver(const HypreSolver&) = delete;
  HypreSolver& operator=(const HypreSolver&) = delete;
  SolverSummary Solve(const CsrMatrix& a, std::span<const double> b, std::span<double> x) override;
  void RequestSetup() override { need_setup_ = true; }
  void SetRelativeTolerance(double relative) override;
  // Preconditioner setups so far (AMG hierarchies or ILU factorizations).
  int setups() const { return setups_; }

 private:
  // CG with AMG; otherwise BiCGStab with ILU.
  bool Amg() const { return options_.type == LinearSolverOptions::Type::kPcgAmg; }
  void Create(const CsrMatrix& a);
  void CreateMatrix(const CsrMatrix& a);
  void CreatePreconditioner();
  void CreateKrylov();
  void Destroy();

  LinearSolverOptions options_;
  const DomainPart* part_ = nullptr;
  struct Impl;
  std::unique_ptr<Impl> impl_;
  bool need_setup_ = true;
  std::map<double, int> reference_iterations_;  // per relative tolerance
  int setups_ = 0;
};

}  // namespace kelvin::cfd
