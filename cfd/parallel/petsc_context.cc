#include "cfd/parallel/petsc_context.h"

#include <petscsys.h>

#include <cstdlib>
#include <stdexcept>

#include "cfd/linalg/hypre_solver.h"

namespace kelvin::cfd {
namespace {

bool g_we_initialized_petsc = false;

void FinalizePetsc() {
  PetscBool finalized = PETSC_FALSE;
  PetscFinalized(&finalized);
  if (g_we_initialized_petsc && !finalized) PetscFinalize();
}

}  // namespace

void EnsurePetsc() {
  EnsureMpi();
  PetscBool initialized = PETSC_FALSE;
  PetscInitialized(&initialized);
  if (initialized) return;
  // Before initialization: keep the process's own signal handling.
  PetscOptionsSetValue(nullptr, "-no_signal_handler", nullptr);
  if (PetscInitializeNoArguments() != 0) throw std::runtime_error("PETSc failed to initialize");
  g_we_initialized_petsc = true;
  // Registered after MPI's finalizer, so it runs first.
  std::atexit(FinalizePetsc);
}

}  // namespace kelvin::cfd
