// ReadCaseSettings (cfd/run/case_loader.h): the sections of a case file that
// need no mesh, and the keys of older layouts, each refused with its
// replacement.
#include <fmt/format.h>

#include <cmath>

#include "cfd/run/case_config.h"
#include "cfd/run/case_loader.h"
#include "data/schema/errors.h"

namespace kelvin::cfd {
namespace {

namespace fs = std::filesystem;

// A key that moved: one error naming where it lives now.
void RefuseMoved(const ConfigNode& node, std::string_view key, std::string_view replacement) {
  if (node.Has(key)) node[key].Fail(fmt::format("no '{}' here any more: {} (see cfd/README.md, 'Older case files')",
                                                key, replacement));
}

CaseReference ReadReference(const ConfigNode& n) {
  n.ExpectKeys({"speed", "direction", "area", "length", "draft"});
  CaseReference r;
  r.speed = n.GetPositive("speed");
  if (n.Has("direction")) {
    r.direction = GetVector(n, "direction");
    if (!r.direction.allFinite() || !(r.direction.norm() > 0.0)) {
      n["direction"].Fail("a non-zero finite vector (the drag direction, that of the flow past the hull)");
    }
    r.direction.normalize();
  } else {
    n.Fail("a direction [x, y, z]: the drag direction, that of the flow past the hull");
  }
  if (n.Has("area")) r.area = n.GetPositive("area");
  if (n.Has("length")) r.length = n.GetPositive("length");
  if (n.Has("draft")) r.draft = n.GetPositive("draft");
  return r;
}

SteadyOptions ReadSteady(const ConfigNode& n) {
  if (!n.Has("quantities")) {
    n.Fail("a quantities list (drag, force, eta, ship_loads): the steady criterion changed, its window is now seconds of "
           "pseudo-time and window_steps counts steps (see cfd/README.md, 'Older case files')");
  }
  n.ExpectKeys({"quantities", "tolerance", "window", "window_steps", "min_windows", "min_steps"});
  SteadyOptions o;
  for (const ConfigNode& item : n["quantities"].Items()) {
    const std::string q = item.As<std::string>();
    if (q == "drag") {
      o.quantities.push_back(SteadyQuantity::kDrag);
    } else if (q == "force") {
      o.quantities.push_back(SteadyQuantity::kForce);
    } else if (q == "eta") {
      o.quantities.push_back(SteadyQuantity::kEta);
    } else if (q == "ship_loads") {
      o.quantities.push_back(SteadyQuantity::kShipLoads);
    } else {
      item.Fail("one of drag, force, eta, ship_loads");
    }
  }
  o.criterion.tolerance = n.Get<double>("tolerance", o.criterion.tolerance);
  o.window_is_flow_through = !n.Has("window");
  o.criterion.window = n.Get<double>("window", o.criterion.window);
  o.criterion.window_steps = n.Get<int>("window_steps", o.criterion.window_steps);
  o.min_windows = n.Get<double>("min_windows", o.min_windows);
  o.min_steps = n.Get<int>("min_steps", o.min_steps);
  ValidateAt(n, [&] { o.Validate(); });
  return o;
}

TimeControlOptions ReadTime(const ConfigNode& t) {
  t.ExpectKeys({"dt", "end", "ramp_steps", "rigid_lid_windows", "initial_velocity", "steady"});
  TimeControlOptions o;
  o.dt = t.GetPositive("dt");
  if (t.Has("end")) o.end = t.GetPositive("end");
  o.ramp_steps = t.Get<int>("ramp_steps", o.ramp_steps);
  o.rigid_lid_windows = t.Get<double>("rigid_lid_windows", o.rigid_lid_windows);
  o.initial_velocity = t.Get<bool>("initial_velocity", o.initial_velocity);
  if (t.Has("steady")) o.steady = ReadSteady(t["steady"]);
  return o;
}

// `partition:` how a run on MPI ranks cuts the mesh (cfd/parallel/partition.h).
PartitionOptions ReadPartition(const ConfigNode& n) {
  n.ExpectKeys({"column_aspect", "imbalance", "min_cells_per_rank"});
  PartitionOptions o;
  o.column_aspect = n.Get<double>("column_aspect", o.column_aspect);
  o.imbalance = n.Get<double>("imbalance", o.imbalance);
  o.min_cells_per_rank = n.Get<int>("min_cells_per_rank", o.min_cells_per_rank);
  ValidateAt(n, [&] { o.Validate(); });
  return o;
}

OutputOptions ReadOutput(const ConfigNode& o, const fs::path& case_dir) {
  RefuseMoved(o, "resistance", "reference: {speed, direction, area} gives the per-step C_T, C_F, C_P");
  if (o.Has("captive") && o["captive"].IsMap()) {
    o["captive"].Fail("true: output.captive is a flag now; the prime scales are reference.length and "
                      "reference.draft (see cfd/README.md, 'Older case files')");
  }
  o.ExpectKeys({"directory", "vtu_interval", "checkpoint_interval", "forces", "captive"});
  OutputOptions out;
  out.directory = o.Get<std::string>("directory", out.directory.string());
  if (out.directory.is_relative()) out.directory = case_dir / out.directory;
  out.vtu_interval = o.Get<int>("vtu_interval", out.vtu_interval);
  out.checkpoint_interval = o.Get<int>("checkpoint_interval", out.checkpoint_interval);
  if (o.Has("forces")) {
    for (const ConfigNode& item : o["forces"].Items()) out.force_patches.push_back(item.As<std::string>());
  }
  out.captive = o.Get<bool>("captive", out.captive);
  return out;
}

ResistanceOptions ReadResistance(const ConfigNode& n, const fs::path& case_dir) {
  RefuseMoved(n, "inflow", "reference: {speed, direction} (direction = inflow / |inflow|)");
  RefuseMoved(n, "wetted_area", "reference.area");
  RefuseMoved(n, "length", "reference.length");
  RefuseMoved(n, "steady",
              "time.steady {quantities: [drag, eta], tolerance, window, window_steps, min_windows} and "
              "time.ramp_steps, time.rigid_lid_windows, time.initial_velocity");
  n.ExpectKeys({"hull", "free_surface", "wave_cuts", "wave_cut_points", "double_body"});
  ResistanceOptions o;
  o.hull_patch = n.Get<std::string>("hull", o.hull_patch);
  o.free_surface_patch = n.Get<std::string>("free_surface", o.free_surface_patch);
  if (n.Has("wave_cuts")) {
    for (const ConfigNode& item : n["wave_cuts"].Items()) o.wave_cut_y.push_back(item.As<double>());
  }
  o.wave_cut_points = n.Get<int>("wave_cut_points", o.wave_cut_points);
  if (n.Has("double_body")) {
    o.double_body = n.Get<std::string>("double_body");
    if (o.double_body.is_relative()) o.double_body = case_dir / o.double_body;
  }
  ValidateAt(n, [&] { o.Validate(); });
  return o;
}

bool HasFreeSurface(const ConfigNode& boundary) {
  for (const std::string& patch : boundary.Keys()) {
    const ConfigNode b = boundary[patch];
    if (b.Has("p") && b["p"].Has("type") && b["p"].Get<std::string>("type") == "linearizedFreeSurface") return true;
  }
  return false;
}

}  // namespace

void ResistanceOptions::Validate() const {
  if (wave_cut_points < 2) throw ConfigError(fmt::format("wave_cut_points = {}; expected >= 2", wave_cut_points));
  if (hull_patch.empty()) throw ConfigError("hull: expected the name of the hull's wall patch");
}

CaseSettings ReadCaseSettings(const ConfigNode& root, const fs::path& case_dir) {
  root.ExpectKeys({"mesh", "physics", "reference", "schemes", "solution", "time", "boundary", "output", "motion",
                   "turbulence", "resistance", "propeller", "rudder", "maneuver", "partition"});
  CaseSettings s;
  s.file = root.source();
  const ConfigNode ph = root["physics"];
  ph.ExpectKeys({"nu", "rho", "body_force"});
  s.nu = ph.GetPositive("nu");
  if (ph.Has("rho")) s.rho = ph.GetPositive("rho");
  if (ph.Has("body_force")) s.body_force = GetVector(ph, "body_force");
  if (root.Has("reference")) s.reference = ReadReference(root["reference"]);
  s.time = ReadTime(root["time"]);
  s.output = ReadOutput(root["output"], case_dir);
  if (root.Has("resistance")) s.resistance = ReadResistance(root["resistance"], case_dir);
  if (root.Has("partition")) s.partition = ReadPartition(root["partition"]);
  s.free_surface = HasFreeSurface(root["boundary"]);
  if (s.time.steady && s.reference.speed == 0.0 && s.time.steady->window_is_flow_through) {
    root["time"]["steady"].Fail("a window (s of pseudo-time; 0: steps only), or reference.speed for one flow-through");
  }
  return s;
}

}  // namespace kelvin::cfd
