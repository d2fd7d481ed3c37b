// The steady resistance report of a run (the `resistance:` section,
// docs/formulation.md sections 3, 5 and 9): per step the resistance split along
// reference.direction d (R = F . d, F the force of the water on the hull):
// friction R_F (wall shear), pressure R_P, total R_T = R_F + R_P, and the
// waterline correction R_WL (cfd/freesurface/wave_analysis.h), reported apart
// and never added to R_T. At the end resistance.h5: coefficients by
// 0.5 rho S U^2 (S = reference.area, the wetted area at rest), the state of
// the steady criterion (time.steady), the hull face forces, and with a free
// surface the wave profile along the hull, the wave cuts and the whole
// pattern. With `double_body` (resistance.h5 of a double-body run on the
// same grid) also the wave-making part C_W = C_P - C_P(double body) and
// R_W = C_W 0.5 rho S U^2, and a loud warning when R_W is negative beyond
// the steady tolerance of R_T: steady waves take energy from the ship
// (docs/formulation.md section 5.3). (R_P at the rigid lid's release is no
// substitute: on the DTC it lies 2.8 N above the settled double body's.)
//
//   resistance:
//     hull: hull                  # wall patch whose force is the resistance
//     free_surface: freeSurface   # linearizedFreeSurface patch (omit: double body)
//     wave_cuts: [0.6, 1.2]       # y of the wave cuts (m)
//     wave_cut_points: 400
//     double_body: ../db/resistance.h5
#pragma once

#include <array>
#include <filesystem>
#include <string>
#include <vector>

#include "cfd/run/case_loader.h"
#include "cfd/run/monitor.h"

namespace kelvin::cfd {

struct HullFaces;  // the hull's faces and their forces at the last step, gathered over the ranks

class ResistanceMonitor final : public Monitor {
 public:
  // The case must have a resistance: section (LoadCase has checked its
  // patches and its reference).
  explicit ResistanceMonitor(const Case& c);

  std::vector<int> ForcePatches() const override { return {hull_}; }
  void AfterStep(const PimpleSolver& solver, const StepRecord& record, History& history) override;
  // Writes <output>/resistance.h5; returns its one-paragraph summary.
  std::vector<std::string> Finish(const PimpleSolver& solver) override;

  // Per recorded step: time, R_T, R_F, R_P, R_WL, force change, eta change.
  const std::vector<std::array<double, 7>>& rows() const { return rows_; }

 private:
  // The report of rank 0 (or the only rank); `faces` gathered by all.
  std::string Write(const std::filesystem::path& file, const HullFaces& faces) const;
  // The split, its coefficients and the steady criterion; the wave-making
  // part against the double body. Each returns its part of the summary.
  std::string WriteSplit(data::H5Writer& writer) const;
  // C_F / C_F0(ITTC-57) at the last step (turbulent cases with
  // reference.length), and a loud warning line when it lies outside
  // [kFrictionLow, kFrictionHigh] (empty otherwise).
  double FrictionRatio() const;
  std::string FrictionWarning() const;
  static constexpr double kFrictionLow = 0.9, kFrictionHigh = 1.2;
  // The free surface's unresolved steps (LinearizedFreeSurface::UnresolvedSteps
  // at U^2 / 4g): their count in `w`, and a warning line when there are any.
  std::string UnresolvedStepsWarning(data::H5Writer& w) const;
  std::string WriteWaveMaking(data::H5Writer& writer) const;
  // A loud line when the wave part R_W (N) is negative beyond the steady
  // criterion's tolerance of |R_T| (empty otherwise).
  std::string NegativeWavePartWarning(double r_w, double r_t) const;
  // Where to look, by the run's linearization of the kinematic condition.
  std::string LinearizationHint() const;
  // 0.5 rho S U^2 (N): the scale of the coefficients.
  double DynamicForce() const { return 0.5 * rho_ * reference_.area * reference_.speed * reference_.speed; }

  ResistanceOptions options_;
  CaseReference reference_;
  double rho_, nu_, g_ = 9.81;
  bool turbulent_ = false;  // a RANS case: its friction is judged against ITTC-57
  std::filesystem::path file_;
  const LinearizedFreeSurface* free_surface_;
  int hull_ = -1;
  double flow_through_ = 0.0;
  SteadyStatus steady_;
  double tolerance_;
  std::vector<std::array<double, 7>> rows_;
  PatchFaceForces last_faces_;  // of the hull at the last step (record.last)
};

}  // namespace kelvin::cfd
