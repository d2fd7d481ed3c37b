// The monitors every `kelvin run` may carry (cfd/run/monitor.h):
// - FieldOutput: VTU cell fields and a PVD series every output.vtu_interval
//   steps and at the last step, and a VTP surface series of each patch whose
//   condition has its own unknowns (eta) and of each turbulence wall (p, U,
//   wallShearStress (kinematic, m^2/s^2, acting on the wall) and yPlus);
// - TurbulenceReport: residuals of k and omega, the cells the bound step
//   lifted, and y+ (min, mean, max) on each wall patch, per step;
// - ForceCoefficients: with reference.speed, the per-step resistance
//   coefficients of the output.forces patches,
//     C_T = (F . d) / (1/2 rho U^2 S),  C_F: viscous part, C_P: pressure part,
//   d = reference.direction, S = reference.area (default: the patches' area).
#pragma once

#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "cfd/io/vtu_writer.h"
#include "cfd/run/case_loader.h"
#include "cfd/run/monitor.h"

namespace kelvin::cfd {

class FieldOutput final : public Monitor {
 public:
  // On MPI ranks each rank writes its piece of every file and rank 0 the
  // parallel index (.pvtu, .pvtp) the series lists.
  FieldOutput(const std::filesystem::path& directory, int interval);
  void AfterStep(const PimpleSolver& solver, const StepRecord& record, History& history) override;

 private:
  void Write(const PimpleSolver& solver);
  std::filesystem::path directory_;
  int interval_;
  PvdSeries pvd_;
  std::map<std::string, PvdSeries> surfaces_;
};

class TurbulenceReport final : public Monitor {
 public:
  void Start(PimpleSolver& solver, History& history, const RunStart& start) override;
  void AfterStep(const PimpleSolver& solver, const StepRecord& record, History& history) override;
  std::vector<std::string> Finish(const PimpleSolver& solver) override;

 private:
  History::Column res_k_ = -1, res_omega_ = -1, bounded_k_ = -1, bounded_omega_ = -1;
  std::vector<History::Column> y_plus_;
  std::vector<WallPatchStats> last_;
};

class ForceCoefficients final : public Monitor {
 public:
  ForceCoefficients(const Case& c);
  void Start(PimpleSolver& solver, History& history, const RunStart& start) override;
  void AfterStep(const PimpleSolver& solver, const StepRecord& record, History& history) override;
  void WriteHistory(data::H5Writer& writer) const override;
  std::vector<std::string> Finish(const PimpleSolver& solver) override;

 private:
  std::vector<int> patches_;
  CaseReference reference_;
  double rho_;
  History::Column columns_[3] = {-1, -1, -1};
  double last_[3] = {0, 0, 0};
};

}  // namespace kelvin::cfd
