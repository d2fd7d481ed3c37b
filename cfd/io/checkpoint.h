// HDF5 checkpoints of the full PIMPLE state (fields, old time levels,
// fluxes, boundary-condition state). Values are stored as IEEE doubles, so a
// run restarted from a checkpoint continues bit for bit. Written atomically.
#pragma once

#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "cfd/solver/pimple_solver.h"

namespace kelvin::cfd {

// Run-level scalars kept with the solver state, by name: what a restarted
// run needs to report as the uninterrupted one would (e.g. the pseudo-time
// at which a resistance run released its rigid lid). Names are plain
// identifiers ([A-Za-z0-9_]).
using CheckpointScalars = std::map<std::string, double>;
// Run-level arrays, by name (the same identifiers): e.g. the steady
// criterion's window, so that a restarted run settles where the
// uninterrupted one does.
using CheckpointArrays = std::map<std::string, std::vector<double>>;

void WriteCheckpoint(const std::filesystem::path& path, const PimpleSolver& solver,
                     const CheckpointScalars& scalars = {}, const CheckpointArrays& arrays = {});
// Restores the state and returns the run scalars (none in checkpoints
// written without them); a DataFileError if the file does not match the mesh.
CheckpointScalars ReadCheckpoint(const std::filesystem::path& path, PimpleSolver& solver);

// The same, from a state rather than a solver, with the cell and face counts
// of its mesh (a run on ranks writes the whole mesh's state: cfd/parallel/
// run_checkpoint.h).
void WriteCheckpointState(const std::filesystem::path& path, const PimpleSolver::State& state, long long n_cells,
                          long long n_faces, const CheckpointScalars& scalars = {},
                          const CheckpointArrays& arrays = {});
struct CheckpointState {
  PimpleSolver::State state;
  long long n_cells = 0, n_faces = 0;  // of the mesh it was written on
  CheckpointScalars scalars;
};
CheckpointState ReadCheckpointState(const std::filesystem::path& path);

// The run scalars alone (a free body restores its pose before the solver
// state places the mesh).
CheckpointScalars ReadCheckpointScalars(const std::filesystem::path& path);
// The run arrays (none in checkpoints written without them).
CheckpointArrays ReadCheckpointArrays(const std::filesystem::path& path);

}  // namespace kelvin::cfd
