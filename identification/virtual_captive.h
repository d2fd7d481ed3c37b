// Virtual captive tests: the forces a captive model would measure in the
// prescribed motions if the hull followed an MMG model exactly. Used to check
// the identification end to end (round trip) and to design campaigns, and
// to run campaign files with solver: mmg (data/schema/campaign_file.h).
#pragma once

#include <cstdint>
#include <string>

#include "data/schema/campaign_file.h"
#include "data/schema/captive_plan.h"
#include "data/schema/captive_run.h"
#include "simulator/mmg/mmg_model.h"
#include "simulator/mmg/ship_parameters.h"

namespace kelvin::ident {

// The ship data of a campaign from an MMG ship definition.
data::CaptiveShip CaptiveShipFrom(const sim::ShipParameters& ship);

// An MMG ship definition (principal particulars only; propeller and rudder
// left empty) from campaign ship data, for evaluating the hull model.
sim::ShipParameters HullShipFrom(const data::CaptiveShip& ship);

// One run with the motion `motion` (its t_ramp is overwritten from the options).
data::CaptiveRun GenerateRun(const sim::MmgModel<double>& model, const std::string& name,
                             data::MotionParameters motion,
                             const data::VirtualCaptiveOptions& options);

data::CaptiveCampaign GenerateCampaign(const sim::MmgModel<double>& model,
                                       const data::CampaignDesign& design,
                                       const data::VirtualCaptiveOptions& options);

// Adds Gaussian noise of standard deviation `fraction` x (RMS of the channel
// over the run's analysis window, i.e. after the ramp-up) to every force
// sample (std::mt19937_64 seeded with `seed`). Channels that are zero over
// the window (Y and N at zero drift) stay noise-free.
void AddForceNoise(data::CaptiveCampaign& campaign, double fraction, std::uint64_t seed);

// Runs a campaign file with the MMG solver (virtual captive tests from the
// ship's MMG model, with the file's noise) and returns the captive runs (the
// cfd solver runs through cfd/campaign/cfd_campaign.h).
data::CaptiveCampaign RunCampaign(const data::CampaignFile& file);

}  // namespace kelvin::ident
