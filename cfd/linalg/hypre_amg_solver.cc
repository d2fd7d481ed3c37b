#include "cfd/linalg/hypre_amg_solver.h"

#include <HYPRE.h>
#include <HYPRE_krylov.h>
#include <HYPRE_parcsr_ls.h>
#include <mpi.h>

#include <cmath>
#include <cstdlib>
#include <vector>

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

struct HypreAmgSolver::Impl {
  int n = 0;
  HYPRE_IJMatrix ij_a = nullptr;
  HYPRE_IJVector ij_b = nullptr;
  HYPRE_IJVector ij_x = nullptr;
  HYPRE_ParCSRMatrix a = nullptr;
  HYPRE_ParVector b = nullptr;
  HYPRE_ParVector x = nullptr;
  HYPRE_Solver pcg = nullptr;
  HYPRE_Solver amg = nullptr;
  std::vector<HYPRE_Int> rows, ncols, row_index;
  bool has_setup = false;
};

HypreAmgSolver::HypreAmgSolver(const LinearSolverOptions& options) : options_(options) {
  options_.Validate();
  EnsureMpi();
}

HypreAmgSolver::~HypreAmgSolver() { Destroy(); }

void HypreAmgSolver::Destroy() {
  if (!impl_) return;
  if (impl_->pcg) HYPRE_ParCSRPCGDestroy(impl_->pcg);
  if (impl_->amg) HYPRE_BoomerAMGDestroy(impl_->amg);
  if (impl_->ij_a) HYPRE_IJMatrixDestroy(impl_->ij_a);
  if (impl_->ij_b) HYPRE_IJVectorDestroy(impl_->ij_b);
  if (impl_->ij_x) HYPRE_IJVectorDestroy(impl_->ij_x);
  impl_.reset();
}

void HypreAmgSolver::Create(const CsrMatrix& a) {
  Destroy();
  impl_ = std::make_unique<Impl>();
  Impl& s = *impl_;
  s.n = static_cast<int>(a.rows());
  const HYPRE_Int lo = 0;
  const HYPRE_Int hi = s.n - 1;
  s.rows.resize(s.n);
  s.ncols.resize(s.n);
  s.row_index.resize(s.n);
  for (int r = 0; r < s.n; ++r) {
    s.rows[r] = r;
    s.ncols[r] = a.outerIndexPtr()[r + 1] - a.outerIndexPtr()[r];
    s.row_index[r] = r;
  }
  // Sparsity, set once.
  HYPRE_IJMatrixCreate(MPI_COMM_WORLD, lo, hi, lo, hi, &s.ij_a);
  HYPRE_IJMatrixSetObjectType(s.ij_a, HYPRE_PARCSR);
  std::vector<HYPRE_Int> offd(s.n, 0);
  HYPRE_IJMatrixSetDiagOffdSizes(s.ij_a, s.ncols.data(), offd.data());
  HYPRE_IJMatrixInitialize(s.ij_a);
  HYPRE_IJMatrixSetValues(s.ij_a, s.n, s.ncols.data(), s.rows.data(), a.innerIndexPtr(), a.valuePtr());
  HYPRE_IJMatrixAssemble(s.ij_a);
  void* obj = nullptr;
  HYPRE_IJMatrixGetObject(s.ij_a, &obj);
  s.a = static_cast<HYPRE_ParCSRMatrix>(obj);
  for (HYPRE_IJVector* v : {&s.ij_b, &s.ij_x}) {
    HYPRE_IJVectorCreate(MPI_COMM_WORLD, lo, hi, v);
    HYPRE_IJVectorSetObjectType(*v, HYPRE_PARCSR);
    HYPRE_IJVectorInitialize(*v);
    HYPRE_IJVectorAssemble(*v);
  }
  HYPRE_IJVectorGetObject(s.ij_b, &obj);
  s.b = static_cast<HYPRE_ParVector>(obj);
  HYPRE_IJVectorGetObject(s.ij_x, &obj);
  s.x = static_cast<HYPRE_ParVector>(obj);

  const AmgOptions& amg = options_.amg;
  HYPRE_BoomerAMGCreate(&s.amg);
  HYPRE_BoomerAMGSetCoarsenType(s.amg, 10);  // HMIS
  HYPRE_BoomerAMGSetInterpType(s.amg, 6);    // extended+i
  HYPRE_BoomerAMGSetPMaxElmts(s.amg, amg.interp_max_elements);
  HYPRE_BoomerAMGSetAggNumLevels(s.amg, amg.aggressive_levels);
  HYPRE_BoomerAMGSetAggInterpType(s.amg, 4);  // multipass on aggressive levels
  HYPRE_BoomerAMGSetStrongThreshold(s.amg, amg.strong_threshold);
  HYPRE_BoomerAMGSetCycleRelaxType(s.amg, 13, 1);  // l1-Gauss-Seidel forward, down
  HYPRE_BoomerAMGSetCycleRelaxType(s.amg, 14, 2);  // l1-Gauss-Seidel backward, up
  HYPRE_BoomerAMGSetCycleRelaxType(s.amg, 9, 3);   // Gaussian elimination, coarsest
  HYPRE_BoomerAMGSetNumSweeps(s.amg, 1);
  HYPRE_BoomerAMGSetMaxIter(s.amg, 1);
  HYPRE_BoomerAMGSetTol(s.amg, 0.0);
  HYPRE_BoomerAMGSetPrintLevel(s.amg, 0);

  HYPRE_ParCSRPCGCreate(MPI_COMM_WORLD, &s.pcg);
  HYPRE_PCGSetMaxIter(s.pcg, options_.max_iterations);
  HYPRE_PCGSetTol(s.pcg, options_.relative_tolerance);
  HYPRE_PCGSetAbsoluteTol(s.pcg, options_.absolute_tolerance);
  HYPRE_PCGSetTwoNorm(s.pcg, 1);
  HYPRE_PCGSetPrintLevel(s.pcg, 0);
  HYPRE_PCGSetLogging(s.pcg, 1);
  HYPRE_ParCSRPCGSetPrecond(s.pcg, HYPRE_BoomerAMGSolve, HYPRE_BoomerAMGSetup, s.amg);
  need_setup_ = true;
}

void HypreAmgSolver::SetRelativeTolerance(double relative) {
  options_.relative_tolerance = relative;
  if (impl_) HYPRE_PCGSetTol(impl_->pcg, relative);
}

SolverSummary HypreAmgSolver::Solve(const CsrMatrix& a, std::span<const double> b, std::span<double> x) {
  SolverSummary summary;
  if (!impl_ || impl_->n != a.rows()) Create(a);
  Impl& s = *impl_;
  summary.initial_residual = NormalizedResidual(a, b, x);
  // Values refilled in place in the existing ParCSR matrix.
  HYPRE_IJMatrixSetValues(s.ij_a, s.n, s.ncols.data(), s.rows.data(), a.innerIndexPtr(), a.valuePtr());
  HYPRE_IJMatrixAssemble(s.ij_a);
  HYPRE_IJVectorSetValues(s.ij_b, s.n, s.row_index.data(), b.data());
  HYPRE_IJVectorSetValues(s.ij_x, s.n, s.row_index.data(), x.data());
  if (need_setup_ || !s.has_setup) {
    HYPRE_ParCSRPCGSetup(s.pcg, s.a, s.b, s.x);
    s.has_setup = true;
    need_setup_ = false;
    summary.setup = true;
    ++setups_;
  }
  HYPRE_ParCSRPCGSolve(s.pcg, s.a, s.b, s.x);
  HYPRE_Int iterations = 0;
  HYPRE_Real rel = 0.0;
  HYPRE_PCGGetNumIterations(s.pcg, &iterations);
  HYPRE_PCGGetFinalRelativeResidualNorm(s.pcg, &rel);
  HYPRE_IJVectorGetValues(s.ij_x, s.n, s.row_index.data(), x.data());
  HYPRE_ClearAllErrors();
  summary.iterations = iterations;
  summary.final_relative_residual = rel;
  summary.converged = iterations < options_.max_iterations && std::isfinite(rel);
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
