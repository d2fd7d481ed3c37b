#include "cfd/parallel/petsc_halo.h"

#include <fmt/format.h>

#include <stdexcept>

#include "cfd/parallel/petsc_context.h"
#include "data/schema/errors.h"

namespace kelvin::cfd {
namespace {

void Check(PetscErrorCode code, const char* what) {
  if (code != 0) throw std::runtime_error(fmt::format("PETSc error {} in {}", static_cast<int>(code), what));
}

}  // namespace

PetscHalo::PetscHalo(MPI_Comm comm, int n_owned, const std::vector<GhostSource>& ghosts)
    : n_local_(n_owned + static_cast<int>(ghosts.size())) {
  EnsurePetsc();
  std::vector<PetscInt> leaves(ghosts.size());
  std::vector<PetscSFNode> remote(ghosts.size());
  for (std::size_t j = 0; j < ghosts.size(); ++j) {
    leaves[j] = n_owned + static_cast<PetscInt>(j);
    remote[j].rank = ghosts[j].rank;
    remote[j].index = ghosts[j].index;
  }
  Check(PetscSFCreate(comm, &sf_), "PetscSFCreate");
  Check(PetscSFSetGraph(sf_, n_owned, static_cast<PetscInt>(ghosts.size()), leaves.data(), PETSC_COPY_VALUES,
                        remote.data(), PETSC_COPY_VALUES),
        "PetscSFSetGraph");
  Check(PetscSFSetUp(sf_), "PetscSFSetUp");
  MPI_Type_contiguous(3, MPI_DOUBLE, &vector_);
  MPI_Type_commit(&vector_);
  MPI_Type_contiguous(9, MPI_DOUBLE, &tensor_);
  MPI_Type_commit(&tensor_);
}

PetscHalo::~PetscHalo() {
  PetscBool finalized = PETSC_FALSE;
  PetscFinalized(&finalized);
  if (!finalized) PetscSFDestroy(&sf_);
  int mpi_finalized = 0;
  MPI_Finalized(&mpi_finalized);
  if (!mpi_finalized) {
    MPI_Type_free(&vector_);
    MPI_Type_free(&tensor_);
  }
}

void PetscHalo::Broadcast(MPI_Datatype unit, void* data, std::size_t size) const {
  KELVIN_CHECK(static_cast<int>(size) >= n_local_, "a halo update needs a value for every local cell");
  // Roots (owned cells) and leaves (ghost cells) are disjoint parts of one array.
  Check(PetscSFBcastBegin(sf_, unit, data, data, MPI_REPLACE), "PetscSFBcastBegin");
  Check(PetscSFBcastEnd(sf_, unit, data, data, MPI_REPLACE), "PetscSFBcastEnd");
}

void PetscHalo::Update(std::span<double> values) const { Broadcast(MPI_DOUBLE, values.data(), values.size()); }
void PetscHalo::Update(std::span<Vector3> values) const { Broadcast(vector_, values.data(), values.size()); }
void PetscHalo::Update(std::span<Matrix3> values) const { Broadcast(tensor_, values.data(), values.size()); }

}  // namespace kelvin::cfd
