// A rank's local mesh from the whole mesh and a partition (docs/formulation.md
// section 13): the owned cells in ascending global order, then the ghost
// cells (the face neighbours owned elsewhere) in ascending global order;
// the internal faces of the owned cells (with the ghost cells as
// neighbours), the boundary faces of the owned cells on their patches, and
// every other face of a ghost cell on the patch "processor" (a face between
// two ghost cells appears once for each). Every rank gets the same patch
// list (empty patches included), so the conditions are built alike.
#pragma once

#include <memory>
#include <span>
#include <vector>

#include "cfd/parallel/domain_part.h"

namespace kelvin::cfd {

inline constexpr const char* kProcessorPatch = "processor";

struct LocalDomain {
  std::unique_ptr<Mesh> mesh;
  std::shared_ptr<const DomainPart> part;
};

// Collective over `comm`: every rank passes the same mesh and partition
// (PartitionCells), with one part per rank.
LocalDomain Decompose(const Mesh& mesh, std::span<const int> cell_rank, MPI_Comm comm);

// The local cells' values of an array over the whole mesh.
template <typename T>
std::vector<T> LocalCells(const DomainPart& part, std::span<const T> global) {
  std::vector<T> out(part.cells.size());
  for (std::size_t i = 0; i < out.size(); ++i) out[i] = global[part.cells[i]];
  return out;
}

// The values of the owned cells of every rank, in the order of the whole
// mesh, on every rank (collective; for checks against a serial run).
std::vector<double> GatherCells(const DomainPart& part, std::span<const double> local);

}  // namespace kelvin::cfd
