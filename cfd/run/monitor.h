// Monitors and couplers of a run (cfd/run/run_driver.h): what a run does
// besides marching the solver, each behind the same hooks, so that a new one
// is added without touching the driver.
//
//   RestoreScalars     on a restart, with the checkpoint's scalars, before the
//                      solver state is read (a free body places the mesh)
//   Start              before the time loop (after a restart, the state is restored)
//   BeforeStep         before each step, with its end time and size (couplers)
//   AfterOuterIteration inside a step, after each PIMPLE outer iteration (couplers)
//   Diverged           after each step: a reason to stop as diverged (body speed)
//   AfterStep          after each finite step, with the step's record
//   Done               after AfterStep: the run has what it was for (a CFD
//                      maneuver finished); it ends as completed
//   BeforeCheckpoint   before the driver writes the solver state (own files first)
//   AddCheckpointScalars/Arrays, RestoreScalars/Arrays  what a restart needs
//   WriteHistory       into history.h5, beside the named columns
//   Finish             at the end of a completed run: its report lines
//
// A monitor gets what it needs from the loaded Case when it is made; it
// never reads the case file.
#pragma once

#include <map>
#include <span>
#include <string>
#include <vector>

#include "cfd/io/checkpoint.h"
#include "cfd/motion/ship_forces.h"
#include "cfd/run/history.h"
#include "cfd/run/time_control.h"
#include "cfd/solver/pimple_solver.h"
#include "data/schema/h5_file.h"

namespace kelvin::cfd {

// Summed pressure and viscous force of the water on one or more patches (N, mesh axes).
struct PatchForce {
  Vector3 pressure = Vector3::Zero();
  Vector3 viscous = Vector3::Zero();
  Vector3 total() const { return pressure + viscous; }
};

// The face forces of the patches the run reads, computed once per step. On
// MPI ranks the faces are the rank's own and every sum is over all ranks.
class StepForces {
 public:
  // Computes the patches' face forces at the solver's present state.
  void Compute(const PimpleSolver& solver, std::span<const int> patches, double rho, double nu);
  // Sets one patch's face forces (a state given rather than computed: tests of monitors).
  void Set(int patch, PatchFaceForces faces);
  // This rank's faces of the patch.
  const PatchFaceForces& Faces(int patch) const;
  PatchForce Sum(int patch) const;
  // Patches summed in the order given.
  PatchForce Sum(std::span<const int> patches) const;
  // Ship-axis loads of the patches about `centre_body` with the mesh at `pose`
  // (SumHullLoads over the ranks).
  HullLoads ShipLoads(const Mesh& mesh, std::span<const int> patches, const Pose& pose,
                      const Vector3& centre_body) const;

 private:
  const DomainPart* part_ = nullptr;
  std::map<int, PatchFaceForces> faces_;
  std::map<int, PatchForce> sums_;
};

struct StepRecord {
  const StepSummary& step;
  const StepForces& forces;
  const SteadyStatus& steady;
  double wall_seconds = 0.0;  // since the start of the time loop
  double cpu_seconds = 0.0;   // process CPU time since the start of the time loop
  double step_cpu_seconds = 0.0;  // CPU time of this step's solve
  bool last = false;          // no step follows (end time or steady)
};

struct RunStart {
  bool restarted = false;
  const CheckpointScalars& scalars;  // of the checkpoint restarted from
};

class Monitor {
 public:
  virtual ~Monitor() = default;
  // Mesh patches whose face forces the monitor reads.
  virtual std::vector<int> ForcePatches() const { return {}; }
  virtual void RestoreScalars(const CheckpointScalars& /*scalars*/) {}
  virtual void Start(PimpleSolver& /*solver*/, History& /*history*/, const RunStart& /*start*/) {}
  virtual void BeforeStep(PimpleSolver& /*solver*/, double /*t_new*/, double /*dt*/) {}
  // Non-empty: the run stops as diverged with this reason.
  virtual std::string Diverged() const { return {}; }
  virtual void AfterOuterIteration(PimpleSolver& /*solver*/, int /*outer*/) {}
  virtual void AfterStep(const PimpleSolver& solver, const StepRecord& record, History& history) = 0;
  virtual void BeforeCheckpoint(const PimpleSolver& /*solver*/) {}
  virtual bool Done() const { return false; }
  virtual void AddCheckpointScalars(CheckpointScalars& /*scalars*/) const {}
  virtual void AddCheckpointArrays(CheckpointArrays& /*arrays*/) const {}
  // On a restart, after RestoreScalars and the solver state.
  virtual void RestoreArrays(const CheckpointArrays& /*arrays*/) {}
  virtual void WriteHistory(data::H5Writer& /*writer*/) const {}
  // Report lines of a completed run (each without a trailing newline).
  virtual std::vector<std::string> Finish(const PimpleSolver& /*solver*/) { return {}; }
};

}  // namespace kelvin::cfd
