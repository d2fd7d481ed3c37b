// The MMG standard model (Yasukawa & Yoshimura 2015, J. Mar. Sci. Technol.
// 20:37-52), 3DoF surge-sway-yaw, templated on the scalar so that the same
// code runs with double in the simulator and with ceres::Jet in
// identification.
//
// Conventions (the paper's, followed throughout kelvin):
// - Ship axes at midship: x forward, y starboard, z down; psi and r positive
//   clockwise seen from above (to starboard).
// - The state velocities are u (surge) and v_m (sway at midship); U =
//   sqrt(u^2 + v_m^2), v' = v_m / U, r' = r Lpp / U, beta = atan(-v_m / u).
// - N is the yaw moment about midship; x_G is the centre of gravity ahead of
//   midship, so the motion equations carry the x_G coupling terms (paper
//   eq. 4). Public implementations differ here (some take v at G, or N about
//   G); kelvin keeps everything at midship, as the paper does.
// - Propeller position x'_P = -0.48 for KVLCC2 is the paper's value (some
//   public codes use -0.5 or -0.69); it enters only beta_P = beta - x'_P r'.
// - Positive rudder angle delta turns the ship to starboard (it gives a
//   negative Y_R at the stern and a positive N_R).
#pragma once

#include <array>
#include <cmath>

#include "simulator/mmg/ship_parameters.h"

namespace kelvin::sim {

template <typename T>
struct PlanarForce {
  T X{};  // N, surge force
  T Y{};  // N, sway force
  T N{};  // N m, yaw moment about midship
};

// Every force component and the intermediate quantities of the model at one
// state, for tests, plots and diagnostics.
template <typename T>
struct MmgForces {
  PlanarForce<T> hull, propeller, rudder, total;
  T U{};        // m/s, speed at midship
  T beta{};     // rad, drift angle at midship
  T w_P{};      // wake fraction at the propeller in maneuvering
  T J_P{};      // propeller advance ratio
  T K_T{};      // thrust coefficient
  T thrust{};   // N
  T u_R{}, v_R{};  // m/s, inflow velocities at the rudder
  T alpha_R{};  // rad, effective rudder inflow angle
  T F_N{};      // N, rudder normal force
};

// State vector layout used by the integrators: earth-fixed position of
// midship, heading, and body velocities.
enum StateIndex : int { kX = 0, kY = 1, kPsi = 2, kU = 3, kV = 4, kR = 5, kStateSize = 6 };

template <typename T>
class MmgModel {
 public:
  MmgModel(const ShipParameters& ship, const HullCoefficients<T>& hull) : ship_(ship), hull_(hull) {}
  explicit MmgModel(const ShipParameters& ship) : ship_(ship), hull_(ship.hull.template Cast<T>()) {}

  const ShipParameters& ship() const { return ship_; }
  const HullCoefficients<T>& hull() const { return hull_; }

  // Nondimensional hull forces X'_H, Y'_H, N'_H at (v', r').
  PlanarForce<T> HullForcesPrime(const T& v_p, const T& r_p) const {
    const HullCoefficients<T>& h = hull_;
    const T v2 = v_p * v_p, r2 = r_p * r_p;
    PlanarForce<T> f;
    f.X = -h.R0 + h.X_vv * v2 + h.X_vr * v_p * r_p + h.X_rr * r2 + h.X_vvvv * v2 * v2;
    f.Y = h.Y_v * v_p + h.Y_r * r_p + h.Y_vvv * v2 * v_p + h.Y_vvr * v2 * r_p + h.Y_vrr * v_p * r2 +
          h.Y_rrr * r2 * r_p;
    f.N = h.N_v * v_p + h.N_r * r_p + h.N_vvv * v2 * v_p + h.N_vvr * v2 * r_p + h.N_vrr * v_p * r2 +
          h.N_rrr * r2 * r_p;
    return f;
  }

  // Dimensional hull forces at body velocities (u, v_m, r). Zero at rest.
  template <typename S>
  PlanarForce<T> HullForces(const S& u, const S& v_m, const S& r) const {
    using std::sqrt;
    const Principal& p = ship_.principal;
    const S U2 = u * u + v_m * v_m;
    PlanarForce<T> f;
    if (!(U2 > S(0))) return f;
    const S U = sqrt(U2);
    const PlanarForce<T> fp = HullForcesPrime(T(v_m / U), T(r * p.Lpp / U));
    const double q = 0.5 * p.rho * p.Lpp * p.d;
    f.X = T(q * U2) * fp.X;
    f.Y = T(q * U2) * fp.Y;
    f.N = T(q * p.Lpp * U2) * fp.N;
    return f;
  }

  // Every force on the ship at body velocities (u, v_m, r), rudder angle
  // delta (rad) and propeller speed n (1/s).
  MmgForces<T> Forces(const T& u, const T& v_m, const T& r, const T& delta, const T& n) const {
    using std::abs;
    using std::atan2;
    using std::cos;
    using std::exp;
    using std::sin;
    using std::sqrt;
    const Principal& p = ship_.principal;
    const PropellerParameters& pp = ship_.propeller;
    const RudderParameters& rp = ship_.rudder;
    const double L = p.Lpp;
    MmgForces<T> out;
    out.hull = HullForces(u, v_m, r);
    const T U2 = u * u + v_m * v_m;
    out.U = sqrt(U2 + T(1e-300));
    const bool moving = U2 > T(0);
    out.beta = moving ? atan2(-v_m, u) : T(0);
    const T r_p = moving ? T(r * L / out.U) : T(0);

    // Propeller (paper eqs. 13-16).
    const T beta_P = out.beta - pp.x_P_prime * r_p;
    const double C2 = beta_P > T(0) ? pp.C2_pos : pp.C2_neg;
    const T one_minus_wP = (1.0 - pp.w_P0) * (1.0 + (1.0 - exp(-pp.C1 * abs(beta_P))) * (C2 - 1.0));
    out.w_P = 1.0 - one_minus_wP;
    const T u_a = u * one_minus_wP;  // advance speed at the propeller
    const double D = pp.D_p;
    T K_T(0);
    if (n != T(0)) {
      out.J_P = u_a / (n * D);
      if (n < T(0) && pp.reverse_kt) {
        const auto& k = *pp.reverse_kt;
        K_T = k[0] + k[1] * out.J_P + k[2] * out.J_P * out.J_P;
      } else {
        K_T = pp.k0 + pp.k1 * out.J_P + pp.k2 * out.J_P * out.J_P;
      }
    }
    out.K_T = K_T;
    const double D4 = D * D * D * D;
    // T = rho n^2 D^4 K_T; astern thrust comes from a negative K_T of the
    // reverse-rotation curve.
    out.thrust = p.rho * n * n * D4 * K_T;
    out.propeller.X = (1.0 - pp.t_P) * out.thrust;

    // Rudder (paper eqs. 17-25). The propeller-race term is written as
    // sqrt(u_a^2 + 8 K_T n^2 D^2 / pi), which equals u_a sqrt(1 + 8 K_T / (pi J^2))
    // and stays regular when u_a -> 0.
    const double eta = D / rp.H_R;
    T race2 = u_a * u_a + 8.0 * K_T * n * n * D * D / M_PI;
    if (race2 < T(0)) race2 = T(0);
    const T race = sqrt(race2 + T(1e-300));
    const T slip = u_a + rp.kappa * (race - u_a);
    T uR2 = eta * slip * slip + (1.0 - eta) * u_a * u_a;
    out.u_R = rp.epsilon * sqrt(uR2 + T(1e-300));
    const T beta_R = out.beta - rp.l_R_prime * r_p;
    const double gamma_R = beta_R < T(0) ? rp.gamma_R_minus : rp.gamma_R_plus;
    out.v_R = out.U * gamma_R * beta_R;
    out.alpha_R = delta - atan2(out.v_R, out.u_R);
    const T UR2 = out.u_R * out.u_R + out.v_R * out.v_R;
    out.F_N = 0.5 * p.rho * rp.A_R * UR2 * rp.f_alpha * sin(out.alpha_R);
    const T cd = cos(delta), sd = sin(delta);
    const double x_R = rp.x_R_prime * L, x_H = rp.x_H_prime * L;
    out.rudder.X = -(1.0 - rp.t_R) * out.F_N * sd;
    out.rudder.Y = -(1.0 + rp.a_H) * out.F_N * cd;
    out.rudder.N = -(x_R + rp.a_H * x_H) * out.F_N * cd;

    out.total.X = out.hull.X + out.propeller.X + out.rudder.X;
    out.total.Y = out.hull.Y + out.rudder.Y;
    out.total.N = out.hull.N + out.rudder.N;
    return out;
  }

  // Dimensional added masses and inertias.
  T AddedMassX() const { return hull_.m_x * MassScale(); }
  T AddedMassY() const { return hull_.m_y * MassScale(); }
  T AddedInertiaZ() const { return hull_.J_z * MassScale() * ship_.principal.Lpp * ship_.principal.Lpp; }

  // Body accelerations (du/dt, dv_m/dt, dr/dt) from the motion equations at
  // midship (paper eq. 4) for given total forces.
  std::array<T, 3> Accelerations(const T& u, const T& v_m, const T& r, const PlanarForce<T>& f) const {
    const double m = ship_.mass();
    const double xG = ship_.principal.x_G;
    const T mx = m + AddedMassX();
    const T my = m + AddedMassY();
    const T Iz = ship_.I_zG() + xG * xG * m + AddedInertiaZ();
    const T du = (f.X + my * v_m * r + xG * m * r * r) / mx;
    // [my, xG m; xG m, Iz] [dv; dr] = [Y - mx u r; N - xG m u r]
    const T rhs_v = f.Y - mx * u * r;
    const T rhs_r = f.N - xG * m * u * r;
    const T det = my * Iz - xG * m * xG * m;
    const T dv = (Iz * rhs_v - xG * m * rhs_r) / det;
    const T dr = (my * rhs_r - xG * m * rhs_v) / det;
    return {du, dv, dr};
  }

  // Time derivative of the full state [x, y, psi, u, v_m, r] (earth-fixed
  // position of midship, x north/forward at psi = 0, y east/starboard).
  void Derivative(const T* s, const T& delta, const T& n, T* ds) const {
    using std::cos;
    using std::sin;
    const T c = cos(s[kPsi]), sn = sin(s[kPsi]);
    ds[kX] = s[kU] * c - s[kV] * sn;
    ds[kY] = s[kU] * sn + s[kV] * c;
    ds[kPsi] = s[kR];
    const MmgForces<T> f = Forces(s[kU], s[kV], s[kR], delta, n);
    const auto acc = Accelerations(s[kU], s[kV], s[kR], f.total);
    ds[kU] = acc[0];
    ds[kV] = acc[1];
    ds[kR] = acc[2];
  }

 private:
  double MassScale() const { return 0.5 * ship_.principal.rho * ship_.principal.Lpp * ship_.principal.Lpp * ship_.principal.d; }

  // The one owned copy (a Simulator and the Bridge refer to their model's): models
  // are built from temporary parameter sets (LoadShip(), identification's HullShipFrom()).
  ShipParameters ship_;
  HullCoefficients<T> hull_;
};

}  // namespace kelvin::sim
