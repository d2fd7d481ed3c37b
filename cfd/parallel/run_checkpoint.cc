#include "cfd/parallel/run_checkpoint.h"

#include <fmt/format.h>

#include "cfd/parallel/state_layout.h"
#include "data/schema/errors.h"

namespace kelvin::cfd {

void WriteRunCheckpoint(const std::filesystem::path& path, const PimpleSolver& solver,
                        const CheckpointScalars& scalars, const CheckpointArrays& arrays) {
  const DomainPart* part = solver.part();
  if (!part || !part->parallel()) {
    WriteCheckpoint(path, solver, scalars, arrays);
    return;
  }
  const PimpleSolver::State whole = GatherState(*part, solver.mesh(), solver.GetState());
  OnFirstRank(part, [&] {
    WriteCheckpointState(path, whole, part->n_global_cells, part->n_global_faces, scalars, arrays);
  });
}

CheckpointScalars ReadRunCheckpoint(const std::filesystem::path& path, PimpleSolver& solver) {
  const DomainPart* part = solver.part();
  if (!part || !part->parallel()) return ReadCheckpoint(path, solver);
  CheckpointState c = ReadCheckpointState(path);
  if (c.n_cells != part->n_global_cells || c.n_faces != part->n_global_faces) {
    throw DataFileError(fmt::format("{}: checkpoint has {} cells and {} faces; the mesh has {} and {}", path.string(),
                                    c.n_cells, c.n_faces, part->n_global_cells, part->n_global_faces));
  }
  try {
    solver.SetState(ScatterState(*part, solver.mesh(), c.state));
  } catch (const DataFileError& e) {
    throw DataFileError(fmt::format("{}: {}", path.string(), e.what()));
  }
  return c.scalars;
}

}  // namespace kelvin::cfd
