// One captive run of a CFD campaign with the body-force propeller and rudder
// working (tests.appendages, data/schema/appendage_runs.h): the campaign's
// case with a free body whose every degree of freedom is held at the run's
// (u, v, r) (cfd/run/free_running_loader.h: free: []), the ship file's
// propeller at the run's rate and its rudder at the run's angle. The same
// grid, numerics and start-up as the bare-hull runs, so that the two can be
// differenced (thrust deduction).
//
// AppendageSampler records, every step, the loads on the body (hull
// pressure and viscous plus the actuators: what MMG calls X_H + X_P + X_R),
// the thrust and the disk's inflow, and the rudder's normal force and
// inflow; it keeps them in the run's checkpoints and gives their means over
// the settled part of the run.
#pragma once

#include <array>
#include <filesystem>
#include <vector>

#include "cfd/run/case_loader.h"
#include "cfd/run/free_running.h"
#include "cfd/run/monitor.h"
#include "data/schema/appendage_runs.h"
#include "data/schema/campaign_file.h"

namespace kelvin::cfd {

class PropellerActuator;
class RudderActuator;

// The case of `test`: the campaign's case file with the motion, propeller:
// and rudder: sections added. Throws ConfigError naming the campaign's case
// or ship file when the case has a motion: section, the ship file has no
// propeller or rudder, or the blade or disk lies outside the mesh.
Case LoadAppendageCase(const data::CampaignFile& f, const data::AppendageTest& test, CaseOverrides overrides);

class AppendageSampler final : public Monitor {
 public:
  // `c` must have been loaded by LoadAppendageCase; the coupler moves its body.
  AppendageSampler(const Case& c, const FreeRunningCoupler& coupler);
  void AfterStep(const PimpleSolver& solver, const StepRecord& record, History& history) override;
  void AddCheckpointArrays(CheckpointArrays& arrays) const override;
  void RestoreArrays(const CheckpointArrays& arrays) override;

  // The means over the samples at t >= from (at least one sample).
  data::AppendageRun Mean(const data::AppendageTest& test, double from) const;
  std::size_t samples() const { return rows_.size(); }

 private:
  // t, X, Y, N, T, U_A, J, K_T, F_N, u_R, v_R
  static constexpr std::size_t kFields = 11;
  const FreeRunningCoupler& coupler_;
  const PropellerActuator* propeller_ = nullptr;
  const RudderActuator* rudder_ = nullptr;
  std::vector<std::array<double, kFields>> rows_;
};

}  // namespace kelvin::cfd
