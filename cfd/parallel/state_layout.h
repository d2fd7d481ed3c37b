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
// whole mesh's order, on `mesh`, the rank's local mesh. Throws DataFileError
// when the state's sizes are not those of the decomposed mesh (a checkpoint of
// another mesh). The turbulence model's arrays move with the cells, its
// wall-face viscosity with the boundary faces; a condition's own unknowns
// (the linearized free surface's eta) cover its whole patch on every rank
// and pass as they are.
PimpleSolver::State ScatterState(const DomainPart& part, const Mesh& mesh, const PimpleSolver::State& global);

// One value per boundary face of the rank's local mesh `mesh`, as the whole
// mesh's boundary faces (n_global_faces - n_global_internal_faces values, in
// its order), on every rank (collective): the checkpoint's boundary arrays.
std::vector<double> GatherBoundaryFaces(const DomainPart& part, const Mesh& mesh, const std::vector<double>& local);

// The index in the whole mesh's patch `patch` of each face of that patch of
// the rank's local mesh `mesh` (collective: the patch's first face in the
// whole mesh is the least over the ranks). Serially 0, 1, 2, ...
std::vector<int> WholePatchIndices(const DomainPart* part, const Mesh& mesh, int patch);

// One vector per face of patch `patch` of the rank's local mesh, as the faces
// of that patch in the whole mesh (in its order), on every rank (collective):
// gathered reports of a patch's faces. Serially the values as they are.
std::vector<Vector3> GatherPatchFaces(const DomainPart* part, const Mesh& mesh, int patch,
                                      std::span<const Vector3> local);

}  // namespace kelvin::cfd
