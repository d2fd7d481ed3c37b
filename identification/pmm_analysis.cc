#include "identification/pmm_analysis.h"

#include <Eigen/Dense>
#include <cmath>
#include <map>

namespace kelvin::ident {

double HarmonicComponents::Amplitude() const { return std::hypot(in_phase, quadrature); }
double HarmonicComponents::Phase() const { return std::atan2(quadrature, in_phase); }

std::array<std::vector<double>, 3> HydrodynamicForces(const data::CaptiveShip& ship,
                                                      const data::CaptiveRun& run) {
  std::array<std::vector<double>, 3> f = run.force;
  if (!run.includes_rigid_body_inertia) return f;
  for (std::size_t i = 0; i < run.time.size(); ++i) {
    const std::array<double, 3> rb =
        data::RigidBodyInertia(ship, data::KinematicsAt(run.motion, ship.Lpp, run.time[i]));
    for (int c = 0; c < 3; ++c) f[c][i] += rb[c];
  }
  return f;
}

RunAnalysis AnalyseRun(const data::CaptiveShip& ship, const data::CaptiveRun& run,
                       std::string_view source) {
  RunAnalysis a;
  a.run = run.name;
  a.kind = run.motion.kind;
  a.window = data::SelectWindow(run, source);
  const auto f = HydrodynamicForces(ship, run);
  const bool harmonic = data::IsHarmonic(run.motion.kind);
  const std::size_t n = a.window.end - a.window.begin;
  // Least squares on [1, cos, sin] over whole periods: the discrete Fourier
  // coefficients for uniform sampling, and still unbiased when it is not.
  Eigen::MatrixXd basis(n, harmonic ? 3 : 1);
  for (std::size_t i = 0; i < n; ++i) {
    const double t = run.time[a.window.begin + i];
    basis(i, 0) = 1.0;
    if (harmonic) {
      basis(i, 1) = std::cos(run.motion.omega * t);
      basis(i, 2) = std::sin(run.motion.omega * t);
    }
  }
  const auto qr = basis.colPivHouseholderQr();
  const double q = ship.ForceScale() * run.motion.U * run.motion.U;
  for (int c = 0; c < 3; ++c) {
    const Eigen::VectorXd y = Eigen::Map<const Eigen::VectorXd>(f[c].data() + a.window.begin, n);
    const Eigen::VectorXd coef = qr.solve(y);
    HarmonicComponents& h = a.force[c];
    h.mean = coef(0);
    if (harmonic) {
      h.in_phase = coef(1);
      h.quadrature = coef(2);
    }
    const double scale = c == 2 ? q * ship.Lpp : q;
    a.force_prime[c] = {h.mean / scale, h.in_phase / scale, h.quadrature / scale};
  }
  return a;
}

namespace {

// Least squares y = sum_j c_j x^p_j over the points; empty when underdetermined.
std::vector<double> PowerFit(const std::vector<double>& x, const std::vector<double>& y,
                             const std::vector<int>& powers) {
  if (x.size() < powers.size()) return {};
  Eigen::MatrixXd a(x.size(), powers.size());
  for (std::size_t i = 0; i < x.size(); ++i) {
    for (std::size_t j = 0; j < powers.size(); ++j) a(i, j) = std::pow(x[i], powers[j]);
  }
  const Eigen::VectorXd b = Eigen::Map<const Eigen::VectorXd>(y.data(), y.size());
  const Eigen::VectorXd c = a.colPivHouseholderQr().solve(b);
  return std::vector<double>(c.data(), c.data() + c.size());
}

}  // namespace

PmmAnalysis AnalyseCampaign(const data::CaptiveCampaign& campaign, std::string_view source) {
  data::ValidateCampaign(campaign, source);
  PmmAnalysis out;
  const data::CaptiveShip& ship = campaign.ship;
  std::vector<double> drift_v, drift_x, drift_y, drift_n;
  // name -> (amplitude^2, value) for the zero-amplitude extrapolation.
  std::map<std::string, std::vector<std::pair<double, double>>> by_amplitude;
  auto add = [&](const std::string& name, const std::string& run, double amplitude, double value) {
    out.estimates.push_back({name, run, amplitude, value});
    by_amplitude[name].push_back({amplitude * amplitude, value});
  };
  for (const data::CaptiveRun& run : campaign.runs) {
    RunAnalysis a = AnalyseRun(ship, run, source);
    const data::MotionParameters& m = run.motion;
    const double omega_p = m.omega * ship.Lpp / m.U;  // prime frequency
    const auto& fp = a.force_prime;
    switch (m.kind) {
      case data::MotionKind::kStaticDrift:
        drift_v.push_back(-std::sin(m.beta));
        drift_x.push_back(fp[0].mean);
        drift_y.push_back(fp[1].mean);
        drift_n.push_back(fp[2].mean);
        break;
      case data::MotionKind::kPureSway: {
        // v' = -v'_a cos(w t), dv' = v'_a w' sin(w t) (dv' = dv L / U^2).
        const double v_a = m.y_a * m.omega / m.U;
        add("Y_v", run.name, v_a, -fp[1].in_phase / v_a);
        add("N_v", run.name, v_a, -fp[2].in_phase / v_a);
        add("Y_vdot", run.name, v_a, fp[1].quadrature / (v_a * omega_p));
        add("N_vdot", run.name, v_a, fp[2].quadrature / (v_a * omega_p));
        break;
      }
      case data::MotionKind::kPureYaw: {
        // r' = -r'_a sin(w t), dr' = -r'_a w' cos(w t) (dr' = dr L^2 / U^2).
        const double r_a = m.psi_a * omega_p;
        add("Y_r", run.name, r_a, -fp[1].quadrature / r_a);
        add("N_r", run.name, r_a, -fp[2].quadrature / r_a);
        add("Y_rdot", run.name, r_a, -fp[1].in_phase / (r_a * omega_p));
        add("N_rdot", run.name, r_a, -fp[2].in_phase / (r_a * omega_p));
        break;
      }
      case data::MotionKind::kYawDrift:
      case data::MotionKind::kCircularMotion:
        break;  // used by the joint fit only
    }
    out.runs.push_back(std::move(a));
  }
  const std::string regression = "static drift regression";
  if (auto c = PowerFit(drift_v, drift_x, {0, 2, 4}); !c.empty() && drift_v.size() >= 4) {
    out.estimates.push_back({"R0_prime", regression, 0, -c[0]});
    out.estimates.push_back({"X_vv", regression, 0, c[1]});
    out.estimates.push_back({"X_vvvv", regression, 0, c[2]});
  }
  if (drift_v.size() >= 3) {
    const auto cy = PowerFit(drift_v, drift_y, {1, 3});
    const auto cn = PowerFit(drift_v, drift_n, {1, 3});
    out.estimates.push_back({"Y_v", regression, 0, cy[0]});
    out.estimates.push_back({"Y_vvv", regression, 0, cy[1]});
    out.estimates.push_back({"N_v", regression, 0, cn[0]});
    out.estimates.push_back({"N_vvv", regression, 0, cn[1]});
  }
  for (const auto& [name, points] : by_amplitude) {
    if (points.size() < 2) continue;
    std::vector<double> a2, v;
    for (const auto& [x, y] : points) {
      a2.push_back(x);
      v.push_back(y);
    }
    bool distinct = false;
    for (double x : a2) distinct = distinct || std::abs(x - a2.front()) > 1e-12;
    if (!distinct) continue;
    const auto c = PowerFit(a2, v, {0, 1});
    out.estimates.push_back({name, "zero-amplitude extrapolation", 0, c[0]});
  }
  return out;
}

}  // namespace kelvin::ident
