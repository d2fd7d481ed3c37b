#include "cfd/bc/curved_wall_pressure.h"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>

#include "cfd/bc/wall_curvature.h"
#include "cfd/fv/cell_velocity.h"

namespace kelvin::cfd {

CurvedWallPressure::CurvedWallPressure(const Mesh& mesh, int patch_index,
                                       const FreeSurfaceOnRanks& ranks) {
  const bool parallel = ranks.part && ranks.part->parallel() && ranks.whole;
  const Mesh& fitted = parallel ? *ranks.whole : mesh;
  WallCurvature curvature;
  curvature.Update(fitted, fitted.patches()[patch_index]);
  const Eigen::Matrix3d& r = fitted.placement_rotation();
  const Patch& patch = mesh.patches()[patch_index];
  KELVIN_CHECK(fitted.patches()[patch_index].name == patch.name,
               "the wall patch has the same index in the whole mesh");
  body_shape_.resize(patch.size);
  for (int i = 0; i < patch.size; ++i) {
    const long long g = parallel ? ranks.part->faces[static_cast<std::size_t>(patch.start + i)] -
                                       fitted.patches()[patch_index].start
                                 : i;
    KELVIN_CHECK(g >= 0 && g < fitted.patches()[patch_index].size,
                 "a wall face of the rank inside the whole patch");
    body_shape_[i] = r.transpose() * curvature.shape(static_cast<int>(g)) * r;
    if (parallel) {
      whole_index_.push_back(static_cast<int>(g));
      owner_.push_back(mesh.owner()[patch.start + i]);
    }
  }
  if (parallel) {
    part_ = ranks.part;
    whole_size_ = fitted.patches()[patch_index].size;
  }
}

void CurvedWallPressure::Update(const BcContext& ctx, std::span<const double>) {
  const Patch& patch = ctx.patch;
  Resize(patch.size);
  if (static_cast<int>(g_.size()) != patch.size) {
    g_.assign(patch.size, 0.0);
    g_step_.assign(patch.size, 0.0);
  }
  // A new step: the last value of the one before is where this one starts.
  if (ctx.time != time_) {
    if (!std::isnan(time_)) {
      g_step_ = g_;
      step_time_ = time_;
    }
    restored_ = false;
  }
  const double dt = std::isnan(step_time_) ? 0.0 : ctx.time - step_time_;
  const Eigen::Matrix3d& r = ctx.mesh.placement_rotation();
  int capped = 0, first = -1;
  double worst = 0.0;  // largest kappa d of a capped face
  for (int i = 0; i < patch.size; ++i) {
    const int f = patch.start + i;
    const double dc = DeltaCoeff(ctx.mesh, f);
    if (!restored_ && !ctx.face_flux.empty()) {
      const Vector3 n = ctx.mesh.face_areas()[f] / ctx.mesh.face_area_magnitudes()[f];
      const Vector3 u = CellVelocityFromFluxes(ctx.mesh, ctx.face_flux, ctx.mesh.owner()[f]);
      const Vector3 ut = u - n * n.dot(u);
      const double d = 1.0 / dc;
      double g = ut.dot(r * (body_shape_[i] * (r.transpose() * ut)));
      const double cap = 0.5 * ut.squaredNorm() / d;
      if (std::abs(g) > cap) {
        if (first < 0) first = f;
        ++capped;
        worst = std::max(worst, std::abs(g) * d / ut.squaredNorm());
        g = std::copysign(cap, g);
      }
      const double speed = ut.norm();
      const double beta = speed > 0.0 ? 1.0 / (1.0 + dt * std::abs(g) / speed) : 1.0;
      g_[i] = g_step_[i] + beta * (g - g_step_[i]);
    }
    vi_[i] = 1.0;
    vb_[i] = g_[i] / dc;
    gi_[i] = 0.0;
    gb_[i] = g_[i];
  }
  time_ = ctx.time;
  if (!restored_ && !ctx.face_flux.empty()) capped_ = capped;
  if (capped > 0 && !warned_) {
    const Vector3& x = ctx.mesh.face_centres()[first];
    spdlog::warn("curvedSlipWall on patch '{}': {} wall faces are too coarse for the wall's curvature (kappa d up to "
                 "{:.3g} against 1/2, first at ({:.4g}, {:.4g}, {:.4g}) m): their pressure gradient is capped at half "
                 "the tangential dynamic head over d, and the pressure there is not resolved; refine the wall cells "
                 "(docs/formulation.md section 4.6)",
                 patch.name, capped, worst, x.x(), x.y(), x.z());
    warned_ = true;
  }
}

std::vector<double> CurvedWallPressure::State() const {
  std::vector<double> s = {time_, step_time_};
  if (!part_) {
    s.insert(s.end(), g_.begin(), g_.end());
    s.insert(s.end(), g_step_.begin(), g_step_.end());
    return s;
  }
  // The faces of the rank's owned cells, in the whole patch (each face is one
  // rank's: a ghost cell's copy lacks some of the fluxes its velocity needs).
  std::vector<double> whole(2 * static_cast<std::size_t>(whole_size_), 0.0);
  for (std::size_t i = 0; i < g_.size(); ++i) {
    if (owner_[i] >= part_->n_owned) continue;
    whole[static_cast<std::size_t>(whole_index_[i])] = g_[i];
    whole[static_cast<std::size_t>(whole_size_ + whole_index_[i])] = g_step_[i];
  }
  part_->SumInPlace(whole);
  s.insert(s.end(), whole.begin(), whole.end());
  return s;
}

void CurvedWallPressure::SetState(std::span<const double> state) {
  if (state.empty()) return;
  KELVIN_CHECK(state.size() >= 2 && (state.size() - 2) % 2 == 0,
               "a curved-wall state of two times and two arrays");
  const std::size_t n = (state.size() - 2) / 2;
  time_ = state[0];
  step_time_ = state[1];
  if (part_) {
    KELVIN_CHECK(n == static_cast<std::size_t>(whole_size_),
                 "a curved-wall state of the whole patch");
    g_.resize(whole_index_.size());
    g_step_.resize(whole_index_.size());
    for (std::size_t i = 0; i < whole_index_.size(); ++i) {
      g_[i] = state[2 + static_cast<std::size_t>(whole_index_[i])];
      g_step_[i] = state[2 + n + static_cast<std::size_t>(whole_index_[i])];
    }
  } else {
    g_.assign(state.begin() + 2, state.begin() + 2 + static_cast<std::ptrdiff_t>(n));
    g_step_.assign(state.begin() + 2 + static_cast<std::ptrdiff_t>(n), state.end());
  }
  restored_ = true;
}

}  // namespace kelvin::cfd
