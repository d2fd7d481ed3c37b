// A rank's part of a decomposed mesh, as the solver sees it (docs/formulation.md
// section 13). The local mesh holds the rank's own cells first, [0, n_owned),
// then one layer of ghost cells: copies of the face neighbours that other
// ranks own. Every face of an owned cell is a face of the local mesh, so the
// face loops of the serial solver compute the fluxes of the owned cells
// unchanged once the ghost values are current; what lands in the ghost cells'
// rows is discarded and overwritten by the halo exchange. The ghost cells
// keep their other faces on the "processor" patch (PatchKind::kProcessor),
// so their geometry is exact.
//
// The linear systems number the cells by rank: rank r's owned cells are the
// rows [first_row, first_row + n_owned) of the global matrix.
//
// A serial run has no DomainPart (the solver's pointer is null) or one with
// size 1; nothing below then communicates.
#pragma once

#include <mpi.h>

#include <functional>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "cfd/fv/gradient.h"
#include "cfd/mesh/mesh.h"

namespace kelvin::cfd {

// Overwrites the ghost entries [n_owned, n_local) of a cell array with the
// values their owning ranks hold (collective over the part's communicator).
class HaloExchange {
 public:
  virtual ~HaloExchange() = default;
  virtual void Update(std::span<double> values) const = 0;
  virtual void Update(std::span<Vector3> values) const = 0;
  virtual void Update(std::span<Matrix3> values) const = 0;
};

struct DomainPart {
  MPI_Comm comm = MPI_COMM_SELF;
  int rank = 0;
  int size = 1;
  int n_owned = 0;
  long long n_global_cells = 0;
  int first_row = 0;
  // Global row of every local cell (owned and ghost).
  std::vector<int> rows;
  // Index in the undecomposed mesh of every local cell. The whole mesh is a
  // Mesh, whose cells and faces are numbered by int, so 32 bits hold them
  // (and a rank holds 4 bytes less per cell and per face than with 64).
  std::vector<int> cells;
  // The face of the undecomposed mesh of every local face, and +1 or -1 as
  // the local face is oriented along it or against it (owned-ghost faces
  // point away from the owned cell).
  long long n_global_faces = 0;
  long long n_global_internal_faces = 0;  // the whole mesh's boundary faces follow these
  std::vector<int> faces;
  std::vector<signed char> face_signs;
  std::shared_ptr<const HaloExchange> halo;
  // Faces between an owned and a ghost cell exist on both ranks, each
  // computing its flux from its own orientation. The rank that owns the
  // face's owner cell in the whole mesh holds the face's value (`cross_roots`,
  // local faces in ascending whole-mesh order); the other rank's copy
  // (`cross_leaves`) is overwritten with it, negated (SyncCrossFaces).
  std::vector<int> cross_roots, cross_leaves;
  std::shared_ptr<const HaloExchange> cross_halo;

  bool parallel() const { return size > 1; }
  // Collective reductions over the ranks (the value itself when serial).
  double Sum(double local) const;
  double Max(double local) const;
  double Min(double local) const;
  bool All(bool local) const;
  // Component-wise sums of a few values at once (one reduction).
  void SumInPlace(std::span<double> values) const;
  // Local index of cell `global` of the undecomposed mesh when this rank owns
  // it, else -1.
  int OwnedCell(long long global) const;
};

// Ghost update through `part` when it is parallel; nothing otherwise.
template <typename T>
void UpdateGhosts(const DomainPart* part, std::span<T> values) {
  if (part && part->parallel()) part->halo->Update(values);
}
template <typename T>
void UpdateGhosts(const DomainPart* part, std::vector<T>& values) {
  UpdateGhosts(part, std::span<T>(values));
}

// Every rank's values one after the other in rank order, on every rank
// (collective; the values themselves when serial).
std::vector<double> AllGather(const DomainPart& part, std::span<const double> local);

// Files of a run on ranks are written once: runs `write` on rank 0 of a
// parallel part (on the only rank otherwise). What it throws there is thrown
// on every rank as a DataFileError with its message, so all stop alike
// (collective). Serially it runs `write` as it is.
void OnFirstRank(const DomainPart* part, const std::function<void()>& write);
// The same over the ranks of `comm` (MPI_COMM_NULL or a single rank: runs
// `write` as it is), for what a run does before its mesh is decomposed.
void OnFirstRank(MPI_Comm comm, const std::function<void()>& write);

// Files written in pieces, one per rank: every rank runs `write`; when it
// throws on any rank, the message of the first such rank is thrown on every
// rank as a DataFileError (collective). Serially `write` as it is.
void OnEveryRank(const DomainPart* part, const std::function<void()>& write);

// Rank 0's `text` on every rank (collective; `text` itself when serial):
// what rank 0 reports of a file only it writes.
std::string FromFirstRank(const DomainPart* part, std::string text);
std::string FromFirstRank(MPI_Comm comm, std::string text);

// Gives the faces between ranks one value: each leaf copy of a face flux
// (local orientation against the whole mesh's) becomes minus the root's
// (collective; nothing when serial). Both ranks then balance their cells with
// the same flux, and a checkpoint in the whole mesh's layout restarts bit for
// bit.
void SyncCrossFaces(const DomainPart* part, std::span<double> face_values);

// The entries of a list of cells of the undecomposed mesh (e.g. an actuator's,
// built on the whole mesh, the same on every rank) that this rank owns: their
// positions in the list and their local cells. Serially (null or one rank)
// every entry, its cell as it is.
struct OwnedEntries {
  std::vector<int> entries;
  std::vector<int> cells;
};
OwnedEntries OwnEntries(const DomainPart* part, std::span<const int> whole_cells);

// Cells whose rows this rank solves: n_owned of a parallel part, else all.
inline int OwnedCells(const DomainPart* part, const Mesh& mesh) {
  return part && part->parallel() ? part->n_owned : mesh.n_cells();
}

}  // namespace kelvin::cfd
