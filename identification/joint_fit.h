// The joint fit: every coefficient of the MMG hull polynomial and the added
// masses (sim::HullCoefficients, 20 values) fitted with Ceres to the force
// time histories of all runs of a campaign together.
//
// Residuals are the nondimensional hydrodynamic forces (X, Y by 0.5 rho L d U^2,
// N by 0.5 rho L^2 d U^2, U the carriage speed of the run) measured minus
// modelled (captive_force_model.h, evaluated with ceres::Jet), over the
// analysis window of each run (whole periods after the ramp-up), divided by
// the noise level sigma of that run and channel. The fit runs twice: first
// with sigma = channel RMS, then with sigma estimated from the first fit's
// residuals (never below min_noise_fraction x the channel RMS), so the
// residuals are whitened and ceres::Covariance gives the parameter covariance
// directly.
//
// Identifiability: a coefficient is flagged when the test matrix does not
// excite its term (joint excitation below min_joint_excitation, see below),
// when it lies in the numerical null space of the (column-normalized)
// Jacobian, or when its standard error exceeds max_relative_std_error x
// |value|. Pairs of free coefficients
// with |correlation| > correlation_limit get a warning. With
// fix_unidentifiable, flagged coefficients are held at their prior mean (or
// 0 without a prior: the term is dropped) and the fit is repeated, so the
// output never carries confident nonsense. The default limit 0.25 asks each
// kept coefficient to lie at least 4 standard errors from zero.
//
// Joint excitation of a hull polynomial term v'^a r'^b (a, b from its name,
// e.g. Y_vrr: a = 1, b = 2; prime velocities v' = v / U, r' = r Lpp / U,
// U = |(u, v)|) is max over the analysed samples of |v'^a r'^b| divided by
// max|v'|^a max|r'|^b over the campaign. Terms of one variable have 1 by
// construction; a cross term reaches about 0.1 or more only when some run
// moves in v and r together (yaw with drift, circular motion with drift).
// Without such runs the cross terms still have a tiny column: pure yaw with
// the path tangent on the centreline has v' = -psi^3 / 3 + ..., about 1e-4,
// so v' r'^2 stays near 1e-4 of its scale. With exact model data that column
// gives a large standard error, but with CFD or tank data (small,
// non-Gaussian model error, whitened to a tiny noise level) the fit uses it
// to absorb the model error and returns huge coefficients (Y_vrr of order
// -5000) with small standard errors. So such a term is flagged before the
// fit, whatever the standard error says, unless it has a prior.
//
// Bounds (default: added masses >= 0, which the simulator requires) are
// enforced by Ceres; a coefficient that ends on its bound is held there and
// the fit repeated, so the covariance is that of the free coefficients.
#pragma once

#include <Eigen/Core>
#include <array>
#include <limits>
#include <map>
#include <string>
#include <vector>

#include "data/schema/captive_run.h"
#include "simulator/mmg/ship_parameters.h"

namespace kelvin::ident {

inline constexpr int kCoefficientCount = sim::HullCoefficients<double>::kCount;

struct Prior {
  double mean = 0;
  double sigma = 0;  // > 0
};

struct JointFitOptions {
  enum class Loss { kNone, kHuber, kCauchy };
  // Robust loss on each sample's whitened (X, Y, N) residual; scale in noise
  // standard deviations.
  Loss loss = Loss::kNone;
  double loss_scale = 3.0;
  // Floor of the noise estimate per run and channel, as a fraction of the
  // channel RMS: no tank or CFD force is known better than this, and it keeps
  // the weights finite for noise-free data.
  double min_noise_fraction = 0.01;
  // Gaussian priors and fixed values by coefficient name (HullCoefficients
  // kNames: "Y_v", "m_x_prime", ...).
  std::map<std::string, Prior> priors;
  std::map<std::string, double> fixed;
  struct Bounds {
    double lower = -std::numeric_limits<double>::infinity();
    double upper = std::numeric_limits<double>::infinity();
  };
  std::map<std::string, Bounds> bounds = {
      {"m_x_prime", {0.0, std::numeric_limits<double>::infinity()}},
      {"m_y_prime", {0.0, std::numeric_limits<double>::infinity()}},
      {"J_z_prime", {0.0, std::numeric_limits<double>::infinity()}}};
  double max_relative_std_error = 0.25;
  // Smallest joint excitation (see above) of a polynomial term for the test
  // matrix to count as exciting it.
  double min_joint_excitation = 0.01;
  double correlation_limit = 0.95;
  // Reciprocal condition (eigenvalue ratio of the normalized normal matrix)
  // below which a direction counts as unidentifiable.
  double null_space_tolerance = 1e-10;
  bool fix_unidentifiable = true;
  int max_iterations = 100;

  // Throws kelvin::ArgumentError naming the option (unknown coefficient
  // names, non-positive prior sigma, ...).
  void Validate() const;
};

enum class CoefficientStatus {
  kIdentified,       // estimated from the data
  kNotIdentifiable,  // flagged; held at its prior mean or 0 when fix_unidentifiable
  kFixed,            // held at a user value
  kAtBound,          // ended on one of its bounds and held there
};
std::string_view CoefficientStatusName(CoefficientStatus status);

struct RunFitStatistics {
  std::string run;
  std::string kind;
  int samples = 0;
  // Per channel X, Y, N, nondimensional: the RMS of measured - fitted, the
  // largest |measured - fitted|, the RMS of the measured force, and the noise
  // sigma used as weight.
  std::array<double, 3> rms_residual{}, max_residual{}, rms_measured{}, sigma{};
};

struct JointFitResult {
  sim::HullCoefficients<double> coefficients;
  std::array<double, kCoefficientCount> std_error{};  // NaN unless kIdentified
  std::array<CoefficientStatus, kCoefficientCount> status{};
  std::array<std::string, kCoefficientCount> note;  // why a coefficient was flagged
  Eigen::Matrix<double, kCoefficientCount, kCoefficientCount>
      covariance;  // zero rows for held coefficients
  Eigen::Matrix<double, kCoefficientCount, kCoefficientCount> correlation;
  struct CorrelatedPair {
    int a = 0, b = 0;
    double correlation = 0;
  };
  std::vector<CorrelatedPair> correlated;
  std::vector<std::string> warnings;
  std::vector<RunFitStatistics> runs;
  bool converged = false;
  std::string solver_report;  // ceres::Summary::BriefReport of the last solve
  int residuals = 0;

  bool Identified(int i) const { return status[i] == CoefficientStatus::kIdentified; }
};

// Fits the campaign. `source` names it in error messages. Throws
// kelvin::DataFileError for an invalid campaign (ValidateCampaign) and
// kelvin::ArgumentError for invalid options.
JointFitResult FitCampaign(const data::CaptiveCampaign& campaign, const JointFitOptions& options,
                           std::string_view source);

// Index of a coefficient name in HullCoefficients::kNames, or -1.
int CoefficientIndex(std::string_view name);

// Joint excitation (see above) of every coefficient's term over the analysed
// samples of the campaign: 1 for terms of one variable that the campaign
// moves, 0 when a factor is never excited, NaN for terms without v', r'
// factors (R0_prime, added masses).
std::array<double, kCoefficientCount> JointExcitation(const data::CaptiveCampaign& campaign,
                                                      std::string_view source);

// Modelled nondimensional hydrodynamic forces of a run at every sample (for
// plots and residual checks), with the given coefficients.
std::array<std::vector<double>, 3> ModelForcesPrime(
    const data::CaptiveShip& ship, const data::CaptiveRun& run,
    const sim::HullCoefficients<double>& coefficients);

}  // namespace kelvin::ident
