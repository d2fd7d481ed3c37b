// The linearized free-surface condition on the calm-water plane z = 0
// (docs/formulation.md section 3). It is the pressure condition of the
// `freeSurface` patch and owns the wave elevation eta (m) of each face.
//
// Dynamic condition:   p_f = g eta_f + p_a,f   (p kinematic, p_a an optional
//                      applied surface pressure, e.g. a moving pressure patch)
// Kinematic condition, on the 2D face mesh of the patch, relative to the mesh:
//   d eta/dt + div_h(c eta) + mu eta = w,   w = F_f / |S_f|
// with mu >= 0 the damping of the beach and c the velocity that carries the
// pattern relative to the mesh, by one of two linearizations:
//  - uniform stream (Neumann-Kelvin, the default): c = -u_b, with u_b the
//    velocity of the mesh through the still water (div_h c = 0 for rigid
//    in-plane motion, so the conservative and the advective forms agree);
//  - local flow (double-body or Dawson type): c = u_h, the horizontal
//    velocity relative to the mesh of a base flow: the double body (the
//    flow slows and turns about bow and stern). Linearizing the exact
//    condition d eta/dt + u . grad_h eta = w on z = eta about a base flow
//    that is symmetric about z = 0 (w = 0 and dp/dz = 0 there, as in the
//    double body), w(eta) = w(0) + eta dw/dz = w(0) - eta div_h u_h by
//    continuity, and the eta div_h u_h term joins the advection into the
//    same conservative form div_h(u_h eta) (Dawson 1977; the consistency of
//    such linearizations is discussed by Raven 1996). The dynamic condition
//    is unchanged, since dp/dz of the base flow vanishes on z = 0.
//    The base flow is the flow of the last pressure solve under the rigid
//    lid (the double body of the run's start; without a lid, the flow of the
//    first pressure solve), frozen when the surface is released: taken from
//    the running solution, dw/dz would include the wave's own flow, whose
//    vertical decay in a boundary-layer cell a few mm high is that cell's
//    scale, not the wave's, and eta dw/dz, a second-order term, then grows
//    the elevation beside the hull without bound (measured on the Wigley).
//    u_h is the cell mean of the flow under each face, from the cell's
//    fluxes, interpolated linearly to the edges (extrapolated by its
//    least-squares gradient on the rim); no flux crosses a wall.
//
// Time discretization (Euler or BDF2, following the solver) with implicit
// first-order upwind advection; the neighbour values and the second-order
// (linear-upwind) deferred correction are taken from the latest iterate, so
// each face reads
//   eta_f = eta*_f + dt'_f F_f / |S_f|,   1/dt'_f = a_t/dt + mu_f + a_ff
// with a_t = 1 (Euler) or 3/2 (BDF2), a_ff the upwind outflow coefficient and
// eta* all the known parts. The lagged parts converge with the PIMPLE
// correctors and vanish from a converged steady state, which therefore solves
// the fully implicit discrete problem.
//
// Implicit gravity-wave coupling: before each pressure solve the predicted
// boundary flux F_f = F_HbyA,f - D_f (p_f - p_P), D_f = rAUf |S_f| / (n.d),
// is substituted into the dynamic condition, which gives the Robin condition
//   p_f = w_f p_ref,f + (1 - w_f) p_P,   w_f = 1 / (1 + g dt'_f D_f / |S_f|),
//   p_ref,f = g (eta*_f + dt'_f F_HbyA,f / |S_f|) + p_a,f.
// It adds a positive diagonal term to the pressure matrix (symmetric positive
// definite as before) and removes the explicit time-step limit of gravity
// waves. After the pressure solve eta is updated from the corrected flux with
// the same formula, so sum_f eta_f |S_f| changes by exactly the volume that
// crossed the patch.
//
// Outside a pressure solve (momentum predictor, output) the condition is the
// Dirichlet value p_f = g eta_f + p_a,f.
//
// Large Courant numbers (measured on the Kelvin pressure-patch case, 16
// faces per wavelength). Without advection (standing wave) the coupling is
// stable at any step. With advection the lagged upstream neighbour is one
// more fixed point for the PIMPLE correctors: it contracts by C / (1 + C)
// per corrector at the patch Courant number C. Unrelaxed PIMPLE reaches the
// steady pattern at Courant 5 and 20 and diverges at 50 (with or without
// the cap below). Relaxed PIMPLE (U 0.7, p 0.3, 4 outer correctors) at
// Courant 100 (120 at the largest cell) with `kinematic_courant` = 2 reaches
// the same steady pattern as Courant 5 (wavelength within 0.01%), in about
// twice the steps; without the cap it stalls or diverges. Solving the
// upstream coupling inside the pressure equation would need extra face
// unknowns; solving it by an upwind sweep with lagged fluxes amplifies flux
// changes by the Courant number and diverges.

#pragma once

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "cfd/bc/boundary_condition.h"
#include "cfd/freesurface/patch_surface.h"
#include "cfd/parallel/domain_part.h"

namespace kelvin::cfd {

struct LinearizedFreeSurfaceOptions {
  double g = 9.81;  // gravitational acceleration, m/s^2
  // Velocity u_b (m/s, mesh coordinates) of the mesh point x through the
  // still water at time t. The pattern moves with -u_b relative to the mesh;
  // a ship-fixed mesh in a uniform inflow U has u_b = -U. Empty: at rest.
  std::function<Vector3(const Vector3& x, double t)> mesh_velocity;
  // Applied kinematic surface pressure p_a (m^2/s^2), e.g. a moving pressure
  // patch. Empty: none.
  std::function<double(const Vector3& x, double t)> surface_pressure;
  // Face value of eta on the edges of the 2D face mesh: first-order upwind;
  // linear upwind (upwind value plus the least-squares gradient of the
  // upwind face); or QUICK, the mean of linear upwind and linear
  // interpolation (third order on uniform grids: phase error O(k^4 dx^4)
  // against (k dx)^2 / 12 for linear upwind, which matters for the
  // wavelength of the pattern). The high-order parts fall back to first
  // order where the advection direction reverses.
  enum class Advection { kUpwind, kLinearUpwind, kQuick };
  Advection advection = Advection::kLinearUpwind;
  // The velocity that carries the pattern (see the top of this file):
  // -u_b (uniform stream) or the local flow relative to the mesh.
  enum class Linearization { kUniformStream, kLocalFlow };
  Linearization linearization = Linearization::kUniformStream;
  // Clips the high-order face value of the linear-upwind and QUICK schemes
  // to the range of eta over the upwind face and its edge neighbours (a
  // Barth-Jespersen-type limiter). Added for hull grids, whose faces next to
  // the waterline are stretched along the hull (aspect ratios above 100) and
  // where the least-squares gradient extrapolates far outside the local
  // range; the shipped hull cases keep it on. Since the 2026-11-22 fix of
  // the advection direction those cases also converge without it (measured
  // that evening: coarse Wigley R_T 66.03 against 66.19 N with it, DTC
  // 19.497 against 19.462 N, Wigley pattern grid with QUICK: wavelength
  // +6.3% against +6.0%). Off by default (the Kelvin-pattern results were
  // measured without it).
  bool limit_advection = false;
  // Patches across which eta is extrapolated at inflow edges (the hull
  // waterline, where the pattern leaves the hull). On every other inflow
  // edge of the patch rim eta = 0 (undisturbed water comes in).
  std::vector<std::string> waterline_patches;

  // Steady (pseudo-transient) runs only: caps the time step of the
  // kinematic condition per face at kinematic_courant times the advection
  // time across the face (local time stepping). It leaves a converged steady
  // state unchanged but makes transients non-physical. 0 = off. With the
  // local flow, a face where the flow converges (more lagged inflow than
  // outflow, toward a stagnation point) also gets the difference, so that its
  // diagonal exceeds the inflow (docs/formulation.md section 3.7).
  double kinematic_courant = 0.0;

  // Damping beach: mu(x) = mu_max s(1 - d/W), with d the distance to the
  // nearest chosen side of the patch's bounding box, W = width * lambda,
  // lambda = 2 pi U^2 / g the transverse wavelength at the reference speed
  // U, mu_max = strength * g / U (the encounter frequency of the transverse
  // waves) and s the smooth ramp 3 x^2 - 2 x^3.
  struct Beach {
    enum class Side { kXMin, kXMax, kYMin, kYMax };
    double width = 0.0;            // in transverse wavelengths; 0 = no beach
    double strength = 1.0;         // mu_max U / g
    double reference_speed = 0.0;  // U, m/s
    std::vector<Side> sides;
  };
  Beach beach;

  // Throws ConfigError naming the option and the value.
  void Validate() const;
};

// A run on MPI ranks (docs/formulation.md section 13): the rank's faces of
// the patch are part of the patch of the undecomposed mesh. The kinematic
// condition is solved on that whole 2D face mesh on every rank (the same
// arithmetic in the same order as serially); each rank sets the pressure
// condition of its own faces, and after each flux correction the ranks'
// new elevations are gathered, so every rank holds all of eta.
struct FreeSurfaceOnRanks {
  const Mesh* whole = nullptr;  // the undecomposed mesh; read only by the constructor
  std::shared_ptr<const DomainPart> part;
};

class LinearizedFreeSurface : public Mixed<double> {
 public:
  // Throws ConfigError if the patch is not a manifold face mesh in z = 0
  // with outward normal +z, or if the options are invalid. `mesh` is the
  // mesh the solver runs on (on ranks: the rank's local mesh, with `ranks`
  // naming the whole one and the part; collective then).
  LinearizedFreeSurface(const Mesh& mesh, int patch_index, LinearizedFreeSurfaceOptions options,
                        FreeSurfaceOnRanks ranks = {});

  void Update(const BcContext& ctx, std::span<const double> cell_values) override;
  void PreparePressureSolve(const BcContext& ctx, const PressureCoupling& coupling) override;
  void CorrectAfterFlux(const BcContext& ctx, std::span<const double> face_flux) override;
  std::string type() const override { return "linearizedFreeSurface"; }
  PatchRole role() const override { return PatchRole::kFreeSurface; }
  std::vector<std::pair<std::string, std::vector<double>>> FaceFields() const override;
  // Faces whose elevation steps by more than `jump` (m) from an edge
  // neighbour's, on the larger side of the step. A wave resolved by the
  // surface mesh changes between faces by at most its amplitude (about U^2 /
  // 2g at most, the stagnation rise) times k dx, about 1/2 or less with 12 or
  // more faces per transverse wavelength: the resistance report checks the
  // steps against U^2 / 4g (docs/formulation.md section 3.1).
  std::vector<int> UnresolvedSteps(double jump) const;
  // Face fields, state, eta(), damping() and surface() cover the whole patch
  // (the undecomposed mesh's patch faces, in its order) on every rank, so
  // they do not depend on the partition.
  // [time, started, old levels, rigid lid, eta, eta^n, eta^{n-1}] (old
  // levels padded with zeros), then, once the local flow's base flow is set,
  // its edge fluxes and face velocities (u, v); SetState also reads the older
  // layout without the rigid-lid flag.
  // SetState of an empty state (the checkpoint of a run without the free
  // surface, e.g. a converged double body) starts from calm water.
  std::vector<double> State() const override;
  void SetState(std::span<const double> state) override;

  // Rigid lid: while set, the patch passes no flux (the double-body
  // condition: zero normal flux, p free) and eta stays as it is. Steady
  // resistance runs start this way and then release the surface, because an
  // impulsive start of the free-surface flow raises a bow wave several times
  // the stagnation head that diverges on hull grids (cfd/freesurface/
  // resistance.h). Kept in the checkpoint state.
  void SetRigidLid(bool rigid) { rigid_lid_ = rigid; }
  bool rigid_lid() const { return rigid_lid_; }
  // Wave elevation per patch face (m), patch face order.
  const std::vector<double>& eta() const { return eta_; }
  // Sets eta (initial condition); the next time step takes it as eta^n.
  void SetEta(std::span<const double> eta);
  // Volume stored in the elevation, sum_f eta_f |S_f| (m^3).
  double Volume() const;
  // Beach damping per face (1/s).
  const std::vector<double>& damping() const { return mu_; }
  const PatchSurface& surface() const { return surface_; }
  const LinearizedFreeSurfaceOptions& options() const { return options_; }

 private:
  // Starts a new time level when ctx.time moves on.
  void AdvanceTime(double time);
  // Face value of the applied pressure at time t (surface face i).
  double SurfacePressure(int i, double time) const;
  // Local flow: sets the base flow (all ranks' faces and edges) from the
  // relative fluxes of ctx.
  void SetBaseFlow(const BcContext& ctx);
  // The local flow's face fields: the base flow, its horizontal divergence
  // (the rate at which the conservative form feeds eta where it converges)
  // and each face's gain, inflow from other faces over outflow (the inflow
  // of undisturbed water or of the waterline across the rim not counted).
  void AppendBaseFlowFields(std::vector<std::pair<std::string, std::vector<double>>>& fields) const;
  // The advecting velocity c at surface face i.
  Vector3 StreamAtFace(int i, double t) const;
  // The known part eta*_f and the implicit diagonal of every surface face
  // (the advection, the beach and the local pseudo-time included).
  void AssembleKinematic(double t, double dt, bool bdf2, std::vector<double>& known, std::vector<double>& diag);

  const Mesh& mesh_;
  int patch_index_;
  LinearizedFreeSurfaceOptions options_;
  PatchSurface surface_;
  // The surface face of each face of the patch in `mesh_` (the identity serially).
  std::vector<int> surface_face_;
  // On ranks: the part, and the surface face of each value the gather of
  // the ranks' new elevations returns (rank by rank).
  std::shared_ptr<const DomainPart> part_;
  std::vector<int> gathered_faces_;
  std::vector<char> extrapolate_rim_;  // per edge: inflow extrapolates eta (waterline)
  std::vector<double> mu_;
  // The local flow's base flow (empty until set): the velocity under each
  // surface face and the flux of each edge, c . n_e |e| out of edge.face (m^2/s).
  std::vector<Vector3> base_velocity_;
  std::vector<double> base_edge_flux_;
  std::vector<double> eta_;
  std::vector<std::vector<double>> eta_old_;  // eta^n, eta^{n-1}
  double time_ = 0.0;
  bool started_ = false;
  bool rigid_lid_ = false;
  // Set by PreparePressureSolve, consumed by CorrectAfterFlux.
  bool armed_ = false;
  std::vector<double> eta_star_;
  std::vector<double> dt_eff_;
  // Scratch.
  std::vector<Vector3> grad_;
  std::vector<double> edge_flux_;
  std::vector<double> eta_min_, eta_max_;  // limiter range per face
  std::vector<char> waterline_fed_;       // per face: inflow across the hull waterline (first order)
  std::vector<double> inflow_;            // per face: the lagged upwind inflow rate (1/s)
};

}  // namespace kelvin::cfd
