// Discretization choices of a run (the `schemes` section of a case file).
#pragma once

#include "cfd/fv/gradient.h"

namespace kelvin::cfd {

enum class TimeScheme { kEuler, kBackward };
// Convection: first-order upwind; linear-upwind (second order, unbounded);
// limited (bounded second order: van Leer TVD limiter on the
// gradient-based ratio); linear (central, unbounded); LUST (3/4 central with
// each side's value carried to the face centre by its gradient, 1/4
// linear upwind; unbounded, less dissipative than linear upwind).
enum class ConvectionScheme { kUpwind, kLinearUpwind, kLimited, kLinear, kLust };

struct SchemeOptions {
  TimeScheme time = TimeScheme::kEuler;
  GradientOptions gradient;
  ConvectionScheme convection = ConvectionScheme::kLinearUpwind;
  // Explicit non-orthogonal correction of the Laplacians (face gradient from
  // the interpolated cell gradient).
  bool non_orthogonal_correction = true;
  // Its form (fv_matrix.h): false keeps OpenFOAM's interpolated gradient;
  // true carries each cell's value to the normal through the face centre,
  // which refinement interfaces (2:1 split faces) need for second order.
  // Used by the momentum and pressure equations of PimpleSolver.
  bool face_centre_correction = false;
  // Skewness correction of the face interpolation in the Rhie-Chow flux
  // (phi_f += grad(phi)_f . (x_f - x_f')): keeps second order on skewed and
  // polyhedral meshes, at the cost of one more vector gradient per corrector.
  bool skew_correction = false;
  // Curvature correction of the momentum Laplacian (nu, or the turbulence
  // model's nu_eff on faces) on skewed and kinked faces
  // (cfd/fv/diffusion_curvature.h): second-order viscous fluxes on polyhedral
  // cells, at the cost of three more vector gradients per momentum assembly.
  // Needs skew_correction.
  bool curvature_correction = false;
  void Validate() const { gradient.Validate(); }
};

}  // namespace kelvin::cfd
