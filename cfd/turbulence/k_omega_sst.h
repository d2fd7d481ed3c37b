// Menter's k-omega SST model in its 2003 form (Menter, Kuntz and Langtry,
// "Ten years of industrial experience with the SST turbulence model",
// Turbulence, Heat and Mass Transfer 4, 2003; the "SST-2003" variant of
// NASA's Turbulence Modeling Resource):
//
//   dk/dt + div(U k) = P~ - beta* omega k + div((nu + sigma_k nu_t) grad k)
//   domega/dt + div(U omega) = gamma P~ / nu_t - beta omega^2
//       + div((nu + sigma_w nu_t) grad omega) + 2 (1 - F1) sigma_w2 grad k . grad omega / omega
//   nu_t = a1 k / max(a1 omega, S F2),   S = sqrt(2 S_ij S_ij)  (strain-based limiter)
//   P~ = min(nu_t S^2, 10 beta* k omega)                     (production limiter)
//
// with the F1 blending of the constants (sigma_k, sigma_w, beta, gamma) and
// the F2 blending of the nu_t limiter. The omega production uses the limited
// P~ (gamma P~ / nu_t = gamma min(S^2, 10 beta* k omega / nu_t)), which keeps
// the two equations consistent in stagnation regions.
//
// Discretization (segregated, once per time step after the PISO correctors):
// Euler or backward in time, bounded convection (upwind, or the van Leer TVD
// scheme) written as div(F phi) - div(F) phi so that a not fully converged
// continuity cannot create or destroy k or omega, destruction terms and the
// negative part of the cross diffusion implicit, the positive parts
// explicit. The matrices are then M-matrices with non-negative sources, so
// k and omega stay positive; a bound step still checks every cell and
// counts (and the run reports) any cell it had to lift to the floor.
//
// Walls: Spalding's law gives u_tau and the wall eddy viscosity at any y+
// (wall_functions.h); omega in the wall cells is fixed to the blended
// viscous/log value (its viscous part consistent with the discrete omega
// equation of the cells beyond, KOmegaSstOptions::wall_omega); k has zero
// gradient at the wall; in log-layer wall cells (y+ above the linear/log
// intersection) the k production is the wall-function value
// u_tau^2 * Cmu^0.25 sqrt(k) / (kappa y), and the strain rate in their nu_t
// limiter is the log law's u_tau / (kappa y): the
// cell gradient of a wall cell sees the jump from the wall value to the
// cell value, U_P / y_P, which overstates the log-layer strain by the
// factor kappa u+ (about 7 at y+ 100), so the limiter would cut the wall
// cell's nu_t by that factor where the log layer has k / omega = kappa u_tau y,
// starve the face between the wall cell and the next of momentum diffusion
// and lower U_P and the friction with it (docs/formulation.md section 8.2;
// on the DTC's snappy grid 3, 4% of the hull friction and up to 19% of it
// locally, BENCHMARKS.md wall_friction_same_grid).
#pragma once

#include <memory>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "cfd/fv/fv_matrix.h"
#include "cfd/fv/schemes.h"
#include "cfd/linalg/linear_solver.h"
#include "cfd/turbulence/turbulence_model.h"
#include "cfd/turbulence/wall_functions.h"

namespace kelvin::cfd {

struct InflowTurbulence {
  double intensity = 0.01;        // I = sqrt(2k/3) / U_ref
  double viscosity_ratio = 5.0;   // nu_t / nu
  double reference_speed = 1.0;   // U_ref (m/s)
  double k(double) const;                 // m^2/s^2
  double omega(double nu) const;          // 1/s
  void Validate() const;
};

struct KOmegaSstOptions {
  // Model constants (set 1 inner, set 2 outer).
  double beta_star = 0.09;
  double a1 = 0.31;
  double sigma_k1 = 0.85, sigma_k2 = 1.0;
  double sigma_w1 = 0.5, sigma_w2 = 0.856;
  double beta1 = 0.075, beta2 = 0.0828;
  double gamma1 = 5.0 / 9.0, gamma2 = 0.44;
  double production_limit = 10.0;  // c1 of the production limiter
  WallLaw wall_law;
  InflowTurbulence inflow;
  ConvectionScheme convection = ConvectionScheme::kUpwind;  // upwind or limited (bounded)
  TimeScheme time = TimeScheme::kEuler;
  double relax = 1.0;  // implicit under-relaxation of k and omega (pseudo-transient runs)
  // Sustaining terms of Spalart and Rumsey (2007, AIAA J. 45:2544; the
  // "SST-sust" variant): + beta* k_amb omega_amb in the k equation and
  // + beta omega_amb^2 in the omega equation, with the inflow values as the
  // ambient state, so the free-stream turbulence does not decay between the
  // inlet and the body. Off by default: with towing-tank inflow values
  // (I = 1%, nu_t/nu = 1-10) the ambient omega exceeds the outer
  // boundary-layer omega of model-scale plates and damps it.
  bool sustain = false;
  // The viscous part of the wall cells' fixed omega (wall_functions.h):
  // kDiscreteSublayer scales the sublayer solution's point value by
  // SublayerOmegaScale() so that the next cells' discrete omega follows the
  // sublayer solution; kPointValue is the point value itself, as OpenFOAM's
  // omegaWallFunction, which on a wall-resolved plate (first cell centre at
  // y+ 1) leaves omega 1.5 times too high in the next cells and C_F 8% below
  // Schoenherr's line (docs/formulation.md section 8.2). The scale acts on
  // wall cells below y+ 5 only (SublayerOmegaScale(y_plus)); wall-function
  // cells take the same value either way.
  enum class WallOmega { kDiscreteSublayer, kPointValue };
  WallOmega wall_omega = WallOmega::kDiscreteSublayer;
  // Tolerances and iteration limit of the k and omega solves (hypre
  // BiCGStab with an ILU(0) preconditioner; the type field is not used).
  LinearSolverOptions solver;
  void Validate() const;
};

class KOmegaSst : public TurbulenceModel {
 public:
  // `roles` has one entry per mesh patch. nu in m^2/s. On a decomposed mesh
  // `part` is the rank's DomainPart (docs/formulation.md section 13): the
  // ghost values of k, omega, nu_t, their gradients and the wall distance
  // are refreshed from their owners, and the solves run on the global rows.
  KOmegaSst(const Mesh& mesh, double nu, KOmegaSstOptions options, std::vector<TurbulencePatchRole> roles,
            std::shared_ptr<const DomainPart> part = nullptr);

  std::string name() const override { return "kOmegaSST"; }
  const DomainPart* part() const override { return part_.get(); }
  void Initialize(const VectorField& U, std::span<const double> flux) override;
  TurbulenceSummary Correct(const TurbulenceInputs& in) override;
  void RefreshGeometry() override {
    grad_.UpdateGeometry();
    geo_ = NonOrthGeometry(mesh_);
  }
  const std::vector<double>& nu_eff_faces() const override { return nu_eff_faces_; }
  const std::vector<double>& nu_t() const override { return nut_; }
  const std::vector<Vector3>& wall_shear_stress() const override { return tau_w_; }
  const std::vector<double>& y_plus() const override { return y_plus_; }
  std::vector<WallPatchStats> WallStats() const override;
  std::vector<TurbulenceOutput> CellOutputs() const override;
  std::vector<std::pair<std::string, std::vector<double>>> State() const override;
  void SetState(const std::vector<std::pair<std::string, std::vector<double>>>& state) override;

  const ScalarField& k() const { return *k_; }
  const ScalarField& omega() const { return *omega_; }
  ScalarField& k() { return *k_; }
  ScalarField& omega() { return *omega_; }
  const std::vector<double>& wall_distance() const { return y_; }
  const std::vector<double>& F1() const { return F1_; }
  const std::vector<double>& strain_rate_squared() const { return S2_; }  // 2 S_ij S_ij

 private:
  // Wall shear, y+, u_tau per wall face and the wall-cell omega, from U.
  void UpdateWall(const VectorField& U);
  // nu_t in the cells from k, omega, S and F2; then the face viscosities.
  void UpdateViscosity();
  // nu + nu_t on every face from the cell nu_t and the wall values.
  void UpdateFaceViscosity();
  // Solves one transport equation; returns the initial residual.
  double Solve(ScalarField& field, FvMatrix<double>& m, int& bounded, double floor, int& iterations);

  template <typename T>
  void Sync(std::vector<T>& values) const {
    UpdateGhosts(part_.get(), values);
  }

  const Mesh& mesh_;
  std::shared_ptr<const DomainPart> part_;
  double nu_;
  KOmegaSstOptions opt_;
  std::vector<TurbulencePatchRole> roles_;
  std::unique_ptr<ScalarField> k_, omega_;
  std::vector<double> nut_, y_, F1_, F2_, S2_;
  std::vector<double> nu_eff_faces_;
  std::vector<Vector3> tau_w_;
  std::vector<double> y_plus_, u_tau_, nut_wall_;
  // Wall cells and their fixed omega (averaged over their wall faces).
  std::vector<int> wall_cells_;
  std::vector<double> wall_cell_omega_;
  std::vector<double> wall_cell_production_;  // -1: use the cell production
  // Strain rate u_tau / (kappa y) of the log law in log-layer wall cells, for
  // the nu_t limiter (-1: the cell's own strain rate).
  std::vector<double> wall_cell_strain_;
  NonOrthGeometry geo_;
  Gradient grad_;
  SparseSystem system_;
  std::unique_ptr<LinearSolver> k_solver_, omega_solver_;
  double k_floor_ = 0.0, omega_floor_ = 0.0;
  bool initialized_ = false;
};

}  // namespace kelvin::cfd
