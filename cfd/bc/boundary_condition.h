// Boundary conditions. Each patch condition exposes OpenFOAM's four
// coefficients per face:
//   face value      phi_b      = value_internal  * phi_P + value_boundary
//   normal gradient snGrad_b   = gradient_internal * phi_P + gradient_boundary
// (component-wise for vectors), refreshed by Update(). Discretization only
// ever reads these coefficients, so a Robin condition such as the linearized
// free surface (p_b = alpha p_P + beta, with its own per-face unknown eta)
// plugs into the pressure equation without the solver knowing about it.
#pragma once

#include <functional>
#include <memory>
#include <span>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "cfd/mesh/mesh.h"
#include "data/schema/errors.h"

namespace kelvin::cfd {

template <typename T>
struct Traits;
template <>
struct Traits<double> {
  static double Zero() { return 0.0; }
  static double One() { return 1.0; }
  static double Mul(double a, double b) { return a * b; }
  static double CmptAv(double a) { return a; }
  static constexpr int kComponents = 1;
  static double Component(double a, int) { return a; }
  static void SetComponent(double& a, int, double v) { a = v; }
  static double MagSqr(double a) { return a * a; }
};
template <>
struct Traits<Vector3> {
  static Vector3 Zero() { return Vector3::Zero(); }
  static Vector3 One() { return Vector3::Ones(); }
  static Vector3 Mul(const Vector3& a, const Vector3& b) { return a.cwiseProduct(b); }
  static double CmptAv(const Vector3& a) { return a.mean(); }
  static constexpr int kComponents = 3;
  static double Component(const Vector3& a, int i) { return a[i]; }
  static void SetComponent(Vector3& a, int i, double v) { a[i] = v; }
  static double MagSqr(const Vector3& a) { return a.squaredNorm(); }
};

// What the pressure corrector hands to the pressure conditions before it
// assembles the pressure equation, so that a condition with its own unknown
// (the free surface, eta) can fold the predicted boundary flux
//   F_f = flux_HbyA_f - rAUf_f |S_f| snGrad(p)_f
// into implicit coefficients. The spans cover every face of the mesh.
struct PressureCoupling {
  double dt = 0.0;                     // s
  bool backward = false;               // second-order backward (BDF2) in time this step
  std::span<const double> rAUf;        // 1/A of the momentum equation on faces (s)
  std::span<const double> flux_HbyA;   // Rhie-Chow flux of H/A (m^3/s)
};

// What a patch is to the flow, as its condition states it (set by the
// condition's class, or at construction where one class serves two roles:
// a fixed velocity is an inflow or a no-slip wall at rest). The turbulence
// model takes its patch treatment from these (TurbulencePatchRoles in
// cfd/turbulence/turbulence_model.h; docs/formulation.md section 8.1).
enum class PatchRole {
  kUnspecified,  // the condition does not say (zero gradient, mixed)
  kInflow,       // prescribed velocity
  kOutflow,      // inflow or outflow as the flux decides (inletOutlet, farField)
  kWall,         // no-slip wall, at rest or moving
  kSymmetry,     // slip wall or symmetry plane
  kFreeSurface,  // the linearized free surface (a pressure condition)
  kEmpty,        // front and back of a 2D mesh
};

// What a condition may look at when it updates.
struct BcContext {
  const Mesh& mesh;
  const Patch& patch;
  double time = 0.0;                    // s
  std::span<const double> face_flux;    // relative volume flux F - F_mesh on all faces (m^3/s); may be empty
};

template <typename T>
class BoundaryCondition {
 public:
  virtual ~BoundaryCondition() = default;
  // Recomputes the coefficients for the current time, flux and cell values.
  virtual void Update(const BcContext& ctx, std::span<const T> cell_values) = 0;
  virtual std::string type() const = 0;
  virtual PatchRole role() const { return PatchRole::kUnspecified; }
  // True when the face value does not depend on the cell value (fixed
  // velocity: the boundary flux is prescribed).
  virtual bool fixes_value() const { return false; }
  // Hook after the pressure correction with the corrected face flux (the
  // free surface updates eta here).
  virtual void CorrectAfterFlux(const BcContext&, std::span<const double> /*face_flux*/) {}
  // Hook before each pressure solve of a corrector (see PressureCoupling);
  // must refresh the four coefficients if it changes them.
  virtual void PreparePressureSolve(const BcContext&, const PressureCoupling&) {}
  // Named per-face fields of the condition's own unknowns (e.g. eta), for
  // patch output. Like State(), over the whole patch of the undecomposed
  // mesh on every MPI rank (cfd/parallel/state_layout.h passes both as they
  // are).
  virtual std::vector<std::pair<std::string, std::vector<double>>> FaceFields() const { return {}; }
  // Extra per-face state (e.g. eta) for checkpoints.
  virtual std::vector<double> State() const { return {}; }
  virtual void SetState(std::span<const double>) {}

  std::span<const T> value_internal() const { return vi_; }
  std::span<const T> value_boundary() const { return vb_; }
  std::span<const T> gradient_internal() const { return gi_; }
  std::span<const T> gradient_boundary() const { return gb_; }

 protected:
  void Resize(int n) {
    if (static_cast<int>(vi_.size()) == n) return;
    vi_.assign(n, Traits<T>::Zero());
    vb_.assign(n, Traits<T>::Zero());
    gi_.assign(n, Traits<T>::Zero());
    gb_.assign(n, Traits<T>::Zero());
  }
  // 1 / (n . d): inverse normal distance from the cell centre to the face.
  static double DeltaCoeff(const Mesh& mesh, int f) {
    const Vector3 n = mesh.face_areas()[f] / mesh.face_area_magnitudes()[f];
    return 1.0 / std::max(n.dot(mesh.deltas()[f]), 0.05 * mesh.deltas()[f].norm());
  }
  void SetFixed(int i, double dc, const T& value) {
    vi_[i] = Traits<T>::Zero();
    vb_[i] = value;
    gi_[i] = -dc * Traits<T>::One();
    gb_[i] = dc * value;
  }
  void SetZeroGradient(int i) {
    vi_[i] = Traits<T>::One();
    vb_[i] = Traits<T>::Zero();
    gi_[i] = Traits<T>::Zero();
    gb_[i] = Traits<T>::Zero();
  }

  std::vector<T> vi_, vb_, gi_, gb_;
};

// A value prescribed as a function of position and time.
template <typename T>
using ValueFunction = std::function<T(const Vector3& x, double t)>;

// Dirichlet: phi_b = value(x_f, t). For p this is the fixed pressure. The
// role defaults to kInflow for a velocity (kUnspecified for a scalar); a
// no-slip wall at rest is FixedValue<Vector3>(Vector3(0, 0, 0), PatchRole::kWall).
template <typename T>
class FixedValue : public BoundaryCondition<T> {
 public:
  explicit FixedValue(ValueFunction<T> value, PatchRole role = DefaultRole())
      : value_(std::move(value)), role_(role) {}
  explicit FixedValue(const T& uniform, PatchRole role = DefaultRole())
      : value_([uniform](const Vector3&, double) { return uniform; }), role_(role) {}
  void Update(const BcContext& ctx, std::span<const T>) override {
    this->Resize(ctx.patch.size);
    for (int i = 0; i < ctx.patch.size; ++i) {
      const int f = ctx.patch.start + i;
      this->SetFixed(i, this->DeltaCoeff(ctx.mesh, f), value_(ctx.mesh.face_centres()[f], ctx.time));
    }
  }
  std::string type() const override { return "fixedValue"; }
  PatchRole role() const override { return role_; }
  bool fixes_value() const override { return true; }

 private:
  static constexpr PatchRole DefaultRole() {
    return std::is_same_v<T, Vector3> ? PatchRole::kInflow : PatchRole::kUnspecified;
  }
  ValueFunction<T> value_;
  PatchRole role_;
};

// Neumann with zero normal gradient: phi_b = phi_P.
template <typename T>
class ZeroGradient : public BoundaryCondition<T> {
 public:
  void Update(const BcContext& ctx, std::span<const T>) override {
    this->Resize(ctx.patch.size);
    for (int i = 0; i < ctx.patch.size; ++i) this->SetZeroGradient(i);
  }
  std::string type() const override { return "zeroGradient"; }
};

// Front and back of a one-cell-thick 2D mesh: no flux and no diffusion, as
// OpenFOAM's "empty" (the solver does not solve the normal component).
template <typename T>
class Empty : public ZeroGradient<T> {
 public:
  std::string type() const override { return "empty"; }
  PatchRole role() const override { return PatchRole::kEmpty; }
};

// No-slip wall moving rigidly: u_b = U + omega x (x_f - x0). With zero
// rates it is the stationary no-slip wall.
class MovingWall : public BoundaryCondition<Vector3> {
 public:
  struct Motion {
    Vector3 velocity = Vector3::Zero();          // m/s
    Vector3 angular_velocity = Vector3::Zero();  // rad/s
    Vector3 centre = Vector3::Zero();            // m
  };
  explicit MovingWall(std::function<Motion(double t)> motion) : motion_(std::move(motion)) {}
  void Update(const BcContext& ctx, std::span<const Vector3>) override;
  std::string type() const override { return "movingWall"; }
  PatchRole role() const override { return PatchRole::kWall; }
  bool fixes_value() const override { return true; }

 private:
  std::function<Motion(double t)> motion_;
};

// Symmetry plane / slip wall for vectors: u_b = (I - n n) u_P. Also used on
// the front and back of 2D meshes ("empty").
class Slip : public BoundaryCondition<Vector3> {
 public:
  explicit Slip(std::string type = "slip") : type_(std::move(type)) {}
  void Update(const BcContext& ctx, std::span<const Vector3> cell_values) override;
  std::string type() const override { return type_; }
  PatchRole role() const override { return PatchRole::kSymmetry; }
  bool fixes_value() const override { return true; }  // zero normal flux

 private:
  std::string type_;
};

// Inflow value where the relative flux enters (F < 0), zero gradient where it
// leaves.
template <typename T>
class InletOutlet : public BoundaryCondition<T> {
 public:
  explicit InletOutlet(const T& inflow) : inflow_(inflow) {}
  void Update(const BcContext& ctx, std::span<const T>) override {
    this->Resize(ctx.patch.size);
    for (int i = 0; i < ctx.patch.size; ++i) {
      const int f = ctx.patch.start + i;
      const double flux = ctx.face_flux.empty() ? 0.0 : ctx.face_flux[f];
      if (flux < 0.0) {
        this->SetFixed(i, this->DeltaCoeff(ctx.mesh, f), inflow_);
      } else {
        this->SetZeroGradient(i);
      }
    }
  }
  std::string type() const override { return "inletOutlet"; }
  PatchRole role() const override { return PatchRole::kOutflow; }

 private:
  T inflow_;
};

// Mixed (Robin): phi_b = f * ref_value + (1 - f) * (phi_P + ref_gradient / dc)
// with the value fraction f in [0, 1] per face. f = 1 is Dirichlet, f = 0 is
// Neumann. Derived conditions (the free surface) reset the three arrays in
// their own Update() and call Mixed::Update to form the coefficients.
template <typename T>
class Mixed : public BoundaryCondition<T> {
 public:
  Mixed(const T& ref_value, const T& ref_gradient, double fraction)
      : uniform_value_(ref_value), uniform_gradient_(ref_gradient), uniform_fraction_(fraction) {}
  void Update(const BcContext& ctx, std::span<const T>) override {
    if (static_cast<int>(fraction_.size()) != ctx.patch.size) {
      ref_value_.assign(ctx.patch.size, uniform_value_);
      ref_gradient_.assign(ctx.patch.size, uniform_gradient_);
      fraction_.assign(ctx.patch.size, uniform_fraction_);
    }
    this->Resize(ctx.patch.size);
    for (int i = 0; i < ctx.patch.size; ++i) {
      const double dc = this->DeltaCoeff(ctx.mesh, ctx.patch.start + i);
      const double w = fraction_[i];
      this->vi_[i] = (1.0 - w) * Traits<T>::One();
      this->vb_[i] = w * ref_value_[i] + (1.0 - w) * ref_gradient_[i] / dc;
      this->gi_[i] = -w * dc * Traits<T>::One();
      this->gb_[i] = w * dc * ref_value_[i] + (1.0 - w) * ref_gradient_[i];
    }
  }
  std::string type() const override { return "mixed"; }
  std::vector<T>& ref_value() { return ref_value_; }
  std::vector<T>& ref_gradient() { return ref_gradient_; }
  std::vector<double>& fraction() { return fraction_; }

 private:
  T uniform_value_;
  T uniform_gradient_;
  double uniform_fraction_;
  std::vector<T> ref_value_;
  std::vector<T> ref_gradient_;
  std::vector<double> fraction_;
};

}  // namespace kelvin::cfd
