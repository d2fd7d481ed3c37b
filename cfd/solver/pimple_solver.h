// Incompressible PIMPLE solver on collocated polyhedral cells (see
// docs/formulation.md section 4). One time step:
//   outer correctors (with under-relaxation and residual control)
//     momentum predictor: ddt(U) + div(F - F_mesh, U) + div(dev(R_eff)) = -grad p + s,
//       div(dev(R_eff)) from the turbulence model (AddDivDevReff), or
//       -div(nu grad U) when laminar
//     PISO correctors: Rhie-Chow flux of HbyA with the transient and
//       relaxation-consistent terms; pressure equation with non-orthogonal
//       correctors (CG + BoomerAMG); conservative flux update; U correction.
// p is the kinematic pressure (m^2/s^2); F the volume flux (m^3/s). The mesh
// flux F_mesh (zero unless a moving-mesh stage sets it) only enters the
// convective flux; continuity uses the absolute flux.
#pragma once

#include <array>
#include <functional>
#include <memory>
#include <vector>

#include "cfd/field/field.h"
#include "cfd/fv/fv_matrix.h"
#include "cfd/fv/gradient.h"
#include "cfd/fv/schemes.h"
#include "cfd/linalg/linear_solver.h"
#include "cfd/parallel/domain_part.h"
#include "cfd/turbulence/turbulence_model.h"

namespace kelvin::cfd {

struct PhysicsOptions {
  double nu = 1e-6;  // kinematic viscosity, m^2/s
  // Optional momentum source per unit mass s(x, t) in m/s^2 (body force,
  // manufactured-solution source).
  std::function<Vector3(const Vector3& x, double t)> source;
  void Validate() const;
};

struct PimpleOptions {
  int n_outer = 1;          // outer correctors (1 = PISO)
  int n_correctors = 2;     // pressure (PISO) correctors per outer iteration
  int n_non_orthogonal = 0; // extra pressure solves per corrector
  bool momentum_predictor = true;
  // Under-relaxation of the non-final outer iterations and of the final one.
  double relax_U = 1.0;
  double relax_p = 1.0;
  double relax_U_final = 1.0;
  double relax_p_final = 1.0;
  // Residual control: outer iterations stop once the initial residuals of U
  // and p of an outer iteration fall below these (0 = run all n_outer).
  double outer_tolerance_U = 0.0;
  double outer_tolerance_p = 0.0;
  LinearSolverOptions momentum_solver;
  LinearSolverOptions pressure_solver = DefaultPressureSolver();
  // Relative tolerance of the last pressure solve of a time step (pFinal).
  double pressure_final_relative_tolerance = 1e-8;
  // Reference cell for a pressure level when no boundary fixes it.
  int p_ref_cell = 0;
  double p_ref_value = 0.0;
  void Validate() const;
  static LinearSolverOptions DefaultPressureSolver() {
    LinearSolverOptions o;
    o.type = LinearSolverOptions::Type::kPcgAmg;
    o.relative_tolerance = 1e-6;
    return o;
  }
};

struct StepSummary {
  int step = 0;
  double time = 0.0;
  double courant_max = 0.0;
  int courant_cell = -1;  // the cell of courant_max (-1: no cells)
  int outer_iterations = 0;
  bool outer_converged = false;
  double initial_residual_U = 0.0;  // first outer iteration, max over components
  double initial_residual_p = 0.0;  // first pressure solve of the step
  int pressure_iterations = 0;      // total over the step
  int momentum_iterations = 0;
  // max over cells of |sum_f F_f| / sum_f |F_f| after the last correction.
  double continuity_error = 0.0;
  // |sum of boundary fluxes| / sum |boundary fluxes|.
  double global_mass_imbalance = 0.0;
  bool finite = true;
};

class PimpleSolver {
 public:
  // On a decomposed mesh `mesh` is the rank's local mesh and `part` its
  // DomainPart (docs/formulation.md section 13): the steps are the serial
  // ones on the owned cells, with the ghost cells refreshed after every
  // update of a cell array that faces read, and the reductions (Courant
  // number, continuity, residuals) global. p_ref_cell is then a cell of the
  // undecomposed mesh. The fields' values must be current on the ghosts at
  // the first step. A turbulence model must be built on the same part
  // (KOmegaSst's `part`). Not yet on ranks: conditions with their own
  // unknowns (the linearized free surface).
  PimpleSolver(const Mesh& mesh, PhysicsOptions physics, SchemeOptions schemes, PimpleOptions pimple,
               std::unique_ptr<VectorField> U, std::unique_ptr<ScalarField> p,
               std::shared_ptr<const DomainPart> part = nullptr);

  // Advances one time step of size dt (s).
  StepSummary Step(double dt);

  double time() const { return time_; }
  int step() const { return step_; }
  const Mesh& mesh() const { return mesh_; }
  VectorField& U() { return *U_; }
  const VectorField& U() const { return *U_; }
  ScalarField& p() { return *p_; }
  const ScalarField& p() const { return *p_; }
  // Absolute volume flux on every face (m^3/s).
  const std::vector<double>& flux() const { return phi_; }
  // Mesh-motion hook: F_mesh on every face (m^3/s).
  void SetMeshFlux(std::vector<double> mesh_flux);
  // RANS closure (null: laminar). The momentum equation then takes its
  // stress term from the model (TurbulenceModel::AddDivDevReff: the face
  // viscosities nu + nu_t, with the wall-function values on walls, and the
  // explicit div(nu_eff dev2(grad(U)^T)) term); the model is corrected once
  // per time step after the final outer iteration.
  void SetTurbulence(std::unique_ptr<TurbulenceModel> model);
  TurbulenceModel* turbulence() { return turbulence_.get(); }
  const TurbulenceModel* turbulence() const { return turbulence_.get(); }
  // Effective viscosity nu (+ nu_t) on face f (m^2/s): what the momentum
  // equation uses, so wall shear forces computed from it are consistent.
  double FaceViscosity(int f) const { return turbulence_ ? turbulence_->nu_eff_faces()[f] : physics_.nu; }
  // The model's summary of the last step (zeros when laminar).
  const TurbulenceSummary& turbulence_summary() const { return turbulence_summary_; }
  // Moving-mesh stage ("moveMesh", before the momentum predictor): each step
  // calls motion(t_new, mesh_flux), which places the mesh at time t_new and
  // fills the mesh flux F_mesh (cfd/motion/mesh_motion.h). The solver then
  // refreshes its cached geometry and carries the old fluxes of the
  // Rhie-Chow transient term to the new face orientation. Also called at
  // the start and on SetState, so a restart sees the same placement.
  using MeshMotion = std::function<void(double t, std::vector<double>& mesh_flux)>;
  void SetMeshMotion(MeshMotion motion) { mesh_motion_ = std::move(motion); }
  // Called after each outer iteration of a step with its index (couplers of
  // the run driver: body motion, propeller and rudder forces).
  using OuterIterationHook = std::function<void(int outer)>;
  void SetOuterIterationHook(OuterIterationHook hook) { outer_hook_ = std::move(hook); }
  // Momentum source per unit mass on each cell (m/s^2, earth axes), set by
  // couplers between outer iterations (the propeller's and rudder's body
  // forces) and added to physics.source; empty (the default) is none. It is
  // not part of State: the coupler that sets it restores it on restart.
  void SetCellSource(std::vector<Vector3> source);
  const std::vector<Vector3>& cell_source() const { return cell_source_; }
  // Recomputes the geometry the solver caches (least-squares gradient
  // vectors, non-orthogonal and skewness corrections) after the mesh moved.
  void RefreshGeometry();
  const PimpleOptions& options() const { return pimple_; }
  // The rank's part of a decomposed mesh (null: serial).
  const DomainPart* part() const { return part_.get(); }

  // Full state for checkpoints: continuing from a restored state gives the
  // same results bit for bit.
  struct State {
    double time = 0.0;
    int step = 0;
    double last_dt = 0.0;
    std::vector<Vector3> U;
    std::vector<std::vector<Vector3>> U_old;
    std::vector<double> p;
    std::vector<double> phi;
    std::vector<std::vector<double>> phi_old;
    std::vector<std::vector<double>> bc_state;  // per U patch then per p patch
    std::vector<std::pair<std::string, std::vector<double>>> turbulence;  // the model's named arrays
  };
  State GetState() const;
  void SetState(const State& state);

 private:
  // The faces' first moments and curvature tensors (curvature correction).
  void UpdateCurvatureGeometry();
  void Initialize();
  // Runs the moving-mesh stage at time_ (no-op without a motion).
  void MoveMesh(bool carry_old_fluxes);
  void AssembleMomentum(double dt, std::span<const double> flux_rel);
  double SolveMomentum(const std::vector<Vector3>& grad_p, StepSummary& summary);
  void PressureCorrector(double dt, bool final_corrector, double alpha_U, double alpha_p,
                         const std::vector<Vector3>& U_prev, const std::vector<double>& phi_prev,
                         StepSummary& summary, bool first_pressure_solve);
  // Rhie-Chow flux of HbyA on every face with the transient and the
  // relaxation-consistent terms, and rAU on the faces.
  void FluxHbyA(double dt, bool backward, double alpha_U, const std::vector<Vector3>& U_prev,
                const std::vector<double>& phi_prev, const std::vector<double>& rAU, const std::vector<Vector3>& HbyA,
                std::vector<double>& rAUf, std::vector<double>& phi_HbyA);
  // The pressure equation laplacian(rAU, p) == div(phiHbyA), solved
  // 1 + n_non_orthogonal times; leaves the conservative flux
  // F = phiHbyA - rAU |S| snGrad(p) of the last solve in phi_.
  void SolvePressure(std::span<const double> rAUf, std::span<const double> phi_HbyA, bool final_corrector,
                     bool first_pressure_solve, StepSummary& summary);
  // F - F_mesh on every face (refreshed on each call).
  std::span<const double> RelativeFlux();
  double ContinuityError(double* global) const;
  // Courant number max and its cell (a cell of the undecomposed mesh on ranks).
  void Courant(double dt, StepSummary& summary) const;
  // Ghost refresh of a cell array (nothing when serial).
  template <typename T>
  void Sync(std::vector<T>& values) const {
    UpdateGhosts(part_.get(), values);
  }
  bool Parallel() const { return part_ && part_->parallel(); }
  int OwnedCells() const { return cfd::OwnedCells(part_.get(), mesh_); }
  // The local reference cell of the pressure level, -1 when another rank owns it.
  int ReferenceCell() const;

  const Mesh& mesh_;
  std::shared_ptr<const DomainPart> part_;
  PhysicsOptions physics_;
  SchemeOptions schemes_;
  PimpleOptions pimple_;
  std::unique_ptr<VectorField> U_;
  std::unique_ptr<ScalarField> p_;
  std::vector<double> phi_;
  std::vector<std::vector<double>> phi_old_;
  std::vector<double> mesh_flux_;
  MeshMotion mesh_motion_;
  OuterIterationHook outer_hook_;
  std::vector<double> flux_rel_;
  bool non_orth_correction_ = true;
  double time_ = 0.0;
  int step_ = 0;
  double last_dt_ = 0.0;
  bool initialized_ = false;

  Gradient grad_;
  NonOrthGeometry non_orth_;
  FvMatrix<Vector3> UEqn_;
  FvMatrix<double> pEqn_;
  // Work arrays of SolvePressure, kept across correctors.
  struct PressureScratch {
    std::vector<double> face_corr, known_flux, diag, rhs, laplacian_flux;
  };
  PressureScratch pressure_scratch_;
  // One matrix with the mesh sparsity, refilled for each momentum component
  // and for the pressure (the AMG solver keeps its own copy).
  SparseSystem system_;
  std::unique_ptr<LinearSolver> momentum_solver_;
  std::unique_ptr<LinearSolver> pressure_solver_;
  // Velocity components that are solved (false for the normal of the empty
  // patches of a 2D mesh; that component stays zero).
  std::array<bool, 3> solve_component_ = {true, true, true};
  std::vector<Matrix3> grad_U_;
  std::vector<Matrix3> grad_U_old_;   // gradient of U at the start of the step (skew correction)
  std::vector<Matrix3> grad_HbyA_;
  std::vector<Vector3> skew_;  // internal faces, only with skew correction
  std::vector<Matrix3> curvature_;  // internal faces, only with the curvature correction
  std::vector<Matrix3> moments_;    // internal faces' first moments M_f, the same
  std::unique_ptr<Gradient> hessian_gradient_;  // least squares, for the Hessians of the same
  std::vector<Vector3> grad_p_;
  std::vector<Vector3> source_;
  std::vector<Vector3> cell_source_;
  std::unique_ptr<TurbulenceModel> turbulence_;
  TurbulenceSummary turbulence_summary_;
};

}  // namespace kelvin::cfd
