// BiCGStab and CG with a Jacobi preconditioner on a decomposed mesh, from
// PETSc's KSP on a shell matrix: the Krylov method multiplies by the solver's
// own CsrMatrix (the owned rows, the ghost entries of the vector brought up
// to date by the part's halo exchange before each product) instead of a copy
// of it, and the right-hand side and solution are the caller's arrays. The
// momentum and scalar equations on ranks, where hypre's ParCSR copy and its
// work vectors made the memory per cell about 0.2 kB larger than serially
// (BENCHMARKS.md parallel_speedup). The pressure keeps hypre's BoomerAMG
// (hypre_solver.h), whose hierarchy needs the assembled matrix anyway.
//
// Converged when ||b - A x||_2 <= max(relative_tolerance ||b||_2,
// absolute_tolerance), the unpreconditioned residual (right preconditioning
// for BiCGStab), as the serial Eigen and the hypre solvers test it.
#pragma once

#include <memory>

#include "cfd/linalg/linear_solver.h"

namespace kelvin::cfd {

class PetscShellSolver : public LinearSolver {
 public:
  // `part` must be parallel, hold a PETSc-initialized process (its halo
  // exchange is PETSc's) and outlive the solver. Types kBiCgStabJacobi and
  // kCgJacobi only.
  PetscShellSolver(const LinearSolverOptions& options, const DomainPart& part);
  ~PetscShellSolver() override;
  PetscShellSolver(const PetscShellSolver&) = delete;
  PetscShellSolver& operator=(const PetscShellSolver&) = delete;
  SolverSummary Solve(const CsrMatrix& a, std::span<const double> b, std::span<double> x) override;
  void SetRelativeTolerance(double relative) override;

 private:
  struct Impl;
  LinearSolverOptions options_;
  const DomainPart& part_;
  std::unique_ptr<Impl> impl_;
};

}  // namespace kelvin::cfd
