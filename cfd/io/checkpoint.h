// HDF5 checkpoints of the full PIMPLE state (fields, old time levels,
// fluxes, boundary-condition state). Values are stored as IEEE doubles, so a
// run restarted from a checkpoint continues bit for bit. Written atomically.
#pragma once

#include <filesystem>

#include "cfd/solver/pimple_solver.h"

namespace kelvin::cfd {

void WriteCheckpoint(const std::filesystem::path& path, const PimpleSolver& solver);
// Restores the state; a DataFileError if the file does not match the mesh.
void ReadCheckpoint(const std::filesystem::path& path, PimpleSolver& solver);

}  // namespace kelvin::cfd
