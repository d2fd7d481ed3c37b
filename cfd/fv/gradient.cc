#include "cfd/fv/gradient.h"

#include <Eigen/LU>
#include <algorithm>

#include "cfd/bc/boundary_condition.h"

namespace kelvin::cfd {
namespace {

inline Vector3 Outer(const Vector3& s, double phi) { return s * phi; }
inline Matrix3 Outer(const Vector3& s, const Vector3& u) { return u * s.transpose(); }
template <typename T>
GradType<T> ZeroGrad() {
  if constexpr (std::is_same_v<T, double>) {
    return Vector3::Zero();
  } else {
    return Matrix3::Zero();
  }
}

}  // namespace

Gradient::Gradient(const Mesh& mesh, GradientOptions options) : mesh_(mesh), options_(options) {
  options_.Validate();
  UpdateGeometry();
}

void Gradient::UpdateGeometry() {
  if (options_.scheme != GradientScheme::kLeastSquares) return;
  const Mesh& mesh = mesh_;
  const int nc = mesh.n_cells();
  const int ni = mesh.n_internal_faces();
  std::vector<Matrix3> dd(nc, Matrix3::Zero());
  auto weight = [](const Vector3& d) { return 1.0 / d.squaredNorm(); };
  for (int f = 0; f < mesh.n_faces(); ++f) {
    const Vector3& d = mesh.deltas()[f];
    const Matrix3 m = weight(d) * d * d.transpose();
    dd[mesh.owner()[f]] += m;
    if (f < ni) dd[mesh.neighbour()[f]] += m;
  }
  std::vector<Matrix3> inv(nc);
  for (int c = 0; c < nc; ++c) inv[c] = dd[c].inverse();
  lsq_owner_.resize(mesh.n_faces());
  lsq_neighbour_.assign(ni, Vector3::Zero());
  for (int f = 0; f < mesh.n_faces(); ++f) {
    const Vector3& d = mesh.deltas()[f];
    lsq_owner_[f] = weight(d) * inv[mesh.owner()[f]] * d;
    if (f < ni) lsq_neighbour_[f] = -weight(d) * inv[mesh.neighbour()[f]] * d;
  }
}

void Gradient::Compute(std::span<const double> cells, std::span<const double> boundary,
                       std::vector<Vector3>& out) const {
  ComputeImpl<double>(cells, boundary, out);
}
void Gradient::Compute(std::span<const Vector3> cells, std::span<const Vector3> boundary,
                       std::vector<Matrix3>& out) const {
  ComputeImpl<Vector3>(cells, boundary, out);
}

template <typename T>
void Gradient::ComputeImpl(std::span<const T> cells, std::span<const T> boundary,
                           std::vector<GradType<T>>& out) const {
  const int nc = mesh_.n_cells();
  const int ni = mesh_.n_internal_faces();
  const int nf = mesh_.n_faces();
  const auto owner = mesh_.owner();
  const auto neighbour = mesh_.neighbour();
  out.assign(nc, ZeroGrad<T>());
  if (options_.scheme == GradientScheme::kGaussLinear) {
    const auto sf = mesh_.face_areas();
    const auto w = mesh_.weights();
    for (int f = 0; f < ni; ++f) {
      const T phi_f = w[f] * cells[owner[f]] + (1.0 - w[f]) * cells[neighbour[f]];
      const GradType<T> g = Outer(sf[f], phi_f);
      out[owner[f]] += g;
      out[neighbour[f]] -= g;
    }
    for (int f = ni; f < nf; ++f) out[owner[f]] += Outer(sf[f], boundary[f - ni]);
    const auto vol = mesh_.cell_volumes();
    for (int c = 0; c < nc; ++c) out[c] /= vol[c];
  } else {
    for (int f = 0; f < ni; ++f) {
      const T d = cells[neighbour[f]] - cells[owner[f]];
      out[owner[f]] += Outer(lsq_owner_[f], d);
      out[neighbour[f]] -= Outer(lsq_neighbour_[f], d);
    }
    for (int f = ni; f < nf; ++f) out[owner[f]] += Outer(lsq_owner_[f], T(boundary[f - ni] - cells[owner[f]]));
  }
  if (options_.limiter == GradientLimiter::kCellLimited) Limit<T>(cells, boundary, out);
}

template <typename T>
void Gradient::Limit(std::span<const T> cells, std::span<const T> boundary, std::vector<GradType<T>>& out) const {
  const int nc = mesh_.n_cells();
  const int ni = mesh_.n_internal_faces();
  const int nf = mesh_.n_faces();
  const auto owner = mesh_.owner();
  const auto neighbour = mesh_.neighbour();
  const auto xf = mesh_.face_centres();
  const auto xc = mesh_.cell_centres();
  constexpr int kN = Traits<T>::kComponents;
  for (int k = 0; k < kN; ++k) {
    std::vector<double> lo(nc), hi(nc), limiter(nc, 1.0);
    for (int c = 0; c < nc; ++c) lo[c] = hi[c] = Traits<T>::Component(cells[c], k);
    for (int f = 0; f < ni; ++f) {
      const double a = Traits<T>::Component(cells[owner[f]], k);
      const double b = Traits<T>::Component(cells[neighbour[f]], k);
      lo[owner[f]] = std::min(lo[owner[f]], b);
      hi[owner[f]] = std::max(hi[owner[f]], b);
      lo[neighbour[f]] = std::min(lo[neighbour[f]], a);
      hi[neighbour[f]] = std::max(hi[neighbour[f]], a);
    }
    for (int f = ni; f < nf; ++f) {
      const double b = Traits<T>::Component(boundary[f - ni], k);
      lo[owner[f]] = std::min(lo[owner[f]], b);
      hi[owner[f]] = std::max(hi[owner[f]], b);
    }
    auto row = [&](int c) -> Vector3 {
      if constexpr (std::is_same_v<T, double>) {
        return out[c];
      } else {
        return out[c].row(k).transpose();
      }
    };
    auto visit = [&](int c, int f) {
      const double phi = Traits<T>::Component(cells[c], k);
      const double delta = row(c).dot(xf[f] - xc[c]);
      if (delta > 1e-300 * std::abs(phi) && delta > 0) {
        limiter[c] = std::min(limiter[c], (hi[c] - phi) / delta);
      } else if (delta < 0) {
        limiter[c] = std::min(limiter[c], (lo[c] - phi) / delta);
      }
    };
    for (int f = 0; f < nf; ++f) {
      visit(owner[f], f);
      if (f < ni) visit(neighbour[f], f);
    }
    for (int c = 0; c < nc; ++c) {
      const double l = std::clamp(limiter[c], 0.0, 1.0);
      if constexpr (std::is_same_v<T, double>) {
        out[c] *= l;
      } else {
        out[c].row(k) *= l;
      }
    }
  }
}

}  // namespace kelvin::cfd
