// Output of an identification: the derivative set as YAML for humans, in the
// derivative-set layout the bridge loads (simulator/mmg/derivative_set.h:
// derivative_set, hull, standard_errors, fit, and interaction with
// interaction_fit when the campaign ran the propeller and rudder; the `hull:` section has the
// keys of a ship file's `hull:` section) and as HDF5 with the full covariance
// and the measured and fitted forces of every run (for
// tools/plot_identification.py). Both files are written atomically.
#pragma once

#include <filesystem>
#include <string>

#include "data/schema/captive_run.h"
#include "simulator/mmg/derivative_set.h"
#include "identification/interaction_fit.h"
#include "identification/joint_fit.h"
#include "identification/pmm_analysis.h"

namespace kelvin::ident {

struct IdentificationReport {
  std::string source;  // the campaign file(s)
  const data::CaptiveCampaign* campaign = nullptr;
  const JointFitResult* fit = nullptr;
  const PmmAnalysis* pmm = nullptr;  // optional cross-check
  const InteractionFitResult* interaction = nullptr;  // optional: the campaign's runs with propeller and rudder
};

// The motions the campaign's runs reached after their ramps: the largest
// |drift angle| and |r'| (written as fit.range, read by the surrogate's
// extrapolation warnings, simulator/maneuvers/identified_range.h).
sim::MotionRange CampaignRange(const data::CaptiveCampaign& campaign);

std::string FormatDerivativeYaml(const IdentificationReport& report);
void WriteDerivativeYaml(const IdentificationReport& report, const std::filesystem::path& path);
void WriteDerivativeH5(const IdentificationReport& report, const std::filesystem::path& path);

// The joint-fit value a classical PMM derivative corresponds to (see
// pmm_analysis.h): e.g. "Y_r" -> Y_r - m'_x, "N_rdot" -> -J'_z. False for
// names without a counterpart.
bool ClassicalCounterpart(const std::string& name, const sim::HullCoefficients<double>& c,
                          double* value);

}  // namespace kelvin::ident
