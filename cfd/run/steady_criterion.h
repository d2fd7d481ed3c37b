// The one steady criterion of a run (`time.steady`, docs/formulation.md
// section 9): pseudo-transient marching stops once the monitored quantities
// have settled.
//
// Each step adds a sample: groups of quantities, each with its own scale
// (e.g. the drag group R_T, R_P, R_F scaled by |R_T|, or the force vector
// scaled by |F|), and optionally the free-surface elevation eta. The window
// holds the newest sample that lies at least `window` seconds of pseudo-time
// back and every later one, and spans at least `window_steps` steps. Over it
//   force change = max_{samples s, groups g, k} |q_gk(s) - q_gk(now)| / |scale_g(now)|,
//   eta change   = max_s ||eta(s) - eta(now)||_2 / ||eta(now)||_2,
// and the run is steady once both are below `tolerance` (NaN until the
// window is full).
#pragma once

#include <deque>
#include <span>
#include <vector>

namespace kelvin::cfd {

struct SteadyCriterionOptions {
  double window = 0.0;   // s of pseudo-time; 0: the window is counted in steps only
  int window_steps = 20;  // the window spans at least this many steps
  double tolerance = 1e-3;  // relative change allowed over the window, in (0, 1)
  // Throws ConfigError naming the option on a bad value.
  void Validate() const;
};

// One group of monitored quantities: values and the magnitude their change
// is measured against.
struct SteadyGroup {
  std::vector<double> values;
  double scale = 0.0;
};

class SteadyCriterion {
 public:
  explicit SteadyCriterion(SteadyCriterionOptions options);

  // Adds the state at pseudo-time `time` (eta empty when not monitored).
  void Add(double time, std::span<const SteadyGroup> groups, std::span<const double> eta);
  // True once a full window exists and both changes are below the tolerance.
  bool Settled() const;
  double force_change() const { return force_change_; }
  // The window as a flat array, for a checkpoint: a restarted run then
  // settles at the step the uninterrupted one would have. Load replaces the
  // window (and the changes measured on it); it throws DataFileError when
  // the array is not one Save wrote.
  std::vector<double> Save() const;
  void Load(std::span<const double> saved);
  double eta_change() const { return eta_change_; }
  const SteadyCriterionOptions& options() const { return options_; }

 private:
  struct Sample {
    double time;
    std::vector<SteadyGroup> groups;
    std::vector<double> eta;
  };
  void Update();  // the changes over a full window (NaN until there is one)
  void Measure();

  SteadyCriterionOptions options_;
  std::deque<Sample> samples_;
  double force_change_;
  double eta_change_;
};

}  // namespace kelvin::cfd
