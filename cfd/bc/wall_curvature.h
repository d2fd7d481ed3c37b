// The curvature of a wall patch: the surface gradient of its outward unit
// normal, S = grad_s n (3 x 3, acting on tangent vectors), fitted per face by
// least squares to the normals of the patch faces that share a point with it
// (their tangent-plane offsets against the normal differences,
// n_j - n_i = S (x_j - x_i)). For a sphere of radius R with the fluid outside,
// S = -(I - n n) / R. At an edge of the surface (a normal that turns by more
// than kEdgeAngle between neighbours) the faces across the edge are left out
// of the fit: a sharp edge has no finite curvature. A tangent direction the
// neighbours do not span (the empty direction of a 2D mesh) gets none. The
// pressure condition of curved slip walls uses it
// (cfd/bc/curved_wall_pressure.h; docs/formulation.md section 4.6).
#pragma once

#include <Eigen/Dense>
#include <vector>

#include "cfd/mesh/mesh.h"

namespace kelvin::cfd {

class WallCurvature {
 public:
  // Normals turning by more than this between two wall faces that share a
  // point mark an edge of the surface (radians, 30 deg).
  static constexpr double kEdgeAngle = 0.5235987755982988;

  // Fits S on every face of `patch` of the mesh as placed now (the mesh
  // moves rigidly: call again after a placement). The face neighbours are
  // found on the first call.
  void Update(const Mesh& mesh, const Patch& patch);
  // S of the patch's face i (patch-local), as of the last Update.
  const Eigen::Matrix3d& shape(int i) const { return shape_[i]; }

 private:
  void BuildNeighbours(const Mesh& mesh, const Patch& patch);

  // CSR: the wall faces sharing a point with face i (patch-local).
  std::vector<int> offsets_, neighbours_;
  std::vector<Eigen::Matrix3d> shape_;
};

}  // namespace kelvin::cfd
