// Free-surface wave analysis on a patch's elevation field eta
// (docs/formulation.md section 5):
// - wave cuts: eta along lines y = const, sampled in the patch face that
//   contains each point and reconstructed linearly with the face gradient;
// - the hull wave profile: eta extrapolated to the waterline edges on the hull;
// - the waterline-integral force R_WL = sum_e 0.5 rho g eta_e^2 n_e over the
//   patch edges on the hull (n_e the in-plane edge normal times the edge
//   length, pointing from the water into the hull: the hydrostatic pressure
//   rho g (eta - z) of the wave crest between z = 0 and z = eta), which the
//   resistance report gives apart from R_T.
#pragma once

#include <span>
#include <vector>

#include "cfd/freesurface/patch_surface.h"
#include "cfd/mesh/mesh.h"

namespace kelvin::cfd {

// Elevation along the line y = y0 at the given x stations; NaN where the
// point lies outside the patch (e.g. inside the hull's waterplane).
std::vector<double> WaveCut(const PatchSurface& surface, std::span<const double> eta, double y0,
                            std::span<const double> x);

struct WaveProfile {
  std::vector<double> x, y, eta;  // per waterline edge on the hull, sorted by (side, x)
};
// eta at the edges of the patch that lie on mesh patch `hull_patch`,
// extrapolated from the face with its least-squares gradient.
WaveProfile HullWaveProfile(const PatchSurface& surface, std::span<const double> eta, int hull_patch);

// Waterline-integral force (N, mesh axes) on the hull: sum over the hull rim
// edges of 0.5 rho g eta_e^2 n_e (see above); eta_e as in HullWaveProfile.
Vector3 WaterlineForce(const PatchSurface& surface, std::span<const double> eta, int hull_patch, double rho,
                       double g);

}  // namespace kelvin::cfd
