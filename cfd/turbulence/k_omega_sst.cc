#include "cfd/turbulence/k_omega_sst.h"

#include <fmt/format.h>

#include <Eigen/SparseCore>

#include <algorithm>
#include <cmath>
#include <limits>

#include "cfd/turbulence/wall_distance.h"
#include "data/schema/errors.h"

namespace kelvin::cfd {

double InflowTurbulence::k(double) const {
  const double u = intensity * reference_speed;
  return 1.5 * u * u;
}

double InflowTurbulence::omega(double nu) const { return k(nu) / (viscosity_ratio * nu); }

void InflowTurbulence::Validate() const {
  if (!(intensity > 0.0 && intensity < 1.0)) {
    throw ConfigError(fmt::format("turbulence.inflow.intensity = {}; expected in (0, 1) (0.01 = 1%)", intensity));
  }
  if (!(viscosity_ratio > 0.0) || !std::isfinite(viscosity_ratio)) {
    throw ConfigError(fmt::format("turbulence.inflow.viscosity_ratio = {}; expected > 0 (nu_t / nu)", viscosity_ratio));
  }
  if (!(reference_speed > 0.0) || !std::isfinite(reference_speed)) {
    throw ConfigError(fmt::format("turbulence.inflow.reference_speed = {}; expected > 0 m/s", reference_speed));
  }
}

void KOmegaSstOptions::Validate() const {
  inflow.Validate();
  if (convection != ConvectionScheme::kUpwind && convection != ConvectionScheme::kLimited) {
    throw ConfigError("turbulence.convection: expected upwind or limited (bounded schemes only)");
  }
  if (!(relax > 0.0 && relax <= 1.0)) throw ConfigError(fmt::format("turbulence.relax = {}; expected in (0, 1]", relax));
  solver.Validate();
}

namespace {

double Blend(double F1, double inner, double outer) { return F1 * inner + (1.0 - F1) * outer; }

}  // namespace

KOmegaSst::KOmegaSst(const Mesh& mesh, double nu, KOmegaSstOptions options, std::vector<TurbulencePatchRole> roles,
                     std::shared_ptr<const DomainPart> part)
    : mesh_(mesh),
      part_(std::move(part)),
      nu_(nu),
      opt_(std::move(options)),
      roles_(std::move(roles)),
      geo_(mesh),
      grad_(mesh, GradientOptions{}),
      system_(mesh) {
  opt_.Validate();
  KELVIN_CHECK(roles_.size() == mesh.patches().size(), "one turbulence role per patch");
  const double k_in = opt_.inflow.k(nu_);
  const double w_in = opt_.inflow.omega(nu_);
  std::vector<std::unique_ptr<BoundaryCondition<double>>> kb, wb;
  std::vector<int> walls;
  for (std::size_t p = 0; p < roles_.size(); ++p) {
    switch (roles_[p]) {
      case TurbulencePatchRole::kInflow:
        kb.push_back(std::make_unique<FixedValue<double>>(k_in));
        wb.push_back(std::make_unique<FixedValue<double>>(w_in));
        break;
      case TurbulencePatchRole::kOutflow:
        kb.push_back(std::make_unique<InletOutlet<double>>(k_in));
        wb.push_back(std::make_unique<InletOutlet<double>>(w_in));
        break;
      case TurbulencePatchRole::kWall:
        walls.push_back(static_cast<int>(p));
        [[fallthrough]];
      case TurbulencePatchRole::kSymmetry:
        kb.push_back(std::make_unique<ZeroGradient<double>>());
        wb.push_back(std::make_unique<ZeroGradient<double>>());
        break;
      case TurbulencePatchRole::kEmpty:
        kb.push_back(std::make_unique<Empty<double>>());
        wb.push_back(std::make_unique<Empty<double>>());
        break;
    }
  }
  k_ = std::make_unique<ScalarField>("k", mesh, std::move(kb));
  omega_ = std::make_unique<ScalarField>("omega", mesh, std::move(wb));
  std::fill(k_->values().begin(), k_->values().end(), k_in);
  std::fill(omega_->values().begin(), omega_->values().end(), w_in);
  // Floors for the bound check: far below any physical value of the run.
  k_floor_ = 1e-14 * k_in;
  omega_floor_ = 1e-14 * w_in;
  y_ = WallDistance(mesh, walls, part_.get());
  const int nc = mesh.n_cells();
  nut_.assign(nc, k_in / w_in);
  F1_.assign(nc, 1.0);
  F2_.assign(nc, 1.0);
  S2_.assign(nc, 0.0);
  nu_eff_faces_.assign(mesh.n_faces(), nu_);
  tau_w_.assign(mesh.n_boundary_faces(), Vector3::Zero());
  y_plus_.assign(mesh.n_boundary_faces(), 0.0);
  u_tau_.assign(mesh.n_boundary_faces(), 0.0);
  nut_wall_.assign(mesh.n_boundary_faces(), 0.0);
  // Wall cells, each once.
  std::vector<char> seen(nc, 0);
  for (int p : walls) {
    const Patch& patch = mesh.patches()[p];
    for (int f = patch.start; f < patch.start + patch.size; ++f) {
      const int c = mesh.owner()[f];
      if (!seen[c]) wall_cells_.push_back(c);
      seen[c] = 1;
    }
  }
  wall_cell_omega_.assign(wall_cells_.size(), w_in);
  wall_cell_production_.assign(wall_cells_.size(), -1.0);
  wall_cell_strain_.assign(wall_cells_.size(), -1.0);
}

void KOmegaSst::Initialize(const VectorField& U, std::span<const double> flux) {
  k_->CorrectBoundary(0.0, flux);
  omega_->CorrectBoundary(0.0, flux);
  UpdateWall(U);
  UpdateViscosity();
  initialized_ = true;
}

void KOmegaSst::UpdateWall(const VectorField& U) {
  const int ni = mesh_.n_internal_faces();
  const double y_lam = opt_.wall_law.YPlusLaminar();
  const double cmu25 = std::pow(opt_.beta_star, 0.25);
  std::vector<double> omega_sum(mesh_.n_cells(), 0.0), prod_sum(mesh_.n_cells(), 0.0);
  std::vector<double> strain_sum(mesh_.n_cells(), 0.0);
  std::vector<int> count(mesh_.n_cells(), 0), log_count(mesh_.n_cells(), 0);
  const bool sublayer = opt_.wall_omega == KOmegaSstOptions::WallOmega::kDiscreteSublayer;
  for (std::size_t p = 0; p < roles_.size(); ++p) {
    if (roles_[p] != TurbulencePatchRole::kWall) continue;
    const Patch& patch = mesh_.patches()[p];
    for (int f = patch.start; f < patch.start + patch.size; ++f) {
      const int b = f - ni;
      const int c = mesh_.owner()[f];
      const Vector3 n = mesh_.face_areas()[f] / mesh_.face_area_magnitudes()[f];
      const double y = std::abs(n.dot(mesh_.face_centres()[f] - mesh_.cell_centres()[c]));
      Vector3 du = U[c] - U.boundary()[b];
      du -= n * n.dot(du);
      const double speed = du.norm();
      const double u_tau = opt_.wall_law.FrictionVelocity(speed, y, nu_);
      u_tau_[b] = u_tau;
      y_plus_[b] = y * u_tau / nu_;
      nut_wall_[b] = speed > 0.0 ? std::max(u_tau * u_tau * y / speed - nu_, 0.0) : 0.0;
      // Kinematic shear stress on the wall, in the direction of the flow
      // past it: (nu + nu_t,w) (u_P - u_w)_t / y.
      tau_w_[b] = (nu_ + nut_wall_[b]) * du / y;
      const double viscous_scale = sublayer ? SublayerOmegaScale(y_plus_[b]) : 1.0;
      omega_sum[c] += WallOmega(y, u_tau, nu_, opt_.wall_law.kappa, opt_.beta1, opt_.beta_star, viscous_scale);
      ++count[c];
      if (y_plus_[b] > y_lam) {
        prod_sum[c] += u_tau * u_tau * cmu25 * std::sqrt(std::max((*k_)[c], 0.0)) / (opt_.wall_law.kappa * y);
        strain_sum[c] += u_tau / (opt_.wall_law.kappa * y);
        ++log_count[c];
      }
    }
  }
  for (std::size_t i = 0; i < wall_cells_.size(); ++i) {
    const int c = wall_cells_[i];
    wall_cell_omega_[i] = omega_sum[c] / count[c];
    wall_cell_production_[i] = log_count[c] > 0 ? prod_sum[c] / log_count[c] : -1.0;
    wall_cell_strain_[i] = log_count[c] > 0 ? strain_sum[c] / log_count[c] : -1.0;
  }
}

void KOmegaSst::UpdateViscosity() {
  const int nc = mesh_.n_cells();
  std::vector<double> strain(nc);
  for (int c = 0; c < nc; ++c) strain[c] = std::sqrt(S2_[c]);
  for (std::size_t i = 0; i < wall_cells_.size(); ++i) {
    if (wall_cell_strain_[i] >= 0.0) strain[wall_cells_[i]] = wall_cell_strain_[i];
  }
  for (int c = 0; c < nc; ++c) {
    const double k = (*k_)[c], w = (*omega_)[c];
    nut_[c] = opt_.a1 * k / std::max(opt_.a1 * w, strain[c] * F2_[c]);
  }
  Sync(nut_);  // a ghost that is a wall cell of its owner takes the owner's limiter
  UpdateFaceViscosity();
}

void KOmegaSst::UpdateFaceViscosity() {
  const int ni = mesh_.n_internal_faces();
  const auto w = mesh_.weights();
  for (int f = 0; f < ni; ++f) {
    nu_eff_faces_[f] = nu_ + w[f] * nut_[mesh_.owner()[f]] + (1.0 - w[f]) * nut_[mesh_.neighbour()[f]];
  }
  for (std::size_t p = 0; p < roles_.size(); ++p) {
    const Patch& patch = mesh_.patches()[p];
    for (int f = patch.start; f < patch.start + patch.size; ++f) {
      nu_eff_faces_[f] = nu_ + (roles_[p] == TurbulencePatchRole::kWall ? nut_wall_[f - ni] : nut_[mesh_.owner()[f]]);
    }
  }
}

double KOmegaSst::Solve(ScalarField& field, FvMatrix<double>& m, int& bounded, double floor, int& iterations) {
  std::vector<double> diag, source;
  m.ComponentSystem(0, diag, source);
  system_.Fill(diag, m.upper, m.lower);
  // Solve for the correction: the wall cells fix omega at values many
  // orders above the free stream, so a tolerance relative to |b| would be
  // met by the wall rows alone and leave the rest of the field unconverged.
  // Relative to the initial residual, the tolerance means what it says.
  const CsrMatrix& a = system_.matrix();
  const Eigen::Map<const Eigen::VectorXd> x(field.values().data(), static_cast<Eigen::Index>(field.values().size()));
  const Eigen::Map<const Eigen::VectorXd> b(source.data(), static_cast<Eigen::Index>(source.size()));
  const Eigen::VectorXd r0 = b - a * x;
  const double residual = NormalizedResidual(a, source, field.values(), part_.get());
  // Every rank must take the same branch below (the solve is collective);
  // the ghost rows of r0 are not equations.
  const int owned = OwnedCells(part_.get(), mesh_);
  const double r0_norm = part_ ? part_->Sum(r0.head(owned).squaredNorm()) : r0.squaredNorm();
  // BiCGStab with an ILU(0) preconditioner (hypre) on the correction, same
  // tolerances as opt_.solver. The k and omega matrices are dominated by
  // upwind convection at the large pseudo-time steps of steady runs; there
  // an incomplete LU is close to exact, where Jacobi needs about as many
  // iterations as there are cells along a streamline.
  std::unique_ptr<LinearSolver>& solver = &field == k_.get() ? k_solver_ : omega_solver_;
  if (!solver) {
    LinearSolverOptions o = opt_.solver;
    o.type = LinearSolverOptions::Type::kBiCgStabIlu;
    solver = LinearSolver::Create(o, part_.get());
  }
  std::vector<double> dx(r0.size(), 0.0);
  if (r0_norm > 0.0) {
    const SolverSummary s = solver->Solve(a, std::span<const double>(r0.data(), r0.size()), dx);
    iterations += s.iterations;
  }
  for (std::size_t c = 0; c < dx.size(); ++c) field.values()[c] += dx[c];
  for (int c = 0; c < owned; ++c) {
    double& v = field.values()[c];
    if (!(v >= floor)) {
      if (std::isfinite(v)) {
        v = floor;
        ++bounded;
      }
    }
  }
  Sync(field.values());
  return residual;
}

TurbulenceSummary KOmegaSst::Correct(const TurbulenceInputs& in) {
  if (!initialized_) Initialize(in.U, in.flux);
  TurbulenceSummary summary;
  const int nc = mesh_.n_cells();
  const int ni = mesh_.n_internal_faces();
  const auto vol = mesh_.cell_volumes();
  const auto w = mesh_.weights();
  k_->StoreOldTime(2);
  omega_->StoreOldTime(2);
  k_->CorrectBoundary(in.time, in.flux);
  omega_->CorrectBoundary(in.time, in.flux);

  // Strain rate, wall quantities, gradients and blending functions.
  for (int c = 0; c < nc; ++c) {
    const Matrix3 S = 0.5 * (in.grad_U[c] + in.grad_U[c].transpose());
    S2_[c] = 2.0 * (S.array() * S.array()).sum();
  }
  UpdateWall(in.U);
  std::vector<Vector3> gk, gw;
  grad_.Compute(std::span<const double>(k_->values()), std::span<const double>(k_->boundary()), gk);
  grad_.Compute(std::span<const double>(omega_->values()), std::span<const double>(omega_->boundary()), gw);
  Sync(gk);
  Sync(gw);
  std::vector<double> cross(nc);  // 2 sigma_w2 grad k . grad omega / omega
  for (int c = 0; c < nc; ++c) {
    const double k = (*k_)[c], om = (*omega_)[c], y = y_[c];
    cross[c] = 2.0 * opt_.sigma_w2 * gk[c].dot(gw[c]) / om;
    const double cd = std::max(cross[c], 1e-10);
    const double a = std::max(std::sqrt(k) / (opt_.beta_star * om * y), 500.0 * nu_ / (y * y * om));
    const double arg1 = std::min(a, 4.0 * opt_.sigma_w2 * k / (cd * y * y));
    F1_[c] = std::tanh(std::pow(arg1, 4));
  }
  // Divergence of the flux: convection is written div(F phi) - div(F) phi.
  std::vector<double> div(nc, 0.0);
  for (int f = 0; f < mesh_.n_faces(); ++f) {
    div[mesh_.owner()[f]] += in.flux[f];
    if (f < ni) div[mesh_.neighbour()[f]] -= in.flux[f];
  }
  // Face diffusivities nu + sigma nu_t with sigma blended by F1.
  auto diffusivity = [&](double s1, double s2) {
    std::vector<double> cell(nc), faces(mesh_.n_faces());
    for (int c = 0; c < nc; ++c) cell[c] = nu_ + Blend(F1_[c], s1, s2) * nut_[c];
    for (int f = 0; f < ni; ++f) faces[f] = w[f] * cell[mesh_.owner()[f]] + (1.0 - w[f]) * cell[mesh_.neighbour()[f]];
    for (int f = ni; f < mesh_.n_faces(); ++f) faces[f] = cell[mesh_.owner()[f]];
    return faces;
  };
  // Production, limited; log-layer wall cells take the wall-function value.
  std::vector<double> P(nc);
  for (int c = 0; c < nc; ++c) {
    P[c] = std::min(nut_[c] * S2_[c], opt_.production_limit * opt_.beta_star * (*k_)[c] * (*omega_)[c]);
  }
  for (std::size_t i = 0; i < wall_cells_.size(); ++i) {
    if (wall_cell_production_[i] >= 0.0) P[wall_cells_[i]] = wall_cell_production_[i];
  }

  const double k_amb = opt_.inflow.k(nu_), omega_amb = opt_.inflow.omega(nu_);
  // omega equation.
  {
    FvMatrix<double> m(mesh_);
    AddDdt(m, *omega_, in.dt, opt_.time);
    AddConvection(m, *omega_, in.flux, opt_.convection, gw);
    for (int c = 0; c < nc; ++c) m.diag[c] -= div[c];
    AddLaplacian(m, *omega_, std::span<const double>(diffusivity(opt_.sigma_w1, opt_.sigma_w2)), geo_,
                 geo_.any_correction ? &gw : nullptr);
    std::vector<double> implicit(nc), explicit_source(nc);
    for (int c = 0; c < nc; ++c) {
      const double om = (*omega_)[c];
      const double gamma = Blend(F1_[c], opt_.gamma1, opt_.gamma2);
      const double beta = Blend(F1_[c], opt_.beta1, opt_.beta2);
      // gamma P~ / nu_t = gamma min(S^2, c1 beta* k omega / nu_t).
      const double limit = opt_.production_limit * opt_.beta_star * (*k_)[c] * om;
      explicit_source[c] = gamma * (nut_[c] > 0.0 ? std::min(S2_[c], limit / nut_[c]) : S2_[c]);
      implicit[c] = beta * om;
      if (opt_.sustain) explicit_source[c] += beta * omega_amb * omega_amb;
      const double cd = (1.0 - F1_[c]) * cross[c];
      if (cd > 0.0) {
        explicit_source[c] += cd;
      } else {
        implicit[c] += -cd / om;
      }
    }
    AddSource(m, std::span<const double>(explicit_source));
    AddImplicitSource(m, implicit);
    m.Relax(std::span<const double>(omega_->values()), opt_.relax);
    SetCellValues(m, wall_cells_, wall_cell_omega_);
    summary.initial_residual_omega = Solve(*omega_, m, summary.bounded_omega, omega_floor_, summary.iterations);
    omega_->CorrectBoundary(in.time, in.flux);
  }
  // k equation.
  {
    FvMatrix<double> m(mesh_);
    AddDdt(m, *k_, in.dt, opt_.time);
    AddConvection(m, *k_, in.flux, opt_.convection, gk);
    for (int c = 0; c < nc; ++c) m.diag[c] -= div[c];
    AddLaplacian(m, *k_, std::span<const double>(diffusivity(opt_.sigma_k1, opt_.sigma_k2)), geo_,
                 geo_.any_correction ? &gk : nullptr);
    std::vector<double> implicit(nc);
    for (int c = 0; c < nc; ++c) implicit[c] = opt_.beta_star * (*omega_)[c];
    if (opt_.sustain) {
      for (int c = 0; c < nc; ++c) P[c] += opt_.beta_star * k_amb * omega_amb;
    }
    AddSource(m, std::span<const double>(P));
    AddImplicitSource(m, implicit);
    m.Relax(std::span<const double>(k_->values()), opt_.relax);
    summary.initial_residual_k = Solve(*k_, m, summary.bounded_k, k_floor_, summary.iterations);
    k_->CorrectBoundary(in.time, in.flux);
  }
  // F2 from the new k and omega, then nu_t.
  for (int c = 0; c < nc; ++c) {
    const double k = (*k_)[c], om = (*omega_)[c], y = y_[c];
    const double arg2 = std::max(2.0 * std::sqrt(k) / (opt_.beta_star * om * y), 500.0 * nu_ / (y * y * om));
    F2_[c] = std::tanh(arg2 * arg2);
  }
  UpdateViscosity();
  if (part_) {
    summary.bounded_k = static_cast<int>(part_->Sum(summary.bounded_k));
    summary.bounded_omega = static_cast<int>(part_->Sum(summary.bounded_omega));
  }
  return summary;
}

std::vector<WallPatchStats> KOmegaSst::WallStats() const {
  std::vector<WallPatchStats> out;
  const int ni = mesh_.n_internal_faces();
  for (std::size_t p = 0; p < roles_.size(); ++p) {
    if (roles_[p] != TurbulencePatchRole::kWall) continue;
    const Patch& patch = mesh_.patches()[p];
    std::vector<double> y_plus(y_plus_.begin() + (patch.start - ni), y_plus_.begin() + (patch.start - ni + patch.size));
    std::vector<double> area(mesh_.face_area_magnitudes().begin() + patch.start,
                             mesh_.face_area_magnitudes().begin() + patch.start + patch.size);
    if (part_ && part_->parallel()) {
      // The patch's faces of every rank (each wall face is one rank's own).
      y_plus = AllGather(*part_, y_plus);
      area = AllGather(*part_, area);
    }
    out.push_back(SummarizeWall(patch.name, y_plus, area));
  }
  return out;
}

std::vector<TurbulenceOutput> KOmegaSst::CellOutputs() const {
  const int nc = mesh_.n_cells();
  const int ni = mesh_.n_internal_faces();
  TurbulenceOutput yp{"yPlus", 1, std::vector<double>(nc, 0.0)};
  TurbulenceOutput tw{"wallShearStress", 3, std::vector<double>(3 * nc, 0.0)};
  for (std::size_t p = 0; p < roles_.size(); ++p) {
    if (roles_[p] != TurbulencePatchRole::kWall) continue;
    const Patch& patch = mesh_.patches()[p];
    for (int f = patch.start; f < patch.start + patch.size; ++f) {
      const int c = mesh_.owner()[f];
      yp.values[c] = std::max(yp.values[c], y_plus_[f - ni]);
      for (int d = 0; d < 3; ++d) tw.values[3 * c + d] = tau_w_[f - ni][d];
    }
  }
  return {{"k", 1, k_->values()}, {"omega", 1, omega_->values()}, {"nut", 1, nut_}, {"wallDistance", 1, y_},
          std::move(yp), std::move(tw)};
}

std::vector<std::pair<std::string, std::vector<double>>> KOmegaSst::State() const {
  std::vector<std::pair<std::string, std::vector<double>>> s = {
      {"k", k_->values()}, {"omega", omega_->values()}, {"nut", nut_}, {"nut_wall", nut_wall_}};
  for (int l = 0; l < k_->n_old(); ++l) s.emplace_back(fmt::format("k_old{}", l), k_->old(l));
  for (int l = 0; l < omega_->n_old(); ++l) s.emplace_back(fmt::format("omega_old{}", l), omega_->old(l));
  return s;
}

void KOmegaSst::SetState(const std::vector<std::pair<std::string, std::vector<double>>>& state) {
  std::vector<std::vector<double>> k_old, omega_old;
  auto expect = [&](const std::vector<double>& v, std::size_t n, const std::string& name) {
    if (v.size() != n) {
      throw DataFileError(fmt::format("turbulence state '{}' has {} values; the mesh needs {}", name, v.size(), n));
    }
  };
  const std::size_t nc = mesh_.n_cells();
  for (const auto& [name, v] : state) {
    if (name == "k") {
      expect(v, nc, name);
      k_->values() = v;
    } else if (name == "omega") {
      expect(v, nc, name);
      omega_->values() = v;
    } else if (name == "nut") {
      expect(v, nc, name);
      nut_ = v;
    } else if (name == "nut_wall") {
      expect(v, mesh_.n_boundary_faces(), name);
      nut_wall_ = v;
    } else if (name.rfind("k_old", 0) == 0) {
      k_old.push_back(v);
    } else if (name.rfind("omega_old", 0) == 0) {
      omega_old.push_back(v);
    } else {
      throw DataFileError(fmt::format("unknown turbulence state '{}' in the checkpoint", name));
    }
  }
  k_->SetOld(std::move(k_old));
  omega_->SetOld(std::move(omega_old));
  // The blending functions and the strain rate are recomputed at the start
  // of the next correction; the face viscosities follow from nu_t.
  UpdateFaceViscosity();
  initialized_ = true;
}

}  // namespace kelvin::cfd
