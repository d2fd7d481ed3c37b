// Checkpoints of a run on any number of ranks (docs/formulation.md section
// 13): one HDF5 file in the layout of the undecomposed mesh (cells and faces
// in its order, fluxes along its face orientation), gathered to and written
// by rank 0, read by every rank for its own part. A checkpoint written on N
// ranks restarts on M, a serial one included: the file is the one
// cfd/io/checkpoint.h writes for the whole mesh. Serially these are
// WriteCheckpoint and ReadCheckpoint.
#pragma once

#include <filesystem>

#include "cfd/io/checkpoint.h"

namespace kelvin::cfd {

// Collective on ranks; a DataFileError (a full disk) is thrown on every rank.
void WriteRunCheckpoint(const std::filesystem::path& path, const PimpleSolver& solver,
                        const CheckpointScalars& scalars, const CheckpointArrays& arrays);
// Restores the solver's part of the state and returns the run scalars; a
// DataFileError naming the file when it holds another mesh's state.
CheckpointScalars ReadRunCheckpoint(const std::filesystem::path& path, PimpleSolver& solver);

}  // namespace kelvin::cfd
