// The force a captive model feels in prescribed motion, according to the MMG
// standard model (Yasukawa & Yoshimura 2015, eq. 4 with the added-mass terms
// moved to the force side):
//   X_hyd = X_H(u, v_m, r) - m_x du + m_y v_m r
//   Y_hyd = Y_H(u, v_m, r) - m_y dv - m_x u r
//   N_hyd = N_H(u, v_m, r) - J_z dr
// with the hull polynomial X_H, Y_H, N_H and the added masses of MmgModel<T>.
// Templated so that the joint fit evaluates it with ceres::Jet parameters and
// the virtual captive generator with double, from the same code.
#pragma once

#include <array>

#include "data/schema/captive_run.h"
#include "simulator/mmg/mmg_model.h"

namespace kelvin::ident {

template <typename T>
std::array<T, 3> CaptiveHydrodynamicForce(const sim::MmgModel<T>& model,
                                          const data::BodyKinematics& k) {
  const sim::PlanarForce<T> h = model.HullForces(k.u, k.v, k.r);
  const T m_x = model.AddedMassX(), m_y = model.AddedMassY(), j_z = model.AddedInertiaZ();
  return {h.X - m_x * k.du + m_y * (k.v * k.r), h.Y - m_y * k.dv - m_x * (k.u * k.r),
          h.N - j_z * k.dr};
}

}  // namespace kelvin::ident
