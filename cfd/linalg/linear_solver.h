// Linear solvers for the cell systems. Created from Options; each solve
// reports a Summary. The pressure solver is CG preconditioned by hypre
// BoomerAMG (see hypre_solver.h); momentum and scalars use BiCGStab with
// a Jacobi preconditioner (Eigen); the k and omega equations of SST use
// hypre's BiCGStab with an ILU(0) preconditioner.
// On a decomposed mesh (a parallel DomainPart) the solvers run on the global
// rows of the owned cells: BiCGStab and CG with Jacobi are PETSc's on a shell
// matrix over the solver's own CsrMatrix (petsc_shell_solver.h), in place of
// Eigen's; AMG and ILU stay hypre's.
#pragma once

#include <memory>
#include <span>
#include <string>

#include "cfd/linalg/sparse_system.h"

namespace kelvin::cfd {

struct DomainPart;

struct AmgOptions {
  // Strength threshold: 0.25 for uniform meshes, 0.5 for wall-graded ones.
  double strong_threshold = 0.25;
  int aggressive_levels = 1;       // aggressive coarsening on the first level(s)
  int interp_max_elements = 4;     // Pmax of ext+i interpolation
  // Rebuild the hierarchy when the iteration count exceeds the count right
  // after the last setup by this factor (the solver also rebuilds at the
  // first solve of every time step; see LinearSolver::RequestSetup()).
  double rebuild_growth = 1.2;
  // Also rebuild at the first pressure solve of every time step (needed for
  // bit-identical restarts; false keeps a hierarchy across steps until the
  // iteration count grows).
  bool rebuild_each_step = true;
  void Validate() const;
};

struct LinearSolverOptions {
  enum class Type { kBiCgStabJacobi, kCgJacobi, kPcgAmg, kBiCgStabIlu };
  Type type = Type::kBiCgStabJacobi;
  double relative_tolerance = 1e-6;   // ||r||_2 / ||b||_2
  double absolute_tolerance = 1e-14;  // ||r||_2
  int max_iterations = 1000;
  AmgOptions amg;
  void Validate() const;
};

struct SolverSummary {
  int iterations = 0;
  // OpenFOAM-normalized residual before the solve (for residual control).
  double initial_residual = 0.0;
  double final_relative_residual = 0.0;  // ||r||_2 / ||b||_2 after the solve
  bool converged = false;
  bool setup = false;  // an AMG hierarchy was (re)built
};

class LinearSolver {
 public:
  virtual ~LinearSolver() = default;
  // Solves A x = b with x as the initial guess.
  virtual SolverSummary Solve(const CsrMatrix& a, std::span<const double> b, std::span<double> x) = 0;
  // Asks for a fresh preconditioner at the next solve (AMG only).
  virtual void RequestSetup() {}
  // Changes the relative tolerance of the next solves.
  virtual void SetRelativeTolerance(double relative) = 0;
  // `part` (null: serial) must outlive the solver. On a parallel part the
  // matrix has a row per local cell; the rows of the owned cells are
  // solved, and x's ghost entries must be current (they are read, not set).
  static std::unique_ptr<LinearSolver> Create(const LinearSolverOptions& options, const DomainPart* part = nullptr);
};

// sum|b - Ax| / (sum|Ax - A xbar| + |b - A xbar|), OpenFOAM's normalization;
// on a parallel part the sums run over the owned rows of every rank.
double NormalizedResidual(const CsrMatrix& a, std::span<const double> b, std::span<const double> x,
                          const DomainPart* part = nullptr);

}  // namespace kelvin::cfd
