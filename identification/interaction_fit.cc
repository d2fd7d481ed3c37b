#include "identification/interaction_fit.h"

#include <ceres/ceres.h>
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "data/schema/errors.h"
#include "simulator/mmg/derivative_set.h"

namespace kelvin::ident {
namespace {

using data::AppendageRun;
constexpr double kStraight = 1e-9;   // |v|, |r| below it: straight ahead
constexpr double kRudderZero = 1e-6;  // rad

bool Straight(const AppendageRun& r) { return std::abs(r.v) < kStraight && std::abs(r.r) < kStraight; }
double Speed(const AppendageRun& r) { return std::hypot(r.u, r.v); }

// The MMG rudder inflow speed from the measured propeller state.
struct InflowSpeedResidual {
  double u_R, U_A, race, eta;
  template <typename T>
  bool operator()(const T* const p, T* residual) const {  // p = (epsilon, kappa)
    const T s = U_A + p[1] * (race - U_A);
    residual[0] = u_R - p[0] * sqrt(eta * s * s + (1.0 - eta) * U_A * U_A);
    return true;
  }
};

// The MMG rudder inflow angle: v_R / U = gamma_R(beta_R) beta_R.
struct InflowAngleResidual {
  double v_R_over_U, beta, r_prime;
  template <typename T>
  bool operator()(const T* const p, T* residual) const {  // p = (gamma_minus, gamma_plus, l_R')
    const T beta_R = beta - p[2] * r_prime;
    const T gamma = beta_R < T(0) ? p[0] : p[1];
    residual[0] = v_R_over_U - gamma * beta_R;
    return true;
  }
};

double Solve(ceres::Problem& problem) {
  ceres::Solver::Options so;
  so.linear_solver_type = ceres::DENSE_QR;
  so.logging_type = ceres::SILENT;
  so.max_num_iterations = 200;
  ceres::Solver::Summary summary;
  ceres::Solve(so, &problem, &summary);
  return summary.final_cost;
}

// Least-squares slope through the origin of y on x; rms of the residual.
std::pair<double, double> SlopeThroughOrigin(const std::vector<double>& x, const std::vector<double>& y) {
  double sxx = 0, sxy = 0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    sxx += x[i] * x[i];
    sxy += x[i] * y[i];
  }
  const double k = sxy / sxx;
  double ss = 0;
  for (std::size_t i = 0; i < x.size(); ++i) ss += (y[i] - k * x[i]) * (y[i] - k * x[i]);
  return {k, std::sqrt(ss / static_cast<double>(x.size()))};
}

class Fit {
 public:
  Fit(const data::AppendageCampaign& c, const InteractionFitOptions& o, const std::string& source) : c_(c), o_(o) {
    for (const AppendageRun& r : c.runs) {
      if (!(r.u > 0.0)) {
        throw InputError(fmt::format("{}: appendage run '{}': u = {}: expected forward speed", source, r.name, r.u));
      }
    }
    sim::PropellerParameters pp = o.propeller;
    sim::RudderParameters rp = o.rudder;
    const auto ship = sim::InteractionFields(pp, rp);
    for (std::size_t i = 0; i < sim::kInteractionKeys.size(); ++i) {
      InteractionCoefficient k;
      k.name = sim::kInteractionKeys[i];
      k.value = k.ship = *ship[i];
      out_.coefficients.push_back(k);
    }
  }

  InteractionFitResult Run() {
    WakeFraction();
    ThrustDeduction();
    InflowSpeed();
    InflowAngle();
    LiftSlope();
    RudderForces();
    return out_;
  }

 private:
  InteractionCoefficient& At(const std::string& name) {
    return *std::find_if(out_.coefficients.begin(), out_.coefficients.end(),
                         [&](const auto& k) { return k.name == name; });
  }
  void Set(const std::string& name, double value, int runs, double rms, const char* units) {
    InteractionCoefficient& k = At(name);
    k.value = value;
    k.identified = true;
    k.runs = runs;
    k.rms = rms;
    k.units = units;
  }
  void Keep(const std::string& name, const std::string& why) {
    out_.warnings.push_back(fmt::format("{} kept at the ship file's {:g}: {}", name, At(name).ship, why));
  }

  void WakeFraction() {
    std::vector<double> w;
    for (const AppendageRun& r : c_.runs)
      if (Straight(r) && r.n > 0.0) w.push_back(1.0 - r.U_A / r.u);
    if (w.empty()) return Keep("w_P0", "no straight-ahead run with the propeller working");
    double mean = 0, ss = 0;
    for (double x : w) mean += x / static_cast<double>(w.size());
    for (double x : w) ss += (x - mean) * (x - mean);
    Set("w_P0", mean, static_cast<int>(w.size()), std::sqrt(ss / static_cast<double>(w.size())), "1");
  }

  void ThrustDeduction() {
    if (!o_.bare_X) return Keep("t_P", "no bare-hull straight-ahead run at the runs' speed in the campaign");
    std::vector<double> T, dX;
    for (const AppendageRun& r : c_.runs) {
      if (Straight(r) && std::abs(r.delta) < kRudderZero && r.n > 0.0) {
        T.push_back(r.T);
        dX.push_back(r.X - *o_.bare_X);
      }
    }
    if (T.empty()) return Keep("t_P", "no straight-ahead run at delta = 0");
    const auto [k, rms] = SlopeThroughOrigin(T, dX);
    Set("t_P", 1.0 - k, static_cast<int>(T.size()), rms, "N");
  }

  void InflowSpeed() {
    const double D = c_.geometry.D_p, eta = D / c_.geometry.H_R;
    double p[2] = {At("epsilon").ship, At("kappa").ship};
    ceres::Problem problem;
    double J_min = 1e300, J_max = -1e300;
    int runs = 0;
    for (const AppendageRun& r : c_.runs) {
      if (!(r.n > 0.0) || !(r.u_R > 0.0)) continue;
      const double race = std::sqrt(std::max(0.0, r.U_A * r.U_A + 8.0 * r.K_T * r.n * r.n * D * D / std::numbers::pi));
      problem.AddResidualBlock(new ceres::AutoDiffCostFunction<InflowSpeedResidual, 1, 2>(
                                   new InflowSpeedResidual{r.u_R, r.U_A, race, eta}),
                               nullptr, p);
      J_min = std::min(J_min, r.J);
      J_max = std::max(J_max, r.J);
      ++runs;
    }
    if (runs == 0) {
      Keep("epsilon", "no run with the propeller working and inflow at the rudder");
      return Keep("kappa", "no run with the propeller working and inflow at the rudder");
    }
    const bool loadings = J_max - J_min > 0.05;
    if (!loadings) {
      problem.SetManifold(p, new ceres::SubsetManifold(2, {1}));
      Keep("kappa", fmt::format("the runs' advance ratios span only {:.3g} to {:.3g} (runs at other propeller rates "
                                "separate kappa from epsilon)",
                                J_min, J_max));
    }
    const double rms = std::sqrt(2.0 * Solve(problem) / runs);
    Set("epsilon", p[0], runs, rms, "m/s");
    if (loadings) Set("kappa", p[1], runs, rms, "m/s");
  }

  void InflowAngle() {
    double p[3] = {At("gamma_R_minus").ship, At("gamma_R_plus").ship, At("l_R_prime").ship};
    ceres::Problem problem;
    int runs = 0, yawing = 0, minus = 0, plus = 0;
    const double L = c_.geometry.Lpp;
    for (const AppendageRun& r : c_.runs) {
      const double U = Speed(r), beta = std::atan2(-r.v, r.u), r_prime = r.r * L / U;
      problem.AddResidualBlock(new ceres::AutoDiffCostFunction<InflowAngleResidual, 1, 3>(
                                   new InflowAngleResidual{r.v_R / U, beta, r_prime}),
                               nullptr, p);
      ++runs;
      if (std::abs(r_prime) > 1e-3) ++yawing;
      const double beta_R = beta - p[2] * r_prime;
      if (beta_R < -1e-3) ++minus;
      if (beta_R > 1e-3) ++plus;
    }
    std::vector<int> held;
    if (minus == 0) held.push_back(0), Keep("gamma_R_minus", "no run with beta_R < 0");
    if (plus == 0) held.push_back(1), Keep("gamma_R_plus", "no run with beta_R > 0");
    if (yawing == 0) held.push_back(2), Keep("l_R_prime", "no yawing run (circular motion)");
    if (held.size() == 3) return;
    if (!held.empty()) problem.SetManifold(p, new ceres::SubsetManifold(3, held));
    const double rms = std::sqrt(2.0 * Solve(problem) / runs);
    if (minus > 0) Set("gamma_R_minus", p[0], runs, rms, "1 (v_R / U)");
    if (plus > 0) Set("gamma_R_plus", p[1], runs, rms, "1 (v_R / U)");
    if (yawing > 0) Set("l_R_prime", p[2], runs, rms, "1 (v_R / U)");
  }

  void LiftSlope() {
    const double deg = std::numbers::pi / 180.0;
    std::vector<double> k, F;
    for (const AppendageRun& r : c_.runs) {
      const double alpha = r.delta - std::atan2(r.v_R, r.u_R);
      if (std::abs(alpha) < 2.0 * deg || std::abs(alpha) > 30.0 * deg) continue;
      k.push_back(0.5 * c_.geometry.rho * c_.geometry.A_R * (r.u_R * r.u_R + r.v_R * r.v_R) * std::sin(alpha));
      F.push_back(r.F_N);
    }
    if (k.empty()) return Keep("f_alpha", "no run with the rudder's inflow angle between 2 and 30 deg");
    const auto [slope, rms] = SlopeThroughOrigin(k, F);
    Set("f_alpha", slope, static_cast<int>(k.size()), rms, "N");
  }

  // Straight-ahead runs against the delta = 0 run at the same rate.
  void RudderForces() {
    const double one_minus_tP = 1.0 - At("t_P").value;
    std::vector<double> fx, dx, fy, dy, dn;
    for (const AppendageRun& r : c_.runs) {
      if (!Straight(r) || std::abs(r.delta) < kRudderZero) continue;
      const auto base = std::find_if(c_.runs.begin(), c_.runs.end(), [&](const AppendageRun& b) {
        return Straight(b) && std::abs(b.delta) < kRudderZero && std::abs(b.n - r.n) <= 1e-9 * std::abs(r.n) &&
               std::abs(b.u - r.u) <= 1e-9 * r.u;
      });
      if (base == c_.runs.end()) continue;
      fx.push_back(-r.F_N * std::sin(r.delta));
      dx.push_back(r.X - base->X - one_minus_tP * (r.T - base->T));
      fy.push_back(-(r.F_N * std::cos(r.delta) - base->F_N));
      dy.push_back(r.Y - base->Y);
      dn.push_back(r.N - base->N);
    }
    if (fx.size() < 2) {
      const std::string why = "fewer than two straight-ahead runs with the rudder over, each with a delta = 0 run "
                              "at its propeller rate";
      for (const char* k : {"t_R", "a_H", "x_H_prime"}) Keep(k, why);
      return;
    }
    const int runs = static_cast<int>(fx.size());
    const auto [kx, rx] = SlopeThroughOrigin(fx, dx);
    Set("t_R", 1.0 - kx, runs, rx, "N");
    const auto [ky, ry] = SlopeThroughOrigin(fy, dy);
    Set("a_H", ky - 1.0, runs, ry, "N");
    const auto [kn, rn] = SlopeThroughOrigin(fy, dn);
    const double L = c_.geometry.Lpp, a_H = ky - 1.0;
    if (std::abs(a_H) < 0.02) {
      return Keep("x_H_prime", fmt::format("a_H = {:.3g} is too small to place its force", a_H));
    }
    Set("x_H_prime", (kn - c_.geometry.x_R_prime * L) / (a_H * L), runs, rn, "N m");
  }

  const data::AppendageCampaign& c_;
  const InteractionFitOptions& o_;
  InteractionFitResult out_;
};

}  // namespace

const InteractionCoefficient& InteractionFitResult::Get(const std::string& name) const {
  const auto it = std::find_if(coefficients.begin(), coefficients.end(), [&](const auto& k) { return k.name == name; });
  KELVIN_CHECK(it != coefficients.end(), "an interaction coefficient's name");
  return *it;
}

std::map<std::string, double> InteractionFitResult::Identified() const {
  std::map<std::string, double> out;
  for (const InteractionCoefficient& k : coefficients)
    if (k.identified) out[k.name] = k.value;
  return out;
}

std::optional<double> BareStraightX(const data::CaptiveCampaign& campaign, double U) {
  for (const data::CaptiveRun& run : campaign.runs) {
    const data::MotionParameters& m = run.motion;
    if (m.kind != data::MotionKind::kStaticDrift || std::abs(m.beta) > 1e-9 || std::abs(m.U - U) > 1e-9 * U) continue;
    const double from = std::max(m.t_ramp, run.t_settle);
    double sum = 0;
    int count = 0;
    for (std::size_t i = 0; i < run.time.size(); ++i) {
      if (run.time[i] < from) continue;
      sum += run.force[0][i];
      ++count;
    }
    if (count > 0) return sum / count;
  }
  return std::nullopt;
}

InteractionFitResult FitInteraction(const data::AppendageCampaign& campaign, const InteractionFitOptions& options,
                                    const std::string& source) {
  const bool base = std::any_of(campaign.runs.begin(), campaign.runs.end(), [](const AppendageRun& r) {
    return Straight(r) && std::abs(r.delta) < kRudderZero;
  });
  if (!base) {
    throw InputError(fmt::format("{}: the appendage runs have no straight-ahead run at delta = 0; expected one (the "
                                 "reference of the rudder-force and thrust-deduction equations)",
                                 source));
  }
  return Fit(campaign, options, source).Run();
}

}  // namespace kelvin::ident
