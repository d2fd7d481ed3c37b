#include "cfd/run/captive_sampler.h"

#include "data/schema/errors.h"

namespace kelvin::cfd {

CaptiveSampler::CaptiveSampler(const Case& c, std::vector<int> hull, PrimeScales scales)
    : motion_(*c.motion), hull_(std::move(hull)), scales_(scales) {
  KELVIN_CHECK(!hull_.empty(), "hull patches to sample");
}

void CaptiveSampler::AfterStep(const PimpleSolver& solver, const StepRecord& record, History&) {
  CaptiveSample s;
  s.time = solver.time();
  s.pose = motion_.body().At(s.time);
  s.loads = record.forces.ShipLoads(solver.mesh(), hull_, s.pose, motion_.body().centre());
  s.prime = scales_.ToPrime(s.loads.Total());
  samples_.push_back(s);
}

void CaptiveSampler::WriteHistory(data::H5Writer& w) const {
  if (!samples_.empty()) WriteCaptiveHistory(w, samples_);
}

}  // namespace kelvin::cfd
