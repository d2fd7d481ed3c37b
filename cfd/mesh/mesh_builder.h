// Assembles a Mesh from faces given in any order: internal faces in either
// orientation and boundary faces by patch. Build() puts them in OpenFOAM's
// order (internal faces by owner, then neighbour; boundary faces patch by
// patch) and drops points no face uses. Used by the built-in generators.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "cfd/mesh/mesh.h"

namespace kelvin::cfd {

class MeshBuilder {
 public:
  // Returns the patch index for AddBoundaryFace.
  int AddPatch(std::string name, PatchKind kind);
  // A face between two cells; `points` may be oriented either way as long as
  // its normal points from cell_a to cell_b (it is flipped when stored with
  // the smaller cell as owner).
  void AddInternalFace(int cell_a, int cell_b, std::vector<int> points);
  // A boundary face of `patch` with an outward normal.
  void AddBoundaryFace(int patch, int cell, std::vector<int> points);

  Mesh Build(std::vector<Vector3> points, std::string source) &&;

 private:
  struct InternalFace {
    int owner;
    int neighbour;
    std::vector<int> points;
  };
  std::vector<InternalFace> internal_;
  std::vector<Patch> patches_;
  std::vector<std::vector<std::pair<int, std::vector<int>>>> boundary_;
};

}  // namespace kelvin::cfd
