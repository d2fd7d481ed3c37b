// Something that acts on a free body through the flow (the propeller, later
// the rudder), driven by the free-running coupler (cfd/run/free_running.h):
// each outer iteration it reads the flow, adds its body force to the cell
// source and its load on the body to `load`.
#pragma once

#include <string>
#include <vector>

#include "cfd/io/checkpoint.h"
#include "cfd/motion/free_body.h"
#include "cfd/run/history.h"
#include "cfd/solver/pimple_solver.h"
#include "data/schema/h5_file.h"

namespace kelvin::cfd {

class BodyActuator {
 public:
  virtual ~BodyActuator() = default;
  // `load`: its load on the body, ship axes about the reference point.
  virtual void Update(const PimpleSolver& solver, const FreeBody& body, int outer, std::vector<Vector3>& cell_source,
                      PlanarLoad& load) = 0;
  virtual void BeforeStep(double /*t_new*/, double /*dt*/) {}
  virtual void Start(History& /*history*/) {}
  virtual void AfterStep(const FreeBody& /*body*/, History& /*history*/) {}
  virtual void AddCheckpointScalars(CheckpointScalars& /*scalars*/) const {}
  virtual void RestoreScalars(const CheckpointScalars& /*scalars*/) {}
  // After a restart: adds the body force it had applied last, so that the
  // first outer iteration sees the cell source of the uninterrupted run.
  virtual void ApplyRestored(const PimpleSolver& /*solver*/, std::vector<Vector3>& /*cell_source*/) const {}
  virtual void WriteHistory(data::H5Writer& /*writer*/) const {}
  virtual std::vector<std::string> Finish() { return {}; }
  virtual std::string Diverged() const { return {}; }
};

}  // namespace kelvin::cfd
