// The solver's state in the order of the undecomposed mesh (docs/formulation.md
// section 13): what a checkpoint must hold so that a run saved on N ranks
// restarts on M. Cell arrays follow the cells of the whole mesh, face arrays
// (the fluxes) its faces and their orientation.
#pragma once

#include "cfd/parallel/domain_part.h"
#include "cfd/solver/pimple_solver.h"

namespace kelvin::cfd {

// The state of every rank's owned cells and faces in the whole mesh's order,
// on every rank (collective over part.comm). `local` is the rank's
// PimpleSolver::GetState() on `mesh`, its local mesh.
PimpleSolver::State GatherState(const DomainPart& part, const Mesh& mesh, const PimpleSolver::State& local);

// The rank's part (owned and ghost cells, local faces) of a state in the
// whole mesh's order. Throws DataFileError when the state's sizes are not
// those of the decomposed mesh (a checkpoint of another mesh), and
// ConfigError for state that is not decomposed yet (conditions with their
// own unknowns, a turbulence model).
PimpleSolver::State ScatterState(const DomainPart& part, const PimpleSolver::State& global);

}  // namespace kelvin::cfd
