// Interface between the PIMPLE solver and a RANS turbulence model
// (architecture: the turbulenceCorrector stage). The model adds the stress
// term div(dev(R_eff)) to the momentum equation (AddDivDevReff, from the
// effective viscosity nu + nu_t on every face; on walls the wall-function
// value that carries the wall shear stress), and the solver calls Correct()
// after the pressure correctors of each time step with the current
// velocity, its gradient and the relative face flux. Without a model the
// solver uses AddLaminarDivDevReff (docs/formulation.md sections 4.2 and 8).
#pragma once

#include <span>
#include <string>
#include <utility>
#include <vector>

#include "cfd/field/field.h"
#include "cfd/fv/fv_matrix.h"
#include "cfd/fv/gradient.h"
#include "cfd/parallel/domain_part.h"
#include "cfd/turbulence/wall_stats.h"

namespace kelvin::cfd {

// What a model does on each patch (TurbulencePatchRoles derives it from the
// velocity and pressure conditions; docs/formulation.md section 8.1).
enum class TurbulencePatchRole {
  kInflow,    // fixed k and omega from the inflow turbulence
  kOutflow,   // inflow values where the flux enters, zero gradient where it leaves
  kWall,      // wall functions / low-Re wall treatment
  kSymmetry,  // zero gradient (slip walls, symmetry planes, the free surface)
  kEmpty,     // front and back of 2D meshes
};

// The turbulence role of a patch from the roles of its conditions, in this
// order: an empty, inflow, wall or symmetry velocity condition gives kEmpty,
// kInflow, kWall or kSymmetry; otherwise the free-surface pressure condition
// gives kSymmetry and anything else (zero gradient, inletOutlet, farField
// velocity) kOutflow.
inline TurbulencePatchRole TurbulencePatchRoleOf(const BoundaryCondition<Vector3>& U,
                                                 const BoundaryCondition<double>& p) {
  switch (U.role()) {
    case PatchRole::kEmpty:
      return TurbulencePatchRole::kEmpty;
    case PatchRole::kInflow:
      return TurbulencePatchRole::kInflow;
    case PatchRole::kWall:
      return TurbulencePatchRole::kWall;
    case PatchRole::kSymmetry:
      return TurbulencePatchRole::kSymmetry;
    default:
      break;
  }
  return p.role() == PatchRole::kFreeSurface ? TurbulencePatchRole::kSymmetry : TurbulencePatchRole::kOutflow;
}

// One role per mesh patch, from the conditions of U and p.
inline std::vector<TurbulencePatchRole> TurbulencePatchRoles(const VectorField& U, const ScalarField& p) {
  KELVIN_CHECK(U.n_patches() == p.n_patches(), "U and p on the same patches");
  std::vector<TurbulencePatchRole> roles;
  for (int k = 0; k < U.n_patches(); ++k) {
    // The ghost cells' outer faces of a decomposed mesh: values overwritten by the halo.
    const bool processor = U.mesh().patches()[k].kind == PatchKind::kProcessor;
    roles.push_back(processor ? TurbulencePatchRole::kSymmetry : TurbulencePatchRoleOf(U.bc(k), p.bc(k)));
  }
  return roles;
}

struct TurbulenceInputs {
  const VectorField& U;
  const std::vector<Matrix3>& grad_U;  // J(i, j) = du_i / dx_j per cell
  std::span<const double> flux;        // relative volume flux F - F_mesh on every face (m^3/s)
  double dt = 0.0;                     // s
  double time = 0.0;                   // s
};

struct TurbulenceSummary {
  double initial_residual_k = 0.0;
  double initial_residual_omega = 0.0;
  int iterations = 0;
  // Cells whose value the bound step lifted to the floor after a solve (a
  // non-zero count is reported; with bounded convection it stays zero).
  int bounded_k = 0;
  int bounded_omega = 0;
};

// A cell field for output (VTK): components 1 or 3, n_cells * components values.
struct TurbulenceOutput {
  std::string name;
  int components = 1;
  std::vector<double> values;
};

class TurbulenceModel {
 public:
  virtual ~TurbulenceModel() = default;
  virtual std::string name() const = 0;
  // The decomposition the model was built on (null: serial).
  virtual const DomainPart* part() const { return nullptr; }
  // Computes nu_t and the wall quantities from the initial fields.
  virtual void Initialize(const VectorField& U, std::span<const double> flux) = 0;
  virtual TurbulenceSummary Correct(const TurbulenceInputs& in) = 0;
  // The mesh moved rigidly: recompute cached geometry (gradient vectors,
  // non-orthogonal corrections). Wall distances do not change.
  virtual void RefreshGeometry() = 0;
  // nu + nu_t on every face (m^2/s).
  virtual const std::vector<double>& nu_eff_faces() const = 0;
  // div(dev(R_eff)) of the momentum equation on its left-hand side
  // (OpenFOAM's divDevReff(U); docs/formulation.md section 4.2), with
  // nu_eff = nu_eff_faces():
  //   -div(nu_eff grad(U))           implicit; its non-orthogonal part
  //                                  explicit from grad_U when asked
  //   -div(nu_eff dev2(grad(U)^T))   explicit from grad_U
  // grad_U: J(i, j) = du_i / dx_j per cell.
  virtual void AddDivDevReff(FvMatrix<Vector3>& UEqn, const VectorField& U, const std::vector<Matrix3>& grad_U,
                             const NonOrthGeometry& geo, bool non_orthogonal_correction) const {
    const std::span<const double> nu_eff(nu_eff_faces());
    AddLaplacian(UEqn, U, nu_eff, geo, non_orthogonal_correction ? &grad_U : nullptr);
    AddDivDev2Transpose(UEqn, nu_eff, grad_U);
  }
  // Turbulent viscosity per cell (m^2/s).
  virtual const std::vector<double>& nu_t() const = 0;
  // Kinematic wall shear stress vector per boundary face (index face -
  // n_internal_faces; zero off the walls), m^2/s^2, acting on the wall.
  virtual const std::vector<Vector3>& wall_shear_stress() const = 0;
  // y+ per boundary face (zero off the walls).
  virtual const std::vector<double>& y_plus() const = 0;
  virtual std::vector<WallPatchStats> WallStats() const = 0;
  // Cell fields for output (k, omega, nu_t; y+ and wall shear in wall cells).
  virtual std::vector<TurbulenceOutput> CellOutputs() const = 0;
  // Full state for checkpoints (named arrays) and its restore.
  virtual std::vector<std::pair<std::string, std::vector<double>>> State() const = 0;
  virtual void SetState(const std::vector<std::pair<std::string, std::vector<double>>>& state) = 0;
};

// The laminar div(dev(R_eff)) with the constant viscosity nu (m^2/s), used
// when no turbulence model is set: -div(nu grad(U)) only. The explicit
// -div(nu dev2(grad(U)^T)) part is omitted, as kelvin always has for laminar
// flow: with constant nu it is -nu grad(div U) / 3, zero for a solenoidal U.
inline void AddLaminarDivDevReff(FvMatrix<Vector3>& UEqn, const VectorField& U, double nu,
                                 const std::vector<Matrix3>& grad_U, const NonOrthGeometry& geo,
                                 bool non_orthogonal_correction) {
  AddLaplacian(UEqn, U, nu, geo, non_orthogonal_correction ? &grad_U : nullptr);
}

}  // namespace kelvin::cfd
