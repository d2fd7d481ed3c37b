#include "cfd/linalg/petsc_shell_solver.h"

#include <fmt/format.h>
#include <petscksp.h>

#include <cmath>
#include <stdexcept>
#include <vector>

#include "cfd/parallel/domain_part.h"
#include "data/schema/errors.h"

namespace kelvin::cfd {
namespace {

void Check(PetscErrorCode code, const char* what) {
  if (code != 0) throw std::runtime_error(fmt::format("PETSc error {} in {}", static_cast<int>(code), what));
}

}  // namespace

struct PetscShellSolver::Impl {
  const CsrMatrix* a = nullptr;  // the matrix of the current solve
  const DomainPart* part = nullptr;
  std::vector<double> local;     // a vector on the local cells, ghosts included
  Mat shell = nullptr;
  KSP ksp = nullptr;
  Vec b = nullptr, x = nullptr;  // wrap the caller's arrays during a solve

  // y = A x on the owned rows.
  static PetscErrorCode Multiply(Mat m, Vec in, Vec out) {
    Impl* s = nullptr;
    PetscCall(MatShellGetContext(m, &s));
    const PetscScalar* xin = nullptr;
    PetscScalar* yout = nullptr;
    const int n = s->part->n_owned;
    PetscCall(VecGetArrayRead(in, &xin));
    std::copy(xin, xin + n, s->local.begin());
    PetscCall(VecRestoreArrayRead(in, &xin));
    UpdateGhosts(s->part, s->local);
    const int* outer = s->a->outerIndexPtr();
    const int* inner = s->a->innerIndexPtr();
    const double* values = s->a->valuePtr();
    PetscCall(VecGetArray(out, &yout));
    for (int r = 0; r < n; ++r) {
      double sum = 0.0;
      for (int k = outer[r]; k < outer[r + 1]; ++k) sum += values[k] * s->local[inner[k]];
      yout[r] = sum;
    }
    PetscCall(VecRestoreArray(out, &yout));
    return 0;
  }

  // The diagonal of the owned rows (local cell r's own column is r).
  static PetscErrorCode Diagonal(Mat m, Vec d) {
    Impl* s = nullptr;
    PetscCall(MatShellGetContext(m, &s));
    PetscScalar* out = nullptr;
    PetscCall(VecGetArray(d, &out));
    for (int r = 0; r < s->part->n_owned; ++r) out[r] = s->a->coeff(r, r);
    PetscCall(VecRestoreArray(d, &out));
    return 0;
  }
};

PetscShellSolver::PetscShellSolver(const LinearSolverOptions& options, const DomainPart& part)
    : options_(options), part_(part), impl_(std::make_unique<Impl>()) {
  options_.Validate();
  KELVIN_CHECK(options_.type == LinearSolverOptions::Type::kBiCgStabJacobi ||
                   options_.type == LinearSolverOptions::Type::kCgJacobi,
               "the shell-matrix solver is BiCGStab or CG with Jacobi");
  PetscBool initialized = PETSC_FALSE;
  PetscInitialized(&initialized);
  KELVIN_CHECK(initialized, "PETSc is initialized by the domain decomposition");
  Impl& s = *impl_;
  s.part = &part_;
  const PetscInt n = part_.n_owned;
  Check(MatCreateShell(part_.comm, n, n, PETSC_DETERMINE, PETSC_DETERMINE, &s, &s.shell), "MatCreateShell");
  Check(MatShellSetOperation(s.shell, MATOP_MULT, reinterpret_cast<void (*)(void)>(&Impl::Multiply)),
        "MatShellSetOperation(MULT)");
  Check(MatShellSetOperation(s.shell, MATOP_GET_DIAGONAL, reinterpret_cast<void (*)(void)>(&Impl::Diagonal)),
        "MatShellSetOperation(GET_DIAGONAL)");
  Check(KSPCreate(part_.comm, &s.ksp), "KSPCreate");
  Check(KSPSetOperators(s.ksp, s.shell, s.shell), "KSPSetOperators");
  const bool cg = options_.type == LinearSolverOptions::Type::kCgJacobi;
  Check(KSPSetType(s.ksp, cg ? KSPCG : KSPBCGS), "KSPSetType");
  PC pc = nullptr;
  Check(KSPGetPC(s.ksp, &pc), "KSPGetPC");
  Check(PCSetType(pc, PCJACOBI), "PCSetType");
  // The unpreconditioned residual: right preconditioning for BiCGStab; CG
  // (left only) computes it alongside.
  if (!cg) Check(KSPSetPCSide(s.ksp, PC_RIGHT), "KSPSetPCSide");
  Check(KSPSetNormType(s.ksp, KSP_NORM_UNPRECONDITIONED), "KSPSetNormType");
  Check(KSPSetInitialGuessNonzero(s.ksp, PETSC_TRUE), "KSPSetInitialGuessNonzero");
  // No divergence test: hypre's and Eigen's solvers have none either.
  Check(KSPSetTolerances(s.ksp, options_.relative_tolerance, options_.absolute_tolerance, 1e300,
                         options_.max_iterations),
        "KSPSetTolerances");
  Check(VecCreateMPIWithArray(part_.comm, 1, n, PETSC_DETERMINE, nullptr, &s.b), "VecCreateMPIWithArray");
  Check(VecCreateMPIWithArray(part_.comm, 1, n, PETSC_DETERMINE, nullptr, &s.x), "VecCreateMPIWithArray");
}

PetscShellSolver::~PetscShellSolver() {
  PetscBool finalized = PETSC_FALSE;
  PetscFinalized(&finalized);
  if (finalized) return;
  Impl& s = *impl_;
  VecDestroy(&s.b);
  VecDestroy(&s.x);
  KSPDestroy(&s.ksp);
  MatDestroy(&s.shell);
}

void PetscShellSolver::SetRelativeTolerance(double relative) {
  options_.relative_tolerance = relative;
  Check(KSPSetTolerances(impl_->ksp, relative, options_.absolute_tolerance, 1e300, options_.max_iterations),
        "KSPSetTolerances");
}

SolverSummary PetscShellSolver::Solve(const CsrMatrix& a, std::span<const double> b, std::span<double> x) {
  Impl& s = *impl_;
  KELVIN_CHECK(a.rows() >= part_.n_owned && static_cast<int>(x.size()) >= part_.n_owned &&
                   static_cast<int>(b.size()) >= part_.n_owned,
               "a row and a value per owned cell");
  SolverSummary summary;
  summary.initial_residual = NormalizedResidual(a, b, x, &part_);
  s.a = &a;
  s.local.resize(x.size());
  Check(VecPlaceArray(s.b, b.data()), "VecPlaceArray");
  Check(VecPlaceArray(s.x, x.data()), "VecPlaceArray");
  // The operator's values changed behind the shell: mark it changed, or PETSc
  // keeps the Jacobi diagonal of an earlier solve (and a restarted run, whose
  // first solve takes a fresh one, would not repeat the uninterrupted run).
  Check(MatAssemblyBegin(s.shell, MAT_FINAL_ASSEMBLY), "MatAssemblyBegin");
  Check(MatAssemblyEnd(s.shell, MAT_FINAL_ASSEMBLY), "MatAssemblyEnd");
  Check(KSPSetOperators(s.ksp, s.shell, s.shell), "KSPSetOperators");
  const PetscErrorCode solved = KSPSolve(s.ksp, s.b, s.x);
  PetscInt iterations = 0;
  PetscReal residual = 0.0, b_norm = 0.0;
  KSPConvergedReason reason = KSP_CONVERGED_ITERATING;
  KSPGetIterationNumber(s.ksp, &iterations);
  KSPGetResidualNorm(s.ksp, &residual);
  KSPGetConvergedReason(s.ksp, &reason);
  VecNorm(s.b, NORM_2, &b_norm);
  VecResetArray(s.b);
  VecResetArray(s.x);
  Check(solved, "KSPSolve");
  s.a = nullptr;
  // The Krylov work vectors (six for BiCGStab, with the Jacobi diagonal) and
  // the ghosted copy live for one solve, as the serial Eigen solver's do;
  // kept between solves they were about 70 B/cell on every rank that the
  // serial run does not hold. The solver's type and settings stay.
  Check(KSPReset(s.ksp), "KSPReset");
  std::vector<double>().swap(s.local);
  summary.iterations = static_cast<int>(iterations);
  summary.final_relative_residual = b_norm > 0.0 ? residual / b_norm : residual;
  summary.converged = reason > 0 && std::isfinite(summary.final_relative_residual);
  return summary;
}

}  // namespace kelvin::cfd
