// The halo exchange of a decomposed mesh on PETSc's star forest (PetscSF):
// the roots are each rank's owned cells, the leaves its ghost cells, each
// pointing at its owner's rank and local index. An update broadcasts the
// roots' values to the leaves (doubles, and 3- and 9-double blocks for
// vectors and gradient tensors).
#pragma once

#include <petscsf.h>

#include <vector>

#include "cfd/parallel/domain_part.h"

namespace kelvin::cfd {

struct GhostSource {
  int rank = 0;   // the owning rank
  int index = 0;  // the cell's local index there
};

class PetscHalo : public HaloExchange {
 public:
  // `ghosts` in the order of the local ghost cells [n_owned, n_owned + size).
  PetscHalo(MPI_Comm comm, int n_owned, const std::vector<GhostSource>& ghosts);
  ~PetscHalo() override;
  PetscHalo(const PetscHalo&) = delete;
  PetscHalo& operator=(const PetscHalo&) = delete;

  void Update(std::span<double> values) const override;
  void Update(std::span<Vector3> values) const override;
  void Update(std::span<Matrix3> values) const override;

 private:
  void Broadcast(MPI_Datatype unit, void* data, std::size_t size) const;

  PetscSF sf_ = nullptr;
  int n_local_ = 0;
  MPI_Datatype vector_ = MPI_DATATYPE_NULL;
  MPI_Datatype tensor_ = MPI_DATATYPE_NULL;
};

}  // namespace kelvin::cfd
