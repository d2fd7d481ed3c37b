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
// sublayer solution 6 nu / (beta1 y^2) and the log-layer value
// u_tau / (sqrt(beta*) kappa y) as sqrt(omega_vis^2 + omega_log^2)
// (each term dominates in its own region; the blend is smooth across the
// buffer layer).
double WallOmega(double y, double u_tau, double nu, double kappa, double beta1, double beta_star);

}  // namespace kelvin::cfd
