// The MMG hull-propeller-rudder interaction coefficients (Yasukawa &
// Yoshimura 2015, eqs. 13-25; docs/formulation.md section 6.4) from captive
// CFD runs with the body-force propeller and rudder working
// (data/schema/appendage_runs.h). The CFD measures what MMG models: the
// advance speed at the disk, the rudder's inflow and normal force, and the
// loads on the whole body; each coefficient is the least-squares answer of
// its own equation over the runs that excite it:
//
//   w_P0            1 - U_A / u over the straight-ahead runs
//   t_P             X - X_bare = (1 - t_P) T over the straight-ahead runs at
//                   delta = 0 (X_bare: the bare hull's straight-ahead X)
//   epsilon, kappa  u_R = epsilon sqrt(eta s^2 + (1 - eta) U_A^2),
//                   s = U_A + kappa (sqrt(U_A^2 + 8 K_T n^2 D^2 / pi) - U_A),
//                   eta = D_p / H_R, over every run (kappa needs runs at
//                   more than one propeller loading)
//   gamma_R+-, l_R  v_R = U gamma_R beta_R, beta_R = beta - l_R' r', over every
//                   run (l_R needs yawing runs; each gamma runs with beta_R of its sign)
//   f_alpha         F_N = 1/2 rho A_R (u_R^2 + v_R^2) f_alpha sin alpha_R,
//                   alpha_R = delta - atan(v_R / u_R), over the runs with
//                   |alpha_R| between 2 deg and 30 deg (below stall)
//   t_R, a_H, x_H   against the same-rate delta = 0 run, straight ahead:
//                   dX - (1 - t_P) dT = -(1 - t_R) F_N sin delta,
//                   dY = -(1 + a_H) d(F_N cos delta),
//                   dN = -(x_R + a_H x_H) d(F_N cos delta)
//
// What the runs do not excite keeps the ship file's value and is named in
// the warnings. Measured u_R, v_R are the CFD rudder's (its own induced
// velocity removed), U_A the CFD disk's.
#pragma once

#include <map>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "data/schema/appendage_runs.h"
#include "data/schema/captive_run.h"
#include "simulator/mmg/ship_parameters.h"

namespace kelvin::ident {

struct InteractionFitOptions {
  // The ship file's values: the starting point, and what stays where the
  // runs excite nothing.
  sim::PropellerParameters propeller;
  sim::RudderParameters rudder;
  // N: the bare hull's X in straight motion at the runs' speed (for t_P).
  std::optional<double> bare_X;
};

struct InteractionCoefficient {
  std::string name;   // as in ship files: t_P, w_P0, epsilon, ...
  double value = 0;   // identified, or the ship file's
  double ship = 0;    // the ship file's
  bool identified = false;
  int runs = 0;       // runs in its equation
  double rms = 0;     // residual of its equation (in its equation's units)
  std::string units;  // of rms
};

struct InteractionFitResult {
  std::vector<InteractionCoefficient> coefficients;  // in sim::kInteractionKeys order
  std::vector<std::string> warnings;
  const InteractionCoefficient& Get(const std::string& name) const;
  // The identified ones, as a derivative set's `interaction:` section.
  std::map<std::string, double> Identified() const;
};

// The bare hull's mean X (N) in the settled samples of the campaign's static
// drift run at beta = 0 and speed U; none without one.
std::optional<double> BareStraightX(const data::CaptiveCampaign& campaign, double U);

// Throws kelvin::InputError naming `source` when there is no straight-ahead
// run at delta = 0 or a run has no forward speed.
InteractionFitResult FitInteraction(const data::AppendageCampaign& campaign, const InteractionFitOptions& options,
                                    const std::string& source);

}  // namespace kelvin::ident
