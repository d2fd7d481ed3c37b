// The free-running coupler of the run driver (cfd/run/monitor.h): it moves
// the free body (cfd/motion/free_body.h) with the loads of the flow inside
// the PIMPLE outer loop.
//
//   BeforeStep           body.BeginStep: the predicted pose places the mesh
//   AfterOuterIteration  hull loads (pressure + viscous, ship axes about the
//                        reference point) + actuators (propeller) -> the
//                        coupling correction -> the mesh flux of the new
//                        velocities (the wall and the free surface read the
//                        body's kinematics themselves)
//   AfterStep            history columns body/* (trajectory, velocities,
//                        loads, the carriage's constraint load, the coupling
//                        change of the last outer iteration)
//   checkpoints          the body state as run scalars (free_body_0 ...),
//                        restored before the solver state places the mesh
//   Diverged             a non-finite body state or a runaway speed
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "cfd/run/case_loader.h"
#include "cfd/run/monitor.h"

namespace kelvin::cfd {

class FreeRunningCoupler final : public Monitor {
 public:
  // `c` must have a free body (motion: {kind: free}); its actuators (the
  // propeller) must outlive the coupler.
  explicit FreeRunningCoupler(const Case& c);

  void RestoreScalars(const CheckpointScalars& scalars) override;
  void Start(PimpleSolver& solver, History& history, const RunStart& start) override;
  void BeforeStep(PimpleSolver& solver, double t_new, double dt) override;
  void AfterOuterIteration(PimpleSolver& solver, int outer) override;
  std::string Diverged() const override;
  void AfterStep(const PimpleSolver& solver, const StepRecord& record, History& history) override;
  void AddCheckpointScalars(CheckpointScalars& scalars) const override;
  void WriteHistory(data::H5Writer& writer) const override;
  std::vector<std::string> Finish(const PimpleSolver& solver) override;

  const FreeBody& body() const { return *body_; }
  // The hull loads of the latest outer iteration.
  const HullLoads& hull_loads() const { return hull_loads_; }
  // The actuators' loads of the latest outer iteration (ship axes, about the reference point).
  const PlanarLoad& actuator_load() const { return actuator_load_; }

 private:
  struct Columns {
    History::Column trajectory, velocity, hull, actuators, constraint, change;
  };

  std::shared_ptr<FreeBody> body_;
  const RigidMeshMotion& motion_;
  std::vector<int> hull_;
  double rho_, nu_, length_;
  std::vector<BodyActuator*> actuators_;
  HullLoads hull_loads_;
  PlanarLoad actuator_load_;
  std::vector<Vector3> cell_source_;
  std::vector<double> mesh_flux_;
  double change_ = 0.0;
  double travelled_ = 0.0;
  Columns columns_{};
};

}  // namespace kelvin::cfd
