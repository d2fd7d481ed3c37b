// Wall laws shared by the turbulence model and the output (y+, wall shear).
//
// kelvin's wall treatment is Spalding's single formula for the inner layer,
//   y+ = u+ + exp(-kappa B) [exp(kappa u+) - 1 - kappa u+ - (kappa u+)^2/2 - (kappa u+)^3/6],
// which is the linear law u+ = y+ for y+ < ~5, the log law
// u+ = ln(y+)/kappa + B for y+ > ~30 and a smooth buffer layer in between.
// Solved for the friction velocity from the wall-parallel velocity of the
// wall cell, it gives the wall eddy viscosity at any first-cell y+, so the
// same grid treatment serves wall-resolved (y+ ~ 1) and wall-function
// (y+ 30-100) grids without a switch in the momentum equation.
#pragma once

namespace kelvin::cfd {

struct WallLaw {
  double kappa = 0.41;
  double B = 5.2;
  // Spalding's y+ for a given u+.
  double YPlus(double u_plus) const;
  // Friction velocity u_tau (m/s) such that (y u_tau / nu, U / u_tau) lies
  // on Spalding's law, for wall-parallel speed U (m/s) at wall distance y (m).
  // Newton on the residual in y+, started from the larger of the linear and
  // log-law estimates; converges to 1e-12 relative in a few iterations.
  double FrictionVelocity(double U, double y, double nu) const;
  // Intersection of the linear and log laws (about 11.5 for kappa 0.41).
  double YPlusLaminar() const;
};

// Wall value of omega in the first cell, blended between the viscous
// sublayer value and the log-layer value u_tau / (sqrt(beta*) kappa y) as
// sqrt(omega_vis^2 + omega_log^2) (each term dominates in its own region;
// the blend is smooth across the buffer layer). The viscous part is
// viscous_scale * 6 nu / (beta1 y^2): 1 gives the point value of the
// sublayer solution at the cell centre (OpenFOAM's omegaWallFunction),
// SublayerOmegaScale() the value that is consistent with the discrete
// omega equation of the cells beyond (docs/formulation.md section 8.2).
double WallOmega(double y, double u_tau, double nu, double kappa, double beta1, double beta_star,
                 double viscous_scale = 1.0);

// The scale c of the wall cell's fixed viscous omega, c * 6 nu / (beta1 y1^2),
// for which the finite-volume sublayer equation
//   d/dy (nu d omega/dy) = beta1 omega^2
// on cells of equal height h has a solution that tends to the exact
// 6 nu / (beta1 y^2) away from the wall. In wall units W = beta1 h^2 omega / nu
// the cell balance reads W_{j-1} - 2 W_j + W_{j+1} = W_j^2 and the exact
// cell-centre values are 6 / (j - 1/2)^2; the scale is W_1 / 24 of the
// discrete solution whose far values are 6 / (j - 1/2 - s)^2 with no shift s
// of the wall: c = 0.26146. With c = 1 (the point value) the discrete solution
// is that of a wall displaced by s = 0.7 cell heights: omega 1.55 times the
// sublayer value in the second cell, 1.15 times in the tenth.
double SublayerOmegaScale();

// The scale a wall cell at `y_plus` takes. The derivation above holds while
// the next cells lie in the viscous sublayer (y+ < 5; the second cell centre
// is at 3 y1 on equal cells): c in full up to y1+ = 5/3, none (1, the point
// value of the validated wall-function treatment) from y1+ = 5, where the wall
// cell itself leaves the sublayer, geometric in ln y+ between.
double SublayerOmegaScale(double y_plus);

}  // namespace kelvin::cfd
