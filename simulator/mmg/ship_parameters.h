// Ship parameters of the MMG standard method (Yasukawa & Yoshimura 2015,
// J. Mar. Sci. Technol. 20:37-52): principal particulars, the nondimensional
// hull derivatives and added masses (the part identification fits), and the
// propeller and rudder interaction coefficients.
//
// Prime system: forces / (0.5 rho L d U^2), moments / (0.5 rho L^2 d U^2),
// masses / (0.5 rho L^2 d), yaw inertia / (0.5 rho L^4 d), v' = v_m / U,
// r' = r L / U, with v_m the sway velocity at midship.
#pragma once

#include <array>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>

#include "simulator/mmg/open_water.h"

namespace kelvin::data {
class ConfigNode;
}  // namespace kelvin::data

namespace kelvin::sim {

// The hull polynomial and added masses, templated so that identification can
// evaluate the same model with ceres::Jet parameters.
template <typename T>
struct HullCoefficients {
  // Surge: X'_H = -R0' + X_vv v'^2 + X_vr v' r' + X_rr r'^2 + X_vvvv v'^4.
  T R0{}, X_vv{}, X_vr{}, X_rr{}, X_vvvv{};
  // Sway: Y'_H = Y_v v' + Y_r r' + Y_vvv v'^3 + Y_vvr v'^2 r' + Y_vrr v' r'^2 + Y_rrr r'^3.
  T Y_v{}, Y_r{}, Y_vvv{}, Y_vvr{}, Y_vrr{}, Y_rrr{};
  // Yaw (about midship), same polynomial form as sway.
  T N_v{}, N_r{}, N_vvv{}, N_vvr{}, N_vrr{}, N_rrr{};
  // Added masses m'_x, m'_y and added yaw inertia J'_z.
  T m_x{}, m_y{}, J_z{};

  static constexpr int kCount = 20;
  // Names in the order of Data(), as written in ship and derivative files.
  static constexpr std::array<std::string_view, kCount> kNames = {
      "R0_prime", "X_vv",  "X_vr",  "X_rr",  "X_vvvv", "Y_v",   "Y_r",   "Y_vvv", "Y_vvr", "Y_vrr",
      "Y_rrr",    "N_v",   "N_r",   "N_vvv", "N_vvr",  "N_vrr", "N_rrr", "m_x_prime", "m_y_prime", "J_z_prime"};

  // Coefficients as a contiguous array in kNames order (for optimizers).
  T* Data() { return &R0; }
  const T* Data() const { return &R0; }
  T& operator[](int i) { return Data()[i]; }
  const T& operator[](int i) const { return Data()[i]; }

  template <typename U>
  HullCoefficients<U> Cast() const {
    HullCoefficients<U> out;
    for (int i = 0; i < kCount; ++i) out[i] = U((*this)[i]);
    return out;
  }
};
static_assert(sizeof(HullCoefficients<double>) == 20 * sizeof(double), "HullCoefficients must be packed");

struct Principal {
  double Lpp = 0;           // m, length between perpendiculars
  double B = 0;             // m, beam
  double d = 0;             // m, draft
  double displacement = 0;  // m^3, volume displacement
  double x_G = 0;           // m, centre of gravity from midship, forward positive
  double k_zz = 0.25;       // yaw radius of gyration / Lpp (I_zG = m (k_zz Lpp)^2)
  double rho = 1025.0;      // kg/m^3
  double wetted_area = 0;   // m^2, optional (0 = unknown); needed for the ITTC friction correction
  double nu = 1.1883e-6;    // m^2/s, kinematic viscosity (fresh water 15 C for model basins)
};

struct PropellerParameters {
  double D_p = 0;      // m, diameter
  double t_P = 0;      // thrust deduction factor
  double w_P0 = 0;     // wake fraction at the propeller in straight motion
  double k0 = 0, k1 = 0, k2 = 0;  // K_T(J) = k0 + k1 J + k2 J^2 (first quadrant)
  double x_P_prime = 0;           // longitudinal propeller position / Lpp
  double C1 = 2.0;                // wake change in maneuvering (paper eq. 16)
  double C2_pos = 1.6, C2_neg = 1.1;
  // Reverse rotation (n < 0): K_T = k0 + k1 J + k2 J^2 with J = u_P / (n D_p)
  // (negative when going ahead), negative K_T meaning astern thrust
  // (T = rho n^2 D^4 K_T). Absent for most published MMG sets.
  std::optional<std::array<double, 3>> reverse_kt;

  // The body-force propeller of the CFD (cfd/propulsion) reads these too:
  std::optional<double> hub_ratio;  // r_hub / R
  double y_P = 0.0;                 // m, shaft axis to starboard of the centreline
  std::optional<double> z_P;        // m, depth of the shaft axis below the design waterline
  // Open-water table (propeller.open_water: {J, K_T, K_Q}); without it the
  // CFD tabulates k0 + k1 J + k2 J^2 with K_Q = q0 + q1 J + q2 J^2 from
  // propeller.K_Q_coefficients, up to the J where K_T = 0.
  std::optional<OpenWaterCurve> open_water;
  std::optional<std::array<double, 3>> kq;
  int blades = 0;  // descriptive (0: not given)
  // The MMG keys (t_P, w_P0, k0..k2) are optional in a ship file without a
  // hull section (a hull for CFD only); false when they are absent.
  bool mmg = true;
};

struct RudderParameters {
  double A_R = 0;    // m^2, rudder area
  double H_R = 0;    // m, rudder span
  double t_R = 0;    // steering resistance deduction
  double a_H = 0;    // rudder force increase factor
  double x_H_prime = 0;  // position of the additional lateral force / Lpp
  double x_R_prime = -0.5;  // rudder position / Lpp
  double gamma_R_minus = 0;  // flow straightening for beta_R < 0
  double gamma_R_plus = 0;   // flow straightening for beta_R > 0
  double l_R_prime = 0;      // effective longitudinal rudder position / Lpp
  double epsilon = 0;        // wake ratio (1 - w_R) / (1 - w_P)
  double kappa = 0;          // propeller race increase factor
  double f_alpha = 0;        // rudder lift gradient
  std::optional<double> z_top;  // m, depth of the blade's top below the design waterline (the CFD rudder)
};

struct ActuatorLimits {
  double rudder_max = 35.0 * 3.14159265358979323846 / 180.0;  // rad
  double rudder_rate = 2.34 * 3.14159265358979323846 / 180.0;  // rad/s
  std::optional<double> rps_max;                                // 1/s; empty: no limit
  double rps_rate = 0;  // 1/s^2, 0 = instantaneous
};

struct ShipParameters {
  std::string name;
  std::string source;        // citation of the parameter set
  std::string scale_name;    // "model" or "full scale" or a custom label
  double scale = 1.0;        // geometric scale ratio to full scale (lambda); 1 at full scale
  Principal principal;
  HullCoefficients<double> hull;
  PropellerParameters propeller;
  RudderParameters rudder;
  ActuatorLimits limits;
  double approach_speed = 0;  // m/s, default approach speed U0 for maneuvers
  // A ship file for CFD alone may leave out the hull and rudder sections
  // (and the MMG propeller keys): the simulator then needs --derivatives
  // and refuses a ship without a rudder (RequireManeuveringModel).
  bool has_hull = true;
  bool has_rudder = true;

  double mass() const { return principal.rho * principal.displacement; }
  double I_zG() const { return mass() * (principal.k_zz * principal.Lpp) * (principal.k_zz * principal.Lpp); }

  // Throws kelvin::ModelError naming the parameter, its value and what is
  // physical (positive mass, rudder area > 0, 0 <= t_P < 1, ...).
  void Validate(const std::string& source_name = "ship") const;

 private:
  void ValidateRudder(const std::string& source_name) const;
};

// Loads a ship file (data/ships/<ship>.yaml). Every unknown key is an error.
ShipParameters LoadShip(const std::filesystem::path& path);
// The same from a ship file already parsed; `path` locates the files it refers to.
ShipParameters LoadShip(const data::ConfigNode& root, const std::filesystem::path& path);

// Throws ConfigError naming `source` when the ship lacks what the MMG model
// needs (hull derivatives, rudder, the MMG propeller keys).
void RequireManeuveringModel(const ShipParameters& ship, const std::string& source);

// The open-water curve of the CFD propeller: the table, or the quadratics
// (see PropellerParameters); a ConfigError naming `source` without K_Q.
OpenWaterCurve CfdOpenWater(const ShipParameters& ship, const std::string& source);

// The same nondimensional model at another geometric scale (Froude scaling):
// lengths x lambda, areas x lambda^2, volume x lambda^3, speeds x sqrt(lambda),
// rudder rate / sqrt(lambda). With `friction_correction`, R0' is corrected by
// the ITTC-1957 friction line difference (C_F(Re_to) - C_F(Re_from)) S / (L d)
// (data::Ittc57FrictionCoefficient), which needs the wetted area.
ShipParameters ScaleShip(const ShipParameters& ship, double lambda, bool friction_correction);

}  // namespace kelvin::sim
