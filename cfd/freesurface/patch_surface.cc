#include "cfd/freesurface/patch_surface.h"

#include <fmt/format.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <unordered_map>

#include "data/schema/errors.h"

namespace kelvin::cfd {
namespace {

std::uint64_t EdgeKey(int a, int b) {
  const auto lo = static_cast<std::uint64_t>(std::min(a, b));
  const auto hi = static_cast<std::uint64_t>(std::max(a, b));
  return (hi << 32) | lo;
}

}  // namespace

PatchSurface::PatchSurface(const Mesh& mesh, int patch_index) {
  KELVIN_CHECK(patch_index >= 0 && patch_index < static_cast<int>(mesh.patches().size()),
               "patch index in range");
  const Patch& patch = mesh.patches()[patch_index];
  name_ = patch.name;
  if (patch.size == 0) {
    throw ConfigError(fmt::format(
        "{}: patch '{}' has no faces; the linearized free surface needs the faces of the "
        "calm-water plane z = 0",
        mesh.source(), patch.name));
  }
  // Bounding box first: its size sets the tolerance of the planarity check.
  min_ = Vector3::Constant(std::numeric_limits<double>::max());
  max_ = Vector3::Constant(std::numeric_limits<double>::lowest());
  for (int f = patch.start; f < patch.start + patch.size; ++f) {
    for (int p : mesh.face(f)) {
      min_ = min_.cwiseMin(mesh.points()[p]);
      max_ = max_.cwiseMax(mesh.points()[p]);
    }
  }
  const double tol = 1e-9 * std::max((max_ - min_).norm(), 1e-3);
  for (int f = patch.start; f < patch.start + patch.size; ++f) {
    const Vector3 n = mesh.face_areas()[f] / mesh.face_area_magnitudes()[f];
    double z_worst = 0.0;
    for (int p : mesh.face(f)) z_worst = std::max(z_worst, std::abs(mesh.points()[p].z()));
    if (z_worst > tol || n.z() < 1.0 - 1e-9) {
      const Vector3& c = mesh.face_centres()[f];
      throw ConfigError(fmt::format(
          "{}: patch '{}' face {} (centre {:.6g} {:.6g} {:.6g}, normal {:.3g} {:.3g} {:.3g}) is "
          "not in the calm-water "
          "plane; the linearized free surface needs every face at z = 0 with its outward normal "
          "along +z",
          mesh.source(), patch.name, f - patch.start, c.x(), c.y(), c.z(), n.x(), n.y(), n.z()));
    }
  }

  const int n = patch.size;
  std::unordered_map<std::uint64_t, int> edge_of;
  std::vector<std::vector<int>> per_face(n);
  for (int i = 0; i < n; ++i) {
    const std::span<const int> pts = mesh.face(patch.start + i);
    for (std::size_t k = 0; k < pts.size(); ++k) {
      const int a = pts[k], b = pts[(k + 1) % pts.size()];
      const auto [it, inserted] = edge_of.emplace(EdgeKey(a, b), static_cast<int>(edges_.size()));
      if (inserted) {
        Edge e;
        e.face = i;
        edges_.push_back(e);
        edge_points_.push_back({a, b});
      } else {
        Edge& e = edges_[it->second];
        if (e.neighbour >= 0 || e.face == i) {
          throw ConfigError(fmt::format(
              "{}: patch '{}': the edge between points {} and {} belongs to more than two "
              "faces; the free surface needs a manifold face mesh",
              mesh.source(), patch.name, a, b));
        }
        e.neighbour = i;
      }
      per_face[i].push_back(it->second);
    }
  }
  face_edge_offsets_.assign(1, 0);
  for (int i = 0; i < n; ++i) {
    face_edges_.insert(face_edges_.end(), per_face[i].begin(), per_face[i].end());
    face_edge_offsets_.push_back(static_cast<int>(face_edges_.size()));
  }

  // Which mesh patch lies across each rim edge (inlet, side, hull...).
  std::unordered_map<std::uint64_t, int> rim_edge;
  for (int e = 0; e < static_cast<int>(edges_.size()); ++e) {
    if (edges_[e].neighbour >= 0) continue;
    const Edge& edge = edges_[e];
    const std::span<const int> pts = mesh.face(patch.start + edge.face);
    for (std::size_t k = 0; k < pts.size(); ++k) {
      const int a = pts[k], b = pts[(k + 1) % pts.size()];
      if (edge_of.at(EdgeKey(a, b)) == e) rim_edge.emplace(EdgeKey(a, b), e);
    }
  }
  for (int q = 0; q < static_cast<int>(mesh.patches().size()); ++q) {
    if (q == patch_index) continue;
    const Patch& other = mesh.patches()[q];
    for (int f = other.start; f < other.start + other.size; ++f) {
      const std::span<const int> pts = mesh.face(f);
      for (std::size_t k = 0; k < pts.size(); ++k) {
        const auto it = rim_edge.find(EdgeKey(pts[k], pts[(k + 1) % pts.size()]));
        if (it != rim_edge.end()) edges_[it->second].rim_patch = q;
      }
    }
  }

  // The body-fixed copy of the geometry (the mesh holds no placement yet at
  // construction, or its body-fixed points when placed: Mesh::SetPlacement).
  std::unordered_map<int, int> compact;
  for (auto& pair : edge_points_) {
    for (int& label : pair) {
      const auto [it, inserted] = compact.emplace(label, static_cast<int>(body_points_.size()));
      if (inserted) body_points_.push_back(mesh.placement_rotation().transpose() *
                                           (mesh.points()[label] - mesh.placement_translation()));
      label = it->second;
    }
  }
  body_centres_.resize(n);
  areas_.resize(n);
  for (int i = 0; i < n; ++i) {
    body_centres_[i] = mesh.placement_rotation().transpose() *
                       (mesh.face_centres()[patch.start + i] - mesh.placement_translation());
    areas_[i] = mesh.face_area_magnitudes()[patch.start + i];
  }
  UpdateGeometry(mesh);
}

void PatchSurface::UpdateGeometry(const Mesh& mesh) {
  const int n = static_cast<int>(face_edge_offsets_.size()) - 1;
  const Eigen::Matrix3d& rotation = mesh.placement_rotation();
  const Vector3& translation = mesh.placement_translation();
  centres_.resize(n);
  for (int i = 0; i < n; ++i) centres_[i] = rotation * body_centres_[i] + translation;
  for (std::size_t e = 0; e < edges_.size(); ++e) {
    Edge& edge = edges_[e];
    const Vector3 xa = rotation * body_points_[edge_points_[e][0]] + translation;
    const Vector3 xb = rotation * body_points_[edge_points_[e][1]] + translation;
    edge.centre = 0.5 * (xa + xb);
    const Vector3 d = xb - xa;
    edge.normal = Vector3(d.y(), -d.x(), 0.0);
    // Faces seen from +z run counter-clockwise, so (dy, -dx) already points
    // out of the face; the check keeps odd point orders safe.
    if (edge.normal.dot(edge.centre - centres_[edge.face]) < 0.0) edge.normal = -edge.normal;
  }

  // Least-squares gradient weights 1/|d|^2 with a pseudo-inverse, so that a
  // row of faces (the surface of a 2D mesh) still gets its one in-line
  // component.
  lsq_inverse_.assign(n, {0.0, 0.0, 0.0, 0.0});
  lsq_valid_.assign(n, 0);
  for (int i = 0; i < n; ++i) {
    Eigen::Matrix2d m = Eigen::Matrix2d::Zero();
    for (int e : face_edges(i)) {
      const Edge& edge = edges_[e];
      if (edge.neighbour < 0) continue;
      const int j = edge.face == i ? edge.neighbour : edge.face;
      const Eigen::Vector2d d = (centres_[j] - centres_[i]).head<2>();
      m += d * d.transpose() / d.squaredNorm();
    }
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eig(m);
    const Eigen::Vector2d lambda = eig.eigenvalues();
    if (!(lambda[1] > 0.0)) continue;
    Eigen::Matrix2d inv = Eigen::Matrix2d::Zero();
    for (int k = 0; k < 2; ++k) {
      if (lambda[k] > 1e-8 * lambda[1])
        inv += eig.eigenvectors().col(k) * eig.eigenvectors().col(k).transpose() / lambda[k];
    }
    lsq_inverse_[i] = {inv(0, 0), inv(0, 1), inv(1, 0), inv(1, 1)};
    lsq_valid_[i] = 1;
  }
}

void PatchSurface::Gradient(std::span<const double> values, std::vector<Vector3>& grad) const {
  KELVIN_CHECK(static_cast<int>(values.size()) == size(), "one value per patch face");
  grad.assign(size(), Vector3::Zero());
  std::vector<Eigen::Vector2d> rhs(size(), Eigen::Vector2d::Zero());
  for (const Edge& e : edges_) {
    if (e.neighbour < 0) continue;
    const Eigen::Vector2d d = (centres_[e.neighbour] - centres_[e.face]).head<2>();
    const Eigen::Vector2d r = d * (values[e.neighbour] - values[e.face]) / d.squaredNorm();
    // d points from face to neighbour; the neighbour sees -d and -(difference).
    rhs[e.face] += r;
    rhs[e.neighbour] += r;
  }
  for (int i = 0; i < size(); ++i) {
    if (!lsq_valid_[i]) continue;
    const auto& m = lsq_inverse_[i];
    grad[i] =
        Vector3(m[0] * rhs[i][0] + m[1] * rhs[i][1], m[2] * rhs[i][0] + m[3] * rhs[i][1], 0.0);
  }
}

}  // namespace kelvin::cfd
