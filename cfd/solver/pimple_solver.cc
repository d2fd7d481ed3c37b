#include "cfd/solver/pimple_solver.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "cfd/fv/diffusion_curvature.h"
#include "data/schema/errors.h"

namespace kelvin::cfd {
namespace {

NonOrthogonalForm NonOrthForm(const SchemeOptions& schemes) {
  return schemes.face_centre_correction ? NonOrthogonalForm::kFaceCentre : NonOrthogonalForm::kInterpolated;
}

}  // namespace

void PhysicsOptions::Validate() const {
  if (!(nu > 0.0) || !std::isfinite(nu)) throw ConfigError(fmt::format("physics.nu = {}; expected > 0 m^2/s", nu));
}

void PimpleOptions::Validate() const {
  if (n_outer < 1) throw ConfigError(fmt::format("solution.n_outer = {}; expected >= 1", n_outer));
  if (n_correctors < 1) throw ConfigError(fmt::format("solution.n_correctors = {}; expected >= 1", n_correctors));
  if (n_non_orthogonal < 0) {
    throw ConfigError(fmt::format("solution.n_non_orthogonal = {}; expected >= 0", n_non_orthogonal));
  }
  for (double a : {relax_U, relax_p, relax_U_final, relax_p_final}) {
    if (!(a > 0.0 && a <= 1.0)) throw ConfigError(fmt::format("relaxation factor {}; expected in (0, 1]", a));
  }
  momentum_solver.Validate();
  pressure_solver.Validate();
  if (!(pressure_final_relative_tolerance >= 0.0 && pressure_final_relative_tolerance < 1.0)) {
    throw ConfigError("solution.pressure.final_relative_tolerance must be in [0, 1)");
  }
}

PimpleSolver::PimpleSolver(const Mesh& mesh, PhysicsOptions physics, SchemeOptions schemes, PimpleOptions pimple,
                           std::unique_ptr<VectorField> U, std::unique_ptr<ScalarField> p,
                           std::shared_ptr<const DomainPart> part)
    : mesh_(mesh),
      part_(std::move(part)),
      physics_(std::move(physics)),
      schemes_(schemes),
      pimple_(pimple),
      U_(std::move(U)),
      p_(std::move(p)),
      phi_(mesh.n_faces(), 0.0),
      mesh_flux_(mesh.n_faces(), 0.0),
      grad_(mesh, schemes.gradient),
      non_orth_(mesh, NonOrthForm(schemes)),
      UEqn_(mesh),
      pEqn_(mesh),
      system_(mesh) {
  physics_.Validate();
  schemes_.Validate();
  pimple_.Validate();
  const long long n_cells = Parallel() ? part_->n_global_cells : mesh.n_cells();
  if (pimple_.p_ref_cell < 0 || pimple_.p_ref_cell >= n_cells) {
    throw ConfigError(fmt::format("solution.p_ref_cell = {}; expected a cell index in [0, {})", pimple_.p_ref_cell,
                                  n_cells));
  }
  for (const Patch& patch : mesh.patches()) {
    if (patch.kind != PatchKind::kEmpty) continue;
    for (int f = patch.start; f < patch.start + patch.size; ++f) {
      const Vector3 n = mesh.face_areas()[f] / mesh.face_area_magnitudes()[f];
      for (int k = 0; k < 3; ++k) {
        if (std::abs(n[k]) > 0.99) solve_component_[k] = false;
      }
    }
  }
  // A rank with no face of the empty patches agrees with those that have one.
  if (Parallel()) {
    for (bool& solve : solve_component_) solve = part_->All(solve);
  }
  // The corrections vanish identically on orthogonal meshes: skip their work.
  non_orth_correction_ = schemes_.non_orthogonal_correction && non_orth_.any_correction;
  if (schemes_.skew_correction) skew_ = mesh.SkewVectors();
  if (schemes_.curvature_correction) {
    if (!schemes_.skew_correction) {
      throw ConfigError("schemes.curvature_correction: expected skew_correction true as well (the Rhie-Chow flux "
                        "through kinked faces takes the skew-corrected gradient)");
    }
    UpdateCurvatureGeometry();
    // Least squares, exact for linear fields on any cells (Gauss is not on
    // split faces, and its Hessians were O(1) wrong there).
    GradientOptions least_squares;
    least_squares.scheme = GradientScheme::kLeastSquares;
    hessian_gradient_ = std::make_unique<Gradient>(mesh, least_squares);
  }
  momentum_solver_ = LinearSolver::Create(pimple_.momentum_solver, part_.get());
  pressure_solver_ = LinearSolver::Create(pimple_.pressure_solver, part_.get());
}

int PimpleSolver::ReferenceCell() const {
  return Parallel() ? part_->OwnedCell(pimple_.p_ref_cell) : pimple_.p_ref_cell;
}

void PimpleSolver::SetMeshFlux(std::vector<double> mesh_flux) {
  KELVIN_CHECK(static_cast<int>(mesh_flux.size()) == mesh_.n_faces(), "mesh flux on every face");
  mesh_flux_ = std::move(mesh_flux);
}

void PimpleSolver::SetCellSource(std::vector<Vector3> source) {
  KELVIN_CHECK(source.empty() || static_cast<int>(source.size()) == mesh_.n_cells(), "a cell source on every cell");
  cell_source_ = std::move(source);
}

void PimpleSolver::SetTurbulence(std::unique_ptr<TurbulenceModel> model) {
  if (model && Parallel() && model->part() != part_.get()) {
    throw ConfigError(fmt::format("turbulence: the {} model was not built on this rank's part of the mesh; expected "
                                  "the DomainPart the solver runs on",
                                  model->name()));
  }
  turbulence_ = std::move(model);
  if (initialized_ && turbulence_) turbulence_->Initialize(*U_, RelativeFlux());
}

void PimpleSolver::RefreshGeometry() {
  grad_.UpdateGeometry();
  if (turbulence_) turbulence_->RefreshGeometry();
  non_orth_ = NonOrthGeometry(mesh_, NonOrthForm(schemes_));
  non_orth_correction_ = schemes_.non_orthogonal_correction && non_orth_.any_correction;
  if (schemes_.skew_correction) skew_ = mesh_.SkewVectors();
  if (schemes_.curvature_correction) {
    UpdateCurvatureGeometry();
    hessian_gradient_->UpdateGeometry();
  }
}

void PimpleSolver::UpdateCurvatureGeometry() {
  moments_ = FaceFirstMoments(mesh_);
  curvature_ = DiffusionCurvatureTensors(mesh_, non_orth_, moments_);
}

void PimpleSolver::MoveMesh(bool carry_old_fluxes) {
  if (!mesh_motion_) return;
  const auto sf = mesh_.face_areas();
  std::vector<Vector3> sf_before;
  if (carry_old_fluxes) sf_before.assign(sf.begin(), sf.end());
  mesh_motion_(time_, mesh_flux_);
  KELVIN_CHECK(static_cast<int>(mesh_flux_.size()) == mesh_.n_faces(), "mesh flux on every face");
  RefreshGeometry();
  if (!carry_old_fluxes) return;
  // The old fluxes crossed the faces in their old orientation. The transient
  // Rhie-Chow term needs phi_old - U_old_f . S_f with the present S_f, so the
  // old fluxes follow the face rotation with the interpolated old velocity
  // (zero change for pure translation).
  const auto w = mesh_.weights();
  const std::size_t levels = std::min(static_cast<std::size_t>(U_->n_old()), phi_old_.size());
  for (std::size_t l = 0; l < levels; ++l) {
    const std::vector<Vector3>& u_old = U_->old(static_cast<int>(l));
    for (int f = 0; f < mesh_.n_internal_faces(); ++f) {
      const Vector3 dS = sf[f] - sf_before[f];
      const int P = mesh_.owner()[f], N = mesh_.neighbour()[f];
      phi_old_[l][f] += (w[f] * u_old[P] + (1.0 - w[f]) * u_old[N]).dot(dS);
    }
    SyncCrossFaces(part_.get(), phi_old_[l]);
  }
}

std::span<const double> PimpleSolver::RelativeFlux() {
  flux_rel_.resize(phi_.size());
  for (std::size_t f = 0; f < phi_.size(); ++f) flux_rel_[f] = phi_[f] - mesh_flux_[f];
  return flux_rel_;
}

void PimpleSolver::Initialize() {
  MoveMesh(false);
  Sync(U_->values());
  Sync(p_->values());
  // Flux from the initial velocity (boundary values from the conditions).
  U_->CorrectBoundary(time_, {});
  const int ni = mesh_.n_internal_faces();
  const auto w = mesh_.weights();
  const auto sf = mesh_.face_areas();
  for (int f = 0; f < ni; ++f) {
    phi_[f] = (w[f] * (*U_)[mesh_.owner()[f]] + (1.0 - w[f]) * (*U_)[mesh_.neighbour()[f]]).dot(sf[f]);
  }
  for (int f = ni; f < mesh_.n_faces(); ++f) phi_[f] = U_->boundary()[f - ni].dot(sf[f]);
  SyncCrossFaces(part_.get(), phi_);
  U_->CorrectBoundary(time_, RelativeFlux());
  p_->CorrectBoundary(time_, RelativeFlux());
  if (turbulence_) turbulence_->Initialize(*U_, RelativeFlux());
  initialized_ = true;
}

void PimpleSolver::AssembleMomentum(double dt, std::span<const double> flux_rel) {
  UEqn_.Reset();
  AddDdt(UEqn_, *U_, dt, schemes_.time);
  grad_.Compute(std::span<const Vector3>(U_->values()), std::span<const Vector3>(U_->boundary()), grad_U_);
  Sync(grad_U_);
  AddConvection(UEqn_, *U_, flux_rel, schemes_.convection, grad_U_);
  // div(dev(R_eff)): the turbulence model's, or the laminar one.
  if (turbulence_) {
    turbulence_->AddDivDevReff(UEqn_, *U_, grad_U_, non_orth_, non_orth_correction_);
  } else {
    AddLaminarDivDevReff(UEqn_, *U_, physics_.nu, grad_U_, non_orth_, non_orth_correction_);
  }
  if (schemes_.curvature_correction) {
    std::array<std::vector<Matrix3>, 3> hessians = ComponentHessians(*hessian_gradient_, grad_U_);
    for (auto& h : hessians) Sync(h);
    if (turbulence_) {
      AddDiffusionCurvature(UEqn_, turbulence_->nu_eff_faces(), curvature_, hessians);
    } else {
      AddDiffusionCurvature(UEqn_, physics_.nu, curvature_, hessians);
    }
  }
  if (physics_.source) {
    source_.resize(mesh_.n_cells());
    for (int c = 0; c < mesh_.n_cells(); ++c) source_[c] = physics_.source(mesh_.cell_centres()[c], time_);
    AddSource(UEqn_, std::span<const Vector3>(source_));
  }
  if (!cell_source_.empty()) AddSource(UEqn_, std::span<const Vector3>(cell_source_));
}

double PimpleSolver::SolveMomentum(const std::vector<Vector3>& grad_p, StepSummary& summary) {
  std::vector<double> diag_k, source_k, x(mesh_.n_cells());
  const auto vol = mesh_.cell_volumes();
  double worst = 0.0;
  bool filled_off_diagonal = false;
  for (int k = 0; k < 3; ++k) {
    if (!solve_component_[k]) {
      for (int c = 0; c < mesh_.n_cells(); ++c) (*U_)[c][k] = 0.0;
      continue;
    }
    UEqn_.ComponentSystem(k, diag_k, source_k);
    for (int c = 0; c < mesh_.n_cells(); ++c) {
      source_k[c] -= grad_p[c][k] * vol[c];
      x[c] = (*U_)[c][k];
    }
    if (!filled_off_diagonal) {
      system_.Fill(diag_k, UEqn_.upper, UEqn_.lower);
      filled_off_diagonal = true;
    } else {
      system_.FillDiagonal(diag_k);
    }
    const SolverSummary s = momentum_solver_->Solve(system_.matrix(), source_k, x);
    summary.momentum_iterations += s.iterations;
    worst = std::max(worst, s.initial_residual);
    if (!std::isfinite(s.initial_residual)) worst = s.initial_residual;
    for (int c = 0; c < mesh_.n_cells(); ++c) (*U_)[c][k] = x[c];
  }
  Sync(U_->values());
  return worst;
}

void PimpleSolver::PressureCorrector(double dt, bool final_corrector, double alpha_U, double alpha_p,
                                     const std::vector<Vector3>& U_prev, const std::vector<double>& phi_prev,
                                     StepSummary& summary, bool first_pressure_solve) {
  const int nc = mesh_.n_cells();

  // rAU = 1/A, HbyA = H/A.
  const std::vector<double> A = UEqn_.A();
  std::vector<double> rAU(nc);
  for (int c = 0; c < nc; ++c) rAU[c] = 1.0 / A[c];
  std::vector<Vector3> HbyA = UEqn_.H(std::span<const Vector3>(U_->values()));
  for (int c = 0; c < nc; ++c) HbyA[c] *= rAU[c];
  // The ghost rows of A and H lack the faces beyond the halo.
  Sync(rAU);
  Sync(HbyA);

  const bool backward = schemes_.time == TimeScheme::kBackward && U_->n_old() >= 2 && phi_old_.size() >= 2;
  std::vector<double> rAUf, phi_HbyA;
  FluxHbyA(dt, backward, alpha_U, U_prev, phi_prev, rAU, HbyA, rAUf, phi_HbyA);

  // Conditions with their own unknowns (the free surface) turn the predicted
  // boundary flux into implicit pressure coefficients; the context carries
  // the last corrector's flux relative to the mesh.
  const PressureCoupling coupling{dt, backward, rAUf, phi_HbyA};
  const std::span<const double> flux_rel = RelativeFlux();
  for (int p = 0; p < p_->n_patches(); ++p) {
    p_->bc(p).PreparePressureSolve(BcContext{mesh_, mesh_.patches()[p], time_, flux_rel}, coupling);
  }

  std::vector<double> p_before(p_->values());
  SolvePressure(rAUf, phi_HbyA, final_corrector, first_pressure_solve, summary);
  // Pressure relaxation for the momentum correction (the flux keeps the
  // unrelaxed pressure, as in OpenFOAM).
  if (alpha_p < 1.0) {
    for (int c = 0; c < nc; ++c) (*p_)[c] = p_before[c] + alpha_p * ((*p_)[c] - p_before[c]);
    p_->CorrectBoundary(time_, RelativeFlux());
  }
  // Let boundary conditions with their own unknowns see the corrected flux.
  for (int p = 0; p < p_->n_patches(); ++p) {
    BcContext ctx{mesh_, mesh_.patches()[p], time_, phi_};
    p_->bc(p).CorrectAfterFlux(ctx, phi_);
  }
  grad_.Compute(std::span<const double>(p_->values()), std::span<const double>(p_->boundary()), grad_p_);
  Sync(grad_p_);
  for (int c = 0; c < nc; ++c) {
    (*U_)[c] = HbyA[c] - rAU[c] * grad_p_[c];
    for (int k = 0; k < 3; ++k) {
      if (!solve_component_[k]) (*U_)[c][k] = 0.0;
    }
  }
  U_->CorrectBoundary(time_, RelativeFlux());
}

void PimpleSolver::FluxHbyA(double dt, bool backward, double alpha_U, const std::vector<Vector3>& U_prev,
                            const std::vector<double>& phi_prev, const std::vector<double>& rAU,
                            const std::vector<Vector3>& HbyA, std::vector<double>& rAUf,
                            std::vector<double>& phi_HbyA) {
  const int ni = mesh_.n_internal_faces();
  const int nf = mesh_.n_faces();
  const auto owner = mesh_.owner();
  const auto neighbour = mesh_.neighbour();
  const auto w = mesh_.weights();
  const auto sf = mesh_.face_areas();
  phi_HbyA.resize(nf);
  rAUf.resize(nf);
  std::vector<Vector3> HbyA_boundary(nf - ni);
  const auto mag = mesh_.face_area_magnitudes();
  for (int p = 0; p < U_->n_patches(); ++p) {
    const Patch& patch = mesh_.patches()[p];
    const auto& bc = U_->bc(p);
    // Where the velocity fixes the flux and the pressure condition is a
    // gradient (a curved slip wall's), the predicted flux carries that
    // gradient so that the corrected flux is the prescribed one.
    const auto& p_bc = p_->bc(p);
    const bool fixed_flux = bc.fixes_value();
    for (int i = 0; i < patch.size; ++i) {
      const int f = patch.start + i;
      rAUf[f] = rAU[owner[f]];
      HbyA_boundary[f - ni] = bc.value_internal()[i].cwiseProduct(HbyA[owner[f]]) + bc.value_boundary()[i];
      phi_HbyA[f] = HbyA_boundary[f - ni].dot(sf[f]);
      if (fixed_flux && p_bc.gradient_internal()[i] == 0.0) {
        phi_HbyA[f] += rAUf[f] * mag[f] * p_bc.gradient_boundary()[i];
      }
    }
  }
  const bool skew = schemes_.skew_correction;
  if (skew) {
    grad_.Compute(std::span<const Vector3>(HbyA), std::span<const Vector3>(HbyA_boundary), grad_HbyA_);
    Sync(grad_HbyA_);
  }
  const std::vector<Vector3>& skew_vec = skew_;
  // Flux of v through the face, the interpolation skew-corrected with the
  // gradient g when asked; with the curvature correction a kinked face adds
  // g_f : M_f^T (cfd/fv/diffusion_curvature.h).
  auto face_flux = [&](const std::vector<Vector3>& v, const std::vector<Matrix3>& g, int f, int P, int N) {
    double out = (w[f] * v[P] + (1.0 - w[f]) * v[N]).dot(sf[f]);
    if (!skew) return out;
    const Matrix3 gf = w[f] * g[P] + (1.0 - w[f]) * g[N];
    out += (gf * skew_vec[f]).dot(sf[f]);
    if (!moments_.empty()) out += gf.cwiseProduct(moments_[f].transpose()).sum();
    return out;
  };
  for (int f = 0; f < ni; ++f) {
    const int P = owner[f], N = neighbour[f];
    rAUf[f] = w[f] * rAU[P] + (1.0 - w[f]) * rAU[N];
    phi_HbyA[f] = face_flux(HbyA, grad_HbyA_, f, P, N);
    double ddt_corr;
    if (backward) {
      Vector3 u_old = w[f] * (2.0 * U_->old(0)[P] - 0.5 * U_->old(1)[P]) +
                      (1.0 - w[f]) * (2.0 * U_->old(0)[N] - 0.5 * U_->old(1)[N]);
      double u_old_flux = u_old.dot(sf[f]);
      if (skew) {
        // 1.5 grad(u^n): the gradient of the BDF2 combination, as the skew term has it.
        const Matrix3 g = 1.5 * (w[f] * grad_U_old_[P] + (1.0 - w[f]) * grad_U_old_[N]);
        u_old_flux += (g * skew_vec[f]).dot(sf[f]);
        if (!moments_.empty()) u_old_flux += g.cwiseProduct(moments_[f].transpose()).sum();
      }
      ddt_corr = (2.0 * phi_old_[0][f] - 0.5 * phi_old_[1][f] - u_old_flux) / dt;
    } else {
      ddt_corr = (phi_old_[0][f] - face_flux(U_->old(0), grad_U_old_, f, P, N)) / dt;
    }
    phi_HbyA[f] += rAUf[f] * ddt_corr;
    if (alpha_U < 1.0) {
      phi_HbyA[f] += (1.0 - alpha_U) * (phi_prev[f] - face_flux(U_prev, grad_U_, f, P, N));
    }
  }
}

void PimpleSolver::SolvePressure(std::span<const double> rAUf, std::span<const double> phi_HbyA,
                                 bool final_corrector, bool first_pressure_solve, StepSummary& summary) {
  const int ni = mesh_.n_internal_faces();
  // Without a boundary that fixes the level, the reference cell fixes it.
  // On ranks: only when no rank has a boundary face that fixes the level.
  const bool needs_reference = Parallel() ? part_->All(NeedsReference(*p_)) : NeedsReference(*p_);
  auto& [face_corr, known_flux, diag, rhs, laplacian_flux] = pressure_scratch_;
  // The flux known before the solve: phiHbyA, less the non-orthogonal part
  // of the Laplacian on corrected meshes.
  std::span<const double> known = phi_HbyA;
  if (non_orth_correction_) {
    known_flux.assign(phi_HbyA.begin(), phi_HbyA.end());
    known = known_flux;
  }
  for (int non_orth = 0; non_orth <= pimple_.n_non_orthogonal; ++non_orth) {
    const bool last_non_orth = non_orth == pimple_.n_non_orthogonal;
    if (non_orth_correction_) {
      grad_.Compute(std::span<const double>(p_->values()), std::span<const double>(p_->boundary()), grad_p_);
      Sync(grad_p_);
      NonOrthogonalFlux(mesh_, rAUf, grad_p_, non_orth_, face_corr);
      for (int f = 0; f < ni; ++f) known_flux[f] = phi_HbyA[f] - face_corr[f];
    }
    // Continuity of F = phiHbyA - rAU |S| snGrad(p): laplacian(rAU, p) ==
    // div(phiHbyA), with the non-orthogonal part of snGrad explicit (it
    // joins phiHbyA in the known flux):
    //   -sum_f rAU_f |S_f| dc_f (p_N - p_P) = -sum_f (phiHbyA_f - rAU_f |S_f| k_f . grad(p)_f)
    pEqn_.Reset();
    AddLaplacian(pEqn_, *p_, rAUf, non_orth_, nullptr);
    AddDivergence(pEqn_, known);
    pEqn_.ComponentSystem(0, diag, rhs);
    if (needs_reference && ReferenceCell() >= 0) SetReference(diag, rhs, ReferenceCell(), pimple_.p_ref_value);
    system_.Fill(diag, pEqn_.upper, pEqn_.lower);
    const bool final_solve = final_corrector && last_non_orth;
    pressure_solver_->SetRelativeTolerance(final_solve ? pimple_.pressure_final_relative_tolerance
                                                       : pimple_.pressure_solver.relative_tolerance);
    const SolverSummary s = pressure_solver_->Solve(system_.matrix(), rhs, p_->values());
    Sync(p_->values());
    summary.pressure_iterations += s.iterations;
    if (first_pressure_solve && non_orth == 0) summary.initial_residual_p = s.initial_residual;
    if (!std::isfinite(s.final_relative_residual)) summary.finite = false;
    p_->CorrectBoundary(time_, RelativeFlux());
  }
  // Conservative flux from the same discrete operator and the last pressure.
  LaplacianFlux(*p_, rAUf, non_orth_, laplacian_flux);
  for (int f = 0; f < mesh_.n_faces(); ++f) phi_[f] = phi_HbyA[f] - laplacian_flux[f];
  if (non_orth_correction_) {
    for (int f = 0; f < ni; ++f) phi_[f] -= face_corr[f];
  }
  SyncCrossFaces(part_.get(), phi_);
}

double PimpleSolver::ContinuityError(double* global) const {
  const int nc = mesh_.n_cells();
  const int ni = mesh_.n_internal_faces();
  std::vector<double> sum(nc, 0.0), abs_sum(nc, 0.0);
  for (int f = 0; f < mesh_.n_faces(); ++f) {
    sum[mesh_.owner()[f]] += phi_[f];
    abs_sum[mesh_.owner()[f]] += std::abs(phi_[f]);
    if (f < ni) {
      sum[mesh_.neighbour()[f]] -= phi_[f];
      abs_sum[mesh_.neighbour()[f]] += std::abs(phi_[f]);
    }
  }
  double worst = 0.0, scale = 0.0;
  const int owned = OwnedCells();
  for (int c = 0; c < owned; ++c) scale = std::max(scale, abs_sum[c]);
  for (int c = 0; c < owned; ++c) worst = std::max(worst, std::abs(sum[c]));
  double boundary = 0.0, boundary_abs = 0.0;
  for (const Patch& patch : mesh_.patches()) {
    if (patch.kind == PatchKind::kProcessor) continue;  // the ghost cells' faces
    for (int f = patch.start; f < patch.start + patch.size; ++f) {
      boundary += phi_[f];
      boundary_abs += std::abs(phi_[f]);
    }
  }
  if (Parallel()) {
    scale = part_->Max(scale);
    worst = part_->Max(worst);
    boundary = part_->Sum(boundary);
    boundary_abs = part_->Sum(boundary_abs);
  }
  if (global) *global = boundary_abs > 0 ? std::abs(boundary) / boundary_abs : std::abs(boundary);
  return scale > 0 ? worst / scale : worst;
}

StepSummary PimpleSolver::Step(double dt) {
  KELVIN_CHECK(dt > 0.0, "positive time step");
  if (!initialized_) Initialize();
  StepSummary summary;
  U_->StoreOldTime(2);
  if (phi_old_.size() < 2) phi_old_.emplace_back();
  for (std::size_t i = phi_old_.size() - 1; i > 0; --i) phi_old_[i].swap(phi_old_[i - 1]);
  phi_old_[0] = phi_;
  time_ += dt;
  ++step_;
  last_dt_ = dt;
  summary.step = step_;
  summary.time = time_;
  MoveMesh(true);
  // Fresh AMG hierarchy each time step (and when the iterations grow).
  if (pimple_.pressure_solver.amg.rebuild_each_step) pressure_solver_->RequestSetup();

  bool converged = false;
  for (int outer = 0; outer < pimple_.n_outer; ++outer) {
    const bool final_outer = outer == pimple_.n_outer - 1 || converged;
    const double alpha_U = final_outer ? pimple_.relax_U_final : pimple_.relax_U;
    const double alpha_p = final_outer ? pimple_.relax_p_final : pimple_.relax_p;
    const std::vector<Vector3> U_prev = U_->values();
    const std::vector<double> phi_prev = phi_;
    const std::span<const double> flux_rel = RelativeFlux();
    U_->CorrectBoundary(time_, flux_rel);
    p_->CorrectBoundary(time_, flux_rel);
    AssembleMomentum(dt, flux_rel);
    if (outer == 0 && schemes_.skew_correction) grad_U_old_ = grad_U_;
    UEqn_.Relax(std::span<const Vector3>(U_->values()), alpha_U);
    double res_U = 0.0;
    if (pimple_.momentum_predictor) {
      grad_.Compute(std::span<const double>(p_->values()), std::span<const double>(p_->boundary()), grad_p_);
      Sync(grad_p_);
      res_U = SolveMomentum(grad_p_, summary);
      U_->CorrectBoundary(time_, flux_rel);
    }
    if (outer == 0) summary.initial_residual_U = res_U;
    const double res_p_before = summary.initial_residual_p;
    for (int corr = 0; corr < pimple_.n_correctors; ++corr) {
      const bool final_corrector = final_outer && corr == pimple_.n_correctors - 1;
      PressureCorrector(dt, final_corrector, alpha_U, alpha_p, U_prev, phi_prev, summary,
                        outer == 0 && corr == 0);
    }
    summary.outer_iterations = outer + 1;
    if (!std::isfinite(res_U)) summary.finite = false;
    if (outer_hook_) outer_hook_(outer);
    if (final_outer && turbulence_) {
      grad_.Compute(std::span<const Vector3>(U_->values()), std::span<const Vector3>(U_->boundary()), grad_U_);
      Sync(grad_U_);
      turbulence_summary_ = turbulence_->Correct(TurbulenceInputs{*U_, grad_U_, RelativeFlux(), dt, time_});
      if (!std::isfinite(turbulence_summary_.initial_residual_k) ||
          !std::isfinite(turbulence_summary_.initial_residual_omega)) {
        summary.finite = false;
      }
    }
    if (final_outer) {
      summary.outer_converged = converged || pimple_.n_outer == 1;
      break;
    }
    // Residual control on this outer iteration's initial residuals.
    const double res_p = outer == 0 ? summary.initial_residual_p : res_p_before;
    if (pimple_.outer_tolerance_U > 0.0 && pimple_.outer_tolerance_p > 0.0 && res_U < pimple_.outer_tolerance_U &&
        res_p < pimple_.outer_tolerance_p) {
      converged = true;
    }
  }
  // Courant number and conservation.
  Courant(dt, summary);
  summary.continuity_error = ContinuityError(&summary.global_mass_imbalance);
  for (int c = 0; c < OwnedCells() && summary.finite; ++c) {
    if (!std::isfinite((*U_)[c].squaredNorm()) || !std::isfinite((*p_)[c])) summary.finite = false;
  }
  if (!std::isfinite(summary.initial_residual_p) || !std::isfinite(summary.initial_residual_U)) summary.finite = false;
  if (Parallel()) summary.finite = part_->All(summary.finite);
  return summary;
}

void PimpleSolver::Courant(double dt, StepSummary& summary) const {
  const auto vol = mesh_.cell_volumes();
  std::vector<double> sum_abs(mesh_.n_cells(), 0.0);
  for (int f = 0; f < mesh_.n_faces(); ++f) {
    sum_abs[mesh_.owner()[f]] += std::abs(phi_[f] - mesh_flux_[f]);
    if (f < mesh_.n_internal_faces()) sum_abs[mesh_.neighbour()[f]] += std::abs(phi_[f] - mesh_flux_[f]);
  }
  summary.courant_cell = mesh_.n_cells() > 0 ? 0 : -1;
  for (int c = 0; c < OwnedCells(); ++c) {
    const double co = 0.5 * dt * sum_abs[c] / vol[c];
    if (co > summary.courant_max) {  // false for NaN: non-finite cells are caught below
      summary.courant_max = co;
      summary.courant_cell = c;
    }
  }
  if (!Parallel()) return;
  // The largest over the ranks, with its cell of the undecomposed mesh.
  struct {
    double value;
    int rank;
  } local{summary.courant_max, part_->rank}, global{};
  MPI_Allreduce(&local, &global, 1, MPI_DOUBLE_INT, MPI_MAXLOC, part_->comm);
  long long cell = part_->cells[summary.courant_cell];
  MPI_Bcast(&cell, 1, MPI_LONG_LONG, global.rank, part_->comm);
  summary.courant_max = global.value;
  summary.courant_cell = static_cast<int>(cell);
}

PimpleSolver::State PimpleSolver::GetState() const {
  State s;
  s.time = time_;
  s.step = step_;
  s.last_dt = last_dt_;
  s.U = U_->values();
  for (int l = 0; l < U_->n_old(); ++l) s.U_old.push_back(U_->old(l));
  s.p = p_->values();
  s.phi = phi_;
  s.phi_old = phi_old_;
  for (int p = 0; p < U_->n_patches(); ++p) s.bc_state.push_back(U_->bc(p).State());
  for (int p = 0; p < p_->n_patches(); ++p) s.bc_state.push_back(p_->bc(p).State());
  if (turbulence_) s.turbulence = turbulence_->State();
  return s;
}

void PimpleSolver::SetState(const State& s) {
  time_ = s.time;
  step_ = s.step;
  last_dt_ = s.last_dt;
  U_->values() = s.U;
  U_->SetOld(s.U_old);
  p_->values() = s.p;
  phi_ = s.phi;
  phi_old_ = s.phi_old;
  for (int p = 0; p < U_->n_patches(); ++p) U_->bc(p).SetState(s.bc_state.at(p));
  for (int p = 0; p < p_->n_patches(); ++p) p_->bc(p).SetState(s.bc_state.at(U_->n_patches() + p));
  initialized_ = true;
  MoveMesh(false);
  U_->CorrectBoundary(time_, RelativeFlux());
  p_->CorrectBoundary(time_, RelativeFlux());
  if (turbulence_) {
    if (s.turbulence.empty()) throw DataFileError("the checkpoint has no turbulence state; the case uses a turbulence model");
    turbulence_->SetState(s.turbulence);
  } else if (!s.turbulence.empty()) {
    throw DataFileError("the checkpoint has a turbulence state; the case is laminar");
  }
}

}  // namespace kelvin::cfd
