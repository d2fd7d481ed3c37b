// Partitioning of a polyhedral mesh over ranks (docs/formulation.md section
// 13): the cell graph (cells joined by their internal faces) is cut by
// PT-Scotch through PETSc's MatPartitioning, with the wall-normal columns of
// thin cells (prism layers) kept whole: cells joined by a face across which
// both are thin are merged into one graph vertex first, weighted by its
// cell count. A cut between two cells of a column would put the strong
// couplings of aspect-ratio-100 cells across ranks (the pressure AMG setup is
// 2.5x slower with such a cut).
#pragma once

#include <mpi.h>

#include <vector>

#include "cfd/mesh/mesh.h"

namespace kelvin::cfd {

struct PartitionOptions {
  // A cell is thin across a face when sqrt(|S_f|) / (V / |S_f|), the face's
  // size over the cell's thickness across it, is at least this.
  double column_aspect = 5.0;
  // Allowed load imbalance of PT-Scotch (0.05 = 5%).
  double imbalance = 0.05;
  // Fewer cells per rank are refused: below a few thousand the halo
  // exchanges and reductions of every step cost more than the rank's share
  // of the work saves (small test cases lower it).
  int min_cells_per_rank = 2000;
  void Validate() const;
};

struct PartitionSummary {
  int n_parts = 0;
  int n_columns = 0;           // graph vertices after merging the columns
  int largest_column = 0;      // cells
  std::vector<int> part_cells; // cells per part
  int cut_faces = 0;           // internal faces between parts
  double imbalance = 0.0;      // max part / mean part - 1
};

// The column of every cell (cells of one column share the index; isolated
// cells are columns of one); returns the number of columns.
int PrismColumns(const Mesh& mesh, double column_aspect, std::vector<int>& column);

// The part (rank) of every cell, in [0, n_parts). Collective over `comm`:
// every rank passes the same whole mesh; the first rank partitions and the
// others receive its answer. n_parts 1 gives zeros without calling the
// partitioner.
std::vector<int> PartitionCells(const Mesh& mesh, int n_parts, MPI_Comm comm, const PartitionOptions& options = {},
                                PartitionSummary* summary = nullptr);

}  // namespace kelvin::cfd
