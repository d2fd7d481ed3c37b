#include "cfd/mesh/mesh_builder.h"

#include <algorithm>
#include <tuple>

namespace kelvin::cfd {

int MeshBuilder::AddPatch(std::string name, PatchKind kind) {
  patches_.push_back({std::move(name), kind, 0, 0});
  boundary_.emplace_back();
  return static_cast<int>(patches_.size()) - 1;
}

void MeshBuilder::AddInternalFace(int cell_a, int cell_b, std::vector<int> points) {
  if (cell_a > cell_b) {
    std::swap(cell_a, cell_b);
    std::reverse(points.begin(), points.end());
  }
  internal_.push_back({cell_a, cell_b, std::move(points)});
}

void MeshBuilder::AddBoundaryFace(int patch, int cell, std::vector<int> points) {
  boundary_[static_cast<std::size_t>(patch)].emplace_back(cell, std::move(points));
}

Mesh MeshBuilder::Build(std::vector<Vector3> points, std::string source) && {
  std::stable_sort(internal_.begin(), internal_.end(), [](const InternalFace& x, const InternalFace& y) {
    return std::tie(x.owner, x.neighbour) < std::tie(y.owner, y.neighbour);
  });
  std::vector<std::vector<int>> faces;
  std::vector<int> owner, neighbour;
  for (auto& f : internal_) {
    faces.push_back(std::move(f.points));
    owner.push_back(f.owner);
    neighbour.push_back(f.neighbour);
  }
  for (std::size_t p = 0; p < patches_.size(); ++p) {
    patches_[p].start = static_cast<int>(faces.size());
    patches_[p].size = static_cast<int>(boundary_[p].size());
    for (auto& [cell, pts] : boundary_[p]) {
      faces.push_back(std::move(pts));
      owner.push_back(cell);
    }
  }
  // Drop points no face uses (e.g. lattice points inside unsplit blocks),
  // numbering the rest in order of first use.
  std::vector<char> used(points.size(), 0);
  for (const auto& f : faces) {
    for (int p : f) used[static_cast<std::size_t>(p)] = 1;
  }
  if (std::find(used.begin(), used.end(), 0) != used.end()) {
    std::vector<int> new_id(points.size(), -1);
    std::vector<Vector3> kept;
    for (auto& f : faces) {
      for (int& p : f) {
        if (new_id[static_cast<std::size_t>(p)] < 0) {
          new_id[static_cast<std::size_t>(p)] = static_cast<int>(kept.size());
          kept.push_back(points[static_cast<std::size_t>(p)]);
        }
        p = new_id[static_cast<std::size_t>(p)];
      }
    }
    points = std::move(kept);
  }
  return Mesh(std::move(points), std::move(faces), std::move(owner), std::move(neighbour), std::move(patches_),
              std::move(source));
}

}  // namespace kelvin::cfd
