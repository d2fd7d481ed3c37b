// Boundary conditions of a case file (the `boundary:` section): one factory
// for the velocity conditions and one for the pressure conditions, the
// linearized free surface among them (cfd/freesurface). A bad type or key is
// one ConfigError naming the file, line and key.
#pragma once

#include <memory>

#include "cfd/bc/boundary_condition.h"
#include "cfd/freesurface/linearized_free_surface.h"
#include "cfd/motion/mesh_motion.h"
#include "data/schema/config.h"

namespace kelvin::cfd {

std::unique_ptr<BoundaryCondition<Vector3>> LoadVelocityBc(const data::ConfigNode& node,
                                                           const RigidMeshMotion* motion);
// On MPI ranks `mesh` is the rank's local mesh and `ranks` names the whole
// mesh and the part (the linearized free surface needs the whole patch).
std::unique_ptr<BoundaryCondition<double>> LoadPressureBc(const data::ConfigNode& node, const Mesh& mesh, int patch,
                                                          const RigidMeshMotion* motion,
                                                          const FreeSurfaceOnRanks& ranks = {});

}  // namespace kelvin::cfd
