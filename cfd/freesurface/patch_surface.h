// The two-dimensional face mesh of a planar boundary patch in z = 0 (the
// free surface): the patch faces are its cells, and two faces that share a
// mesh edge are neighbours. The linearized free surface advects the wave
// elevation eta on this mesh, so it needs what a 2D finite-volume method
// needs: edges with their in-plane normals, the faces on either side, and
// for edges on the rim of the patch the mesh patch on the other side
// (inlet, side wall, hull), plus a least-squares gradient of a face field.
#pragma once

#include <array>
#include <span>
#include <string>
#include <vector>

#include "cfd/mesh/mesh.h"

namespace kelvin::cfd {

class PatchSurface {
 public:
  struct Edge {
    int face = -1;       // local face index (the side the normal points away from)
    int neighbour = -1;  // local face index across the edge; -1 on the rim of the patch
    int rim_patch = -1;  // rim edges: index of the mesh patch that shares the edge (-1 if none)
    Vector3 centre = Vector3::Zero();  // m
    Vector3 normal = Vector3::Zero();  // in-plane, |normal| = edge length (m), out of `face`
  };

  // Builds the surface of mesh patch `patch_index`. Throws ConfigError
  // naming the patch and the offending face if the patch is not in the plane
  // z = 0 with its outward normal along +z, or if an edge is shared by more
  // than two of its faces.
  PatchSurface(const Mesh& mesh, int patch_index);

  // Recomputes the geometry (centres, edge centres and normals,
  // least-squares weights) at the rigid placement of `mesh` (Mesh::
  // SetPlacement), for a mesh that moves rigidly in the plane; the topology
  // stays. The surface keeps its own body-fixed copy of the patch geometry,
  // so `mesh` may be the one it was built from or, on MPI ranks, the rank's
  // part of it (the placement is the same).
  void UpdateGeometry(const Mesh& mesh);

  int size() const { return static_cast<int>(centres_.size()); }
  const std::string& name() const { return name_; }
  // Face centres and areas (m, m^2), local face order = patch face order.
  std::span<const Vector3> centres() const { return centres_; }
  std::span<const double> areas() const { return areas_; }
  const std::vector<Edge>& edges() const { return edges_; }
  // Edges of local face i (CSR).
  std::span<const int> face_edges(int i) const {
    return {face_edges_.data() + face_edge_offsets_[i],
            face_edges_.data() + face_edge_offsets_[i + 1]};
  }
  // Bounding box of the patch points at construction (m).
  const Vector3& min() const { return min_; }
  const Vector3& max() const { return max_; }

  // Least-squares gradient (x and y components; z is zero) of a face field
  // from the edge neighbours. Faces whose neighbours do not span the plane
  // get a zero gradient and valid_gradient(i) == false.
  void Gradient(std::span<const double> values, std::vector<Vector3>& grad) const;
  bool valid_gradient(int i) const { return lsq_valid_[i] != 0; }

 private:
  std::string name_;
  std::vector<Vector3> centres_;
  std::vector<double> areas_;
  std::vector<Edge> edges_;
  std::vector<std::array<int, 2>> edge_points_;  // indices into body_points_ of each edge
  // Body-fixed geometry at construction: the patch's points and face centres.
  std::vector<Vector3> body_points_;
  std::vector<Vector3> body_centres_;
  std::vector<int> face_edge_offsets_;
  std::vector<int> face_edges_;
  Vector3 min_ = Vector3::Zero();
  Vector3 max_ = Vector3::Zero();
  // Inverse of the 2x2 least-squares matrix sum d d^T per face (row major).
  std::vector<std::array<double, 4>> lsq_inverse_;
  std::vector<char> lsq_valid_;
};

}  // namespace kelvin::cfd
