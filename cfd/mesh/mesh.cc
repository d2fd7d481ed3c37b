#include "cfd/mesh/mesh.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <numeric>
#include <queue>

#include "data/schema/errors.h"

namespace kelvin::cfd {

std::string PatchKindName(PatchKind kind) {
  switch (kind) {
    case PatchKind::kPatch:
      return "patch";
    case PatchKind::kWall:
      return "wall";
    case PatchKind::kSymmetry:
      return "symmetryPlane";
    case PatchKind::kEmpty:
      return "empty";
    case PatchKind::kProcessor:
      return "processor";
  }
  return "patch";
}

Mesh::Mesh(std::vector<Vector3> points, std::vector<std::vector<int>> faces, std::vector<int> owner,
           std::vector<int> neighbour, std::vector<Patch> patches, std::string source)
    : points_(std::move(points)),
      owner_(std::move(owner)),
      neighbour_(std::move(neighbour)),
      patches_(std::move(patches)),
      source_(std::move(source)) {
  // The mesh keeps these arrays for its lifetime: no spare capacity from how
  // a reader or the decomposition grew them (up to twice the size).
  points_.shrink_to_fit();
  owner_.shrink_to_fit();
  neighbour_.shrink_to_fit();
  // Compact face storage.
  face_offsets_.assign(faces.size() + 1, 0);
  for (std::size_t f = 0; f < faces.size(); ++f) {
    face_offsets_[f + 1] = face_offsets_[f] + static_cast<int>(faces[f].size());
  }
  face_points_.reserve(face_offsets_.back());
  for (auto& f : faces) {
    face_points_.insert(face_points_.end(), f.begin(), f.end());
    std::vector<int>().swap(f);
  }
  n_cells_ = 0;
  for (int c : owner_) n_cells_ = std::max(n_cells_, c + 1);
  for (int c : neighbour_) n_cells_ = std::max(n_cells_, c + 1);
  CheckTopology();
  BuildCellFaces();
  ComputeGeometry();
}

int Mesh::FindPatch(const std::string& name) const {
  for (std::size_t i = 0; i < patches_.size(); ++i) {
    if (patches_[i].name == name) return static_cast<int>(i);
  }
  return -1;
}

void Mesh::CheckTopology() const {
  const int nf = n_faces();
  const int np = n_points();
  if (static_cast<int>(face_offsets_.size()) - 1 != nf) {
    throw DataFileError(fmt::format("{}: owner has {} entries but there are {} faces; expected one owner per face",
                                    source_, nf, face_offsets_.size() - 1));
  }
  if (n_internal_faces() > nf) {
    throw DataFileError(fmt::format("{}: neighbour has {} entries but there are only {} faces", source_,
                                    n_internal_faces(), nf));
  }
  for (int f = 0; f < nf; ++f) {
    if (face(f).size() < 3) {
      throw DataFileError(
          fmt::format("{}: face {} has {} points; expected at least 3", source_, f, face(f).size()));
    }
    for (int p : face(f)) {
      if (p < 0 || p >= np) {
        throw DataFileError(fmt::format("{}: face {} refers to point {}; expected an index in [0, {})", source_, f,
                                        p, np));
      }
    }
    if (owner_[f] < 0) {
      throw DataFileError(fmt::format("{}: owner of face {} is {}; expected a cell index >= 0", source_, f,
                                      owner_[f]));
    }
  }
  for (int f = 0; f < n_internal_faces(); ++f) {
    if (neighbour_[f] < 0 || neighbour_[f] == owner_[f]) {
      throw DataFileError(fmt::format("{}: neighbour of internal face {} is {} (owner {}); expected a different "
                                      "cell index >= 0",
                                      source_, f, neighbour_[f], owner_[f]));
    }
  }
  int expected_start = n_internal_faces();
  for (const Patch& p : patches_) {
    if (p.start != expected_start || p.size < 0) {
      throw DataFileError(fmt::format("{}: patch '{}' has startFace {} nFaces {}; expected startFace {} (patches "
                                      "must follow the internal faces without gaps)",
                                      source_, p.name, p.start, p.size, expected_start));
    }
    expected_start += p.size;
  }
  if (expected_start != nf) {
    throw DataFileError(fmt::format("{}: the patches cover faces up to {} but there are {} faces", source_,
                                    expected_start, nf));
  }
}

void Mesh::BuildCellFaces() {
  cell_face_offsets_.assign(n_cells_ + 1, 0);
  for (int f = 0; f < n_faces(); ++f) cell_face_offsets_[owner_[f] + 1]++;
  for (int f = 0; f < n_internal_faces(); ++f) cell_face_offsets_[neighbour_[f] + 1]++;
  for (int c = 0; c < n_cells_; ++c) cell_face_offsets_[c + 1] += cell_face_offsets_[c];
  cell_faces_.assign(cell_face_offsets_.back(), 0);
  std::vector<int> fill(cell_face_offsets_.begin(), cell_face_offsets_.end() - 1);
  for (int f = 0; f < n_faces(); ++f) {
    cell_faces_[fill[owner_[f]]++] = f;
    if (f < n_internal_faces()) cell_faces_[fill[neighbour_[f]]++] = f;
  }
  for (int c = 0; c < n_cells_; ++c) {
    if (cell_face_offsets_[c + 1] - cell_face_offsets_[c] < 4) {
      throw DataFileError(fmt::format("{}: cell {} has {} faces; expected at least 4 (a closed polyhedron)", source_,
                                      c, cell_face_offsets_[c + 1] - cell_face_offsets_[c]));
    }
  }
}

void Mesh::ComputeGeometry() {
  const int nf = n_faces();
  face_centres_.assign(nf, Vector3::Zero());
  face_areas_.assign(nf, Vector3::Zero());
  face_mag_.assign(nf, 0.0);
  // Faces: triangles fanned around the point average (as OpenFOAM does).
  for (int f = 0; f < nf; ++f) {
    const std::span<const int> fp = face(f);
    const std::size_t n = fp.size();
    if (n == 3) {
      const Vector3& a = points_[fp[0]];
      const Vector3& b = points_[fp[1]];
      const Vector3& c = points_[fp[2]];
      face_centres_[f] = (a + b + c) / 3.0;
      face_areas_[f] = 0.5 * (b - a).cross(c - a);
    } else {
      Vector3 mid = Vector3::Zero();
      for (int p : fp) mid += points_[p];
      mid /= static_cast<double>(n);
      Vector3 sum_n = Vector3::Zero();
      for (std::size_t i = 0; i < n; ++i) {
        const Vector3& a = points_[fp[i]];
        const Vector3& b = points_[fp[(i + 1) % n]];
        sum_n += (b - a).cross(mid - a);
      }
      const double sum_n_mag = sum_n.norm();
      const Vector3 n_hat = sum_n_mag > 0 ? Vector3(sum_n / sum_n_mag) : Vector3::Zero();
      Vector3 sum_ac = Vector3::Zero();
      double sum_a = 0.0;
      for (std::size_t i = 0; i < n; ++i) {
        const Vector3& a = points_[fp[i]];
        const Vector3& b = points_[fp[(i + 1) % n]];
        const Vector3 tri_n = (b - a).cross(mid - a);
        const double area = tri_n.dot(n_hat);
        sum_ac += area * (a + b + mid);
        sum_a += area;
      }
      face_centres_[f] = std::abs(sum_a) > 0 ? Vector3(sum_ac / (3.0 * sum_a)) : mid;
      face_areas_[f] = 0.5 * sum_n;
    }
    face_mag_[f] = face_areas_[f].norm();
    if (!(face_mag_[f] > 0.0)) {
      throw DataFileError(fmt::format("{}: face {} has zero area; expected a non-degenerate polygon", source_, f));
    }
  }
  // Cells: pyramids on each face with apex at the face-centre average.
  cell_centres_.assign(n_cells_, Vector3::Zero());
  cell_volumes_.assign(n_cells_, 0.0);
  std::vector<Vector3> estimate(n_cells_, Vector3::Zero());
  for (int c = 0; c < n_cells_; ++c) {
    for (int k = cell_face_offsets_[c]; k < cell_face_offsets_[c + 1]; ++k) estimate[c] += face_centres_[cell_faces_[k]];
    estimate[c] /= static_cast<double>(cell_face_offsets_[c + 1] - cell_face_offsets_[c]);
  }
  auto add_pyramid = [&](int c, int f, double sign) {
    const double v3 = sign * face_areas_[f].dot(face_centres_[f] - estimate[c]);
    cell_centres_[c] += v3 * (0.75 * face_centres_[f] + 0.25 * estimate[c]);
    cell_volumes_[c] += v3;
  };
  for (int f = 0; f < nf; ++f) {
    add_pyramid(owner_[f], f, 1.0);
    if (f < n_internal_faces()) add_pyramid(neighbour_[f], f, -1.0);
  }
  for (int c = 0; c < n_cells_; ++c) {
    if (!(cell_volumes_[c] > 0.0)) {
      throw DataFileError(fmt::format("{}: cell {} has volume {:.6g} m^3; expected a positive volume (check the "
                                      "face orientation: normals must point from owner to neighbour / out of the "
                                      "domain)",
                                      source_, c, cell_volumes_[c] / 3.0));
    }
    cell_centres_[c] /= cell_volumes_[c];
    cell_volumes_[c] /= 3.0;
  }
  // Interpolation weights and deltas.
  weights_.assign(nf, 1.0);
  deltas_.assign(nf, Vector3::Zero());
  for (int f = 0; f < nf; ++f) {
    const Vector3& xp = cell_centres_[owner_[f]];
    if (f < n_internal_faces()) {
      const Vector3& xn = cell_centres_[neighbour_[f]];
      const double d_own = std::abs(face_areas_[f].dot(face_centres_[f] - xp));
      const double d_nei = std::abs(face_areas_[f].dot(xn - face_centres_[f]));
      weights_[f] = d_nei / (d_own + d_nei);
      deltas_[f] = xn - xp;
    } else {
      deltas_[f] = face_centres_[f] - xp;
    }
  }
}

std::vector<Vector3> Mesh::SkewVectors() const {
  std::vector<Vector3> skew(n_internal_faces());
  for (int f = 0; f < n_internal_faces(); ++f) {
    const Vector3& xp = cell_centres_[owner_[f]];
    const double t = (face_centres_[f] - xp).dot(face_areas_[f]) / deltas_[f].dot(face_areas_[f]);
    skew[f] = face_centres_[f] - (xp + t * deltas_[f]);
  }
  return skew;
}

double Mesh::total_volume() const { return std::accumulate(cell_volumes_.begin(), cell_volumes_.end(), 0.0); }

MeshQuality Mesh::Quality() const {
  MeshQuality q;
  q.n_cells = n_cells_;
  q.n_faces = n_faces();
  q.n_internal_faces = n_internal_faces();
  q.n_points = n_points();
  q.total_volume = total_volume();
  q.min_volume = *std::min_element(cell_volumes_.begin(), cell_volumes_.end());
  q.max_volume = *std::max_element(cell_volumes_.begin(), cell_volumes_.end());
  double sum_angle = 0.0;
  const std::vector<Vector3> skew = SkewVectors();
  for (int f = 0; f < n_internal_faces(); ++f) {
    const double c = deltas_[f].dot(face_areas_[f]) / (deltas_[f].norm() * face_mag_[f]);
    const double angle = std::acos(std::clamp(c, -1.0, 1.0)) * 180.0 / std::numbers::pi;
    q.max_non_orthogonality = std::max(q.max_non_orthogonality, angle);
    sum_angle += angle;
    q.max_skewness = std::max(q.max_skewness, skew[f].norm() / deltas_[f].norm());
  }
  q.mean_non_orthogonality = n_internal_faces() > 0 ? sum_angle / n_internal_faces() : 0.0;
  for (int c = 0; c < n_cells_; ++c) {
    double sum_mag = 0.0;
    for (int k = cell_face_offsets_[c]; k < cell_face_offsets_[c + 1]; ++k) sum_mag += face_mag_[cell_faces_[k]];
    // 1 for a cube; grows with stretching.
    q.max_aspect_ratio = std::max(q.max_aspect_ratio, sum_mag / (6.0 * std::pow(cell_volumes_[c], 2.0 / 3.0)));
  }
  Vector3 open = Vector3::Zero();
  double sum_mag = 0.0;
  for (int f = n_internal_faces(); f < n_faces(); ++f) {
    open += face_areas_[f];
    sum_mag += face_mag_[f];
  }
  q.boundary_openness = sum_mag > 0 ? open.norm() / sum_mag : 0.0;
  return q;
}

std::string MeshQuality::Report() const {
  return fmt::format(
      "cells {}  faces {} (internal {})  points {}\n"
      "volume total {:.9g} m^3, cell min {:.4g} max {:.4g}\n"
      "non-orthogonality max {:.3f} deg, mean {:.3f} deg\n"
      "skewness max {:.4f}, aspect ratio max {:.3f}, boundary openness {:.3g}\n",
      n_cells, n_faces, n_internal_faces, n_points, total_volume, min_volume, max_volume, max_non_orthogonality,
      mean_non_orthogonality, max_skewness, max_aspect_ratio, boundary_openness);
}

int Mesh::Bandwidth() const {
  int bw = 0;
  for (int f = 0; f < n_internal_faces(); ++f) bw = std::max(bw, std::abs(neighbour_[f] - owner_[f]));
  return bw;
}

void Mesh::SetPlacement(const Eigen::Matrix3d& rotation, const Vector3& translation) {
  if (body_.points.empty()) body_ = {points_, cell_centres_, face_centres_, face_areas_, deltas_};
  rotation_ = rotation;
  translation_ = translation;
  auto place = [&](const std::vector<Vector3>& from, std::vector<Vector3>& to) {
    for (std::size_t i = 0; i < from.size(); ++i) to[i] = rotation * from[i] + translation;
  };
  auto turn = [&](const std::vector<Vector3>& from, std::vector<Vector3>& to) {
    for (std::size_t i = 0; i < from.size(); ++i) to[i] = rotation * from[i];
  };
  place(body_.points, points_);
  place(body_.cell_centres, cell_centres_);
  place(body_.face_centres, face_centres_);
  turn(body_.face_areas, face_areas_);
  turn(body_.deltas, deltas_);
}

std::pair<int, int> Mesh::RenumberCells() {
  KELVIN_CHECK(body_.points.empty(), "renumber a mesh before its first placement");
  const int before = Bandwidth();
  const int n = n_cells_;
  std::vector<std::vector<int>> adj(n);
  for (int f = 0; f < n_internal_faces(); ++f) {
    adj[owner_[f]].push_back(neighbour_[f]);
    adj[neighbour_[f]].push_back(owner_[f]);
  }
  std::vector<int> order;
  order.reserve(n);
  std::vector<char> seen(n, 0);
  // Cuthill-McKee from a minimum-degree cell of each connected component.
  std::vector<int> by_degree(n);
  std::iota(by_degree.begin(), by_degree.end(), 0);
  std::stable_sort(by_degree.begin(), by_degree.end(),
                   [&](int a, int b) { return adj[a].size() < adj[b].size(); });
  for (int start : by_degree) {
    if (seen[start]) continue;
    std::queue<int> q;
    q.push(start);
    seen[start] = 1;
    while (!q.empty()) {
      const int c = q.front();
      q.pop();
      order.push_back(c);
      std::vector<int> next;
      for (int nb : adj[c]) {
        if (!seen[nb]) {
          seen[nb] = 1;
          next.push_back(nb);
        }
      }
      std::stable_sort(next.begin(), next.end(), [&](int a, int b) { return adj[a].size() < adj[b].size(); });
      for (int nb : next) q.push(nb);
    }
  }
  std::reverse(order.begin(), order.end());
  std::vector<int> new_index(n);
  for (int i = 0; i < n; ++i) new_index[order[i]] = i;
  for (int f = 0; f < n_faces(); ++f) owner_[f] = new_index[owner_[f]];
  for (int f = 0; f < n_internal_faces(); ++f) {
    neighbour_[f] = new_index[neighbour_[f]];
    if (owner_[f] > neighbour_[f]) {
      std::swap(owner_[f], neighbour_[f]);
      std::reverse(face_points_.begin() + face_offsets_[f], face_points_.begin() + face_offsets_[f + 1]);
    }
  }
  SortInternalFaces();
  BuildCellFaces();
  ComputeGeometry();
  return {before, Bandwidth()};
}

void Mesh::SortInternalFaces() {
  const int ni = n_internal_faces();
  std::vector<int> perm(ni);
  std::iota(perm.begin(), perm.end(), 0);
  std::sort(perm.begin(), perm.end(), [&](int a, int b) {
    return owner_[a] != owner_[b] ? owner_[a] < owner_[b] : neighbour_[a] < neighbour_[b];
  });
  std::vector<int> offsets(face_offsets_.size(), 0), points;
  points.reserve(face_points_.size());
  std::vector<int> own(ni), nei(ni);
  for (int i = 0; i < ni; ++i) {
    const std::span<const int> fp = face(perm[i]);
    points.insert(points.end(), fp.begin(), fp.end());
    offsets[i + 1] = static_cast<int>(points.size());
    own[i] = owner_[perm[i]];
    nei[i] = neighbour_[perm[i]];
  }
  for (int f = ni; f < n_faces(); ++f) {
    const std::span<const int> fp = face(f);
    points.insert(points.end(), fp.begin(), fp.end());
    offsets[f + 1] = static_cast<int>(points.size());
  }
  face_offsets_ = std::move(offsets);
  face_points_ = std::move(points);
  for (int i = 0; i < ni; ++i) {
    owner_[i] = own[i];
    neighbour_[i] = nei[i];
  }
}

}  // namespace kelvin::cfd
