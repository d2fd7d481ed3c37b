// PETSc for the domain decomposition (the partitioner and the halo's star
// forest): initialized once per process on top of MPI (EnsureMpi), without
// PETSc's signal handlers (the run layer owns SIGTERM and SIGINT), and
// finalized at exit before MPI. Collective over MPI_COMM_WORLD: every rank
// calls it before any rank uses PETSc.
#pragma once

namespace kelvin::cfd {

void EnsurePetsc();

}  // namespace kelvin::cfd
