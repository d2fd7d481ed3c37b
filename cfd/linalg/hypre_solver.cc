#include "cfd/linalg/hypre_solver.h"

#include <HYPRE.h>
#include <HYPRE_krylov.h>
#include <HYPRE_parcsr_ls.h>
#include <mpi.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <vector>

#include "cfd/parallel/domain_part.h"
#include "data/schema/errors.h"

namespace kelvin::cfd {

namespace {
bool g_we_initialized_mpi = false;
void FinalizeMpi() {
  int finalized = 0;
  MPI_Finalized(&finalized);
  if (!finalized && g_we_initialized_mpi) {
    HYPRE_Finalize();
    MPI_Finalize();
  }
}
}  // namespace

void EnsureMpi() {
  int initialized = 0;
  MPI_Initialized(&initialized);
  if (!initialized) {
    MPI_Init(nullptr, nullptr);
    g_we_initialized_mpi = true;
    HYPRE_Init();
    std::atexit(FinalizeMpi);
  }
}

struct HypreSolver::Impl {
  int n = 0;            // rows solved here
  int matrix_rows = 0;  // rows of the matrix given (local cells)
  HYPRE_IJMatrix ij_a = nullptr;
  HYPRE_IJVector ij_b = nullptr;
  HYPRE_IJVector ij_x = nullptr;
  HYPRE_ParCSRMatrix a = nullptr;
  HYPRE_ParVector b = nullptr;
  HYPRE_ParVector x = nullptr;
  HYPRE_Solver krylov = nullptr;   // PCG or BiCGStab
  HYPRE_Solver precond = nullptr;  // BoomerAMG or ILU (null: diagonal scaling)
  std::vector<HYPRE_Int> rows, ncols, row_index;
  bool has_setup = false;
};

namespace {

// Copies the values of `a`'s first `n` rows into the IJ matrix. Serially the
// matrix's own column indices are the global ones. On ranks the columns are
// translated to global rows a block of rows at a time, so no copy of the
// column indices outlives the call (a whole one would be 4 bytes per
// non-zero, about 28 B/cell on hexahedra, that the serial solver does not
// hold).
void SetValues(HYPRE_IJMatrix ij, int n, HYPRE_Int* ncols, const HYPRE_BigInt* rows, const CsrMatrix& a,
               const DomainPart* part) {
  if (!part) {
    HYPRE_IJMatrixSetValues(ij, n, ncols, rows, a.innerIndexPtr(), a.valuePtr());
    return;
  }
  constexpr int kBlockRows = 4096;
  const int* outer = a.outerIndexPtr();
  std::vector<HYPRE_BigInt> columns;
  for (int r0 = 0; r0 < n; r0 += kBlockRows) {
    const int r1 = std::min(n, r0 + kBlockRows);
    columns.resize(outer[r1] - outer[r0]);
    for (int k = outer[r0]; k < outer[r1]; ++k) columns[k - outer[r0]] = part->rows[a.innerIndexPtr()[k]];
    HYPRE_IJMatrixSetValues(ij, r1 - r0, ncols + r0, rows + r0, columns.data(),
                            a.valuePtr() + outer[r0]);
  }
}

}  // namespace

HypreSolver::HypreSolver(const LinearSolverOptions& options, const DomainPart* part)
    : options_(options), part_(part && part->parallel() ? part : nullptr) {
  options_.Validate();
  KELVIN_CHECK(Amg() || options_.type == LinearSolverOptions::Type::kBiCgStabIlu,
               "hypre's solvers here are CG with AMG and BiCGStab with ILU");
  EnsureMpi();
}

HypreSolver::~HypreSolver() { Destroy(); }

void HypreSolver::Destroy() {
  if (!impl_) return;
  if (impl_->krylov) {
    if (Amg()) {
      HYPRE_ParCSRPCGDestroy(impl_->krylov);
    } else {
      HYPRE_ParCSRBiCGSTABDestroy(impl_->krylov);
    }
  }
  if (impl_->precond) {
    if (Amg()) {
      HYPRE_BoomerAMGDestroy(impl_->precond);
    } else {
      HYPRE_ILUDestroy(impl_->precond);
    }
  }
  if (impl_->ij_a) HYPRE_IJMatrixDestroy(impl_->ij_a);
  if (impl_->ij_b) HYPRE_IJVectorDestroy(impl_->ij_b);
  if (impl_->ij_x) HYPRE_IJVectorDestroy(impl_->ij_x);
  impl_.reset();
}

void HypreSolver::Create(const CsrMatrix& a) {
  Destroy();
  impl_ = std::make_unique<Impl>();
  CreateMatrix(a);
  CreatePreconditioner();
  CreateKrylov();
  need_setup_ = true;
}

void HypreSolver::CreateMatrix(const CsrMatrix& a) {
  Impl& s = *impl_;
  const MPI_Comm comm = part_ ? part_->comm : MPI_COMM_SELF;  // serial solves are each process's own
  s.matrix_rows = static_cast<int>(a.rows());
  s.n = part_ ? part_->n_owned : static_cast<int>(a.rows());
  const HYPRE_Int lo = part_ ? part_->first_row : 0;
  const HYPRE_Int hi = lo + s.n - 1;
  s.rows.resize(s.n);
  s.ncols.resize(s.n);
  s.row_index.resize(s.n);
  std::vector<HYPRE_Int> diag(s.n, 0), offd(s.n, 0);
  const int* outer = a.outerIndexPtr();
  for (int r = 0; r < s.n; ++r) {
    s.rows[r] = lo + r;
    s.ncols[r] = outer[r + 1] - outer[r];
    s.row_index[r] = lo + r;
    diag[r] = s.ncols[r];
  }
  if (part_) {
    // Owned columns go to the diagonal block, ghost columns off it.
    for (int r = 0; r < s.n; ++r) {
      diag[r] = 0;
      for (int k = outer[r]; k < outer[r + 1]; ++k) (a.innerIndexPtr()[k] < part_->n_owned ? diag[r] : offd[r])++;
    }
  }
  // Sparsity, set once.
  HYPRE_IJMatrixCreate(comm, lo, hi, lo, hi, &s.ij_a);
  HYPRE_IJMatrixSetObjectType(s.ij_a, HYPRE_PARCSR);
  HYPRE_IJMatrixSetDiagOffdSizes(s.ij_a, diag.data(), offd.data());
  HYPRE_IJMatrixInitialize(s.ij_a);
  SetValues(s.ij_a, s.n, s.ncols.data(), s.rows.data(), a, part_);
  HYPRE_IJMatrixAssemble(s.ij_a);
  void* obj = nullptr;
  HYPRE_IJMatrixGetObject(s.ij_a, &obj);
  s.a = static_cast<HYPRE_ParCSRMatrix>(obj);
  for (HYPRE_IJVector* v : {&s.ij_b, &s.ij_x}) {
    HYPRE_IJVectorCreate(comm, lo, hi, v);
    HYPRE_IJVectorSetObjectType(*v, HYPRE_PARCSR);
    HYPRE_IJVectorInitialize(*v);
    HYPRE_IJVectorAssemble(*v);
  }
  HYPRE_IJVectorGetObject(s.ij_b, &obj);
  s.b = static_cast<HYPRE_ParVector>(obj);
  HYPRE_IJVectorGetObject(s.ij_x, &obj);
  s.x = static_cast<HYPRE_ParVector>(obj);
}

void HypreSolver::CreatePreconditioner() {
  Impl& s = *impl_;
  if (Amg()) {
    const AmgOptions& amg = options_.amg;
    HYPRE_BoomerAMGCreate(&s.precond);
    HYPRE_BoomerAMGSetCoarsenType(s.precond, 10);  // HMIS
    HYPRE_BoomerAMGSetInterpType(s.precond, 6);    // extended+i
    HYPRE_BoomerAMGSetPMaxElmts(s.precond, amg.interp_max_elements);
    HYPRE_BoomerAMGSetAggNumLevels(s.precond, amg.aggressive_levels);
    HYPRE_BoomerAMGSetAggInterpType(s.precond, 4);  // multipass on aggressive levels
    HYPRE_BoomerAMGSetStrongThreshold(s.precond, amg.strong_threshold);
    HYPRE_BoomerAMGSetCycleRelaxType(s.precond, 13, 1);  // l1-Gauss-Seidel forward, down
    HYPRE_BoomerAMGSetCycleRelaxType(s.precond, 14, 2);  // l1-Gauss-Seidel backward, up
    HYPRE_BoomerAMGSetCycleRelaxType(s.precond, 9, 3);   // Gaussian elimination, coarsest
    HYPRE_BoomerAMGSetNumSweeps(s.precond, 1);
    HYPRE_BoomerAMGSetMaxIter(s.precond, 1);
    HYPRE_BoomerAMGSetTol(s.precond, 0.0);
    HYPRE_BoomerAMGSetPrintLevel(s.precond, 0);
  } else if (options_.type == LinearSolverOptions::Type::kBiCgStabIlu) {
    HYPRE_ILUCreate(&s.precond);
    HYPRE_ILUSetType(s.precond, 0);             // block Jacobi ILU(k): one block per rank
    HYPRE_ILUSetLevelOfFill(s.precond, 0);      // ILU(0): the matrix's own sparsity
    HYPRE_ILUSetLocalReordering(s.precond, 0);  // cell order of the mesh (no RCM pass per setup)
    HYPRE_ILUSetMaxIter(s.precond, 1);
    HYPRE_ILUSetTol(s.precond, 0.0);
    HYPRE_ILUSetPrintLevel(s.precond, 0);
  }
}

void HypreSolver::CreateKrylov() {
  Impl& s = *impl_;
  const MPI_Comm comm = part_ ? part_->comm : MPI_COMM_SELF;  // serial solves are each process's own
  if (Amg()) {
    HYPRE_ParCSRPCGCreate(comm, &s.krylov);
    HYPRE_PCGSetMaxIter(s.krylov, options_.max_iterations);
    HYPRE_PCGSetTol(s.krylov, options_.relative_tolerance);
    HYPRE_PCGSetAbsoluteTol(s.krylov, options_.absolute_tolerance);
    HYPRE_PCGSetTwoNorm(s.krylov, 1);
    HYPRE_PCGSetPrintLevel(s.krylov, 0);
    HYPRE_PCGSetLogging(s.krylov, 1);
    HYPRE_ParCSRPCGSetPrecond(s.krylov, HYPRE_BoomerAMGSolve, HYPRE_BoomerAMGSetup, s.precond);
    return;
  }
  HYPRE_ParCSRBiCGSTABCreate(comm, &s.krylov);
  HYPRE_ParCSRBiCGSTABSetMaxIter(s.krylov, options_.max_iterations);
  HYPRE_ParCSRBiCGSTABSetTol(s.krylov, options_.relative_tolerance);
  HYPRE_ParCSRBiCGSTABSetAbsoluteTol(s.krylov, options_.absolute_tolerance);
  HYPRE_ParCSRBiCGSTABSetPrintLevel(s.krylov, 0);
  HYPRE_ParCSRBiCGSTABSetLogging(s.krylov, 1);
  HYPRE_ParCSRBiCGSTABSetPrecond(s.krylov, HYPRE_ILUSolve, HYPRE_ILUSetup, s.precond);
}

void HypreSolver::SetRelativeTolerance(double relative) {
  options_.relative_tolerance = relative;
  if (!impl_) return;
  if (Amg()) {
    HYPRE_PCGSetTol(impl_->krylov, relative);
  } else {
    HYPRE_ParCSRBiCGSTABSetTol(impl_->krylov, relative);
  }
}

SolverSummary HypreSolver::Solve(const CsrMatrix& a, std::span<const double> b, std::span<double> x) {
  SolverSummary summary;
  if (!impl_ || impl_->matrix_rows != a.rows()) Create(a);
  Impl& s = *impl_;
  summary.initial_residual = NormalizedResidual(a, b, x, part_);
  // Values refilled in place in the existing ParCSR matrix.
  SetValues(s.ij_a, s.n, s.ncols.data(), s.rows.data(), a, part_);
  HYPRE_IJMatrixAssemble(s.ij_a);
  HYPRE_IJVectorSetValues(s.ij_b, s.n, s.row_index.data(), b.data());
  HYPRE_IJVectorSetValues(s.ij_x, s.n, s.row_index.data(), x.data());
  // ILU: a new factorization for the new values.
  if (options_.type == LinearSolverOptions::Type::kBiCgStabIlu) need_setup_ = true;
  if (need_setup_ || !s.has_setup) {
    if (Amg()) {
      HYPRE_ParCSRPCGSetup(s.krylov, s.a, s.b, s.x);
    } else {
      HYPRE_ParCSRBiCGSTABSetup(s.krylov, s.a, s.b, s.x);
    }
    s.has_setup = true;
    need_setup_ = false;
    summary.setup = true;
    ++setups_;
  }
  HYPRE_Int iterations = 0;
  HYPRE_Real rel = 0.0;
  if (Amg()) {
    HYPRE_ParCSRPCGSolve(s.krylov, s.a, s.b, s.x);
    HYPRE_PCGGetNumIterations(s.krylov, &iterations);
    HYPRE_PCGGetFinalRelativeResidualNorm(s.krylov, &rel);
  } else {
    HYPRE_ParCSRBiCGSTABSolve(s.krylov, s.a, s.b, s.x);
    HYPRE_ParCSRBiCGSTABGetNumIterations(s.krylov, &iterations);
    HYPRE_ParCSRBiCGSTABGetFinalRelativeResidualNorm(s.krylov, &rel);
  }
  HYPRE_IJVectorGetValues(s.ij_x, s.n, s.row_index.data(), x.data());
  HYPRE_ClearAllErrors();
  summary.iterations = iterations;
  summary.final_relative_residual = rel;
  summary.converged = iterations < options_.max_iterations && std::isfinite(rel);
  if (!Amg()) return summary;
  // Growth test against the count of the first solve with the same
  // tolerance since the last setup (intermediate and final correctors use
  // different tolerances, so their counts are not comparable).
  if (summary.setup) reference_iterations_.clear();
  const auto it = reference_iterations_.find(options_.relative_tolerance);
  if (it == reference_iterations_.end()) {
    reference_iterations_[options_.relative_tolerance] = std::max(1, static_cast<int>(iterations));
  } else if (iterations > options_.amg.rebuild_growth * it->second) {
    need_setup_ = true;
  }
  return summary;
}

}  // namespace kelvin::cfd
