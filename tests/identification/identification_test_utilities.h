// Shared fixtures for identification tests: the standard virtual captive
// campaign of the KVLCC2 (Yasukawa & Yoshimura 2015 coefficients).
#pragma once

#include "identification/virtual_captive.h"
#include "tests/simulator/simulator_test_utilities.h"

namespace kelvin::ident::fixtures {

inline data::CaptiveCampaign StandardCampaign(const sim::ShipParameters& ship, bool combined,
                                              bool inertia = true) {
  data::VirtualCaptiveOptions o;
  o.include_rigid_body_inertia = inertia;
  return GenerateCampaign(sim::MmgModel<double>(ship),
                          data::StandardDesign(ship.approach_speed, combined), o);
}

}  // namespace kelvin::ident::fixtures
