// Steady runs by pseudo-transient marching (`time.steady` in a case file) and
// resistance coefficients (`output.resistance`).
//
// A steady case marches PIMPLE with large time steps and stops before
// `time.end` once the force on the `output.forces` patches has settled: over
// the last `window` steps every component of the summed force (pressure +
// viscous) varies by less than `tolerance` times the magnitude of the mean
// force, and at least `min_steps` steps were run.
//
// With `output.resistance: {speed, direction, area}` the history gets the
// resistance coefficients of the force patches,
//   C_T = (F . d) / (1/2 rho U^2 S),  C_F: viscous part, C_P: pressure part,
// d the unit drag direction (the direction of the flow relative to the hull),
// S the reference area (default: the area of the force patches, i.e. the
// wetted surface of the hull of a double-body grid).
#pragma once

#include <deque>
#include <string>
#include <vector>

#include "cfd/mesh/mesh.h"
#include "data/schema/config.h"

namespace kelvin::cfd {

struct SteadyControl {
  int window = 0;          // steps; 0: no steady stop
  double tolerance = 0.0;  // relative range of the force over the window
  int min_steps = 0;
  bool enabled() const { return window > 0; }
};

// Reads `time.steady: {window, tolerance, min_steps}`.
SteadyControl LoadSteadyControl(const data::ConfigNode& node);

// Watches the summed force of the monitored patches step by step.
class ForceConvergence {
 public:
  explicit ForceConvergence(SteadyControl control) : control_(control) {}
  // Adds the force of one step; true once the force has settled.
  bool Add(const Vector3& force);
  // Largest component range over the window / |mean force| (infinity until
  // the window is full).
  double change() const { return change_; }
  int steps() const { return steps_; }

 private:
  SteadyControl control_;
  std::deque<Vector3> window_;
  double change_ = 0.0;
  int steps_ = 0;
};

struct ResistanceReference {
  double speed = 0.0;  // m/s; 0: not requested
  Vector3 direction = Vector3(1, 0, 0);  // unit drag direction (required in the file)
  double area = 0.0;   // m^2; 0: the area of the force patches
  bool enabled() const { return speed > 0.0; }
};

// Reads `output.resistance: {speed, direction, area}`.
ResistanceReference LoadResistanceReference(const data::ConfigNode& node);

// Total face area of the named patches (m^2).
double PatchArea(const Mesh& mesh, const std::vector<std::string>& patches);

}  // namespace kelvin::cfd
