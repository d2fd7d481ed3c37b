// Unit tests of the linearized free surface (its 2D face mesh:
// patch_surface_test.cc): the Robin coefficients of the implicit gravity-wave coupling and the
// elevation update (Euler and BDF2), the kinematic advection on the patch,
// the local-flow linearization, the beach, checkpoint state, the rigid-lid
// start, the first-order faces behind a hull waterline, and the errors for a
// patch off z = 0.
#include "cfd/freesurface/linearized_free_surface.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <numbers>
#include <random>

#include "cfd/mesh/box_mesh.h"
#include "data/schema/errors.h"
#include "tests/cfd/freesurface/free_surface_test_support.h"

namespace kelvin::cfd {
namespace {

using testing::Box;

TEST(LinearizedFreeSurface, PatchOffTheCalmWaterPlaneIsAConfigError) {
  const Mesh mesh = Box({3, 3, 2});
  for (const char* name : {"zmin", "xmax"}) {
    try {
      LinearizedFreeSurface bc(mesh, mesh.FindPatch(name), {});
      FAIL() << name;
    } catch (const ConfigError& e) {
      EXPECT_NE(std::string(e.what()).find("not in the calm-water plane"), std::string::npos)
          << e.what();
      EXPECT_NE(std::string(e.what()).find(name), std::string::npos) << e.what();
    }
  }
  // The top of a box that ends at z = 0.2 is horizontal but not at z = 0.
  const Mesh high = Box({3, 3, 2}, false, Vector3(0, 0, -1), Vector3(1, 1, 0.2));
  EXPECT_THROW(LinearizedFreeSurface(high, high.FindPatch("zmax"), {}), ConfigError);
}

TEST(LinearizedFreeSurface, OptionsAreValidated) {
  LinearizedFreeSurfaceOptions o;
  o.g = -9.81;
  EXPECT_THROW(o.Validate(), ConfigError);
  o = {};
  o.beach.width = 1.0;  // no reference speed, no sides
  EXPECT_THROW(o.Validate(), ConfigError);
  o.beach.reference_speed = 1.0;
  EXPECT_THROW(o.Validate(), ConfigError);
  o.beach.sides = {LinearizedFreeSurfaceOptions::Beach::Side::kXMax};
  EXPECT_NO_THROW(o.Validate());
  o.beach.strength = 0.0;
  EXPECT_THROW(o.Validate(), ConfigError);
}

// Robin coefficients against the formulas of the header, then the solver's
// boundary flux from them, the elevation update, and p_f = g eta + p_a.
TEST(LinearizedFreeSurface, RobinCoefficientsAndConsistentElevationUpdate) {
  const Mesh mesh = Box({4, 3, 2}, true);
  const int top = mesh.FindPatch("zmax");
  const Patch& patch = mesh.patches()[top];
  constexpr double kG = 9.81, kPa = 0.3;
  LinearizedFreeSurfaceOptions o;
  o.g = kG;
  o.surface_pressure = [](const Vector3&, double) { return kPa; };
  LinearizedFreeSurface bc(mesh, top, o);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const int n = patch.size;
  std::vector<double> eta0(n);
  for (double& e : eta0) e = 0.01 * u(rng);
  bc.SetEta(eta0);
  std::vector<double> cells(mesh.n_cells());
  for (double& c : cells) c = u(rng);

  // Outside a pressure solve: Dirichlet p_f = g eta + p_a.
  bc.Update(BcContext{mesh, patch, 0.0, {}}, cells);
  for (int i = 0; i < n; ++i) {
    EXPECT_EQ(bc.value_internal()[i], 0.0);
    EXPECT_NEAR(bc.value_boundary()[i], kG * eta0[i] + kPa, 1e-14);
  }

  std::vector<double> rAUf(mesh.n_faces()), phi_HbyA(mesh.n_faces()), flux(mesh.n_faces(), 0.0);
  std::vector<double> eta_prev = eta0, eta_prev2;
  const double dt = 0.1;
  for (int step = 1; step <= 2; ++step) {
    const double t = step * dt;
    for (double& r : rAUf) r = 0.05 * (1.5 + u(rng));
    for (double& f : phi_HbyA) f = 0.01 * u(rng);
    const bool backward = step == 2;
    const BcContext ctx{mesh, patch, t, flux};
    bc.Update(ctx, cells);  // starts the new time level
    bc.PreparePressureSolve(ctx, PressureCoupling{dt, backward, rAUf, phi_HbyA});
    const double a_t = backward ? 1.5 : 1.0;
    for (int i = 0; i < n; ++i) {
      const int f = patch.start + i;
      const double mag = mesh.face_area_magnitudes()[f];
      const Vector3 nf = mesh.face_areas()[f] / mag;
      const double dc = 1.0 / nf.dot(mesh.deltas()[f]);
      const double dt_eff = dt / a_t;
      const double eta_star =
          backward ? (2.0 * eta_prev[i] - 0.5 * eta_prev2[i]) / 1.5 : eta_prev[i];
      const double D = rAUf[f] * mag * dc;
      const double w = 1.0 / (1.0 + kG * dt_eff * D / mag);
      const double ref = kG * (eta_star + dt_eff * phi_HbyA[f] / mag) + kPa;
      EXPECT_NEAR(bc.value_internal()[i], 1.0 - w, 1e-14);
      EXPECT_NEAR(bc.value_boundary()[i], w * ref, 1e-14);
      // Negative: a positive diagonal term in the pressure matrix (SPD).
      EXPECT_LT(bc.gradient_internal()[i], 0.0);
      EXPECT_NEAR(bc.gradient_internal()[i], -w * dc, 1e-12 * dc);
      EXPECT_NEAR(bc.gradient_boundary()[i], w * dc * ref, 1e-12 * dc);
    }
    // The solver's boundary flux from these coefficients, then eta.
    for (int i = 0; i < n; ++i) {
      const int f = patch.start + i;
      const double sn_grad =
          bc.gradient_internal()[i] * cells[mesh.owner()[f]] + bc.gradient_boundary()[i];
      flux[f] = phi_HbyA[f] - rAUf[f] * mesh.face_area_magnitudes()[f] * sn_grad;
    }
    const double volume_before = bc.Volume();
    bc.CorrectAfterFlux(ctx, flux);
    double sum_flux = 0.0;
    for (int i = 0; i < n; ++i) {
      const int f = patch.start + i;
      const double p_f = bc.value_internal()[i] * cells[mesh.owner()[f]] + bc.value_boundary()[i];
      EXPECT_NEAR(kG * bc.eta()[i] + kPa, p_f, 1e-13);
      sum_flux += flux[f];
    }
    if (!backward) {
      EXPECT_NEAR(bc.Volume(), volume_before + dt * sum_flux, 1e-16);
    }
    eta_prev2 = eta_prev;
    eta_prev = bc.eta();
  }
}

// The kinematic condition alone (zero flux): a bump advected with c = -u_b
// on an 80 x 4 patch (long enough that the downstream tail of implicit
// upwinding stays inside). Conservative upwinding moves the centroid by exactly
// U dt per step and keeps the volume; the first-order scheme keeps eta >= 0;
// the lagged parts converge over repeated corrector calls.
// Pure advection of the elevation of `bc` (no flux through the surface):
// `steps` steps of dt, each with 40 lagged corrector passes; `after_step`
// runs after each step.
template <typename F>
void AdvectEta(LinearizedFreeSurface& bc, const Mesh& mesh, const Patch& patch, double dt, int steps, F&& after_step) {
  const std::vector<double> zero(mesh.n_faces(), 0.0);
  bc.Update(BcContext{mesh, patch, 0.0, zero}, {});
  for (int step = 1; step <= steps; ++step) {
    const BcContext ctx{mesh, patch, step * dt, zero};
    bc.Update(ctx, {});
    for (int it = 0; it < 40; ++it) {
      bc.PreparePressureSolve(ctx, PressureCoupling{dt, false, zero, zero});
      bc.CorrectAfterFlux(ctx, zero);
    }
    after_step();
  }
}

TEST(LinearizedFreeSurface, AdvectionMovesTheCentroidAtTheMeshSpeed) {
  const Mesh mesh = Box({80, 4, 1}, false, Vector3(0, 0, -0.1), Vector3(8, 0.4, 0));
  const int top = mesh.FindPatch("zmax");
  const Patch& patch = mesh.patches()[top];
  constexpr double kU = 0.7;
  using Advection = LinearizedFreeSurfaceOptions::Advection;
  for (Advection scheme : {Advection::kUpwind, Advection::kLinearUpwind, Advection::kQuick}) {
    LinearizedFreeSurfaceOptions o;
    o.mesh_velocity = [](const Vector3&, double) { return Vector3(-kU, 0.0, 0.0); };
    o.advection = scheme;
    LinearizedFreeSurface bc(mesh, top, o);
    std::vector<double> eta(patch.size);
    for (int i = 0; i < patch.size; ++i)
      eta[i] = std::exp(-std::pow((bc.surface().centres()[i].x() - 1.2) / 0.25, 2));
    bc.SetEta(eta);
    auto centroid = [&]() {
      double m = 0.0, mx = 0.0;
      for (int i = 0; i < patch.size; ++i) {
        m += bc.eta()[i] * bc.surface().areas()[i];
        mx += bc.eta()[i] * bc.surface().areas()[i] * bc.surface().centres()[i].x();
      }
      return std::pair{m, mx / m};
    };
    const auto [m0, x0] = centroid();
    const double dt = 0.05;  // Courant number 0.35
    double min_eta = 0.0;
    AdvectEta(bc, mesh, patch, dt, 20, [&] {
      for (double e : bc.eta()) min_eta = std::min(min_eta, e);
    });
    const auto [m1, x1] = centroid();
    EXPECT_NEAR(m1, m0, 1e-12 * m0);
    EXPECT_NEAR(x1 - x0, kU * 20 * dt, 1e-9);
    if (scheme == Advection::kUpwind) {
      EXPECT_GE(min_eta, 0.0);
    }
  }
}

// The discretization has no preferred direction: a hump advected toward +x
// and its mirror image advected toward -x stay mirror images, and the
// high-order schemes keep more of the peak than first-order upwinding in
// both directions. (Before 2026-11-22 the high-order correction was dropped
// on every edge whose upwind face is the edge's neighbour, i.e. for advection
// against the edge orientation: hull cases, whose stream runs toward -x,
// were first order everywhere and lost their waves within a wavelength.)
TEST(LinearizedFreeSurface, AdvectionIsTheSameInBothDirections) {
  const Mesh mesh = Box({80, 4, 1}, false, Vector3(0, 0, -0.1), Vector3(8, 0.4, 0));
  const int top = mesh.FindPatch("zmax");
  const Patch& patch = mesh.patches()[top];
  constexpr double kU = 0.7, kDt = 0.1;  // Courant number 0.7
  using Advection = LinearizedFreeSurfaceOptions::Advection;
  // eta after 30 steps of pure advection at mesh velocity (sign * kU, 0)
  // from a hump at x0.
  auto advect = [&](Advection scheme, double sign, double x0) {
    LinearizedFreeSurfaceOptions o;
    o.mesh_velocity = [sign](const Vector3&, double) { return Vector3(sign * kU, 0.0, 0.0); };
    o.advection = scheme;
    LinearizedFreeSurface bc(mesh, top, o);
    std::vector<double> eta(patch.size);
    for (int i = 0; i < patch.size; ++i) eta[i] = std::exp(-std::pow((bc.surface().centres()[i].x() - x0) / 0.3, 2));
    bc.SetEta(eta);
    AdvectEta(bc, mesh, patch, kDt, 30, [] {});
    std::vector<std::pair<double, double>> out;  // (x, eta), y-averaged by sorting
    for (int i = 0; i < patch.size; ++i) out.emplace_back(bc.surface().centres()[i].x(), bc.eta()[i]);
    return out;
  };
  auto peak = [](const std::vector<std::pair<double, double>>& f) {
    double m = 0.0;
    for (const auto& [x, e] : f) m = std::max(m, e);
    return m;
  };
  const double first_order = peak(advect(Advection::kUpwind, -1.0, 2.0));
  for (Advection scheme : {Advection::kLinearUpwind, Advection::kQuick}) {
    const auto forward = advect(scheme, -1.0, 2.0);   // pattern moves toward +x
    const auto backward = advect(scheme, +1.0, 6.0);  // the mirror image, toward -x
    double worst = 0.0;
    for (const auto& [x, e] : forward) {
      double mirrored = std::nan("");
      for (const auto& [xb, eb] : backward) {
        if (std::abs(xb - (8.0 - x)) < 1e-9) mirrored = eb;
      }
      worst = std::max(worst, std::abs(e - mirrored));
    }
    std::printf("scheme %d: peak %.4f toward +x, %.4f toward -x (first-order upwind %.4f); mirror mismatch %.2e\n",
                static_cast<int>(scheme), peak(forward), peak(backward), first_order, worst);
    EXPECT_LT(worst, 1e-12);
    EXPECT_GT(peak(backward), first_order + 0.05);
  }
}

// The local-flow linearization (double-body type): eta is carried by the
// flow under the surface, u = (U0 + a x, 0, -a z) (solenoidal, slowing the
// surface stream at x = 0 and speeding it up downstream), with a uniform rise
// w0 through the surface and calm water coming in at x = 0. The steady
// condition div_h(u_h eta) = w0 gives u_h eta = w0 x: eta = w0 x / (U0 + a x).
// First-order upwinding in conservative form telescopes to that value at each
// face's outflow edge, exactly; the advective form u . grad eta = w0 would
// give (w0 / a) ln(1 + a x / U0) instead (2.20 w0 at x = 4 against 1.33 w0),
// and the uniform stream w0 x / U0 (4 w0). Linear upwinding converges to the
// analytic value at the face centres.
struct SteadyStream {
  explicit SteadyStream(int n = 40) : mesh(Box({n, 2, 2}, false, Vector3(0, 0, -0.2), Vector3(4, 0.2, 0))) {}
  Mesh mesh;
  static constexpr double kU0 = 1.0, kA = 0.5, kW0 = 0.01;
  // Fluxes of the flow through every face (exact for the linear field on planar faces).
  std::vector<double> Flow(double a) const {
    std::vector<double> flux(mesh.n_faces());
    for (int f = 0; f < mesh.n_faces(); ++f) {
      const Vector3& x = mesh.face_centres()[f];
      flux[f] = Vector3(kU0 + a * x.x(), 0.0, -a * x.z()).dot(mesh.face_areas()[f]);
    }
    return flux;
  }
  // The exact steady elevation div_h(u_h eta) = w0 with eta = 0 at x = 0.
  static double Exact(double x) { return kW0 * x / (kU0 + kA * x); }
  // The steady elevation of `o` with the flow of `flow` under the surface
  // (the condition stays in `bc`).
  std::vector<double> Eta(const LinearizedFreeSurfaceOptions& o, const std::vector<double>& flow) {
    const int top = mesh.FindPatch("zmax");
    const Patch& patch = mesh.patches()[top];
    LinearizedFreeSurfaceOptions capped = o;
    capped.kinematic_courant = 2.0;  // leaves the steady state as it is (docs/formulation.md section 3.7)
    bc = std::make_unique<LinearizedFreeSurface>(mesh, top, capped);
    const std::vector<double> zero(mesh.n_faces(), 0.0);
    std::vector<double> rise(mesh.n_faces(), 0.0);
    for (int f = patch.start; f < patch.start + patch.size; ++f) rise[f] = kW0 * mesh.face_area_magnitudes()[f];
    bc->Update(BcContext{mesh, patch, 0.0, flow}, {});
    const double dt = 1.0;
    for (int step = 1; step <= 100; ++step) {
      const BcContext ctx{mesh, patch, step * dt, flow};
      bc->Update(ctx, {});
      for (int it = 0; it < 40; ++it) {
        bc->PreparePressureSolve(ctx, PressureCoupling{dt, false, zero, zero});
        bc->CorrectAfterFlux(ctx, rise);
      }
    }
    return bc->eta();
  }
  std::unique_ptr<LinearizedFreeSurface> bc;
};

TEST(LinearizedFreeSurface, LocalFlowCarriesEtaWithTheStreamUnderTheSurface) {
  SteadyStream s;
  using Advection = LinearizedFreeSurfaceOptions::Advection;
  using Linearization = LinearizedFreeSurfaceOptions::Linearization;
  LinearizedFreeSurfaceOptions o;
  o.linearization = Linearization::kLocalFlow;
  o.advection = Advection::kUpwind;
  const std::vector<double> eta = s.Eta(o, s.Flow(SteadyStream::kA));
  const double dx = 4.0 / 40;
  double worst = 0.0;
  for (std::size_t i = 0; i < eta.size(); ++i) {
    const double x_out = s.bc->surface().centres()[i].x() + 0.5 * dx;
    worst = std::max(worst, std::abs(eta[i] - SteadyStream::Exact(x_out)));
  }
  std::printf("first-order upwind: largest difference from w0 x_e / u(x_e) at the outflow edges %.2e (eta at the "
              "outlet %.5f, w0 %.2f)\n", worst, *std::max_element(eta.begin(), eta.end()), SteadyStream::kW0);
  EXPECT_LT(worst, 1e-12);

  // Linear upwind at the face centres: second order (the error of the
  // inflow face, first order there, is carried downstream at second order).
  o.advection = Advection::kLinearUpwind;
  std::array<double, 2> error{};
  for (int k = 0; k < 2; ++k) {
    SteadyStream grid(40 << k);
    const std::vector<double> eta2 = grid.Eta(o, grid.Flow(SteadyStream::kA));
    double sum = 0.0;
    for (std::size_t i = 0; i < eta2.size(); ++i) {
      sum += std::pow(eta2[i] - SteadyStream::Exact(grid.bc->surface().centres()[i].x()), 2);
    }
    error[k] = std::sqrt(sum / eta2.size());
  }
  const double order = std::log2(error[0] / error[1]);
  std::printf("linear upwind: RMS error %.3e (40 faces along), %.3e (80): order %.2f\n", error[0], error[1], order);
  EXPECT_GT(order, 1.8);
}

// The local flow's base flow is the flow under the rigid lid, frozen when
// the surface is released: a different flow afterwards (in a run, the wave's
// own) does not carry eta. Released into the uniform stream after a lid over
// the slowing stream, eta settles at the exact steady elevation of the
// slowing stream (first-order upwind: exact at the outflow edges), not at the
// uniform stream's w0 x / U0, and the reverse.
TEST(LinearizedFreeSurface, LocalFlowKeepsTheBaseFlowOfTheRigidLid) {
  SteadyStream s;
  LinearizedFreeSurfaceOptions o;
  o.linearization = LinearizedFreeSurfaceOptions::Linearization::kLocalFlow;
  o.advection = LinearizedFreeSurfaceOptions::Advection::kUpwind;
  o.kinematic_courant = 2.0;
  const int top = s.mesh.FindPatch("zmax");
  const Patch& patch = s.mesh.patches()[top];
  const std::vector<double> zero(s.mesh.n_faces(), 0.0), one(s.mesh.n_faces(), 1.0);
  std::vector<double> rise(s.mesh.n_faces(), 0.0);
  for (int f = patch.start; f < patch.start + patch.size; ++f) {
    rise[f] = SteadyStream::kW0 * s.mesh.face_area_magnitudes()[f];
  }
  auto released = [&](const std::vector<double>& under_lid, const std::vector<double>& after) {
    LinearizedFreeSurface bc(s.mesh, top, o);
    bc.SetRigidLid(true);
    for (int step = 0; step < 3; ++step) {
      const BcContext lid{s.mesh, patch, 0.5 * step, under_lid};
      bc.Update(lid, {});
      bc.PreparePressureSolve(lid, PressureCoupling{0.5, false, one, zero});
      bc.CorrectAfterFlux(lid, zero);
    }
    bc.SetRigidLid(false);
    for (int step = 1; step <= 100; ++step) {
      const BcContext ctx{s.mesh, patch, 1.0 + step, after};
      bc.Update(ctx, {});
      for (int it = 0; it < 40; ++it) {
        bc.PreparePressureSolve(ctx, PressureCoupling{1.0, false, zero, zero});
        bc.CorrectAfterFlux(ctx, rise);
      }
    }
    return bc.eta();
  };
  const double dx = 4.0 / 40;
  const std::vector<double> slowing = released(s.Flow(SteadyStream::kA), s.Flow(0.0));
  const std::vector<double> uniform = released(s.Flow(0.0), s.Flow(SteadyStream::kA));
  double worst_slowing = 0.0, worst_uniform = 0.0;
  for (int i = 0; i < patch.size; ++i) {
    const double x_out = s.mesh.face_centres()[patch.start + i].x() + 0.5 * dx;
    worst_slowing = std::max(worst_slowing, std::abs(slowing[i] - SteadyStream::Exact(x_out)));
    worst_uniform = std::max(worst_uniform, std::abs(uniform[i] - SteadyStream::kW0 * x_out / SteadyStream::kU0));
  }
  EXPECT_LT(worst_slowing, 1e-12);
  EXPECT_LT(worst_uniform, 1e-12);
}

// A stream slowing almost to rest at the outflow edge, u = 1 - 0.2475 x on
// 0 <= x <= 4: the base flow of the last column of faces (x = 3.9 to 4)
// comes in at u(3.9) = 0.03475 and leaves at u(4) = 0.01, a gain (inflow over
// outflow) of 3.475; each face's gain is the surface field base_flow_gain,
// written once the base flow is set.
TEST(LinearizedFreeSurface, LocalFlowWritesTheBaseFlowAndItsGains) {
  SteadyStream s;
  LinearizedFreeSurfaceOptions o;
  o.linearization = LinearizedFreeSurfaceOptions::Linearization::kLocalFlow;
  const int top = s.mesh.FindPatch("zmax");
  const auto fields_before = LinearizedFreeSurface(s.mesh, top, o).FaceFields();
  EXPECT_EQ(fields_before.size(), 2u);  // eta and beach_damping: no base flow yet
  s.Eta(o, s.Flow(-0.2475));
  const auto fields = s.bc->FaceFields();
  auto field = [&](const std::string& name) {
    const auto it = std::find_if(fields.begin(), fields.end(), [&](const auto& f) { return f.first == name; });
    EXPECT_NE(it, fields.end()) << name;
    return it == fields.end() ? std::vector<double>{} : it->second;
  };
  const std::vector<double> gain = field("base_flow_gain"), u = field("base_flow_x"), div = field("base_flow_divergence");
  ASSERT_EQ(gain.size(), static_cast<std::size_t>(s.bc->surface().size()));
  for (int i = 0; i < s.bc->surface().size(); ++i) {
    const double x = s.bc->surface().centres()[i].x();
    // The first column's inflow crosses the rim with undisturbed water (eta = 0): nothing to amplify.
    const double expected = x < 0.1 ? 0.0 : (1.0 - 0.2475 * (x - 0.05)) / (1.0 - 0.2475 * (x + 0.05));
    EXPECT_NEAR(gain[i], expected, 1e-9) << "x " << x;
    EXPECT_NEAR(u[i], 1.0 - 0.2475 * x, 1e-12) << "x " << x;
    EXPECT_NEAR(div[i], -0.2475, 1e-9) << "x " << x;
  }
}

// Unresolved steps: a smooth wave of height 0.1 m over faces 0.1 m apart
// (neighbours differ by at most 0.032 m) has none at a jump of 0.05 m; a face
// raised by 0.2 m and one lowered by 0.2 m are found (not their neighbours,
// on the smaller side of each step); a ramp rising 0.02 m per face has none,
// one rising 0.2 m per face steps everywhere but at its lowest column.
TEST(LinearizedFreeSurface, FindsUnresolvedSteps) {
  SteadyStream s;
  const int top = s.mesh.FindPatch("zmax");
  LinearizedFreeSurface bc(s.mesh, top, {});
  const int n = bc.surface().size();
  auto x = [&](int i) { return bc.surface().centres()[i].x(); };
  std::vector<double> eta(n);
  for (int i = 0; i < n; ++i) eta[i] = 0.1 * std::sin(std::numbers::pi * x(i));
  bc.SetEta(eta);
  EXPECT_TRUE(bc.UnresolvedSteps(0.05).empty());
  eta[17] += 0.2;
  eta[40] -= 0.2;
  bc.SetEta(eta);
  EXPECT_EQ(bc.UnresolvedSteps(0.05), (std::vector<int>{17, 40}));
  for (int i = 0; i < n; ++i) eta[i] = 0.2 * x(i);
  bc.SetEta(eta);
  EXPECT_TRUE(bc.UnresolvedSteps(0.05).empty());
  for (int i = 0; i < n; ++i) eta[i] = 2.0 * x(i);
  bc.SetEta(eta);
  const std::vector<int> steep = bc.UnresolvedSteps(0.05);
  EXPECT_EQ(steep.size(), static_cast<std::size_t>(n - 2));  // 40 x 2 faces
  for (int i : steep) EXPECT_GT(x(i), 0.1);
}

// In a uniform stream the two linearizations are the same condition: the
// local flow of a mesh at rest in the stream U0 gives the elevation of the
// uniform-stream form with the mesh moving at -U0 through still water.
TEST(LinearizedFreeSurface, LocalFlowInAUniformStreamIsTheUniformStreamForm) {
  SteadyStream s;
  using Linearization = LinearizedFreeSurfaceOptions::Linearization;
  LinearizedFreeSurfaceOptions local;
  local.linearization = Linearization::kLocalFlow;
  const std::vector<double> a = s.Eta(local, s.Flow(0.0));
  LinearizedFreeSurfaceOptions uniform;
  uniform.mesh_velocity = [](const Vector3&, double) { return Vector3(-SteadyStream::kU0, 0.0, 0.0); };
  const std::vector<double> b = s.Eta(uniform, std::vector<double>(s.mesh.n_faces(), 0.0));
  double worst = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) worst = std::max(worst, std::abs(a[i] - b[i]));
  EXPECT_LT(worst, 1e-14);
  EXPECT_GT(*std::max_element(a.begin(), a.end()), 0.039);  // w0 L / U0 = 0.04, less half a face
}

TEST(LinearizedFreeSurface, BeachRampsToItsMaximumAtTheChosenSides) {
  const Mesh mesh = Box({50, 10, 1}, false, Vector3(0, 0, -1), Vector3(10, 2, 0));
  constexpr double kU = 1.25, kG = 9.81;
  LinearizedFreeSurfaceOptions o;
  o.g = kG;
  o.beach.width = 1.0;
  o.beach.strength = 2.0;
  o.beach.reference_speed = kU;
  o.beach.sides = {LinearizedFreeSurfaceOptions::Beach::Side::kXMax};
  const LinearizedFreeSurface bc(mesh, mesh.FindPatch("zmax"), o);
  const double width = 2.0 * std::numbers::pi * kU * kU / kG;
  const double mu_max = 2.0 * kG / kU;
  for (int i = 0; i < bc.surface().size(); ++i) {
    const double x = bc.surface().centres()[i].x();
    const double s = std::clamp(1.0 - (10.0 - x) / width, 0.0, 1.0);
    EXPECT_NEAR(bc.damping()[i], mu_max * s * s * (3.0 - 2.0 * s), 1e-12);
    if (x < 10.0 - width) {
      EXPECT_EQ(bc.damping()[i], 0.0);
    }
  }
}

TEST(LinearizedFreeSurface, StateRoundTripAndWrongSize) {
  const Mesh mesh = Box({3, 2, 1});
  const int top = mesh.FindPatch("zmax");
  LinearizedFreeSurface a(mesh, top, {}), b(mesh, top, {});
  a.SetEta(std::vector<double>{0.1, 0.2, 0.3, 0.4, 0.5, 0.6});
  const std::vector<double> zero(mesh.n_faces(), 0.0);
  a.Update(BcContext{mesh, mesh.patches()[top], 0.0, zero}, {});
  a.Update(BcContext{mesh, mesh.patches()[top], 0.5, zero}, {});  // eta^n <- eta
  b.SetState(a.State());
  EXPECT_EQ(b.State(), a.State());
  EXPECT_EQ(b.eta(), a.eta());
  EXPECT_THROW(b.SetState(std::vector<double>{1.0, 2.0}), DataFileError);

  // The rigid-lid flag travels with the state; the older layout without it
  // (3 header values) still reads, as a free surface.
  a.SetRigidLid(true);
  b.SetState(a.State());
  EXPECT_TRUE(b.rigid_lid());
  std::vector<double> old_layout = a.State();
  old_layout.erase(old_layout.begin() + 3);
  b.SetState(old_layout);
  EXPECT_FALSE(b.rigid_lid());
  EXPECT_EQ(b.eta(), a.eta());

  // The local flow's base flow travels with the state once it is set; a
  // uniform-stream condition without a mesh velocity reads that state and
  // advects nothing with it.
  LinearizedFreeSurfaceOptions local;
  local.linearization = LinearizedFreeSurfaceOptions::Linearization::kLocalFlow;
  LinearizedFreeSurface c(mesh, top, local), d(mesh, top, local);
  std::vector<double> stream(mesh.n_faces());
  for (int f = 0; f < mesh.n_faces(); ++f) stream[f] = Vector3(0.3, 0.1, 0.0).dot(mesh.face_areas()[f]);
  const BcContext ctx{mesh, mesh.patches()[top], 0.5, stream};
  c.Update(ctx, {});
  c.PreparePressureSolve(ctx, PressureCoupling{0.5, false, zero, zero});
  ASSERT_GT(c.State().size(), a.State().size());
  d.SetState(c.State());
  EXPECT_EQ(d.State(), c.State());
  std::vector<double> truncated = c.State();
  truncated.pop_back();
  EXPECT_THROW(d.SetState(truncated), DataFileError);
  b.SetState(c.State());
  b.Update(ctx, {});
  b.PreparePressureSolve(ctx, PressureCoupling{0.5, false, zero, zero});
  b.CorrectAfterFlux(ctx, zero);
  EXPECT_EQ(b.eta(), c.eta());
}

// A rigid lid passes no flux and keeps eta, so a displaced surface stays
// displaced and the water stays at rest; released, the same hump sloshes
// (flux through the patch) and the elevation volume still follows the flux.
TEST(LinearizedFreeSurface, RigidLidHoldsTheSurfaceUntilReleased) {
  BoxMeshOptions mo;
  mo.min = Vector3(0.0, 0.0, -0.4);
  mo.max = Vector3(1.0, 0.6, 0.0);
  mo.cells = {10, 6, 5};
  mo.perturbation = 0.2;
  const Mesh mesh = MakeBoxMesh(mo);
  LinearizedFreeSurface* fs = nullptr;
  auto solver = testing::MakeWaterBox(mesh, {}, TimeScheme::kEuler, &fs, 2, 1e-12);
  const Patch& top = mesh.patches()[mesh.FindPatch("zmax")];
  const std::vector<double> eta = testing::OffCentreHump(fs->surface());
  fs->SetEta(eta);
  fs->SetRigidLid(true);
  const double dt = 0.05;
  auto max_flux = [&]() {
    double m = 0.0;
    for (int f = top.start; f < top.start + top.size; ++f) m = std::max(m, std::abs(solver->flux()[f]));
    return m;
  };
  for (int n = 0; n < 10; ++n) {
    ASSERT_TRUE(solver->Step(dt).finite);
    EXPECT_LT(max_flux(), 1e-15);
  }
  EXPECT_EQ(fs->eta(), eta);
  double max_u = 0.0;
  for (int c = 0; c < mesh.n_cells(); ++c) max_u = std::max(max_u, solver->U()[c].norm());
  EXPECT_LT(max_u, 1e-12);

  fs->SetRigidLid(false);
  const double V0 = fs->Volume();
  double V_prev = V0, worst_balance = 0.0, largest_flux = 0.0;
  for (int n = 0; n < 10; ++n) {
    ASSERT_TRUE(solver->Step(dt).finite);
    worst_balance = std::max(worst_balance, std::abs(fs->Volume() - V_prev - dt * testing::PatchFlux(*solver, top)));
    largest_flux = std::max(largest_flux, max_flux());
    V_prev = fs->Volume();
  }
  // Released: the hump drives a flux of the order of its collapse rate
  // (0.02 m over a quarter period of the shortest waves, ~0.1 s, times a face
  // area of 0.01 m^2 gives ~2e-3 m^3/s).
  EXPECT_GT(largest_flux, 1e-4);
  EXPECT_LT(worst_balance, 1e-15);
}

// Behind a surface-piercing block the uniform advection enters the patch
// across the block's waterline (eta extrapolated there). Those faces have
// only the time term (and the kinematic-Courant cap) on their diagonal, so a
// lagged high-order correction of their outflow is amplified at every
// iteration; they are first order, and the elevation stays bounded by its
// initial range at patch Courant number 10 with the cap of the hull cases
// (kinematic_courant 2). With the high-order correction on those faces it
// grew to 1e129 in 10 steps (and to 7e4 at Courant 3).
TEST(LinearizedFreeSurface, FacesFedAcrossTheWaterlineStayBoundedAtLargeCourant) {
  BoxMeshOptions mo;
  mo.min = Vector3(0, -2, -1);
  mo.max = Vector3(6, 2, 0);
  mo.cells = {24, 16, 2};
  mo.obstacle_min = {8, 6, 1};
  mo.obstacle_max = {14, 10, 2};
  const Mesh mesh = MakeBoxMesh(mo);
  const int top = mesh.FindPatch("zmax");
  const Patch& patch = mesh.patches()[top];
  constexpr double kU = 2.0;
  LinearizedFreeSurfaceOptions o;
  o.mesh_velocity = [](const Vector3&, double) { return Vector3(-kU, 0.0, 0.0); };
  o.advection = LinearizedFreeSurfaceOptions::Advection::kLinearUpwind;
  o.limit_advection = true;
  o.waterline_patches = {"obstacle"};
  o.kinematic_courant = 2.0;
  LinearizedFreeSurface bc(mesh, top, o);
  std::vector<double> eta(patch.size);
  for (int i = 0; i < patch.size; ++i) {
    const Vector3& x = bc.surface().centres()[i];
    eta[i] = 0.05 * std::sin(1.3 * x.x()) * std::cos(0.9 * x.y());
  }
  bc.SetEta(eta);
  const std::vector<double> zero(mesh.n_faces(), 0.0);
  const double dt = 10 * 0.25 / kU;  // Courant number 10 on 0.25 m faces
  bc.Update(BcContext{mesh, patch, 0.0, zero}, {});
  double start = 0.0, worst_iterate = 0.0, worst_step = 0.0;
  for (double e : eta) start = std::max(start, std::abs(e));
  for (int step = 1; step <= 10; ++step) {
    const BcContext ctx{mesh, patch, step * dt, zero};
    bc.Update(ctx, {});
    for (int it = 0; it < 20; ++it) {
      bc.PreparePressureSolve(ctx, PressureCoupling{dt, false, zero, zero});
      bc.CorrectAfterFlux(ctx, zero);
      for (double e : bc.eta()) worst_iterate = std::max(worst_iterate, std::abs(e));
    }
    for (double e : bc.eta()) worst_step = std::max(worst_step, std::abs(e));
  }
  std::printf("max |eta|: start %.5f, any iterate %.5f, end of any step %.5f\n", start, worst_iterate, worst_step);
  // The lagged iterates of the limited scheme may overshoot the local range
  // by a few per cent (1% measured); growth is what must not happen.
  EXPECT_LE(worst_iterate, 1.05 * start);
  EXPECT_LE(worst_step, 1.05 * start);
}

}  // namespace
}  // namespace kelvin::cfd
