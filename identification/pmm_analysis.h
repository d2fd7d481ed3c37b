// Classical PMM analysis: the mean and first harmonic of each force channel
// over whole periods after the ramp-up, phase referenced to the prescribed
// motion (t = 0 of the motion law), with the rigid-body inertia removed where
// the series include it; static drift regression; and the classical per-test
// derivatives (Y_v, Y_vdot, N_v, N_vdot from pure sway; Y_r, Y_rdot, N_r,
// N_rdot from pure yaw) as a cross-check of the joint fit.
//
// Classical derivatives are in the prime system and absorb every term with
// the same phase, so in MMG terms (captive_force_model.h), for small
// amplitudes: Y'_v -> Y_v, N'_v -> N_v, Y'_vdot -> -m'_y, N'_vdot -> 0,
// Y'_r -> Y_r - m'_x, N'_r -> N_r, Y'_rdot -> 0, N'_rdot -> -J'_z. The
// cubic terms add 3/4 of their coefficient times the amplitude squared to
// the first harmonic; with two or more amplitudes the values are also
// extrapolated linearly in amplitude^2 to zero amplitude, which removes it.
#pragma once

#include <array>
#include <string>
#include <vector>

#include "data/schema/captive_run.h"

namespace kelvin::ident {

// F(t) ~ mean + in_phase cos(omega t) + quadrature sin(omega t) (steady runs:
// mean only).
struct HarmonicComponents {
  double mean = 0;
  double in_phase = 0;
  double quadrature = 0;
  double Amplitude() const;
  double Phase() const;  // rad, of the first harmonic: F1 = A cos(omega t - phase)
};

struct RunAnalysis {
  std::string run;
  data::MotionKind kind = data::MotionKind::kStaticDrift;
  data::AnalysisWindow window;
  // Hydrodynamic X [N], Y [N], N [N m] (rigid-body inertia removed).
  std::array<HarmonicComponents, 3> force;
  // The same divided by 0.5 rho L d U^2 (forces) and 0.5 rho L^2 d U^2 (N).
  std::array<HarmonicComponents, 3> force_prime;
};

// The hydrodynamic force series of a run: the measured series plus M_RB a
// when the run includes rigid-body inertia, unchanged otherwise.
std::array<std::vector<double>, 3> HydrodynamicForces(const data::CaptiveShip& ship,
                                                      const data::CaptiveRun& run);

RunAnalysis AnalyseRun(const data::CaptiveShip& ship, const data::CaptiveRun& run,
                       std::string_view source);

struct ClassicalEstimate {
  std::string name;      // e.g. "Y_v", "N_rdot" (prime)
  std::string source;    // run name, "static drift regression" or "zero-amplitude extrapolation"
  double amplitude = 0;  // v'_a or r'_a of the run (0 for regressions and extrapolations)
  double value = 0;
};

struct PmmAnalysis {
  std::vector<RunAnalysis> runs;
  std::vector<ClassicalEstimate> estimates;
};

// Analyses every run and extracts the classical derivatives: static drift
// regression (needs >= 2 drift angles; X' = -R0' + X_vv v'^2 + X_vvvv v'^4
// with >= 3, Y' = Y_v v' + Y_vvv v'^3 and N' alike), and per-run pure sway
// and pure yaw values. Throws DataFileError for runs that fail validation.
PmmAnalysis AnalyseCampaign(const data::CaptiveCampaign& campaign, std::string_view source);

}  // namespace kelvin::ident
