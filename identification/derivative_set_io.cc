#include "identification/derivative_set_io.h"

#include <fmt/format.h>
#include <yaml-cpp/yaml.h>

#include <cmath>
#include <numbers>

#include "data/schema/atomic_file.h"
#include "data/schema/h5_file.h"

namespace kelvin::ident {

namespace {

constexpr const auto& kNames = sim::HullCoefficients<double>::kNames;

std::string Number(double v) { return std::isfinite(v) ? fmt::format("{:.6g}", v) : "null"; }

}  // namespace

sim::MotionRange CampaignRange(const data::CaptiveCampaign& campaign) {
  sim::MotionRange range;
  for (const data::CaptiveRun& run : campaign.runs) {
    for (double t : run.time) {
      if (t < run.motion.t_ramp) continue;
      const data::BodyKinematics k = data::KinematicsAt(run.motion, campaign.ship.Lpp, t);
      range.Include(k.u, k.v, k.r, campaign.ship.Lpp);
    }
  }
  return range;
}

bool ClassicalCounterpart(const std::string& name, const sim::HullCoefficients<double>& c,
                          double* value) {
  if (name == "Y_v")
    *value = c.Y_v;
  else if (name == "N_v")
    *value = c.N_v;
  else if (name == "Y_vdot")
    *value = -c.m_y;
  else if (name == "N_vdot")
    *value = 0.0;
  else if (name == "Y_r")
    *value = c.Y_r - c.m_x;
  else if (name == "N_r")
    *value = c.N_r;
  else if (name == "Y_rdot")
    *value = 0.0;
  else if (name == "N_rdot")
    *value = -c.J_z;
  else if (name == "Y_vvv")
    *value = c.Y_vvv;
  else if (name == "N_vvv")
    *value = c.N_vvv;
  else if (name == "R0_prime")
    *value = c.R0;
  else if (name == "X_vv")
    *value = c.X_vv;
  else if (name == "X_vvvv")
    *value = c.X_vvvv;
  else
    return false;
  return true;
}

namespace {

// The identified interaction coefficients (read by the surrogate) and how
// each was found (informative).
void EmitInteraction(const InteractionFitResult& r, YAML::Emitter& y) {
  y << YAML::Key << "interaction" << YAML::Value
    << YAML::Comment("MMG interaction coefficients from the captive runs with propeller and rudder; they replace "
                     "the ship file's")
    << YAML::BeginMap;
  for (const InteractionCoefficient& k : r.coefficients)
    if (k.identified) y << YAML::Key << k.name << YAML::Value << Number(k.value);
  y << YAML::EndMap;
  y << YAML::Key << "interaction_fit" << YAML::Value << YAML::BeginMap;
  y << YAML::Key << "coefficients" << YAML::Value << YAML::BeginSeq;
  for (const InteractionCoefficient& k : r.coefficients) {
    y << YAML::Flow << YAML::BeginMap;
    y << YAML::Key << "name" << YAML::Value << k.name;
    y << YAML::Key << "value" << YAML::Value << Number(k.value);
    y << YAML::Key << "ship_file" << YAML::Value << Number(k.ship);
    y << YAML::Key << "identified" << YAML::Value << k.identified;
    if (k.identified) {
      y << YAML::Key << "runs" << YAML::Value << k.runs;
      y << YAML::Key << "rms_residual" << YAML::Value << Number(k.rms);
      y << YAML::Key << "units" << YAML::Value << k.units;
    }
    y << YAML::EndMap;
  }
  y << YAML::EndSeq;
  y << YAML::Key << "warnings" << YAML::Value << YAML::BeginSeq;
  for (const std::string& w : r.warnings) y << w;
  y << YAML::EndSeq;
  y << YAML::EndMap;
}

}  // namespace

std::string FormatDerivativeYaml(const IdentificationReport& rep) {
  const JointFitResult& fit = *rep.fit;
  YAML::Emitter y;
  y << YAML::Comment(
      "kelvin identify: MMG hull derivatives and added masses, prime system (Yasukawa & Yoshimura "
      "2015).\n"
      "Forces / (0.5 rho L d U^2), moment / (0.5 rho L^2 d U^2), masses / (0.5 rho L^2 d),\n"
      "J_z / (0.5 rho L^4 d). The hull: section uses the keys of a ship file's hull: section;\n"
      "the layout is the derivative-set contract of simulator/mmg/derivative_set.h.\n"
      "Standard errors are 1 sigma from ceres::Covariance; null = not estimated.");
  y << YAML::BeginMap;
  y << YAML::Key << "derivative_set" << YAML::Value << YAML::BeginMap;
  y << YAML::Key << "name" << YAML::Value
    << rep.campaign->ship.name + " hull derivatives identified by kelvin identify";
  y << YAML::Key << "ship" << YAML::Value << rep.campaign->ship.name;
  y << YAML::Key << "source" << YAML::Value << rep.source;
  y << YAML::EndMap;

  y << YAML::Key << "hull" << YAML::Value << YAML::BeginMap;
  for (int i = 0; i < kCoefficientCount; ++i) {
    y << YAML::Key << std::string(kNames[i]) << YAML::Value << fit.coefficients[i];
    if (!fit.Identified(i)) y << YAML::Comment(std::string(CoefficientStatusName(fit.status[i])));
  }
  y << YAML::EndMap;

  y << YAML::Key << "standard_errors" << YAML::Value << YAML::BeginMap;
  for (int i = 0; i < kCoefficientCount; ++i) {
    y << YAML::Key << std::string(kNames[i]) << YAML::Value;
    if (std::isfinite(fit.std_error[i])) {
      y << fit.std_error[i];
    } else {
      y << YAML::Null;
    }
  }
  y << YAML::EndMap;

  y << YAML::Key << "fit" << YAML::Value << YAML::BeginMap;
  y << YAML::Key << "runs" << YAML::Value << rep.campaign->runs.size();
  y << YAML::Key << "residuals" << YAML::Value << fit.residuals;
  y << YAML::Key << "converged" << YAML::Value << fit.converged;
  y << YAML::Key << "solver" << YAML::Value << fit.solver_report;
  const sim::MotionRange range = CampaignRange(*rep.campaign);
  y << YAML::Key << "range" << YAML::Value
    << YAML::Comment("the largest |drift| and |r'| of the runs after their ramps: beyond them the derivatives are "
                     "extrapolated")
    << YAML::Flow << YAML::BeginMap << YAML::Key << "drift_deg" << YAML::Value
    << Number(range.drift * 180.0 / std::numbers::pi) << YAML::Key << "r_prime" << YAML::Value
    << Number(range.r_prime) << YAML::EndMap;
  y << YAML::Key << "status" << YAML::Value << YAML::BeginMap;
  for (int i = 0; i < kCoefficientCount; ++i) {
    std::string s(CoefficientStatusName(fit.status[i]));
    if (!fit.note[i].empty() && !fit.Identified(i)) s += ": " + fit.note[i];
    y << YAML::Key << std::string(kNames[i]) << YAML::Value << s;
  }
  y << YAML::EndMap;

  y << YAML::Key << "warnings" << YAML::Value << YAML::BeginSeq;
  for (const std::string& w : fit.warnings) y << w;
  y << YAML::EndSeq;

  y << YAML::Key << "run_residuals" << YAML::Value
    << YAML::Comment("nondimensional, per channel X, Y, N") << YAML::BeginSeq;
  for (const RunFitStatistics& st : fit.runs) {
    y << YAML::BeginMap;
    y << YAML::Key << "run" << YAML::Value << st.run;
    y << YAML::Key << "kind" << YAML::Value << st.kind;
    y << YAML::Key << "samples" << YAML::Value << st.samples;
    auto triple = [&](const char* key, const std::array<double, 3>& v) {
      y << YAML::Key << key << YAML::Value << YAML::Flow << YAML::BeginSeq << Number(v[0])
        << Number(v[1]) << Number(v[2]) << YAML::EndSeq;
    };
    triple("rms_residual", st.rms_residual);
    triple("max_residual", st.max_residual);
    triple("rms_measured", st.rms_measured);
    triple("noise_sigma", st.sigma);
    y << YAML::EndMap;
  }
  y << YAML::EndSeq;

  if (rep.pmm) {
    y << YAML::Key << "pmm_cross_check" << YAML::Value
      << YAML::Comment("classical per-test derivatives and the joint-fit value they correspond to")
      << YAML::BeginSeq;
    for (const ClassicalEstimate& e : rep.pmm->estimates) {
      y << YAML::Flow << YAML::BeginMap;
      y << YAML::Key << "name" << YAML::Value << e.name;
      y << YAML::Key << "source" << YAML::Value << e.source;
      if (e.amplitude > 0) y << YAML::Key << "amplitude" << YAML::Value << Number(e.amplitude);
      y << YAML::Key << "value" << YAML::Value << Number(e.value);
      double joint = 0;
      if (ClassicalCounterpart(e.name, fit.coefficients, &joint)) {
        y << YAML::Key << "joint_fit" << YAML::Value << Number(joint);
      }
      y << YAML::EndMap;
    }
    y << YAML::EndSeq;
  }
  y << YAML::EndMap;  // fit
  if (rep.interaction) EmitInteraction(*rep.interaction, y);
  y << YAML::EndMap;
  return std::string(y.c_str()) + "\n";
}

void WriteDerivativeYaml(const IdentificationReport& report, const std::filesystem::path& path) {
  data::WriteFileAtomically(path, FormatDerivativeYaml(report));
}

void WriteDerivativeH5(const IdentificationReport& rep, const std::filesystem::path& path) {
  const JointFitResult& fit = *rep.fit;
  const data::CaptiveCampaign& c = *rep.campaign;
  data::H5Writer w(path);
  w.SetAttribute("/", "schema", "kelvin.derivatives/1");
  w.SetAttribute("/", "source", rep.source);
  w.SetAttribute("/", "ship", c.ship.name);
  w.SetAttribute("/", "converged", fit.converged ? 1.0 : 0.0);
  std::vector<std::string> names(kNames.begin(), kNames.end());
  w.WriteStrings("/names", names, "coefficient names (HullCoefficients kNames order)");
  std::vector<std::string> status;
  for (int i = 0; i < kCoefficientCount; ++i)
    status.emplace_back(CoefficientStatusName(fit.status[i]));
  w.WriteStrings("/status", status, "identified, not identifiable or fixed, per coefficient");
  std::vector<double> values(fit.coefficients.Data(), fit.coefficients.Data() + kCoefficientCount);
  w.WriteArray("/coefficients", values, {kCoefficientCount}, "-",
               "prime hull derivatives and added masses");
  std::vector<double> se(fit.std_error.begin(), fit.std_error.end());
  w.WriteArray("/std_error", se, {kCoefficientCount}, "-",
               "1-sigma standard errors (NaN = not estimated)");
  std::vector<double> cov(fit.covariance.data(), fit.covariance.data() + fit.covariance.size());
  w.WriteArray("/covariance", cov, {kCoefficientCount, kCoefficientCount}, "-",
               "covariance of the coefficients (symmetric; zero for held coefficients)");
  std::vector<double> cor(fit.correlation.data(), fit.correlation.data() + fit.correlation.size());
  w.WriteArray("/correlation", cor, {kCoefficientCount, kCoefficientCount}, "-",
               "correlation matrix");
  w.WriteStrings("/warnings", fit.warnings.empty() ? std::vector<std::string>{""} : fit.warnings,
                 "identifiability and solver warnings");
  for (std::size_t r = 0; r < c.runs.size(); ++r) {
    const data::CaptiveRun& run = c.runs[r];
    const std::string g = "/runs/" + run.name;
    const data::AnalysisWindow win = data::SelectWindow(run, rep.source);
    w.SetAttribute(g, "kind", data::MotionKindName(run.motion.kind));
    w.SetAttribute(g, "window_begin", static_cast<double>(win.begin));
    w.SetAttribute(g, "window_end", static_cast<double>(win.end));
    const auto measured = HydrodynamicForces(c.ship, run);
    const auto fitted = ModelForcesPrime(c.ship, run, fit.coefficients);
    const double q = c.ship.ForceScale() * run.motion.U * run.motion.U;
    w.WriteArray(g + "/time", run.time, {run.time.size()}, "s", "time");
    for (int ch = 0; ch < 3; ++ch) {
      const double scale = ch == 2 ? q * c.ship.Lpp : q;
      std::vector<double> mp(measured[ch].size());
      for (std::size_t i = 0; i < mp.size(); ++i) mp[i] = measured[ch][i] / scale;
      const std::string name(data::kChannelNames[ch]);
      w.WriteArray(g + "/measured_" + name, mp, {mp.size()}, "-",
                   "measured hydrodynamic force, nondimensional (rigid-body inertia removed)");
      w.WriteArray(g + "/fitted_" + name, fitted[ch], {fitted[ch].size()}, "-",
                   "fitted force, nondimensional");
    }
    if (r < fit.runs.size()) {
      const RunFitStatistics& st = fit.runs[r];
      w.WriteArray(g + "/rms_residual",
                   std::vector<double>(st.rms_residual.begin(), st.rms_residual.end()), {3}, "-",
                   "RMS residual X, Y, N over the analysis window");
      w.WriteArray(g + "/noise_sigma", std::vector<double>(st.sigma.begin(), st.sigma.end()), {3},
                   "-", "noise level used as weight, X, Y, N");
    }
  }
  w.Commit();
}

}  // namespace kelvin::ident
