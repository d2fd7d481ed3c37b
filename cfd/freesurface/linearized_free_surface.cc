#include "cfd/freesurface/linearized_free_surface.h"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <numeric>

#include "cfd/fv/cell_velocity.h"
#include "data/schema/errors.h"

namespace kelvin::cfd {
namespace {

bool LocalFlow(const LinearizedFreeSurfaceOptions& o) {
  return o.linearization == LinearizedFreeSurfaceOptions::Linearization::kLocalFlow;
}

}  // namespace

void LinearizedFreeSurfaceOptions::Validate() const {
  if (!(g > 0.0) || !std::isfinite(g))
    throw ConfigError(fmt::format("g = {}; expected > 0 m/s^2", g));
  if (!(kinematic_courant >= 0.0) || !std::isfinite(kinematic_courant)) {
    throw ConfigError(
        fmt::format("kinematic_courant = {}; expected >= 0 (0 = off)", kinematic_courant));
  }
  if (!(beach.width >= 0.0) || !std::isfinite(beach.width)) {
    throw ConfigError(
        fmt::format("beach.width = {}; expected >= 0 transverse wavelengths", beach.width));
  }
  if (beach.width > 0.0) {
    if (!(beach.strength > 0.0) || !std::isfinite(beach.strength)) {
      throw ConfigError(
          fmt::format("beach.strength = {}; expected > 0 (mu_max U / g)", beach.strength));
    }
    if (!(beach.reference_speed > 0.0) || !std::isfinite(beach.reference_speed)) {
      throw ConfigError(
          fmt::format("beach reference speed = {} m/s; a beach is sized in transverse wavelengths "
                      "2 pi U^2 / g and needs a "
                      "mesh speed U > 0",
                      beach.reference_speed));
    }
    if (beach.sides.empty())
      throw ConfigError("beach.sides is empty; expected some of xmin, xmax, ymin, ymax");
  }
}

namespace {

// The surface face (index in the whole patch) of each face of the patch in
// the rank's mesh: its face in the undecomposed mesh less the patch start
// there. Every face of the whole patch is one rank's own (the free surface
// bounds owned cells only), which the gather of the faces checks.
bool Parallel(const FreeSurfaceOnRanks& ranks) { return ranks.part && ranks.part->parallel(); }

std::vector<int> SurfaceFaces(const Mesh& mesh, int patch_index, const FreeSurfaceOnRanks& ranks) {
  const Patch& patch = mesh.patches()[patch_index];
  std::vector<int> faces(static_cast<std::size_t>(patch.size));
  if (!Parallel(ranks)) {
    std::iota(faces.begin(), faces.end(), 0);
    return faces;
  }
  KELVIN_CHECK(ranks.whole && ranks.whole->patches()[patch_index].name == patch.name,
               "the free-surface patch has the same index in the whole mesh");
  const Patch& whole = ranks.whole->patches()[patch_index];
  for (int i = 0; i < patch.size; ++i) {
    const long long g = ranks.part->faces[static_cast<std::size_t>(patch.start + i)] - whole.start;
    KELVIN_CHECK(g >= 0 && g < whole.size, "a free-surface face of the rank inside the whole patch");
    faces[static_cast<std::size_t>(i)] = static_cast<int>(g);
  }
  return faces;
}

}  // namespace

LinearizedFreeSurface::LinearizedFreeSurface(const Mesh& mesh, int patch_index,
                                             LinearizedFreeSurfaceOptions options, FreeSurfaceOnRanks ranks)
    : Mixed<double>(0.0, 0.0, 1.0),
      mesh_(mesh),
      patch_index_(patch_index),
      options_(std::move(options)),
      surface_(Parallel(ranks) && ranks.whole ? *ranks.whole : mesh, patch_index),
      surface_face_(SurfaceFaces(mesh, patch_index, ranks)) {
  options_.Validate();
  const int n = surface_.size();
  eta_.assign(n, 0.0);
  eta_star_.assign(n, 0.0);
  dt_eff_.assign(n, 0.0);
  const std::size_t own = surface_face_.size();
  ref_value().assign(own, 0.0);
  ref_gradient().assign(own, 0.0);
  fraction().assign(own, 1.0);
  if (Parallel(ranks)) {
    part_ = ranks.part;
    const std::vector<double> mine(surface_face_.begin(), surface_face_.end());
    const std::vector<double> all = AllGather(*part_, mine);
    std::vector<int> seen(static_cast<std::size_t>(n), 0);
    for (double g : all) {
      gathered_faces_.push_back(static_cast<int>(g));
      ++seen[static_cast<std::size_t>(g)];
    }
    KELVIN_CHECK(std::all_of(seen.begin(), seen.end(), [](int k) { return k == 1; }),
                 "every free-surface face is on exactly one rank");
  }

  extrapolate_rim_.assign(surface_.edges().size(), 0);
  for (const std::string& name : options_.waterline_patches) {
    const int q = mesh.FindPatch(name);
    if (q < 0 || q == patch_index) {
      throw ConfigError(fmt::format("waterline patch '{}' is not another patch of the mesh {}",
                                    name, mesh.source()));
    }
    for (std::size_t e = 0; e < surface_.edges().size(); ++e) {
      if (surface_.edges()[e].rim_patch == q) extrapolate_rim_[e] = 1;
    }
  }

  mu_.assign(n, 0.0);
  const auto& beach = options_.beach;
  if (beach.width > 0.0) {
    const double U = beach.reference_speed;
    const double width = beach.width * 2.0 * std::numbers::pi * U * U / options_.g;
    const double mu_max = beach.strength * options_.g / U;
    for (int i = 0; i < n; ++i) {
      const Vector3& x = surface_.centres()[i];
      double d = std::numeric_limits<double>::max();
      for (auto side : beach.sides) {
        switch (side) {
          case LinearizedFreeSurfaceOptions::Beach::Side::kXMin:
            d = std::min(d, x.x() - surface_.min().x());
            break;
          case LinearizedFreeSurfaceOptions::Beach::Side::kXMax:
            d = std::min(d, surface_.max().x() - x.x());
            break;
          case LinearizedFreeSurfaceOptions::Beach::Side::kYMin:
            d = std::min(d, x.y() - surface_.min().y());
            break;
          case LinearizedFreeSurfaceOptions::Beach::Side::kYMax:
            d = std::min(d, surface_.max().y() - x.y());
            break;
        }
      }
      const double s = std::clamp(1.0 - d / width, 0.0, 1.0);
      mu_[i] = mu_max * s * s * (3.0 - 2.0 * s);
    }
  }
}

double LinearizedFreeSurface::SurfacePressure(int i, double time) const {
  return options_.surface_pressure ? options_.surface_pressure(surface_.centres()[i], time) : 0.0;
}

void LinearizedFreeSurface::AdvanceTime(double time) {
  if (!started_) {
    started_ = true;
    time_ = time;
    return;
  }
  if (time > time_) {
    // A new time step: the converged elevation becomes eta^n.
    if (eta_old_.size() < 2) eta_old_.emplace_back();
    for (std::size_t l = eta_old_.size() - 1; l > 0; --l) eta_old_[l].swap(eta_old_[l - 1]);
    eta_old_[0] = eta_;
    time_ = time;
    armed_ = false;
    // A moving mesh is placed at the new time before its conditions update;
    // the patch moves rigidly in the plane, so only its geometry changes (the
    // beach, computed once, moves with the mesh).
    surface_.UpdateGeometry(mesh_);
  }
}

void LinearizedFreeSurface::Update(const BcContext& ctx, std::span<const double> cell_values) {
  KELVIN_CHECK(&ctx.patch == &mesh_.patches()[patch_index_],
               "free surface updated on its own patch");
  AdvanceTime(ctx.time);
  // Between pressure solves the condition is the plain dynamic condition;
  // during one it keeps the Robin coefficients the pressure equation used,
  // so the flux computed from them is the one eta is updated from.
  if (!armed_) {
    for (std::size_t i = 0; i < surface_face_.size(); ++i) {
      const int s = surface_face_[i];
      fraction()[i] = rigid_lid_ ? 0.0 : 1.0;
      ref_value()[i] = options_.g * eta_[s] + SurfacePressure(s, ctx.time);
      ref_gradient()[i] = 0.0;
    }
  }
  Mixed<double>::Update(ctx, cell_values);
}

void LinearizedFreeSurface::PreparePressureSolve(const BcContext& ctx,
                                                 const PressureCoupling& coupling) {
  AdvanceTime(ctx.time);
  KELVIN_CHECK(coupling.dt > 0.0, "positive time step");
  const Patch& patch = mesh_.patches()[patch_index_];
  const std::size_t own = surface_face_.size();
  // The local flow's base flow follows the flow under the lid and stays as
  // it was when the surface is released.
  if (LocalFlow(options_) && (rigid_lid_ || base_velocity_.empty())) SetBaseFlow(ctx);
  if (rigid_lid_) {
    // Zero flux: the normal pressure gradient balances the predicted flux,
    // F_f = F_HbyA,f - rAU_f |S_f| dp/dn = 0.
    for (std::size_t i = 0; i < own; ++i) {
      const int f = patch.start + static_cast<int>(i);
      fraction()[i] = 0.0;
      ref_gradient()[i] = coupling.flux_HbyA[f] / (coupling.rAUf[f] * mesh_.face_area_magnitudes()[f]);
    }
    armed_ = true;
    Mixed<double>::Update(ctx, {});
    return;
  }
  const double t = ctx.time;
  const bool bdf2 = coupling.backward && eta_old_.size() >= 2;
  // Every rank assembles the whole surface (the lagged parts read eta
  // across the partition) and keeps eta*_f and dt'_f of every face.
  std::vector<double>& known = eta_star_;
  std::vector<double> diag;
  AssembleKinematic(t, coupling.dt, bdf2, known, diag);
  for (int s = 0; s < surface_.size(); ++s) {
    // Non-finite (a diverging run): the elevation turns non-finite and the
    // solver reports the divergence.
    KELVIN_CHECK(diag[s] > 0.0 || !std::isfinite(diag[s]), "positive free-surface diagonal");
    dt_eff_[s] = 1.0 / diag[s];
    eta_star_[s] = dt_eff_[s] * known[s];
  }
  // The Robin condition of the faces in this mesh.
  for (std::size_t i = 0; i < own; ++i) {
    const int s = surface_face_[i];
    const int f = patch.start + static_cast<int>(i);
    const double mag = mesh_.face_area_magnitudes()[f];
    ref_gradient()[i] = 0.0;
    const double D = coupling.rAUf[f] * mag * DeltaCoeff(mesh_, f);
    const double c = options_.g * dt_eff_[s] * D / mag;
    fraction()[i] = 1.0 / (1.0 + c);
    ref_value()[i] = options_.g * (eta_star_[s] + dt_eff_[s] * coupling.flux_HbyA[f] / mag) + SurfacePressure(s, t);
  }
  armed_ = true;
  Mixed<double>::Update(ctx, {});
}

void LinearizedFreeSurface::SetBaseFlow(const BcContext& ctx) {
  KELVIN_CHECK(ctx.face_flux.size() == static_cast<std::size_t>(mesh_.n_faces()),
               "the relative face fluxes for the local-flow free surface");
  const Patch& patch = mesh_.patches()[patch_index_];
  const std::size_t own = surface_face_.size();
  std::vector<double> u(own), v(own);
  for (std::size_t i = 0; i < own; ++i) {
    const int f = patch.start + static_cast<int>(i);
    const Vector3 c = CellVelocityFromFluxes(mesh_, ctx.face_flux, mesh_.owner()[f]);
    u[i] = c.x();
    v[i] = c.y();
  }
  const int n = surface_.size();
  std::vector<double> all_u(n), all_v(n);
  if (part_) {
    const std::vector<double> gu = AllGather(*part_, u), gv = AllGather(*part_, v);
    for (std::size_t k = 0; k < gu.size(); ++k) {
      all_u[gathered_faces_[k]] = gu[k];
      all_v[gathered_faces_[k]] = gv[k];
    }
  } else {
    for (std::size_t i = 0; i < own; ++i) {
      all_u[surface_face_[i]] = u[i];
      all_v[surface_face_[i]] = v[i];
    }
  }
  base_velocity_.resize(n);
  for (int i = 0; i < n; ++i) base_velocity_[i] = Vector3(all_u[i], all_v[i], 0.0);
  // The edge fluxes: the velocity interpolated linearly between the two
  // face centres, and on the rim extrapolated from the face by its
  // least-squares gradient. The local flow does not cross a wall (the hull's
  // waterline, where the uniform stream does and eta is extrapolated): no
  // flux there. The extrapolated cell velocity would leave some, of either
  // sign, and an inflow across the waterline lowers the implicit diagonal.
  std::vector<Vector3> gu, gv;
  surface_.Gradient(all_u, gu);
  surface_.Gradient(all_v, gv);
  const auto& edges = surface_.edges();
  base_edge_flux_.resize(edges.size());
  for (std::size_t e = 0; e < edges.size(); ++e) {
    const auto& edge = edges[e];
    const int a = edge.face;
    const bool wall = edge.rim_patch >= 0 && mesh_.patches()[edge.rim_patch].kind == PatchKind::kWall;
    if (edge.neighbour < 0 && (extrapolate_rim_[e] || wall)) {
      base_edge_flux_[e] = 0.0;
      continue;
    }
    Vector3 c;
    if (edge.neighbour < 0) {
      const Vector3 d = edge.centre - surface_.centres()[a];
      c = base_velocity_[a] + Vector3(gu[a].dot(d), gv[a].dot(d), 0.0);
    } else {
      const double to_a = (edge.centre - surface_.centres()[a]).norm();
      const double to_b = (surface_.centres()[edge.neighbour] - edge.centre).norm();
      const double w = to_b / (to_a + to_b);
      c = w * base_velocity_[a] + (1.0 - w) * base_velocity_[edge.neighbour];
    }
    base_edge_flux_[e] = c.dot(edge.normal);
  }
}

Vector3 LinearizedFreeSurface::StreamAtFace(int i, double t) const {
  if (LocalFlow(options_)) return base_velocity_[i];
  return -options_.mesh_velocity(surface_.centres()[i], t);
}

void LinearizedFreeSurface::AssembleKinematic(double t, double dt, bool bdf2, std::vector<double>& known,
                                              std::vector<double>& diag) {
  const int n = surface_.size();
  const double a_t = bdf2 ? 1.5 : 1.0;
  const std::vector<double>& eta0 = eta_old_.empty() ? eta_ : eta_old_[0];
  known.assign(n, 0.0);
  diag.assign(n, 0.0);
  // The known part per unit time: the old levels ...
  for (int i = 0; i < n; ++i) {
    known[i] = bdf2 ? (2.0 * eta0[i] - 0.5 * eta_old_[1][i]) / dt : eta0[i] / dt;
    diag[i] = a_t / dt + mu_[i];
  }
  // ... and the advection relative to the mesh, c = -u_b or the local flow,
  // in conservative form on the edges (flux q_e = c . n_e |e| out of
  // edge.face). (A base flow read from the checkpoint of a local-flow run
  // does not advect a uniform-stream one.)
  const bool local = LocalFlow(options_);
  if (local ? !base_velocity_.empty() : static_cast<bool>(options_.mesh_velocity)) {
    const auto& edges = surface_.edges();
    if (local) {
      edge_flux_ = base_edge_flux_;
    } else {
      edge_flux_.resize(edges.size());
      for (std::size_t e = 0; e < edges.size(); ++e) {
        edge_flux_[e] = -options_.mesh_velocity(edges[e].centre, t).dot(edges[e].normal);
      }
    }
    using Advection = LinearizedFreeSurfaceOptions::Advection;
    const bool second_order = options_.advection != Advection::kUpwind;
    const bool quick = options_.advection == Advection::kQuick;
    if (second_order) surface_.Gradient(eta_, grad_);
    // Local range of eta (face and edge neighbours) for the limiter.
    const bool limit = second_order && options_.limit_advection;
    if (limit) {
      eta_min_.assign(eta_.begin(), eta_.end());
      eta_max_.assign(eta_.begin(), eta_.end());
      for (const auto& edge : edges) {
        if (edge.neighbour < 0) continue;
        const int a = edge.face, b = edge.neighbour;
        eta_min_[a] = std::min(eta_min_[a], eta_[b]);
        eta_max_[a] = std::max(eta_max_[a], eta_[b]);
        eta_min_[b] = std::min(eta_min_[b], eta_[a]);
        eta_max_[b] = std::max(eta_max_[b], eta_[a]);
      }
    }
    auto area = [&](int i) { return surface_.areas()[i]; };
    // High-order correction eta_e - eta_up on edge e from the upwind face u
    // (lagged iterate), or 0 (first order) where u has no gradient or the
    // velocity at u points the other way across the edge. Linear upwind:
    // eta_u + grad_u . (x_e - x_u). QUICK: the mean of that and the linear
    // interpolation between u and the downwind face d (d < 0 on the rim:
    // linear upwind).
    auto unlimited = [&](std::size_t e, int u, int d, double q_out_of_u) {
      if (!second_order || !surface_.valid_gradient(u)) return 0.0;
      // The advection velocity at u, as a flux out of u across the edge (the
      // edge normal points out of edge.face, into its neighbour).
      const double out_of_u = u == edges[e].face ? 1.0 : -1.0;
      const double q_at_u = out_of_u * StreamAtFace(u, t).dot(edges[e].normal);
      if (q_at_u * q_out_of_u <= 0.0) return 0.0;
      const double lud = grad_[u].dot(edges[e].centre - surface_.centres()[u]);
      if (!quick || d < 0) return lud;
      const double to_u = (edges[e].centre - surface_.centres()[u]).norm();
      const double to_d = (surface_.centres()[d] - edges[e].centre).norm();
      const double linear = to_u / (to_u + to_d) * (eta_[d] - eta_[u]);
      return 0.5 * (lud + linear);
    };
    // Faces fed across the hull waterline (extrapolated inflow edge) stay
    // first order on every edge. Their implicit diagonal is only the time
    // term plus the inflow from the other water faces (the waterline inflow
    // cancels most of the outflow coefficient), while a high-order
    // correction scales with the full outflow: lagged, it is amplified by
    // that ratio (about 1/cell width along a sloping stern waterline) and
    // diverges within a few steps at patch Courant numbers above about 2.
    waterline_fed_.assign(surface_.size(), 0);
    inflow_.assign(surface_.size(), 0.0);
    for (std::size_t e = 0; e < edges.size(); ++e) {
      if (edges[e].neighbour < 0 && extrapolate_rim_[e] && edge_flux_[e] < 0.0) waterline_fed_[edges[e].face] = 1;
    }
    auto correction = [&](std::size_t e, int u, int d, double q_out_of_u) {
      if (waterline_fed_[u]) return 0.0;
      const double c = unlimited(e, u, d, q_out_of_u);
      if (!limit) return c;
      return std::clamp(eta_[u] + c, eta_min_[u], eta_max_[u]) - eta_[u];
    };
    for (std::size_t e = 0; e < edges.size(); ++e) {
      const auto& edge = edges[e];
      const double q = edge_flux_[e];
      const int a = edge.face;
      if (edge.neighbour >= 0) {
        const int b = edge.neighbour;
        const int up = q >= 0.0 ? a : b;
        const int down = q >= 0.0 ? b : a;
        const double qa = std::abs(q);
        // Implicit upwind outflow of `up`; `down` receives it from the lagged
        // iterate.
        diag[up] += qa / area(up);
        known[down] += qa * eta_[up] / area(down);
        inflow_[down] += qa / area(down);
        const double dc = qa * correction(e, up, down, qa);
        known[up] -= dc / area(up);
        known[down] += dc / area(down);
      } else if (q >= 0.0) {
        diag[a] += q / area(a);
        known[a] -= q * correction(e, a, -1, q) / area(a);
      } else if (extrapolate_rim_[e]) {
        // Waterline inflow: the pattern leaves the hull with the elevation of
        // the face (zero gradient), implicit.
        diag[a] += q / area(a);
      }
      // Other inflow rim edges bring undisturbed water: eta_e = 0.
    }
  }

  if (options_.kinematic_courant > 0.0) {
    // Local pseudo-time: where the advection rate a_ff exceeds
    // kinematic_courant / dt, the time term becomes a_ff / kinematic_courant
    // (eta - eta^n), so that the lagged upstream coupling contracts by
    // C / (1 + C) per corrector. A steady state does not depend on it.
    // Where the local flow converges (toward a stagnation point) the lagged
    // inflow exceeds the outflow, eta grows at the rate of the difference
    // (the eta div_h u_h part of the condition), and the rate is raised by
    // it, so that the diagonal exceeds the inflow by the same margin.
    for (int i = 0; i < n; ++i) {
      const double outflow = diag[i] - a_t / dt - mu_[i];
      const double rate = local && !inflow_.empty() && inflow_[i] > outflow
                              ? inflow_[i] / options_.kinematic_courant + (inflow_[i] - outflow)
                              : outflow / options_.kinematic_courant;
      if (rate <= a_t / dt) continue;
      known[i] +=
          rate * eta0[i] - (bdf2 ? (2.0 * eta0[i] - 0.5 * eta_old_[1][i]) / dt : eta0[i] / dt);
      diag[i] += rate - a_t / dt;
    }
  }
}

void LinearizedFreeSurface::CorrectAfterFlux(const BcContext&, std::span<const double> face_flux) {
  if (!armed_) return;
  if (rigid_lid_) {
    armed_ = false;
    return;
  }
  const Patch& patch = mesh_.patches()[patch_index_];
  std::vector<double> own(surface_face_.size());
  for (std::size_t i = 0; i < own.size(); ++i) {
    const int s = surface_face_[i];
    const int f = patch.start + static_cast<int>(i);
    own[i] = eta_star_[s] + dt_eff_[s] * face_flux[f] / mesh_.face_area_magnitudes()[f];
  }
  if (part_) {
    // Every rank's faces, so that every rank holds the whole of eta.
    const std::vector<double> all = AllGather(*part_, own);
    for (std::size_t k = 0; k < all.size(); ++k) eta_[gathered_faces_[k]] = all[k];
  } else {
    for (std::size_t i = 0; i < own.size(); ++i) eta_[surface_face_[i]] = own[i];
  }
  armed_ = false;
}

std::vector<std::pair<std::string, std::vector<double>>> LinearizedFreeSurface::FaceFields() const {
  std::vector<std::pair<std::string, std::vector<double>>> fields = {{"eta", eta_}, {"beach_damping", mu_}};
  if (!base_velocity_.empty()) AppendBaseFlowFields(fields);
  return fields;
}

void LinearizedFreeSurface::AppendBaseFlowFields(std::vector<std::pair<std::string, std::vector<double>>>& fields) const {
  const int n = surface_.size();
  std::vector<double> u(n), v(n);
  for (int i = 0; i < n; ++i) {
    u[i] = base_velocity_[i].x();
    v[i] = base_velocity_[i].y();
  }
  // Per face, the base flow's outflow, its inflow from other faces, and its
  // inflow across the rim (m^2/s).
  std::vector<double> out(n, 0.0), in(n, 0.0), rim_in(n, 0.0);
  const auto& edges = surface_.edges();
  for (std::size_t e = 0; e < edges.size(); ++e) {
    const double q = base_edge_flux_[e];
    const int a = edges[e].face, b = edges[e].neighbour;
    if (q > 0.0) {
      out[a] += q;
      if (b >= 0) in[b] += q;
    } else if (b >= 0) {
      out[b] -= q;
      in[a] -= q;
    } else {
      rim_in[a] -= q;
    }
  }
  std::vector<double> divergence(n), gain(n);
  for (int i = 0; i < n; ++i) {
    divergence[i] = (out[i] - in[i] - rim_in[i]) / surface_.areas()[i];
    gain[i] = out[i] > 0.0 ? in[i] / out[i] : (in[i] > 0.0 ? std::numeric_limits<double>::infinity() : 0.0);
  }
  fields.emplace_back("base_flow_x", std::move(u));
  fields.emplace_back("base_flow_y", std::move(v));
  fields.emplace_back("base_flow_divergence", std::move(divergence));
  fields.emplace_back("base_flow_gain", std::move(gain));
}

std::vector<int> LinearizedFreeSurface::UnresolvedSteps(double jump) const {
  std::vector<char> flagged(eta_.size(), 0);
  for (const auto& edge : surface_.edges()) {
    if (edge.neighbour < 0) continue;
    const int a = edge.face, b = edge.neighbour;
    if (std::abs(eta_[a] - eta_[b]) <= jump) continue;
    flagged[std::abs(eta_[a]) >= std::abs(eta_[b]) ? a : b] = 1;
  }
  std::vector<int> faces;
  for (std::size_t i = 0; i < flagged.size(); ++i) {
    if (flagged[i]) faces.push_back(static_cast<int>(i));
  }
  return faces;
}

std::vector<double> LinearizedFreeSurface::State() const {
  const std::size_t n = eta_.size();
  std::vector<double> s = {time_, started_ ? 1.0 : 0.0, static_cast<double>(eta_old_.size()),
                           rigid_lid_ ? 1.0 : 0.0};
  s.insert(s.end(), eta_.begin(), eta_.end());
  for (std::size_t l = 0; l < 2; ++l) {
    if (l < eta_old_.size()) {
      s.insert(s.end(), eta_old_[l].begin(), eta_old_[l].end());
    } else {
      s.insert(s.end(), n, 0.0);
    }
  }
  s.insert(s.end(), base_edge_flux_.begin(), base_edge_flux_.end());
  for (const Vector3& u : base_velocity_) {
    s.push_back(u.x());
    s.push_back(u.y());
  }
  return s;
}

void LinearizedFreeSurface::SetState(std::span<const double> s) {
  const std::size_t n = eta_.size();
  if (s.empty()) {
    // A checkpoint of a run without the free surface on this patch (e.g.
    // the double body): calm water, the next step starts the levels.
    std::fill(eta_.begin(), eta_.end(), 0.0);
    eta_old_.clear();
    base_velocity_.clear();
    base_edge_flux_.clear();
    started_ = false;
    armed_ = false;
    return;
  }
  // Header of 4 values (with the rigid-lid flag) or 3 (older checkpoints);
  // the base flow of the local flow after the levels, once it is set.
  const std::size_t base = surface_.edges().size() + 2 * n;
  const std::size_t header = s.size() == 3 + 3 * n ? 3 : 4;
  const bool with_base = s.size() == 4 + 3 * n + base;
  if (s.size() != header + 3 * n && !with_base) {
    throw DataFileError(fmt::format(
        "free-surface state of patch '{}' has {} values; expected {} for {} faces ({} with the base flow of {} edges)",
        surface_.name(), s.size(), 4 + 3 * n, n, 4 + 3 * n + base, surface_.edges().size()));
  }
  time_ = s[0];
  started_ = s[1] != 0.0;
  const auto levels = static_cast<std::size_t>(s[2]);
  rigid_lid_ = header == 4 && s[3] != 0.0;
  eta_.assign(s.begin() + static_cast<std::ptrdiff_t>(header),
              s.begin() + static_cast<std::ptrdiff_t>(header + n));
  eta_old_.clear();
  for (std::size_t l = 0; l < std::min<std::size_t>(levels, 2); ++l) {
    const auto first = s.begin() + static_cast<std::ptrdiff_t>(header + (l + 1) * n);
    eta_old_.emplace_back(first, first + static_cast<std::ptrdiff_t>(n));
  }
  base_velocity_.clear();
  base_edge_flux_.clear();
  if (with_base) {
    const std::size_t e0 = 4 + 3 * n, edges = surface_.edges().size();
    base_edge_flux_.assign(s.begin() + static_cast<std::ptrdiff_t>(e0),
                           s.begin() + static_cast<std::ptrdiff_t>(e0 + edges));
    for (std::size_t i = 0; i < n; ++i) base_velocity_.emplace_back(s[e0 + edges + 2 * i], s[e0 + edges + 2 * i + 1], 0.0);
  }
  armed_ = false;
  // A released surface with waves and no base flow (the checkpoint of a
  // uniform-stream run): the next pressure solve's flow, waves and all,
  // becomes the base flow.
  const bool waves = std::any_of(eta_.begin(), eta_.end(), [](double e) { return e != 0.0; });
  if (LocalFlow(options_) && !with_base && !rigid_lid_ && waves && (!part_ || part_->rank == 0)) {
    spdlog::warn("free surface '{}': linearization local_flow restarted from a checkpoint of a released surface "
                 "without a base flow (written by a uniform_stream run?): the kinematic condition is linearized about "
                 "the restarted run's first flow, waves included, not about a double body; restart from a rigid-lid "
                 "or double-body checkpoint (docs/formulation.md section 3.1)",
                 surface_.name());
  }
}

void LinearizedFreeSurface::SetEta(std::span<const double> eta) {
  KELVIN_CHECK(eta.size() == eta_.size(), "one elevation per patch face");
  eta_.assign(eta.begin(), eta.end());
}

double LinearizedFreeSurface::Volume() const {
  double v = 0.0;
  for (int i = 0; i < surface_.size(); ++i) v += eta_[i] * surface_.areas()[i];
  return v;
}

}  // namespace kelvin::cfd
