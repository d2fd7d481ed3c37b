// The `motion: {kind: free}` section of a case file: a free-running body
// (cfd/motion/free_body.h) whose mass properties, and the added masses of
// its stabilised coupling, come from the same ship file the simulator reads
// (simulator/mmg/ship_parameters.h):
//
//   motion:
//     kind: free
//     ship: ../../ships/wigley.yaml  # m = rho displacement, x_G, I_zG = m (k_zz Lpp)^2
//     centre: [0.5, 0, 0]            # reference point (midship), grid axes (m)
//     free: [surge]                  # the degrees of freedom that move: surge, sway, yaw
//     initial: {u: 1.0, v: 0.0, r: 0.0}  # ship axes: m/s, m/s, rad/s
//     heading_deg: 0
//     ramp_time: 1.0                 # s, start-up of the initial velocities (towed)
//     release_time: 3.0              # s, free degrees of freedom move after it
//     external_load: {X: 0.0, Y: 0.0, N: 0.0}  # N, N m, ship axes (tow force, F_D)
//     coupling:
//       scheme: stabilised           # stabilised | explicit (the naive staggered scheme)
//       added_mass: ship             # ship (hull.m_x_prime, m_y_prime, J_z_prime) | [m_x, m_y, J_z] | none
//       relaxation: 1.0
//     hull_patches: [hull]           # default: output.forces
//     divergence_factor: 10          # a body speed above 10 x the initial speed stops the run
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "cfd/motion/free_body.h"
#include "data/schema/config.h"
#include "simulator/mmg/ship_parameters.h"

namespace kelvin::cfd {

struct FreeRunningSettings {
  std::filesystem::path ship_file;
  sim::ShipParameters ship;
  FreeBodyOptions body;
  std::vector<std::string> hull_patches;  // empty: output.forces
};

bool IsFreeMotion(const data::ConfigNode& motion);

// Reads the section; `bdf2` is the solver's backward time scheme.
FreeRunningSettings LoadFreeRunning(const data::ConfigNode& motion, const std::filesystem::path& case_dir,
                                    bool bdf2);

}  // namespace kelvin::cfd
