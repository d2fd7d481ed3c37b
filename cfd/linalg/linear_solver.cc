#include "cfd/linalg/linear_solver.h"

#include <fmt/format.h>

#include <Eigen/IterativeLinearSolvers>
#include <cmath>

#include "cfd/linalg/hypre_solver.h"
#include "cfd/linalg/petsc_shell_solver.h"
#include "cfd/parallel/domain_part.h"
#include "data/schema/errors.h"

namespace kelvin::cfd {

void AmgOptions::Validate() const {
  if (!(strong_threshold > 0.0 && strong_threshold < 1.0)) {
    throw ConfigError(fmt::format("amg.strong_threshold = {}; expected in (0, 1)", strong_threshold));
  }
  if (aggressive_levels < 0) throw ConfigError("amg.aggressive_levels must be >= 0");
  if (interp_max_elements < 0) throw ConfigError("amg.interp_max_elements must be >= 0");
  if (!(rebuild_growth >= 1.0)) throw ConfigError("amg.rebuild_growth must be >= 1");
}

void LinearSolverOptions::Validate() const {
  if (!(relative_tolerance >= 0.0 && relative_tolerance < 1.0)) {
    throw ConfigError(fmt::format("relative_tolerance = {}; expected in [0, 1)", relative_tolerance));
  }
  if (!(absolute_tolerance >= 0.0)) {
    throw ConfigError(fmt::format("absolute_tolerance = {}; expected >= 0", absolute_tolerance));
  }
  if (max_iterations < 1) throw ConfigError(fmt::format("max_iterations = {}; expected >= 1", max_iterations));
  amg.Validate();
}

double NormalizedResidual(const CsrMatrix& a, std::span<const double> b, std::span<const double> x,
                          const DomainPart* part) {
  const bool parallel = part && part->parallel();
  const int n = parallel ? part->n_owned : static_cast<int>(a.rows());
  if (!parallel && n == 0) return 0.0;
  double xbar = 0.0;
  for (int r = 0; r < n; ++r) xbar += x[r];
  xbar = parallel ? part->Sum(xbar) / static_cast<double>(part->n_global_cells) : xbar / n;
  double res = 0.0, norm = 0.0;
  const int* outer = a.outerIndexPtr();
  const int* inner = a.innerIndexPtr();
  const double* val = a.valuePtr();
  for (int r = 0; r < n; ++r) {
    double ax = 0.0, row_sum = 0.0;
    for (int k = outer[r]; k < outer[r + 1]; ++k) {
      ax += val[k] * x[inner[k]];
      row_sum += val[k];
    }
    res += std::abs(b[r] - ax);
    norm += std::abs(ax - row_sum * xbar) + std::abs(b[r] - row_sum * xbar);
  }
  if (parallel) {
    res = part->Sum(res);
    norm = part->Sum(norm);
  }
  return res / (norm + 1e-20);
}

namespace {

template <typename Solver>
SolverSummary EigenSolve(const LinearSolverOptions& opt, const CsrMatrix& a, std::span<const double> b,
                         std::span<double> x) {
  SolverSummary s;
  s.initial_residual = NormalizedResidual(a, b, x);
  Eigen::Map<const Eigen::VectorXd> bv(b.data(), static_cast<Eigen::Index>(b.size()));
  Eigen::Map<Eigen::VectorXd> xv(x.data(), static_cast<Eigen::Index>(x.size()));
  const double bnorm = bv.norm();
  if (bnorm == 0.0) {
    xv.setZero();
    s.converged = true;
    return s;
  }
  Solver solver;
  solver.setMaxIterations(opt.max_iterations);
  solver.setTolerance(std::max(opt.relative_tolerance, opt.absolute_tolerance / bnorm));
  solver.compute(a);
  const Eigen::VectorXd guess = xv;
  xv = solver.solveWithGuess(bv, guess);
  s.iterations = static_cast<int>(solver.iterations());
  s.final_relative_residual = solver.error();
  s.converged = solver.info() == Eigen::Success;
  return s;
}

class BiCgStabJacobi : public LinearSolver {
 public:
  explicit BiCgStabJacobi(const LinearSolverOptions& o) : opt_(o) {}
  SolverSummary Solve(const CsrMatrix& a, std::span<const double> b, std::span<double> x) override {
    return EigenSolve<Eigen::BiCGSTAB<CsrMatrix, Eigen::DiagonalPreconditioner<double>>>(opt_, a, b, x);
  }
  void SetRelativeTolerance(double relative) override { opt_.relative_tolerance = relative; }

 private:
  LinearSolverOptions opt_;
};

class CgJacobi : public LinearSolver {
 public:
  explicit CgJacobi(const LinearSolverOptions& o) : opt_(o) {}
  SolverSummary Solve(const CsrMatrix& a, std::span<const double> b, std::span<double> x) override {
    return EigenSolve<Eigen::ConjugateGradient<CsrMatrix, Eigen::Lower | Eigen::Upper,
                                               Eigen::DiagonalPreconditioner<double>>>(opt_, a, b, x);
  }
  void SetRelativeTolerance(double relative) override { opt_.relative_tolerance = relative; }

 private:
  LinearSolverOptions opt_;
};

}  // namespace

std::unique_ptr<LinearSolver> LinearSolver::Create(const LinearSolverOptions& options, const DomainPart* part) {
  options.Validate();
  if (part && part->parallel()) {
    if (options.type == LinearSolverOptions::Type::kBiCgStabJacobi ||
        options.type == LinearSolverOptions::Type::kCgJacobi) {
      return std::make_unique<PetscShellSolver>(options, *part);
    }
    return std::make_unique<HypreSolver>(options, part);
  }
  switch (options.type) {
    case LinearSolverOptions::Type::kBiCgStabJacobi:
      return std::make_unique<BiCgStabJacobi>(options);
    case LinearSolverOptions::Type::kCgJacobi:
      return std::make_unique<CgJacobi>(options);
    case LinearSolverOptions::Type::kPcgAmg:
    case LinearSolverOptions::Type::kBiCgStabIlu:
      return std::make_unique<HypreSolver>(options);
  }
  return nullptr;
}

}  // namespace kelvin::cfd
