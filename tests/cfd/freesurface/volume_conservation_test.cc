// Acceptance 1 of issue 6: in a closed box (slip walls, linearized free
// surface on top, no hull) the volume stored in the elevation,
// V = sum_f eta_f |S_f|, equals its initial value plus the time-integrated
// net flux through the patch to round-off, step by step, for Euler and BDF2
// (1.5 V^{n+1} - 2 V^n + 0.5 V^{n-1} = dt sum F^{n+1}), on perturbed
// hexahedra and on split-face polyhedra. Since the box is closed, sum F is the
// sum of the pressure-equation residuals, so V also stays at its initial
// value to the solver tolerance.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "tests/cfd/freesurface/free_surface_test_support.h"

namespace kelvin::cfd {
namespace {

struct Variant {
  const char* name;
  bool polyhedral;
  double perturbation;
  TimeScheme time;
};

TEST(VolumeConservation, ElevationVolumeEqualsIntegratedFluxToRoundOff) {
  for (const Variant& v : {Variant{"perturbed hexahedra, Euler", false, 0.2, TimeScheme::kEuler},
                           Variant{"perturbed hexahedra, BDF2", false, 0.2, TimeScheme::kBackward},
                           Variant{"polyhedra, BDF2", true, 0.0, TimeScheme::kBackward}}) {
    BoxMeshOptions mo;
    mo.min = Vector3(0.0, 0.0, -0.4);
    mo.max = Vector3(1.0, 0.6, 0.0);
    mo.cells = {10, 6, 5};
    mo.polyhedral = v.polyhedral;
    mo.perturbation = v.perturbation;
    Mesh mesh = MakeBoxMesh(mo);
    mesh.RenumberCells();
    LinearizedFreeSurface* fs = nullptr;
    LinearizedFreeSurfaceOptions o;
    // Looser solver tolerance than the wave tests: conservation of V against
    // the flux must not depend on it.
    auto solver = testing::MakeWaterBox(mesh, o, v.time, &fs, 2, 1e-6);
    const Patch& top = mesh.patches()[mesh.FindPatch("zmax")];
    fs->SetEta(testing::OffCentreHump(fs->surface()));
    const double V0 = fs->Volume();
    double V_prev = V0, V_prev2 = V0, worst_balance = 0.0, worst_drift = 0.0, flux_scale = 0.0;
    const double dt = 0.05;
    for (int n = 1; n <= 30; ++n) {
      const StepSummary s = solver->Step(dt);
      ASSERT_TRUE(s.finite);
      const double V = fs->Volume();
      const double F = testing::PatchFlux(*solver, top);
      double abs_flux = 0.0;
      for (int f = top.start; f < top.start + top.size; ++f)
        abs_flux += std::abs(solver->flux()[f]);
      flux_scale = std::max(flux_scale, dt * abs_flux);
      // The solver uses Euler on its first step.
      const bool bdf2 = v.time == TimeScheme::kBackward && n >= 2;
      const double balance =
          bdf2 ? 1.5 * V - 2.0 * V_prev + 0.5 * V_prev2 - dt * F : V - V_prev - dt * F;
      worst_balance = std::max(worst_balance, std::abs(balance));
      worst_drift = std::max(worst_drift, std::abs(V - V0));
      V_prev2 = V_prev;
      V_prev = V;
    }
    std::printf(
        "%s: V0 = %.6e m^3, max |volume balance| = %.2e m^3 (%.1e of dt sum|F| = %.2e), max |V - "
        "V0| = "
        "%.2e m^3\n",
        v.name, V0, worst_balance, worst_balance / flux_scale, flux_scale, worst_drift);
    // Round-off: a few ulps of the terms summed over ~60 faces.
    EXPECT_LT(worst_balance, 1e-14 * V0) << v.name;
    // Closed box: sum F is the residual of the pressure solve (relative
    // tolerance 1e-6), a tiny fraction of the sloshing flux.
    EXPECT_LT(worst_drift, 1e-6 * V0) << v.name;
    EXPECT_GT(flux_scale, 1e-3 * V0) << v.name << ": the surface must actually move";
  }
}

}  // namespace
}  // namespace kelvin::cfd
