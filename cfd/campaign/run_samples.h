// The samples file of one CFD captive run (samples.h5 while it runs,
// result.h5 when it is done): the sampled hull loads with their pressure and
// viscous parts and prime-system values, the step reached, the run's cost and
// whether it settled; and the extra channels the campaign file carries beside
// X, Y, N. Written atomically (data::H5Writer).
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "cfd/motion/rigid_motion.h"
#include "cfd/motion/ship_forces.h"
#include "data/schema/h5_file.h"

namespace kelvin::cfd {

// Cost of a run so far, carried across resumes in the samples file: process
// CPU time of the time steps (s), the largest Courant number and the cells
// (the PMM cost benchmark reads them from result.h5).
struct RunCost {
  double cpu_seconds = 0.0;
  double courant_max = 0.0;
  double cells = 0.0;
};

// Whether a steady run settled: the result file's attributes, read back
// into the campaign's captive runs.
struct Settle {
  int settled = -1;  // -1: no criterion
  double change = 0.0;
  double t_settle = 0.0;  // s, start of the settled part
};

void WriteSamples(const std::filesystem::path& path, const std::vector<CaptiveSample>& samples,
                  int step, int steps, const RunCost& cost, const Settle& settle = {});
std::vector<CaptiveSample> ReadSamples(const std::filesystem::path& path,
                                       const RigidMotion& motion);
// The pressure and viscous parts and the prime-system loads of one run,
// beside its X, Y, N, under runs/<run>/ of the campaign file.
void WriteExtraChannels(data::H5Writer& w, const std::string& run,
                        const std::vector<CaptiveSample>& samples);

}  // namespace kelvin::cfd
