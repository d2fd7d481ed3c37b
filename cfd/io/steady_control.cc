#include "cfd/io/steady_control.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace kelvin::cfd {

SteadyControl LoadSteadyControl(const data::ConfigNode& node) {
  node.ExpectKeys({"window", "tolerance", "min_steps"});
  SteadyControl c;
  c.window = node.Get<int>("window");
  if (c.window < 2) node["window"].Fail("an integer number of steps >= 2");
  c.tolerance = node.GetPositive("tolerance");
  c.min_steps = node.Get<int>("min_steps", c.window);
  if (c.min_steps < c.window) node["min_steps"].Fail("an integer number of steps >= window");
  return c;
}

bool ForceConvergence::Add(const Vector3& force) {
  ++steps_;
  window_.push_back(force);
  if (static_cast<int>(window_.size()) > control_.window) window_.pop_front();
  if (static_cast<int>(window_.size()) < control_.window) {
    change_ = std::numeric_limits<double>::infinity();
    return false;
  }
  Vector3 lo = window_.front(), hi = window_.front(), mean = Vector3::Zero();
  for (const Vector3& f : window_) {
    lo = lo.cwiseMin(f);
    hi = hi.cwiseMax(f);
    mean += f;
  }
  mean /= static_cast<double>(window_.size());
  const double scale = mean.norm();
  change_ = scale > 0.0 ? (hi - lo).maxCoeff() / scale : std::numeric_limits<double>::infinity();
  return steps_ >= control_.min_steps && change_ < control_.tolerance;
}

ResistanceReference LoadResistanceReference(const data::ConfigNode& node) {
  node.ExpectKeys({"speed", "direction", "area"});
  ResistanceReference r;
  r.speed = node.GetPositive("speed");
  const std::vector<double> d = node["direction"].As<std::vector<double>>();
  if (d.size() != 3) node["direction"].Fail("a list of 3 numbers (the drag direction)");
  r.direction = Vector3(d[0], d[1], d[2]);
  if (!r.direction.allFinite() || !(r.direction.norm() > 0.0)) {
    node["direction"].Fail("a non-zero finite vector (the drag direction, that of the flow past the hull)");
  }
  r.direction.normalize();
  if (node.Has("area")) r.area = node.GetPositive("area");
  return r;
}

double PatchArea(const Mesh& mesh, const std::vector<std::string>& patches) {
  double area = 0.0;
  for (const std::string& name : patches) {
    const Patch& p = mesh.patches()[mesh.FindPatch(name)];
    for (int f = p.start; f < p.start + p.size; ++f) area += mesh.face_area_magnitudes()[f];
  }
  return area;
}

}  // namespace kelvin::cfd
