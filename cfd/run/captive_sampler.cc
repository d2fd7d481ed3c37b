#include "cfd/run/captive_sampler.h"

#include "data/schema/errors.h"

namespace kelvin::cfd {

CaptiveSampler::CaptiveSampler(const Case& c, std::vector<int> hull, PrimeScales scales)
    : motion_(*c.motion), hull_(std::move(hull)), scales_(scales) {
  KELVIN_CHECK(!hull_.empty(), "hull patches to sample");
}

void CaptiveSampler::AfterStep(const PimpleSolver& solver, const StepRecord& record, History&) {
  std::vector<const PatchFaceForces*> faces;
  for (int k : hull_) faces.push_back(&record.forces.Faces(k));
  CaptiveSample s;
  s.time = solver.time();
  s.pose = motion_.body().At(s.time);
  s.loads = SumHullLoads(solver.mesh(), hull_, faces, s.pose, motion_.body().centre());
  s.prime = scales_.ToPrime(s.loads.Total());
  samples_.push_back(s);
}

void CaptiveSampler::WriteHistory(data::H5Writer& w) const {
  if (!samples_.empty()) WriteCaptiveHistory(w, samples_);
}

}  // namespace kelvin::cfd
