#include "cfd/parallel/partition.h"

#include <fmt/format.h>
#include <petscmat.h>
#include <ptscotch.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <numeric>
#include <stdexcept>

#include "cfd/parallel/petsc_context.h"
#include "data/schema/errors.h"

namespace kelvin::cfd {
namespace {

void Check(PetscErrorCode code, const char* what) {
  if (code != 0) throw std::runtime_error(fmt::format("PETSc error {} in {}", static_cast<int>(code), what));
}

// An array from PetscMalloc, which MatCreateMPIAdj and the vertex weights
// take over (PETSc's allocation macro casts C-style).
PetscInt* PetscArray(int n) {
  PetscInt* p = nullptr;
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wold-style-cast"
  Check(PetscMalloc1(std::max(n, 1), &p), "PetscMalloc1");
#pragma GCC diagnostic pop
  return p;
}

int Find(std::vector<int>& parent, int i) {
  while (parent[i] != i) {
    parent[i] = parent[parent[i]];
    i = parent[i];
  }
  return i;
}

// The columns' graph: one vertex per column, an edge per pair of columns
// that share faces, weighted by the number of faces.
struct ColumnGraph {
  std::vector<int> offsets;  // CSR
  std::vector<int> targets;
  std::vector<int> weights;
  std::vector<int> cells;  // vertex weights
};

ColumnGraph BuildColumnGraph(const Mesh& mesh, const std::vector<int>& column, int n_columns) {
  std::vector<std::pair<int, int>> edges;
  edges.reserve(2 * static_cast<std::size_t>(mesh.n_internal_faces()));
  for (int f = 0; f < mesh.n_internal_faces(); ++f) {
    const int a = column[mesh.owner()[f]], b = column[mesh.neighbour()[f]];
    if (a == b) continue;
    edges.emplace_back(a, b);
    edges.emplace_back(b, a);
  }
  std::sort(edges.begin(), edges.end());
  ColumnGraph g;
  g.offsets.assign(n_columns + 1, 0);
  for (std::size_t i = 0; i < edges.size();) {
    std::size_t j = i;
    while (j < edges.size() && edges[j] == edges[i]) ++j;
    g.targets.push_back(edges[i].second);
    g.weights.push_back(static_cast<int>(j - i));
    ++g.offsets[edges[i].first + 1];
    i = j;
  }
  std::partial_sum(g.offsets.begin(), g.offsets.end(), g.offsets.begin());
  g.cells.assign(n_columns, 0);
  for (int c : column) ++g.cells[c];
  return g;
}

// PT-Scotch on the column graph through MatPartitioning, on one process:
// the whole graph on PETSC_COMM_SELF of the first rank, the parts broadcast
// to the others. (Distributed over several processes, Debian's threaded
// PT-Scotch deadlocks in its graph folding unless MPI runs with
// MPI_THREAD_MULTIPLE; every rank holds the whole mesh here anyway.)
std::vector<int> PartitionGraphOnOneProcess(const ColumnGraph& g, int n_parts, double imbalance) {
  const int n = static_cast<int>(g.cells.size());
  const int nnz = g.offsets[n];
  PetscInt* ia = PetscArray(n + 1);
  PetscInt* ja = PetscArray(nnz);
  PetscInt* values = PetscArray(nnz);
  PetscInt* vertex = PetscArray(n);
  for (int v = 0; v <= n; ++v) ia[v] = g.offsets[v];
  for (int k = 0; k < nnz; ++k) {
    ja[k] = g.targets[k];
    values[k] = g.weights[k];
  }
  for (int v = 0; v < n; ++v) vertex[v] = g.cells[v];
  Mat adj = nullptr;
  Check(MatCreateMPIAdj(PETSC_COMM_SELF, n, n, ia, ja, values, &adj), "MatCreateMPIAdj");
  MatPartitioning part = nullptr;
  Check(MatPartitioningCreate(PETSC_COMM_SELF, &part), "MatPartitioningCreate");
  Check(MatPartitioningSetAdjacency(part, adj), "MatPartitioningSetAdjacency");
  Check(MatPartitioningSetNParts(part, n_parts), "MatPartitioningSetNParts");
  Check(MatPartitioningSetType(part, MATPARTITIONINGPTSCOTCH), "MatPartitioningSetType(ptscotch)");
  Check(MatPartitioningPTScotchSetImbalance(part, imbalance), "MatPartitioningPTScotchSetImbalance");
  Check(MatPartitioningSetVertexWeights(part, vertex), "MatPartitioningSetVertexWeights");
  IS is = nullptr;
  // Threaded PT-Scotch cuts the same graph differently from run to run, and
  // its random generator runs on from one partition to the next: one thread
  // and a reset generator make the partition, and with it every run on ranks,
  // reproducible.
  setenv("SCOTCH_PTHREAD_NUMBER", "1", 1);
  SCOTCH_randomReset();
  Check(MatPartitioningApply(part, &is), "MatPartitioningApply");
  const PetscInt* idx = nullptr;
  Check(ISGetIndices(is, &idx), "ISGetIndices");
  std::vector<int> out(idx, idx + n);
  Check(ISRestoreIndices(is, &idx), "ISRestoreIndices");
  ISDestroy(&is);
  MatPartitioningDestroy(&part);
  MatDestroy(&adj);
  return out;
}

std::vector<int> PartitionGraph(const ColumnGraph& g, int n_parts, MPI_Comm comm, double imbalance) {
  EnsurePetsc();  // collective over MPI_COMM_WORLD: on every rank first
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  std::vector<int> out(g.cells.size());
  if (rank == 0) out = PartitionGraphOnOneProcess(g, n_parts, imbalance);
  MPI_Bcast(out.data(), static_cast<int>(out.size()), MPI_INT, 0, comm);
  return out;
}

}  // namespace

int PrismColumns(const Mesh& mesh, double column_aspect, std::vector<int>& column) {
  const int nc = mesh.n_cells();
  std::vector<int> parent(nc);
  std::iota(parent.begin(), parent.end(), 0);
  const auto vol = mesh.cell_volumes();
  const auto area = mesh.face_area_magnitudes();
  // Thin across f: sqrt(A) / (V / A) = A^1.5 / V >= column_aspect.
  auto thin = [&](int c, double a) { return a * std::sqrt(a) >= column_aspect * vol[c]; };
  for (int f = 0; f < mesh.n_internal_faces(); ++f) {
    const int P = mesh.owner()[f], N = mesh.neighbour()[f];
    if (thin(P, area[f]) && thin(N, area[f])) parent[Find(parent, P)] = Find(parent, N);
  }
  column.assign(nc, -1);
  std::vector<int> id(nc, -1);
  int n = 0;
  for (int c = 0; c < nc; ++c) {
    const int root = Find(parent, c);
    if (id[root] < 0) id[root] = n++;
    column[c] = id[root];
  }
  return n;
}

std::vector<int> PartitionCells(const Mesh& mesh, int n_parts, MPI_Comm comm, const PartitionOptions& options,
                                PartitionSummary* summary) {
  options.Validate();
  if (n_parts < 1) throw ConfigError(fmt::format("{} parts; expected at least 1", n_parts));
  if (n_parts > 1 && mesh.n_cells() < static_cast<long long>(n_parts) * options.min_cells_per_rank) {
    throw ConfigError(fmt::format("{}: {} cells over {} ranks is {} per rank; expected at least {} cells per rank "
                                  "(partition.min_cells_per_rank; with fewer the halo exchanges cost more than the "
                                  "rank saves): run on at most {} rank(s)",
                                  mesh.source(), mesh.n_cells(), n_parts, mesh.n_cells() / n_parts,
                                  options.min_cells_per_rank,
                                  std::max(1, mesh.n_cells() / options.min_cells_per_rank)));
  }
  std::vector<int> column;
  const int n_columns = PrismColumns(mesh, options.column_aspect, column);
  if (n_columns < n_parts) {
    throw ConfigError(fmt::format("{}: {} cells in {} prism columns cannot be split over {} ranks; expected at least "
                                  "one column per rank",
                                  mesh.source(), mesh.n_cells(), n_columns, n_parts));
  }
  std::vector<int> cell_part(mesh.n_cells(), 0);
  const ColumnGraph graph = BuildColumnGraph(mesh, column, n_columns);
  if (n_parts > 1) {
    const std::vector<int> column_part = PartitionGraph(graph, n_parts, comm, options.imbalance);
    for (int c = 0; c < mesh.n_cells(); ++c) cell_part[c] = column_part[column[c]];
  }
  if (summary) {
    summary->n_parts = n_parts;
    summary->n_columns = n_columns;
    summary->largest_column = *std::max_element(graph.cells.begin(), graph.cells.end());
    summary->part_cells.assign(n_parts, 0);
    for (int p : cell_part) ++summary->part_cells[p];
    summary->cut_faces = 0;
    for (int f = 0; f < mesh.n_internal_faces(); ++f) {
      summary->cut_faces += cell_part[mesh.owner()[f]] != cell_part[mesh.neighbour()[f]];
    }
    const double mean = static_cast<double>(mesh.n_cells()) / n_parts;
    summary->imbalance =
        *std::max_element(summary->part_cells.begin(), summary->part_cells.end()) / mean - 1.0;
  }
  return cell_part;
}

}  // namespace kelvin::cfd
