// Polyhedral finite-volume mesh with OpenFOAM-style face addressing.
//
// Faces are stored once: internal faces first (each has an owner cell and a
// neighbour cell with owner < neighbour, normal pointing from owner to
// neighbour), then the boundary faces grouped by patch (owner only, normal
// pointing out of the domain). Geometry is in body axes and SI units (m);
// SetPlacement() moves it rigidly into the earth frame (moving-mesh runs).
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <span>
#include <string>
#include <vector>

namespace kelvin::cfd {

using Vector3 = Eigen::Vector3d;

// Patch kinds as OpenFOAM's boundary file names them. `kEmpty` marks the
// front and back of a one-cell-thick 2D mesh. `kProcessor` holds the outer
// faces of the ghost cells of a rank's part of a decomposed mesh
// (cfd/parallel/decompose.h); no condition of the case applies there.
enum class PatchKind { kPatch, kWall, kSymmetry, kEmpty, kProcessor };

struct Patch {
  std::string name;
  PatchKind kind = PatchKind::kPatch;
  int start = 0;  // first face index
  int size = 0;   // number of faces
};

// Quality figures of a mesh (see Mesh::Quality()).
struct MeshQuality {
  int n_cells = 0;
  int n_faces = 0;
  int n_internal_faces = 0;
  int n_points = 0;
  double total_volume = 0.0;       // m^3
  double min_volume = 0.0;         // m^3
  double max_volume = 0.0;         // m^3
  double max_non_orthogonality = 0.0;   // degrees
  double mean_non_orthogonality = 0.0;  // degrees
  double max_skewness = 0.0;       // OpenFOAM's definition, dimensionless
  double max_aspect_ratio = 0.0;
  double boundary_openness = 0.0;  // |sum of boundary Sf| / sum |Sf|
  std::string Report() const;
};

class Mesh {
 public:
  // Builds a mesh from points, faces (point lists, right-hand rule gives the
  // normal), owner/neighbour addressing and patches. Computes the geometry.
  // `source` names where the mesh came from in error messages. Throws
  // DataFileError for inconsistent input (index out of range, faces not in
  // order, a cell with non-positive volume, ...).
  Mesh(std::vector<Vector3> points, std::vector<std::vector<int>> faces, std::vector<int> owner,
       std::vector<int> neighbour, std::vector<Patch> patches, std::string source = "<mesh>");

  int n_cells() const { return n_cells_; }
  int n_faces() const { return static_cast<int>(owner_.size()); }
  int n_internal_faces() const { return static_cast<int>(neighbour_.size()); }
  int n_boundary_faces() const { return n_faces() - n_internal_faces(); }
  int n_points() const { return static_cast<int>(points_.size()); }

  const std::vector<Vector3>& points() const { return points_; }
  // Point labels of face f.
  std::span<const int> face(int f) const {
    return {face_points_.data() + face_offsets_[f], face_points_.data() + face_offsets_[f + 1]};
  }
  // All faces, as a range of point-label spans (stored compactly, CSR).
  class FaceRange {
   public:
    class Iterator {
     public:
      Iterator(const Mesh* mesh, int f) : mesh_(mesh), f_(f) {}
      std::span<const int> operator*() const { return mesh_->face(f_); }
      Iterator& operator++() {
        ++f_;
        return *this;
      }
      bool operator!=(const Iterator& o) const { return f_ != o.f_; }

     private:
      const Mesh* mesh_;
      int f_;
    };
    explicit FaceRange(const Mesh* mesh) : mesh_(mesh) {}
    Iterator begin() const { return {mesh_, 0}; }
    Iterator end() const { return {mesh_, mesh_->n_faces()}; }
    std::span<const int> operator[](int f) const { return mesh_->face(f); }
    std::size_t size() const { return static_cast<std::size_t>(mesh_->n_faces()); }

   private:
    const Mesh* mesh_;
  };
  FaceRange faces() const { return FaceRange(this); }
  std::span<const int> owner() const { return owner_; }
  std::span<const int> neighbour() const { return neighbour_; }
  const std::vector<Patch>& patches() const { return patches_; }
  // Index of the patch called `name`, or -1.
  int FindPatch(const std::string& name) const;
  const std::string& source() const { return source_; }

  // Geometry.
  std::span<const Vector3> cell_centres() const { return cell_centres_; }
  std::span<const double> cell_volumes() const { return cell_volumes_; }
  std::span<const Vector3> face_centres() const { return face_centres_; }
  // Face area vectors Sf (|Sf| = area, owner -> neighbour or outward).
  std::span<const Vector3> face_areas() const { return face_areas_; }
  std::span<const double> face_area_magnitudes() const { return face_mag_; }
  // Linear interpolation weight of the owner on internal faces
  // (phi_f = w phi_P + (1 - w) phi_N); 1 on boundary faces.
  std::span<const double> weights() const { return weights_; }
  // d = x_N - x_P on internal faces, x_f - x_P on boundary faces.
  std::span<const Vector3> deltas() const { return deltas_; }
  // Skewness vectors x_f - x_f' (x_f' is where the line P-N crosses the face
  // plane) of the internal faces, computed on demand (not stored: most runs
  // never need them).
  std::vector<Vector3> SkewVectors() const;
  // Faces of each cell, CSR: cell_faces()[cell_face_offsets()[c] ...].
  std::span<const int> cell_face_offsets() const { return cell_face_offsets_; }
  std::span<const int> cell_faces() const { return cell_faces_; }

  double total_volume() const;
  MeshQuality Quality() const;

  // Rigid placement (docs/formulation.md section 2): every point, centre,
  // area vector and delta becomes x_E = rotation * xi + translation of the
  // body-fixed geometry given at construction (kept aside on the first call),
  // so repeated placements never accumulate round-off. Volumes, areas and
  // weights do not change. Identity restores the body-fixed geometry.
  // Geometry cached elsewhere (gradient and non-orthogonal vectors) must be
  // refreshed by its owner (PimpleSolver::RefreshGeometry).
  void SetPlacement(const Eigen::Matrix3d& rotation, const Vector3& translation);
  const Eigen::Matrix3d& placement_rotation() const { return rotation_; }
  const Vector3& placement_translation() const { return translation_; }

  // Renumbers the cells by reverse Cuthill-McKee to shrink the matrix
  // bandwidth (better cache use). Faces are re-sorted to keep the upper
  // triangular order; geometry is recomputed. Returns the bandwidth before
  // and after.
  std::pair<int, int> RenumberCells();
  // max |owner - neighbour| over internal faces.
  int Bandwidth() const;

 private:
  void CheckTopology() const;
  void ComputeGeometry();
  void SortInternalFaces();
  void BuildCellFaces();

  std::vector<Vector3> points_;
  std::vector<int> face_offsets_;  // n_faces + 1
  std::vector<int> face_points_;
  std::vector<int> owner_;
  std::vector<int> neighbour_;
  std::vector<Patch> patches_;
  std::string source_;
  int n_cells_ = 0;

  std::vector<Vector3> cell_centres_;
  std::vector<double> cell_volumes_;
  std::vector<Vector3> face_centres_;
  std::vector<Vector3> face_areas_;
  std::vector<double> face_mag_;
  std::vector<double> weights_;
  std::vector<Vector3> deltas_;
  std::vector<int> cell_face_offsets_;
  std::vector<int> cell_faces_;

  // Body-fixed copies of the vector geometry (empty until the first placement).
  struct BodyGeometry {
    std::vector<Vector3> points, cell_centres, face_centres, face_areas, deltas;
  };
  BodyGeometry body_;
  Eigen::Matrix3d rotation_ = Eigen::Matrix3d::Identity();
  Vector3 translation_ = Vector3::Zero();
};

std::string PatchKindName(PatchKind kind);

}  // namespace kelvin::cfd
