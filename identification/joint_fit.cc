#include "identification/joint_fit.h"

#include <ceres/ceres.h>
#include <fmt/format.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>

#include "data/schema/errors.h"
#include "identification/captive_force_model.h"
#include "identification/pmm_analysis.h"
#include "identification/virtual_captive.h"
#include "simulator/mmg/mmg_model.h"

namespace kelvin::ident {

namespace {

using Names = decltype(sim::HullCoefficients<double>::kNames);
constexpr const Names& kNames = sim::HullCoefficients<double>::kNames;
constexpr int kP = kCoefficientCount;

// One sample of one run: kinematics, measured hydrodynamic force and the
// weights 1 / (force scale x sigma) per channel.
struct Sample {
  data::BodyKinematics k;
  std::array<double, 3> measured{};  // N, N, N m
  std::array<double, 3> weight{};    // 1 / (scale sigma)
};

// The residual of one sample, evaluated with double or ceres::Jet.
// The optimizer works on scaled parameters phi = theta / scale (Jacobi
// scaling: every Jacobian column has unit norm), so the rank decisions of
// ceres::Covariance do not depend on the units of the coefficients.
struct SampleResidual {
  const sim::ShipParameters* ship;
  const Sample* sample;
  const std::array<double, kP>* scale;

  template <typename T>
  bool operator()(const T* phi, T* residual) const {
    sim::HullCoefficients<T> h;
    for (int i = 0; i < kP; ++i) h[i] = phi[i] * (*scale)[i];
    const sim::MmgModel<T> model(*ship, h);
    const std::array<T, 3> f = CaptiveHydrodynamicForce(model, sample->k);
    for (int c = 0; c < 3; ++c) residual[c] = (sample->measured[c] - f[c]) * sample->weight[c];
    return true;
  }
};

struct PriorResidual {
  int index;
  Prior prior;
  double scale;
  template <typename T>
  bool operator()(const T* phi, T* residual) const {
    residual[0] = (phi[index] * scale - prior.mean) / prior.sigma;
    return true;
  }
};

struct RunData {
  const data::CaptiveRun* run = nullptr;
  std::array<double, 3> scale{};         // q U^2, q U^2, q L U^2
  std::array<double, 3> rms_measured{};  // prime
  std::vector<Sample> samples;
};

// Whitened Jacobian rows (3 per sample) and residuals of every sample.
void EvaluateAll(const sim::ShipParameters& ship, const std::vector<RunData>& runs,
                 const double* theta, Eigen::MatrixXd* jacobian, Eigen::VectorXd* residual) {
  using Jet = ceres::Jet<double, kP>;
  std::array<Jet, kP> jt;
  for (int i = 0; i < kP; ++i) jt[i] = Jet(theta[i], i);
  const std::array<double, kP> unit = [] {
    std::array<double, kP> u;
    u.fill(1.0);
    return u;
  }();
  std::size_t rows = 0;
  for (const RunData& r : runs) rows += 3 * r.samples.size();
  if (jacobian) jacobian->resize(static_cast<Eigen::Index>(rows), kP);
  if (residual) residual->resize(static_cast<Eigen::Index>(rows));
  Eigen::Index row = 0;
  if (!jacobian) {  // residuals only: plain doubles
    for (const RunData& r : runs) {
      for (const Sample& s : r.samples) {
        std::array<double, 3> e;
        SampleResidual{&ship, &s, &unit}(theta, e.data());
        for (int c = 0; c < 3; ++c, ++row) (*residual)(row) = e[c];
      }
    }
    return;
  }
  for (const RunData& r : runs) {
    for (const Sample& s : r.samples) {
      std::array<Jet, 3> e;
      SampleResidual{&ship, &s, &unit}(jt.data(), e.data());
      for (int c = 0; c < 3; ++c, ++row) {
        if (jacobian) jacobian->row(row) = e[c].v.transpose();
        if (residual) (*residual)(row) = e[c].a;
      }
    }
  }
}

// Exponents (a, b) of v' and r' in a hull polynomial term from its name
// ("Y_vrr" -> (1, 2)); false for names that are not such a term.
bool TermExponents(std::string_view name, int* a, int* b) {
  if (name.size() < 3 || name[1] != '_' || (name[0] != 'X' && name[0] != 'Y' && name[0] != 'N'))
    return false;
  *a = 0;
  *b = 0;
  for (const char ch : name.substr(2)) {
    if (ch == 'v') {
      ++*a;
    } else if (ch == 'r') {
      ++*b;
    } else {
      return false;
    }
  }
  return *a + *b > 0;
}

std::string Monomial(int a, int b) {
  auto power = [](std::string_view x, int p) -> std::string {
    if (p == 0) return "";
    return p == 1 ? std::string(x) : fmt::format("{}^{}", x, p);
  };
  const std::string v = power("v'", a), r = power("r'", b);
  return v.empty() ? r : (r.empty() ? v : v + " " + r);
}

}  // namespace

std::array<double, kCoefficientCount> JointExcitation(const data::CaptiveCampaign& campaign,
                                                      std::string_view source) {
  std::vector<std::array<double, 2>> vr;  // (v', r') of every analysed sample
  double v_max = 0, r_max = 0;
  for (const data::CaptiveRun& run : campaign.runs) {
    const data::AnalysisWindow w = data::SelectWindow(run, source);
    for (std::size_t i = w.begin; i < w.end; ++i) {
      const data::BodyKinematics k = data::KinematicsAt(run.motion, campaign.ship.Lpp, run.time[i]);
      const double U = std::hypot(k.u, k.v);
      if (!(U > 0)) continue;
      vr.push_back({k.v / U, k.r * campaign.ship.Lpp / U});
      v_max = std::max(v_max, std::abs(vr.back()[0]));
      r_max = std::max(r_max, std::abs(vr.back()[1]));
    }
  }
  std::array<double, kP> out;
  for (int i = 0; i < kP; ++i) {
    int a = 0, b = 0;
    if (!TermExponents(kNames[i], &a, &b)) {
      out[i] = std::numeric_limits<double>::quiet_NaN();
      continue;
    }
    const double scale = std::pow(v_max, a) * std::pow(r_max, b);
    double term = 0;
    for (const auto& s : vr) term = std::max(term, std::abs(std::pow(s[0], a) * std::pow(s[1], b)));
    out[i] = scale > 0 ? term / scale : 0.0;
  }
  return out;
}

int CoefficientIndex(std::string_view name) {
  for (int i = 0; i < kP; ++i) {
    if (kNames[i] == name) return i;
  }
  return -1;
}

std::string_view CoefficientStatusName(CoefficientStatus status) {
  switch (status) {
    case CoefficientStatus::kIdentified:
      return "identified";
    case CoefficientStatus::kNotIdentifiable:
      return "not identifiable";
    case CoefficientStatus::kFixed:
      return "fixed";
    case CoefficientStatus::kAtBound:
      return "at bound";
  }
  return "?";
}

void JointFitOptions::Validate() const {
  auto check_name = [](const std::string& what, const std::string& name) {
    if (CoefficientIndex(name) < 0) {
      throw ArgumentError(
          fmt::format("joint fit option '{}': unknown coefficient '{}'; valid names: {}", what,
                      name, fmt::join(kNames, ", ")));
    }
  };
  for (const auto& [name, prior] : priors) {
    check_name("priors", name);
    if (!(prior.sigma > 0) || !std::isfinite(prior.sigma) || !std::isfinite(prior.mean)) {
      throw ArgumentError(fmt::format(
          "joint fit option 'priors.{}': mean {} sigma {}: expected a finite mean and a "
          "finite positive sigma",
          name, prior.mean, prior.sigma));
    }
  }
  for (const auto& [name, value] : fixed) {
    check_name("fixed", name);
    if (!std::isfinite(value)) {
      throw ArgumentError(
          fmt::format("joint fit option 'fixed.{}' = {}: expected a finite value", name, value));
    }
  }
  auto positive = [](std::string_view key, double v) {
    if (!(v > 0) || !std::isfinite(v)) {
      throw ArgumentError(
          fmt::format("joint fit option '{}' = {}: expected a finite positive number", key, v));
    }
  };
  positive("loss_scale", loss_scale);
  positive("min_noise_fraction", min_noise_fraction);
  positive("max_relative_std_error", max_relative_std_error);
  positive("null_space_tolerance", null_space_tolerance);
  if (!(min_joint_excitation >= 0 && min_joint_excitation < 1)) {
    throw ArgumentError(fmt::format(
        "joint fit option 'min_joint_excitation' = {}: expected a number in [0, 1) (0 turns the "
        "check off)",
        min_joint_excitation));
  }
  for (const auto& [name, b] : bounds) {
    check_name("bounds", name);
    if (!(b.lower < b.upper) || std::isnan(b.lower) || std::isnan(b.upper)) {
      throw ArgumentError(
          fmt::format("joint fit option 'bounds.{}': [{}, {}]: expected lower < upper", name,
                      b.lower, b.upper));
    }
  }
  if (!(correlation_limit > 0 && correlation_limit < 1)) {
    throw ArgumentError(
        fmt::format("joint fit option 'correlation_limit' = {}: expected a number in (0, 1)",
                    correlation_limit));
  }
  if (max_iterations < 1) {
    throw ArgumentError(
        fmt::format("joint fit option 'max_iterations' = {}: expected at least 1", max_iterations));
  }
}

std::array<std::vector<double>, 3> ModelForcesPrime(
    const data::CaptiveShip& ship, const data::CaptiveRun& run,
    const sim::HullCoefficients<double>& coefficients) {
  const sim::MmgModel<double> model(HullShipFrom(ship), coefficients);
  const double q = ship.ForceScale() * run.motion.U * run.motion.U;
  std::array<std::vector<double>, 3> out;
  for (auto& o : out) o.resize(run.time.size());
  for (std::size_t i = 0; i < run.time.size(); ++i) {
    const auto f =
        CaptiveHydrodynamicForce(model, data::KinematicsAt(run.motion, ship.Lpp, run.time[i]));
    out[0][i] = f[0] / q;
    out[1][i] = f[1] / q;
    out[2][i] = f[2] / (q * ship.Lpp);
  }
  return out;
}

JointFitResult FitCampaign(const data::CaptiveCampaign& campaign, const JointFitOptions& options,
                           std::string_view source) {
  options.Validate();
  data::ValidateCampaign(campaign, source);
  const data::CaptiveShip& ship = campaign.ship;
  const sim::ShipParameters hull_ship = HullShipFrom(ship);

  // Samples of every run's analysis window, with the inertia removed.
  std::vector<RunData> runs;
  runs.reserve(campaign.runs.size());
  for (const data::CaptiveRun& run : campaign.runs) {
    RunData rd;
    rd.run = &run;
    const data::AnalysisWindow w = data::SelectWindow(run, source);
    const auto f = HydrodynamicForces(ship, run);
    const double q = ship.ForceScale() * run.motion.U * run.motion.U;
    rd.scale = {q, q, q * ship.Lpp};
    for (std::size_t i = w.begin; i < w.end; ++i) {
      Sample s;
      s.k = data::KinematicsAt(run.motion, ship.Lpp, run.time[i]);
      for (int c = 0; c < 3; ++c) {
        s.measured[c] = f[c][i];
        rd.rms_measured[c] += (f[c][i] / rd.scale[c]) * (f[c][i] / rd.scale[c]);
      }
      rd.samples.push_back(s);
    }
    for (int c = 0; c < 3; ++c) {
      rd.rms_measured[c] = std::sqrt(rd.rms_measured[c] / static_cast<double>(rd.samples.size()));
    }
    runs.push_back(std::move(rd));
  }

  // Reference level of each run and channel for the first-pass weights and
  // the noise floor: the channel RMS of the run, or the campaign RMS of the
  // channel where the run's channel is (numerically) zero, as Y and N of a
  // static drift run at beta = 0.
  std::array<double, 3> campaign_rms{};
  std::size_t campaign_samples = 0;
  for (const RunData& rd : runs) {
    for (int c = 0; c < 3; ++c)
      campaign_rms[c] += rd.rms_measured[c] * rd.rms_measured[c] * rd.samples.size();
    campaign_samples += rd.samples.size();
  }
  for (int c = 0; c < 3; ++c) {
    campaign_rms[c] = std::sqrt(campaign_rms[c] / static_cast<double>(campaign_samples));
    if (!(campaign_rms[c] > 0)) {
      throw DataFileError(fmt::format("{}: channel '{}' is identically zero in every run", source,
                                      data::kChannelNames[c]));
    }
  }
  std::vector<std::array<double, 3>> reference(runs.size());
  for (std::size_t r = 0; r < runs.size(); ++r) {
    for (int c = 0; c < 3; ++c) {
      const double rms = runs[r].rms_measured[c];
      reference[r][c] = rms > 1e-6 * campaign_rms[c] ? rms : campaign_rms[c];
    }
  }

  JointFitResult result;
  std::array<double, kP> theta{};
  std::array<bool, kP> held{};  // fixed by the user or flagged
  for (int i = 0; i < kP; ++i) result.status[i] = CoefficientStatus::kIdentified;
  for (const auto& [name, value] : options.fixed) {
    const int i = CoefficientIndex(name);
    theta[i] = value;
    held[i] = true;
    result.status[i] = CoefficientStatus::kFixed;
  }
  for (const auto& [name, prior] : options.priors) {
    const int i = CoefficientIndex(name);
    if (!held[i]) theta[i] = prior.mean;
  }

  // Terms the test matrix does not excite (cross terms without combined
  // runs): flagged before any fit, since model error, not noise, decides
  // their standard error (joint_fit.h).
  std::array<bool, kP> unexcited{};
  const std::array<double, kP> excitation = JointExcitation(campaign, source);
  for (int i = 0; i < kP; ++i) {
    int a = 0, b = 0;
    if (held[i] || options.priors.count(std::string(kNames[i])) ||
        !(excitation[i] < options.min_joint_excitation) || !TermExponents(kNames[i], &a, &b))
      continue;
    unexcited[i] = true;
    const std::string missing =
        a == 0   ? "no run has a yaw rate r' (pure yaw, yaw with drift or circular motion)"
        : b == 0 ? "no run has a sway velocity v' (static drift or pure sway)"
                 : "no run moves in v' and r' together (yaw with drift, circular motion with drift)";
    result.note[i] = fmt::format(
        "not excited by the test matrix: |{}| reaches at most {:.2g} of its scale {} over the "
        "analysed samples (limit {:g}); {}",
        Monomial(a, b), excitation[i],
        a == 0 || b == 0 ? Monomial(a, b)
                         : fmt::format("max|v'|{} max|r'|{}", a > 1 ? fmt::format("^{}", a) : "",
                                       b > 1 ? fmt::format("^{}", b) : ""),
        options.min_joint_excitation, missing);
    if (options.fix_unidentifiable) {
      held[i] = true;
      theta[i] = 0.0;
      result.status[i] = CoefficientStatus::kNotIdentifiable;
      result.note[i] += "; term dropped (held at 0)";
    }
  }

  // Noise level per run and channel (prime units); first pass: channel RMS.
  std::vector<std::array<double, 3>> sigma(runs.size());
  for (std::size_t r = 0; r < runs.size(); ++r) sigma[r] = reference[r];

  auto set_weights = [&]() {
    for (std::size_t r = 0; r < runs.size(); ++r) {
      for (Sample& s : runs[r].samples) {
        for (int c = 0; c < 3; ++c) s.weight[c] = 1.0 / (runs[r].scale[c] * sigma[r][c]);
      }
    }
  };

  ceres::Solver::Summary summary;
  std::array<double, kP> scale{};
  std::array<double, kP> phi{};
  auto solve = [&](bool with_covariance) {
    // Column norms of the whitened Jacobian (the model is linear in theta,
    // so they do not depend on it), plus the prior rows.
    Eigen::MatrixXd jac;
    EvaluateAll(hull_ship, runs, theta.data(), &jac, nullptr);
    for (int i = 0; i < kP; ++i) {
      double n2 = jac.col(i).squaredNorm();
      const auto prior = options.priors.find(std::string(kNames[i]));
      if (prior != options.priors.end()) n2 += 1.0 / (prior->second.sigma * prior->second.sigma);
      scale[i] = n2 > 0 ? 1.0 / std::sqrt(n2) : 1.0;
      phi[i] = theta[i] / scale[i];
    }
    ceres::Problem::Options po;
    ceres::Problem problem(po);
    for (const RunData& r : runs) {
      for (const Sample& s : r.samples) {
        auto* cost = new ceres::AutoDiffCostFunction<SampleResidual, 3, kP>(
            new SampleResidual{&hull_ship, &s, &scale});
        ceres::LossFunction* loss = nullptr;
        if (options.loss == JointFitOptions::Loss::kHuber)
          loss = new ceres::HuberLoss(options.loss_scale);
        if (options.loss == JointFitOptions::Loss::kCauchy)
          loss = new ceres::CauchyLoss(options.loss_scale);
        problem.AddResidualBlock(cost, loss, phi.data());
      }
    }
    for (const auto& [name, prior] : options.priors) {
      const int i = CoefficientIndex(name);
      if (held[i]) continue;
      problem.AddResidualBlock(new ceres::AutoDiffCostFunction<PriorResidual, 1, kP>(
                                   new PriorResidual{i, prior, scale[i]}),
                               nullptr, phi.data());
    }
    std::vector<int> held_indices;
    for (int i = 0; i < kP; ++i) {
      if (held[i]) held_indices.push_back(i);
    }
    if (static_cast<int>(held_indices.size()) == kP) {
      problem.SetParameterBlockConstant(phi.data());
    } else if (!held_indices.empty()) {
      problem.SetManifold(phi.data(), new ceres::SubsetManifold(kP, held_indices));
    }
    for (const auto& [name, b] : options.bounds) {
      const int i = CoefficientIndex(name);
      if (held[i]) continue;
      phi[i] = std::clamp(theta[i], b.lower, b.upper) / scale[i];  // start inside the box
      if (std::isfinite(b.lower)) problem.SetParameterLowerBound(phi.data(), i, b.lower / scale[i]);
      if (std::isfinite(b.upper)) problem.SetParameterUpperBound(phi.data(), i, b.upper / scale[i]);
    }
    ceres::Solver::Options so;
    so.linear_solver_type = ceres::DENSE_NORMAL_CHOLESKY;
    so.max_num_iterations = options.max_iterations;
    so.num_threads = 1;
    so.function_tolerance = 1e-14;
    so.gradient_tolerance = 1e-14;
    so.parameter_tolerance = 1e-12;
    so.logging_type = ceres::SILENT;
    ceres::Solve(so, &problem, &summary);
    for (int i = 0; i < kP; ++i) {
      if (!held[i]) theta[i] = phi[i] * scale[i];
    }
    result.converged = summary.termination_type == ceres::CONVERGENCE;
    result.solver_report = summary.BriefReport();

    // Covariance of the free coefficients; DENSE_SVD with the near-null
    // directions dropped (they are reported as not identifiable below).
    result.covariance.setZero();
    if (with_covariance && static_cast<int>(held_indices.size()) < kP) {
      ceres::Covariance::Options co;
      co.algorithm_type = ceres::DENSE_SVD;
      co.null_space_rank = -1;
      co.min_reciprocal_condition_number = options.null_space_tolerance;
      co.num_threads = 1;
      ceres::Covariance covariance(co);
      std::vector<const double*> blocks = {phi.data()};
      Eigen::Matrix<double, kP, kP> c_phi;
      if (covariance.Compute(blocks, &problem)) {
        covariance.GetCovarianceMatrix(blocks, c_phi.data());
        for (int i = 0; i < kP; ++i) {
          for (int j = 0; j < kP; ++j) result.covariance(i, j) = scale[i] * c_phi(i, j) * scale[j];
        }
      } else {
        result.covariance.setConstant(std::numeric_limits<double>::quiet_NaN());
        result.warnings.push_back("ceres::Covariance failed; standard errors are unavailable");
      }
    }
  };

  // Residual statistics and the noise estimate from the current fit.
  auto residual_statistics = [&]() {
    Eigen::VectorXd e;
    EvaluateAll(hull_ship, runs, theta.data(), nullptr, &e);
    int free = 0;
    for (int i = 0; i < kP; ++i) free += held[i] ? 0 : 1;
    const double total = static_cast<double>(e.size());
    const double dof_factor = total / std::max(1.0, total - free);
    result.runs.clear();
    Eigen::Index row = 0;
    for (std::size_t r = 0; r < runs.size(); ++r) {
      RunFitStatistics st;
      st.run = runs[r].run->name;
      st.kind = std::string(data::MotionKindName(runs[r].run->motion.kind));
      st.samples = static_cast<int>(runs[r].samples.size());
      std::array<std::vector<double>, 3> abs_dev;
      for (std::size_t i = 0; i < runs[r].samples.size(); ++i) {
        for (int c = 0; c < 3; ++c, ++row) {
          const double d = e(row) * sigma[r][c];  // back to prime units
          st.rms_residual[c] += d * d;
          st.max_residual[c] = std::max(st.max_residual[c], std::abs(d));
          abs_dev[c].push_back(std::abs(d));
        }
      }
      for (int c = 0; c < 3; ++c) {
        st.rms_residual[c] = std::sqrt(st.rms_residual[c] / st.samples);
        st.rms_measured[c] = runs[r].rms_measured[c];
        double noise = st.rms_residual[c] * std::sqrt(dof_factor);
        if (options.loss != JointFitOptions::Loss::kNone) {
          // Robust scale: 1.4826 x median absolute residual.
          auto& v = abs_dev[c];
          std::nth_element(v.begin(), v.begin() + static_cast<long>(v.size() / 2), v.end());
          noise = 1.4826 * v[v.size() / 2] * std::sqrt(dof_factor);
        }
        sigma[r][c] = std::max(noise, options.min_noise_fraction * reference[r][c]);
      }
      result.runs.push_back(st);
    }
  };

  // Fit, re-weight, fit; then flag and (optionally) hold the unidentifiable
  // coefficients and refit with the noise levels already estimated, until
  // nothing new is flagged.
  for (int round = 0; round <= kP; ++round) {
    if (round == 0) {
      set_weights();
      solve(false);
      residual_statistics();
    }
    set_weights();
    solve(true);
    residual_statistics();
    for (std::size_t r = 0; r < runs.size(); ++r) {
      for (int c = 0; c < 3; ++c) result.runs[r].sigma[c] = sigma[r][c];
    }

    // Coefficients that ended on a bound: hold them there and refit.
    bool any_bound = false;
    for (const auto& [name, b] : options.bounds) {
      const int i = CoefficientIndex(name);
      if (held[i]) continue;
      for (const double edge : {b.lower, b.upper}) {
        if (std::isfinite(edge) &&
            std::abs(theta[i] - edge) <= 1e-9 * std::max(1.0, std::abs(edge))) {
          held[i] = true;
          any_bound = true;
          theta[i] = edge;
          result.status[i] = CoefficientStatus::kAtBound;
          result.note[i] = fmt::format("ended on its bound {}; held there", edge);
          result.warnings.push_back(fmt::format("{} {}", kNames[i], result.note[i]));
        }
      }
    }
    if (any_bound) continue;

    // Null space of the normalized whitened normal matrix.
    Eigen::MatrixXd jac;
    EvaluateAll(hull_ship, runs, theta.data(), &jac, nullptr);
    std::vector<int> free_idx;
    for (int i = 0; i < kP; ++i) {
      if (!held[i]) free_idx.push_back(i);
    }
    const int nf = static_cast<int>(free_idx.size());
    std::array<bool, kP> flag{};
    if (nf > 0) {
      Eigen::MatrixXd g(nf, nf);
      Eigen::VectorXd norm(nf);
      for (int a = 0; a < nf; ++a) norm(a) = jac.col(free_idx[a]).norm();
      for (int a = 0; a < nf; ++a) {
        for (int b = 0; b < nf; ++b) {
          const double na = norm(a), nb = norm(b);
          g(a, b) = (na > 0 && nb > 0) ? jac.col(free_idx[a]).dot(jac.col(free_idx[b])) / (na * nb)
                                       : (a == b);
        }
      }
      for (const auto& [name, prior] : options.priors) {
        // A prior row (theta_i - mean) / sigma makes its coefficient
        // identifiable whatever the data say.
        const int i = CoefficientIndex(name);
        for (int a = 0; a < nf; ++a) {
          if (free_idx[a] != i) continue;
          const double n_data2 = norm(a) * norm(a), n_prior2 = 1.0 / (prior.sigma * prior.sigma);
          const double f = std::sqrt(n_data2 / (n_data2 + n_prior2));  // rescale row and column a
          for (int b = 0; b < nf; ++b) {
            g(a, b) *= f;
            g(b, a) *= f;
          }
          g(a, a) += n_prior2 / (n_data2 + n_prior2);
        }
      }
      const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(g);
      const double lmax = eig.eigenvalues().maxCoeff();
      for (int k = 0; k < nf; ++k) {
        if (eig.eigenvalues()(k) > options.null_space_tolerance * lmax) continue;
        for (int a = 0; a < nf; ++a) {
          const int i = free_idx[a];
          if (std::abs(eig.eigenvectors()(a, k)) > 0.1 || norm(a) == 0) {
            if (!flag[i] && !unexcited[i]) {  // an unexcited term keeps its own note
              flag[i] = true;
              result.note[i] = "in the null space of the tests (rank-deficient covariance)";
            }
          }
        }
      }
    }
    // Standard errors and correlations.
    for (int i = 0; i < kP; ++i) {
      result.std_error[i] =
          held[i] ? std::numeric_limits<double>::quiet_NaN() : std::sqrt(result.covariance(i, i));
    }
    result.correlation.setZero();
    for (int i = 0; i < kP; ++i) {
      for (int j = 0; j < kP; ++j) {
        const double d = std::sqrt(result.covariance(i, i) * result.covariance(j, j));
        result.correlation(i, j) = d > 0 ? result.covariance(i, j) / d : (i == j ? 1.0 : 0.0);
      }
    }
    for (int i = 0; i < kP; ++i) {
      if (held[i] || flag[i] || unexcited[i]) continue;
      const double rel = result.std_error[i] / std::abs(theta[i]);
      if (!(rel <= options.max_relative_std_error)) {
        flag[i] = true;
        result.note[i] = fmt::format(
            "standard error {:.3g} is {:.0f}% of the value {:.4g} (limit {:.0f}%)",
            result.std_error[i], 100 * rel, theta[i], 100 * options.max_relative_std_error);
      }
    }
    bool any_flag = false;
    for (int i = 0; i < kP; ++i) any_flag = any_flag || flag[i];
    if (!any_flag || !options.fix_unidentifiable) {
      for (int i = 0; i < kP; ++i) {
        if (flag[i] || unexcited[i]) result.status[i] = CoefficientStatus::kNotIdentifiable;
      }
      break;
    }
    for (int i = 0; i < kP; ++i) {
      if (!flag[i]) continue;
      held[i] = true;
      result.status[i] = CoefficientStatus::kNotIdentifiable;
      const auto prior = options.priors.find(std::string(kNames[i]));
      theta[i] = prior != options.priors.end() ? prior->second.mean : 0.0;
      result.note[i] +=
          prior != options.priors.end() ? "; held at its prior mean" : "; term dropped (held at 0)";
    }
  }

  for (int i = 0; i < kP; ++i) {
    result.coefficients[i] = theta[i];
    if (!result.Identified(i)) result.std_error[i] = std::numeric_limits<double>::quiet_NaN();
    if (result.status[i] == CoefficientStatus::kNotIdentifiable) {
      result.warnings.push_back(
          fmt::format("{} is not identifiable from these tests: {}", kNames[i], result.note[i]));
    }
  }
  for (int i = 0; i < kP; ++i) {
    for (int j = i + 1; j < kP; ++j) {
      if (!result.Identified(i) || !result.Identified(j)) continue;
      if (std::abs(result.correlation(i, j)) > options.correlation_limit) {
        result.correlated.push_back({i, j, result.correlation(i, j)});
        result.warnings.push_back(
            fmt::format("{} and {} are not separable by these tests (correlation {:+.3f})",
                        kNames[i], kNames[j], result.correlation(i, j)));
      }
    }
  }
  result.residuals = 0;
  for (const RunData& r : runs) result.residuals += 3 * static_cast<int>(r.samples.size());
  if (!result.converged)
    result.warnings.push_back("the solver did not converge: " + result.solver_report);
  for (const data::CaptiveRun& run : campaign.runs) {
    if (run.settled != 0) continue;
    result.warnings.push_back(fmt::format(
        "run '{}' did not settle (its loads still changed by {:.2g} of |(X, Y)| over the last window): its mean "
        "includes the start-up transient; run it longer (cfd.steady_duration)",
        run.name, run.settle_change));
  }
  return result;
}

}  // namespace kelvin::ident
