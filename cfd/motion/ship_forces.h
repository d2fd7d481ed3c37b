// Hull forces in ship axes (docs/formulation.md section 5): x forward,
// y starboard, z down, the yaw moment N about the reference point (midship),
// pressure and viscous parts kept apart, and the MMG prime system
// (forces / (0.5 rho L T U^2), moment / (0.5 rho L^2 T U^2)).
#pragma once

#include <span>
#include <string>
#include <vector>

#include "cfd/motion/mesh_motion.h"
#include "cfd/solver/pimple_solver.h"
#include "data/schema/h5_file.h"

namespace kelvin::cfd {

// X, Y (N) and N (N m) in ship axes.
struct PlanarLoad {
  double X = 0.0, Y = 0.0, N = 0.0;
};

struct HullLoads {
  PlanarLoad pressure;
  PlanarLoad viscous;
  PlanarLoad Total() const {
    return {pressure.X + viscous.X, pressure.Y + viscous.Y, pressure.N + viscous.N};
  }
};

// Force of the water on each face of a mesh patch (N, mesh axes) at the
// solver's present state: pressure rho p_f S_f (S_f points out of the water,
// into the body) and viscous -rho nu_f dU/dn |S_f| (nu_f with the wall
// function's eddy viscosity under a turbulence model, else nu). Their sums
// are the patch forces of the run history; per face they give the
// distribution of the resistance over the hull (resistance.h5 hull_faces) and,
// summed with their arms, the hull loads below.
struct PatchFaceForces {
  std::vector<Vector3> pressure, viscous;
};
PatchFaceForces ComputePatchFaceForces(const PimpleSolver& solver, int patch, double rho, double nu);

// Loads on the patches `patches` (mesh patch indices) at the solver's present
// state, with the mesh placed at `pose`. p is kinematic, so forces are times
// rho; nu is the kinematic viscosity of the wall shear stress.
// The same from face forces already computed (faces[k] those of patches[k]).
HullLoads SumHullLoads(const Mesh& mesh, std::span<const int> patches,
                       std::span<const PatchFaceForces* const> faces, const Pose& pose,
                       const Vector3& centre_body);
// Sums loads of each rank's own faces over the ranks of `part` (in place;
// nothing when serial or null).
void SumOverRanks(const DomainPart* part, HullLoads& loads);
// On MPI ranks the loads of every rank's faces (collective).
HullLoads ComputeHullLoads(const PimpleSolver& solver, std::span<const int> patches, double rho,
                           double nu, const Pose& pose, const Vector3& centre_body);

// Prime system scales.
struct PrimeScales {
  double rho = 1000.0;  // kg/m^3
  double length = 0.0;  // Lpp (m)
  double draft = 0.0;   // T (m)
  double speed = 0.0;   // U (m/s), the carriage speed
  PlanarLoad ToPrime(const PlanarLoad& load) const;
};

// One sample of the ship-axis loads with the body kinematics.
struct CaptiveSample {
  double time = 0.0;  // s
  Pose pose;
  HullLoads loads;
  PlanarLoad prime;
};

// Writes the samples as the group `captive` (time, X, Y, N, their pressure
// and viscous parts, X_prime, Y_prime, N_prime, pose x0, y0, psi and body
// velocities u, v, r), each with units.
void WriteCaptiveHistory(data::H5Writer& w, const std::vector<CaptiveSample>& samples);

}  // namespace kelvin::cfd
