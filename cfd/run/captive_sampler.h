// Captive force sampling (`output.captive: true`, and every CFD captive run of
// a campaign): each step, the loads on the hull patches in ship axes about
// the motion's reference point, pressure and viscous apart, and the MMG prime
// system with reference.length, reference.draft and the carriage speed
// (cfd/motion/ship_forces.h). In history.h5 as the group `captive`.
#pragma once

#include <vector>

#include "cfd/run/case_loader.h"
#include "cfd/run/monitor.h"

namespace kelvin::cfd {

class CaptiveSampler final : public Monitor {
 public:
  // hull: the patches whose loads are sampled; the case needs a motion.
  CaptiveSampler(const Case& c, std::vector<int> hull, PrimeScales scales);

  std::vector<int> ForcePatches() const override { return hull_; }
  void AfterStep(const PimpleSolver& solver, const StepRecord& record, History& history) override;
  void WriteHistory(data::H5Writer& writer) const override;

  // The samples of a run resumed from a checkpoint (those up to its step).
  void Restore(std::vector<CaptiveSample> samples) { samples_ = std::move(samples); }
  const std::vector<CaptiveSample>& samples() const { return samples_; }

 private:
  const RigidMeshMotion& motion_;
  std::vector<int> hull_;
  PrimeScales scales_;
  std::vector<CaptiveSample> samples_;
};

}  // namespace kelvin::cfd
