#include "cfd/bc/wall_curvature.h"

#include <algorithm>
#include <cmath>

namespace kelvin::cfd {

void WallCurvature::BuildNeighbours(const Mesh& mesh, const Patch& patch) {
  std::vector<std::vector<int>> point_faces(mesh.n_points());
  for (int i = 0; i < patch.size; ++i) {
    for (int pt : mesh.face(patch.start + i)) point_faces[pt].push_back(i);
  }
  offsets_.assign(1, 0);
  neighbours_.clear();
  std::vector<int> found;
  for (int i = 0; i < patch.size; ++i) {
    found.clear();
    for (int pt : mesh.face(patch.start + i)) {
      for (int j : point_faces[pt]) {
        if (j != i) found.push_back(j);
      }
    }
    std::sort(found.begin(), found.end());
    found.erase(std::unique(found.begin(), found.end()), found.end());
    neighbours_.insert(neighbours_.end(), found.begin(), found.end());
    offsets_.push_back(static_cast<int>(neighbours_.size()));
  }
}

// Per face: n_j - n_i = A a_j over the neighbours on the same side of any
// edge, a_j the offset x_j - x_i in the face's tangent basis (t1, t2); then
// S = A [t1 t2]^T, symmetrized in the tangent plane.
void WallCurvature::Update(const Mesh& mesh, const Patch& patch) {
  if (static_cast<int>(offsets_.size()) != patch.size + 1) BuildNeighbours(mesh, patch);
  shape_.assign(patch.size, Eigen::Matrix3d::Zero());
  const double cos_edge = std::cos(kEdgeAngle);
  for (int i = 0; i < patch.size; ++i) {
    const int f = patch.start + i;
    const Vector3 n = mesh.face_areas()[f] / mesh.face_area_magnitudes()[f];
    const Vector3 t1 = n.unitOrthogonal();
    const Vector3 t2 = n.cross(t1);
    Eigen::Matrix2d aa = Eigen::Matrix2d::Zero();
    Eigen::Matrix<double, 3, 2> na = Eigen::Matrix<double, 3, 2>::Zero();
    for (int k = offsets_[i]; k < offsets_[i + 1]; ++k) {
      const int g = patch.start + neighbours_[k];
      const Vector3 nj = mesh.face_areas()[g] / mesh.face_area_magnitudes()[g];
      if (nj.dot(n) < cos_edge) continue;
      const Vector3 dx = mesh.face_centres()[g] - mesh.face_centres()[f];
      const Eigen::Vector2d a(t1.dot(dx), t2.dot(dx));
      aa += a * a.transpose();
      na += (nj - n) * a.transpose();
    }
    // Least squares through the pseudo-inverse: a direction the neighbours
    // do not span (the empty direction of a one-cell-thick 2D mesh, a strip
    // of faces) gets no curvature.
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eig(aa);
    const double largest = eig.eigenvalues()(1);
    if (!(largest > 0.0)) continue;
    Eigen::Matrix2d pinv = Eigen::Matrix2d::Zero();
    for (int k = 0; k < 2; ++k) {
      const double l = eig.eigenvalues()(k);
      if (l > 1e-6 * largest)
        pinv += eig.eigenvectors().col(k) * eig.eigenvectors().col(k).transpose() / l;
    }
    Eigen::Matrix<double, 3, 2> tangent;
    tangent << t1, t2;
    // In the tangent plane, and symmetric (a shape operator).
    const Eigen::Matrix3d plane = Eigen::Matrix3d::Identity() - n * n.transpose();
    const Eigen::Matrix3d fit = plane * na * pinv * tangent.transpose();
    shape_[i] = 0.5 * (fit + fit.transpose());
  }
}

}  // namespace kelvin::cfd
