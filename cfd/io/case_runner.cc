#include "cfd/io/case_runner.h"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <array>
#include <chrono>
#include <ctime>
#include <cmath>
#include <map>

#include "cfd/bc/outlet_inlet.h"
#include "cfd/freesurface/linearized_free_surface.h"
#include "cfd/freesurface/resistance.h"
#include "cfd/io/checkpoint.h"
#include "cfd/io/vtu_writer.h"
#include "cfd/mesh/box_mesh.h"
#include "cfd/mesh/poly_mesh_reader.h"
#include "cfd/motion/ship_forces.h"
#include "cfd/turbulence/k_omega_sst.h"
#include "data/report/progress.h"
#include "data/schema/errors.h"
#include "data/schema/h5_file.h"

namespace kelvin::cfd {
namespace {

namespace fs = std::filesystem;
using data::ConfigNode;

Vector3 GetVector(const ConfigNode& node, std::string_view key) {
  const std::vector<double> v = node[key].As<std::vector<double>>();
  if (v.size() != 3) node[key].Fail("a list of 3 numbers");
  return Vector3(v[0], v[1], v[2]);
}

template <typename E>
E GetEnum(const ConfigNode& node, std::string_view key, E fallback,
          std::initializer_list<std::pair<const char*, E>> choices) {
  if (!node.Has(key)) return fallback;
  const std::string text = node.Get<std::string>(key);
  std::string names;
  for (const auto& [name, value] : choices) {
    if (text == name) return value;
    names += (names.empty() ? "" : ", ") + std::string(name);
  }
  node[key].Fail("one of " + names);
}

std::unique_ptr<Mesh> LoadMesh(const ConfigNode& m, const fs::path& case_dir, const fs::path& poly_mesh_override) {
  m.ExpectKeys({"box", "poly_mesh", "renumber"});
  std::unique_ptr<Mesh> mesh;
  if (m.Has("box") == m.Has("poly_mesh")) m.Fail("exactly one of 'box' or 'poly_mesh'");
  if (m.Has("box")) {
    const ConfigNode b = m["box"];
    b.ExpectKeys({"min", "max", "cells", "grading", "empty", "perturbation", "polyhedral", "seed", "obstacle"});
    BoxMeshOptions o;
    o.min = b.Has("min") ? GetVector(b, "min") : o.min;
    o.max = GetVector(b, "max");
    const std::vector<double> cells = b["cells"].As<std::vector<double>>();
    if (cells.size() != 3) b["cells"].Fail("a list of 3 integers");
    for (int d = 0; d < 3; ++d) o.cells[d] = static_cast<int>(cells[d]);
    if (b.Has("grading")) {
      const std::vector<double> g = b["grading"].As<std::vector<double>>();
      if (g.size() != 3) b["grading"].Fail("a list of 3 numbers");
      for (int d = 0; d < 3; ++d) o.grading[d] = g[d];
    }
    o.perturbation = b.Get<double>("perturbation", 0.0);
    o.polyhedral = b.Get<bool>("polyhedral", false);
    o.seed = static_cast<unsigned>(b.Get<int>("seed", 1));
    if (b.Has("obstacle")) {
      // Blocks removed from the box: {min: [i, j, k], max: [i, j, k]} (cell indices, max exclusive).
      const ConfigNode ob = b["obstacle"];
      ob.ExpectKeys({"min", "max"});
      for (const char* key : {"min", "max"}) {
        const std::vector<double> v = ob[key].As<std::vector<double>>();
        if (v.size() != 3) ob[key].Fail("a list of 3 cell indices");
        for (int d = 0; d < 3; ++d) (key[1] == 'i' ? o.obstacle_min : o.obstacle_max)[d] = static_cast<int>(v[d]);
      }
      if (!o.has_obstacle()) ob.Fail("max > min along every axis");
    }
    if (b.Has("empty")) {
      const std::string axis = b.Get<std::string>("empty");
      const int d = axis == "x" ? 0 : axis == "y" ? 1 : axis == "z" ? 2 : -1;
      if (d < 0) b["empty"].Fail("x, y or z (the one-cell axis of a 2D case)");
      o.kinds[2 * d] = o.kinds[2 * d + 1] = PatchKind::kEmpty;
    }
    try {
      o.Validate();
    } catch (const ConfigError& e) {
      b.Fail(e.what());
    }
    mesh = std::make_unique<Mesh>(MakeBoxMesh(o));
  } else {
    fs::path dir = m.Get<std::string>("poly_mesh");
    if (dir.is_relative()) dir = case_dir / dir;
    if (!poly_mesh_override.empty()) dir = poly_mesh_override;
    mesh = std::make_unique<Mesh>(ReadPolyMesh(dir));
  }
  if (m.Get<bool>("renumber", true)) mesh->RenumberCells();
  return mesh;
}

LinearSolverOptions LoadSolver(const ConfigNode& n, LinearSolverOptions o, bool pressure) {
  if (pressure) {
    n.ExpectKeys({"solver", "relative_tolerance", "absolute_tolerance", "max_iterations",
                  "final_relative_tolerance", "strong_threshold", "aggressive_levels", "interp_max_elements",
                  "rebuild_growth", "rebuild_each_step"});
  } else {
    n.ExpectKeys({"solver", "relative_tolerance", "absolute_tolerance", "max_iterations"});
  }
  o.type = GetEnum(n, "solver", o.type,
                   {{"bicgstab", LinearSolverOptions::Type::kBiCgStabJacobi},
                    {"cg", LinearSolverOptions::Type::kCgJacobi},
                    {"pcg_amg", LinearSolverOptions::Type::kPcgAmg}});
  o.relative_tolerance = n.Get<double>("relative_tolerance", o.relative_tolerance);
  o.absolute_tolerance = n.Get<double>("absolute_tolerance", o.absolute_tolerance);
  o.max_iterations = n.Get<int>("max_iterations", o.max_iterations);
  o.amg.strong_threshold = n.Get<double>("strong_threshold", o.amg.strong_threshold);
  o.amg.aggressive_levels = n.Get<int>("aggressive_levels", o.amg.aggressive_levels);
  o.amg.interp_max_elements = n.Get<int>("interp_max_elements", o.amg.interp_max_elements);
  o.amg.rebuild_growth = n.Get<double>("rebuild_growth", o.amg.rebuild_growth);
  o.amg.rebuild_each_step = n.Get<bool>("rebuild_each_step", o.amg.rebuild_each_step);
  try {
    o.Validate();
  } catch (const ConfigError& e) {
    n.Fail(e.what());
  }
  return o;
}

std::unique_ptr<BoundaryCondition<Vector3>> LoadVelocityBc(const ConfigNode& n, const RigidMeshMotion* motion) {
  const std::string type = n.Get<std::string>("type");
  if (type == "movingWallVelocity") {
    // No-slip wall moving with the mesh (the body of the motion section).
    n.ExpectKeys({"type"});
    if (!motion) n["type"].Fail("a condition other than movingWallVelocity: it needs a motion: section");
    return std::make_unique<MovingWall>([motion](double t) { return motion->WallMotion(t); });
  }
  if (type == "fixedValue") {
    n.ExpectKeys({"type", "value"});
    return std::make_unique<FixedValue<Vector3>>(GetVector(n, "value"));
  }
  if (type == "noSlip") {
    n.ExpectKeys({"type"});
    return std::make_unique<FixedValue<Vector3>>(Vector3(0, 0, 0));
  }
  if (type == "movingWall") {
    n.ExpectKeys({"type", "velocity", "angular_velocity", "centre"});
    MovingWall::Motion m;
    if (n.Has("velocity")) m.velocity = GetVector(n, "velocity");
    if (n.Has("angular_velocity")) m.angular_velocity = GetVector(n, "angular_velocity");
    if (n.Has("centre")) m.centre = GetVector(n, "centre");
    return std::make_unique<MovingWall>([m](double) { return m; });
  }
  if (type == "zeroGradient") {
    n.ExpectKeys({"type"});
    return std::make_unique<ZeroGradient<Vector3>>();
  }
  if (type == "slip") {
    n.ExpectKeys({"type"});
    return std::make_unique<Slip>();
  }
  if (type == "inletOutlet") {
    n.ExpectKeys({"type", "inflow"});
    return std::make_unique<InletOutlet<Vector3>>(GetVector(n, "inflow"));
  }
  if (type == "farField") {
    n.ExpectKeys({"type", "inflow", "band"});
    return std::make_unique<FarField<Vector3>>(GetVector(n, "inflow"), true, n.GetPositive("band"));
  }
  if (type == "empty") {
    n.ExpectKeys({"type"});
    return std::make_unique<Empty<Vector3>>();
  }
  n["type"].Fail(
      "one of fixedValue, noSlip, movingWall, movingWallVelocity, zeroGradient, slip, inletOutlet, farField, empty");
}

// p: {type: linearizedFreeSurface, g, mesh_velocity, advection, beach: {width, strength, sides},
// waterline_patches, pressure_patch: {centre, radius, head}, kinematic_courant, limit_advection} on a patch in z = 0 (see cfd/freesurface/linearized_free_surface.h).
// With a motion: section the mesh velocity is the rigid-body velocity of the
// moving grid, u_b = V + Omega x (x - c), in the earth frame the patch
// geometry is placed in each step (the kinematic condition advects eta
// relative to the moving mesh, docs/lfs-formulation.md section 3); the
// beach scales with the motion's forward speed.
std::unique_ptr<BoundaryCondition<double>> LoadFreeSurface(const ConfigNode& n, const Mesh& mesh, int patch,
                                                           const RigidMeshMotion* motion) {
  n.ExpectKeys({"type", "g", "mesh_velocity", "advection", "beach", "waterline_patches", "pressure_patch",
                "kinematic_courant", "limit_advection"});
  LinearizedFreeSurfaceOptions o;
  o.limit_advection = n.Get<bool>("limit_advection", false);
  if (n.Has("g")) o.g = n.GetPositive("g");
  Vector3 u_b = Vector3::Zero();
  if (n.Has("mesh_velocity")) {
    if (motion) n["mesh_velocity"].Fail("no mesh_velocity: with a motion: section it is the motion's velocity");
    u_b = GetVector(n, "mesh_velocity");
    if (u_b.z() != 0.0) n["mesh_velocity"].Fail("an in-plane velocity [u, v, 0] (the free surface stays at z = 0)");
    o.mesh_velocity = [u_b](const Vector3&, double) { return u_b; };
  } else if (motion) {
    u_b = Vector3(motion->motion().options().speed, 0.0, 0.0);
    o.mesh_velocity = [motion](const Vector3& x, double t) { return motion->PointVelocity(x, t); };
  }
  using Advection = LinearizedFreeSurfaceOptions::Advection;
  o.advection = GetEnum(n, "advection", o.advection,
                        {{"upwind", Advection::kUpwind},
                         {"linear_upwind", Advection::kLinearUpwind},
                         {"quick", Advection::kQuick}});
  if (n.Has("kinematic_courant")) o.kinematic_courant = n.GetPositive("kinematic_courant");
  if (n.Has("beach")) {
    const ConfigNode b = n["beach"];
    b.ExpectKeys({"width", "strength", "sides"});
    o.beach.width = b.GetPositive("width");
    if (b.Has("strength")) o.beach.strength = b.GetPositive("strength");
    if (u_b.norm() == 0.0) {
      b["width"].Fail("a mesh_velocity != 0 first: the beach width is in transverse wavelengths 2 pi U^2 / g");
    }
    o.beach.reference_speed = u_b.norm();
    using Side = LinearizedFreeSurfaceOptions::Beach::Side;
    for (const ConfigNode& item : b["sides"].Items()) {
      const std::string side = item.As<std::string>();
      if (side == "xmin") {
        o.beach.sides.push_back(Side::kXMin);
      } else if (side == "xmax") {
        o.beach.sides.push_back(Side::kXMax);
      } else if (side == "ymin") {
        o.beach.sides.push_back(Side::kYMin);
      } else if (side == "ymax") {
        o.beach.sides.push_back(Side::kYMax);
      } else {
        item.Fail("one of xmin, xmax, ymin, ymax (sides of the patch's bounding box)");
      }
    }
    if (o.beach.sides.empty()) b["sides"].Fail("at least one of xmin, xmax, ymin, ymax");
  }
  if (n.Has("pressure_patch")) {
    // A Gaussian surface pressure p_a = g head exp(-|x - c|^2 / r^2) (a
    // Havelock pressure distribution: the hull-free Kelvin-wake case).
    const ConfigNode pp = n["pressure_patch"];
    pp.ExpectKeys({"centre", "radius", "head"});
    const std::vector<double> c = pp["centre"].As<std::vector<double>>();
    if (c.size() != 2) pp["centre"].Fail("a list of 2 numbers [x, y] (m)");
    const double radius = pp.GetPositive("radius");
    const double head = pp.Get<double>("head");
    if (!std::isfinite(head)) pp["head"].Fail("a finite pressure head (m)");
    const double g = o.g;
    const Vector3 centre(c[0], c[1], 0.0);
    o.surface_pressure = [=](const Vector3& x, double) {
      return g * head * std::exp(-(x - centre).head<2>().squaredNorm() / (radius * radius));
    };
  }
  if (n.Has("waterline_patches")) {
    for (const ConfigNode& item : n["waterline_patches"].Items()) {
      const std::string name = item.As<std::string>();
      const int q = mesh.FindPatch(name);
      if (q < 0 || q == patch) item.Fail("another patch of the mesh (the hull at the waterline)");
      o.waterline_patches.push_back(name);
    }
  }
  try {
    return std::make_unique<LinearizedFreeSurface>(mesh, patch, std::move(o));
  } catch (const ConfigError& e) {
    n["type"].Fail(std::string("a patch that can carry the free surface; ") + e.what());
  }
}

std::unique_ptr<BoundaryCondition<double>> LoadPressureBc(const ConfigNode& n, const Mesh& mesh, int patch,
                                                          const RigidMeshMotion* motion) {
  const std::string type = n.Get<std::string>("type");
  if (type == "fixedValue") {
    n.ExpectKeys({"type", "value"});
    return std::make_unique<FixedValue<double>>(n.Get<double>("value"));
  }
  if (type == "zeroGradient") {
    n.ExpectKeys({"type"});
    return std::make_unique<ZeroGradient<double>>();
  }
  if (type == "outletInlet") {
    n.ExpectKeys({"type", "value"});
    return std::make_unique<OutletInlet<double>>(n.Get<double>("value", 0.0));
  }
  if (type == "farField") {
    n.ExpectKeys({"type", "value", "band"});
    return std::make_unique<FarField<double>>(n.Get<double>("value", 0.0), false, n.GetPositive("band"));
  }
  if (type == "empty") {
    n.ExpectKeys({"type"});
    return std::make_unique<Empty<double>>();
  }
  if (type == "mixed") {
    n.ExpectKeys({"type", "value", "gradient", "fraction"});
    const double f = n.Get<double>("fraction");
    if (!(f >= 0.0 && f <= 1.0)) n["fraction"].Fail("a value fraction in [0, 1]");
    return std::make_unique<Mixed<double>>(n.Get<double>("value", 0.0), n.Get<double>("gradient", 0.0), f);
  }
  if (type == "linearizedFreeSurface") return LoadFreeSurface(n, mesh, patch, motion);
  n["type"].Fail("one of fixedValue, zeroGradient, outletInlet, farField, empty, mixed, linearizedFreeSurface");
}

}  // namespace

Case LoadCase(const ConfigNode& root, const fs::path& case_dir, const CaseOverrides& overrides) {
  root.ExpectKeys(
      {"mesh", "physics", "schemes", "solution", "time", "boundary", "output", "motion", "turbulence", "resistance"});
  Case c;
  if (!overrides.poly_mesh.empty() && !root["mesh"].Has("poly_mesh")) {
    root["mesh"].Fail("a poly_mesh entry (the grid is replaced by another grid of the family)");
  }
  c.mesh = LoadMesh(root["mesh"], case_dir, overrides.poly_mesh);
  const Mesh& mesh = *c.mesh;
  if (overrides.motion && root.Has("motion")) root["motion"].Fail("no motion: section (the campaign sets it)");
  if (overrides.motion) {
    c.motion = std::make_unique<RigidMeshMotion>(*c.mesh, RigidMotion(*overrides.motion));
  } else if (root.Has("motion")) {
    c.motion = std::make_unique<RigidMeshMotion>(*c.mesh, RigidMotion(LoadMotionOptions(root["motion"])));
  }

  const ConfigNode ph = root["physics"];
  ph.ExpectKeys({"nu", "rho", "body_force"});
  PhysicsOptions physics;
  physics.nu = ph.GetPositive("nu");
  c.rho = ph.Has("rho") ? ph.GetPositive("rho") : 1000.0;
  if (ph.Has("body_force")) {
    const Vector3 g = GetVector(ph, "body_force");
    physics.source = [g](const Vector3&, double) { return g; };
  }

  SchemeOptions schemes;
  if (root.Has("schemes")) {
    const ConfigNode s = root["schemes"];
    s.ExpectKeys({"time", "gradient", "limiter", "convection", "non_orthogonal_correction", "skew_correction"});
    schemes.time = GetEnum(s, "time", schemes.time, {{"euler", TimeScheme::kEuler}, {"backward", TimeScheme::kBackward}});
    schemes.gradient.scheme = GetEnum(s, "gradient", schemes.gradient.scheme,
                                      {{"gauss", GradientScheme::kGaussLinear},
                                       {"least_squares", GradientScheme::kLeastSquares}});
    schemes.gradient.limiter = GetEnum(s, "limiter", schemes.gradient.limiter,
                                       {{"none", GradientLimiter::kNone}, {"cell", GradientLimiter::kCellLimited}});
    schemes.convection = GetEnum(s, "convection", schemes.convection,
                                 {{"upwind", ConvectionScheme::kUpwind},
                                  {"linear_upwind", ConvectionScheme::kLinearUpwind},
                                  {"limited", ConvectionScheme::kLimited},
                                  {"linear", ConvectionScheme::kLinear}});
    schemes.non_orthogonal_correction = s.Get<bool>("non_orthogonal_correction", true);
    schemes.skew_correction = s.Get<bool>("skew_correction", false);
  }

  PimpleOptions pimple;
  if (root.Has("solution")) {
    const ConfigNode s = root["solution"];
    s.ExpectKeys({"n_outer", "n_correctors", "n_non_orthogonal", "momentum_predictor", "relax", "residual_control",
                  "momentum", "pressure", "p_ref_cell", "p_ref_value"});
    pimple.n_outer = s.Get<int>("n_outer", pimple.n_outer);
    pimple.n_correctors = s.Get<int>("n_correctors", pimple.n_correctors);
    pimple.n_non_orthogonal = s.Get<int>("n_non_orthogonal", pimple.n_non_orthogonal);
    pimple.momentum_predictor = s.Get<bool>("momentum_predictor", true);
    if (s.Has("relax")) {
      const ConfigNode r = s["relax"];
      r.ExpectKeys({"U", "p", "U_final", "p_final"});
      pimple.relax_U = r.Get<double>("U", 1.0);
      pimple.relax_p = r.Get<double>("p", 1.0);
      pimple.relax_U_final = r.Get<double>("U_final", 1.0);
      pimple.relax_p_final = r.Get<double>("p_final", 1.0);
    }
    if (s.Has("residual_control")) {
      const ConfigNode r = s["residual_control"];
      r.ExpectKeys({"U", "p"});
      pimple.outer_tolerance_U = r.Get<double>("U", 0.0);
      pimple.outer_tolerance_p = r.Get<double>("p", 0.0);
    }
    if (s.Has("momentum")) pimple.momentum_solver = LoadSolver(s["momentum"], pimple.momentum_solver, false);
    if (s.Has("pressure")) {
      pimple.pressure_solver = LoadSolver(s["pressure"], pimple.pressure_solver, true);
      pimple.pressure_final_relative_tolerance =
          s["pressure"].Get<double>("final_relative_tolerance", pimple.pressure_final_relative_tolerance);
    }
    pimple.p_ref_cell = s.Get<int>("p_ref_cell", 0);
    pimple.p_ref_value = s.Get<double>("p_ref_value", 0.0);
  }

  const ConfigNode t = root["time"];
  t.ExpectKeys({"dt", "end", "steady"});
  if (t.Has("steady")) c.steady = LoadSteadyControl(t["steady"]);
  c.dt = overrides.dt > 0.0 ? overrides.dt : t.GetPositive("dt");
  // A harmonic motion with `periods` sets the end time.
  const double motion_end = c.motion ? c.motion->motion().options().EndTime() : 0.0;
  if (motion_end > 0.0 && t.Has("end")) t["end"].Fail("no end time: motion.periods sets it");
  c.end_time = overrides.end_time > 0.0 ? overrides.end_time : motion_end > 0.0 ? motion_end : t.GetPositive("end");

  // Boundary: every patch needs a condition for U and p, and every key must
  // be a patch of the mesh.
  const ConfigNode b = root["boundary"];
  std::vector<std::string> patch_names;
  for (const Patch& p : mesh.patches()) patch_names.push_back(p.name);
  b.ExpectKeys(patch_names);
  std::vector<std::unique_ptr<BoundaryCondition<Vector3>>> u_bcs;
  std::vector<std::unique_ptr<BoundaryCondition<double>>> p_bcs;
  std::vector<std::string> u_types;  // as written in the case (noSlip and fixedValue differ for turbulence)
  for (const Patch& p : mesh.patches()) {
    u_types.push_back(b.Has(p.name) ? b[p.name]["U"].Get<std::string>("type") : "empty");
    if (!b.Has(p.name)) {
      if (p.kind == PatchKind::kEmpty) {
        u_bcs.push_back(std::make_unique<Empty<Vector3>>());
        p_bcs.push_back(std::make_unique<Empty<double>>());
        continue;
      }
      b.Fail(fmt::format("a condition for patch '{}' (patches: {})", p.name, fmt::join(patch_names, ", ")));
    }
    const ConfigNode pn = b[p.name];
    pn.ExpectKeys({"U", "p"});
    u_bcs.push_back(LoadVelocityBc(pn["U"], c.motion.get()));
    p_bcs.push_back(LoadPressureBc(pn["p"], mesh, static_cast<int>(p_bcs.size()), c.motion.get()));
    if (p_bcs.back()->type() == "linearizedFreeSurface" && u_bcs.back()->type() != "zeroGradient") {
      pn["U"]["type"].Fail("zeroGradient on a linearizedFreeSurface patch (its flux comes from the pressure equation)");
    }
  }
  auto U = std::make_unique<VectorField>("U", mesh, std::move(u_bcs));
  auto p = std::make_unique<ScalarField>("p", mesh, std::move(p_bcs));

  const ConfigNode o = root["output"];
  o.ExpectKeys({"directory", "vtu_interval", "checkpoint_interval", "forces", "captive", "resistance"});
  c.output_directory = o.Get<std::string>("directory", "results");
  if (c.output_directory.is_relative()) c.output_directory = case_dir / c.output_directory;
  c.vtu_interval = o.Get<int>("vtu_interval", 0);
  c.checkpoint_interval = o.Get<int>("checkpoint_interval", 0);
  if (o.Has("forces")) {
    for (const ConfigNode& item : o["forces"].Items()) {
      const std::string name = item.As<std::string>();
      if (mesh.FindPatch(name) < 0) {
        item.Fail(fmt::format("a patch of the mesh ({})", fmt::join(patch_names, ", ")));
      }
      c.force_patches.push_back(name);
    }
  }
  if (c.steady.enabled() && c.force_patches.empty()) {
    t["steady"].Fail("output.forces naming the patches whose force decides when the run is steady");
  }
  if (o.Has("resistance")) {
    c.resistance = LoadResistanceReference(o["resistance"]);
    if (c.force_patches.empty()) o["resistance"].Fail("output.forces naming the hull patches");
    if (c.resistance.area == 0.0) c.resistance.area = PatchArea(mesh, c.force_patches);
  }
  if (o.Has("captive")) {
    // Ship-axis loads on the force patches, prime system with these scales.
    const ConfigNode cap = o["captive"];
    cap.ExpectKeys({"length", "draft"});
    if (!c.motion) cap.Fail("a motion: section (ship-axis loads follow the body)");
    if (c.force_patches.empty()) cap.Fail("output.forces naming the hull patches");
    c.captive_length = cap.GetPositive("length");
    c.captive_draft = cap.GetPositive("draft");
  }
  try {
    c.solver = std::make_unique<PimpleSolver>(mesh, physics, schemes, pimple, std::move(U), std::move(p));
  } catch (const ConfigError& e) {
    root["solution"].Fail(e.what());
  }
  if (c.motion) c.motion->Attach(*c.solver);
  if (root.Has("turbulence")) {
    const ConfigNode tn = root["turbulence"];
    tn.ExpectKeys({"model", "inflow", "convection", "relax"});
    const std::string model = tn.Get<std::string>("model");
    if (model != "kOmegaSST" && model != "laminar") tn["model"].Fail("kOmegaSST or laminar");
    if (model == "kOmegaSST") {
      KOmegaSstOptions so;
      if (tn.Has("inflow")) {
        const ConfigNode in = tn["inflow"];
        in.ExpectKeys({"intensity", "viscosity_ratio", "reference_speed"});
        so.inflow.intensity = in.Get<double>("intensity", so.inflow.intensity);
        so.inflow.viscosity_ratio = in.Get<double>("viscosity_ratio", so.inflow.viscosity_ratio);
        so.inflow.reference_speed = in.GetPositive("reference_speed");
      } else {
        tn.Fail("an inflow section with reference_speed (m/s), and optionally intensity and viscosity_ratio");
      }
      so.convection = GetEnum(tn, "convection", ConvectionScheme::kUpwind,
                             {{"upwind", ConvectionScheme::kUpwind}, {"limited", ConvectionScheme::kLimited}});
      so.relax = tn.Get<double>("relax", 1.0);
      try {
        so.Validate();
      } catch (const ConfigError& e) {
        tn.Fail(e.what());
      }
      // What each patch is to k and omega follows from its velocity
      // condition: prescribed inflow, walls, outflow, zero-gradient planes.
      std::vector<TurbulencePatchRole> roles;
      for (int k = 0; k < static_cast<int>(mesh.patches().size()); ++k) {
        const std::string& u_type = u_types[k];
        const std::string p_type = c.solver->p().bc(k).type();
        if (u_type == "empty") {
          roles.push_back(TurbulencePatchRole::kEmpty);
        } else if (u_type == "fixedValue") {
          roles.push_back(TurbulencePatchRole::kInflow);
        } else if (u_type == "movingWall" || u_type == "movingWallVelocity" || u_type == "noSlip") {
          roles.push_back(TurbulencePatchRole::kWall);
        } else if (u_type == "slip" || p_type == "linearizedFreeSurface") {
          roles.push_back(TurbulencePatchRole::kSymmetry);
        } else {
          roles.push_back(TurbulencePatchRole::kOutflow);
        }
      }
      bool any_wall = false;
      for (TurbulencePatchRole r : roles) any_wall = any_wall || r == TurbulencePatchRole::kWall;
      if (!any_wall) tn["model"].Fail("a case with at least one wall patch (U: noSlip or movingWall) for kOmegaSST");
      c.solver->SetTurbulence(std::make_unique<KOmegaSst>(mesh, physics.nu, so, roles));
    }
  }
  return c;
}

namespace {

// Pressure and viscous force on a patch (N): p is kinematic, so times rho.
std::pair<Vector3, Vector3> PatchForce(const PimpleSolver& s, int patch_index, double rho, double nu) {
  const PatchFaceForces ff = ComputePatchFaceForces(s, patch_index, rho, nu);
  Vector3 fp = Vector3::Zero(), fv = Vector3::Zero();
  for (std::size_t i = 0; i < ff.pressure.size(); ++i) {
    fp += ff.pressure[i];
    fv += ff.viscous[i];
  }
  return {fp, fv};
}

}  // namespace

RunSummary RunCase(const fs::path& case_file, const RunOptions& options) {
  const ConfigNode root = ConfigNode::LoadFile(case_file);
  CaseOverrides overrides;
  overrides.poly_mesh = options.poly_mesh_override;
  Case c = LoadCase(root, case_file.parent_path(), overrides);
  if (!options.output_override.empty()) c.output_directory = options.output_override;
  PimpleSolver& solver = *c.solver;
  const Mesh& mesh = *c.mesh;
  spdlog::info("mesh quality:\n{}", mesh.Quality().Report());
  const double nu = root["physics"].GetPositive("nu");
  fs::create_directories(c.output_directory);
  RunSummary summary;
  summary.output_directory = c.output_directory;
  CheckpointScalars restored;
  if (!options.restart.empty()) restored = ReadCheckpoint(options.restart, solver);
  // Steady resistance (the `resistance:` section): uniform start, time-step
  // ramp, convergence stop and resistance.h5 (cfd/freesurface/resistance.h).
  std::unique_ptr<ResistanceMonitor> resistance;
  if (root.Has("resistance")) {
    resistance = LoadResistance(root["resistance"], solver, root["physics"], case_file.parent_path());
    resistance->Start(solver, !options.restart.empty(), restored);
  }

  std::vector<std::vector<double>> history;  // rows: time, Co, resU, resp, continuity, forces...
  std::vector<CaptiveSample> captive_rows;      // ship-axis loads (motion with output.captive)
  std::vector<int> force_patch_index;
  for (const std::string& name : c.force_patches) force_patch_index.push_back(mesh.FindPatch(name));
  PvdSeries pvd(c.output_directory / "fields.pvd");
  std::map<std::string, PvdSeries> surface_pvd;
  auto write_fields = [&]() {
    VtuCellData u{"U", 3, {}}, p{"p", 1, {}};
    for (int i = 0; i < mesh.n_cells(); ++i) {
      for (int k = 0; k < 3; ++k) u.values.push_back(solver.U()[i][k]);
      p.values.push_back(solver.p()[i]);
    }
    const fs::path file = c.output_directory / fmt::format("fields_{:06d}.vtu", solver.step());
    std::vector<VtuCellData> cell_data = {u, p};
    if (solver.turbulence()) {
      for (TurbulenceOutput& t : solver.turbulence()->CellOutputs()) {
        cell_data.push_back({t.name, t.components, std::move(t.values)});
      }
    }
    WriteVtu(file, mesh, cell_data);
    pvd.Add(solver.time(), file);
    // Patches whose conditions have their own unknowns (eta): a surface file
    // with those, p and U per face, in a series of their own.
    for (int k = 0; k < solver.p().n_patches(); ++k) {
      auto fields = solver.p().bc(k).FaceFields();
      if (fields.empty()) continue;
      const Patch& patch = mesh.patches()[k];
      std::vector<VtuCellData> data;
      for (auto& [name, values] : fields) data.push_back({name, 1, std::move(values)});
      VtuCellData pf{"p", 1, {}}, uf{"U", 3, {}};
      for (int f = patch.start; f < patch.start + patch.size; ++f) {
        pf.values.push_back(solver.p().boundary()[f - mesh.n_internal_faces()]);
        for (int d = 0; d < 3; ++d) uf.values.push_back(solver.U().boundary()[f - mesh.n_internal_faces()][d]);
      }
      data.push_back(std::move(pf));
      data.push_back(std::move(uf));
      const fs::path surface_file = c.output_directory / fmt::format("{}_{:06d}.vtp", patch.name, solver.step());
      WritePatchVtp(surface_file, mesh, patch, data);
      auto [series, inserted] = surface_pvd.try_emplace(patch.name, c.output_directory / (patch.name + ".pvd"));
      series->second.Add(solver.time(), surface_file);
    }
  };
  // Turbulence per step: residuals of k and omega, cells lifted by the bound
  // step, and y+ (min, mean, max) on each wall patch.
  std::vector<std::array<double, 4>> turbulence_rows;
  // output.resistance: C_T, C_F (viscous), C_P (pressure) per step.
  std::vector<std::array<double, 3>> resistance_rows;
  ForceConvergence steady(c.steady);
  std::vector<std::vector<WallPatchStats>> wall_rows;
  constexpr std::size_t kForceColumn = 9;
  auto write_history = [&]() {
    data::H5Writer w(c.output_directory / "history.h5");
    const std::size_t rows = history.size();
    auto column = [&](std::size_t col) {
      std::vector<double> v(rows);
      for (std::size_t r = 0; r < rows; ++r) v[r] = history[r][col];
      return v;
    };
    w.WriteArray("time", column(0), {rows}, "s", "simulated time at the end of each step");
    w.WriteArray("courant", column(1), {rows}, "1", "maximum Courant number");
    w.WriteArray("residuals/U", column(2), {rows}, "1", "initial normalized momentum residual of the step");
    w.WriteArray("residuals/p", column(3), {rows}, "1", "initial normalized pressure residual of the step");
    w.WriteArray("continuity", column(4), {rows}, "1", "max_cells |sum F| / sum |F| after the correction");
    w.WriteArray("wall_time", column(5), {rows}, "s", "wall-clock time since the start of the time loop");
    w.WriteArray("outer_iterations", column(6), {rows}, "1", "PIMPLE outer iterations of the step");
    w.WriteArray("pressure_iterations", column(7), {rows}, "1", "pressure CG iterations of the step");
    w.WriteArray("cpu_time", column(8), {rows}, "s", "process CPU time since the start of the time loop");
    for (std::size_t k = 0; k < c.force_patches.size(); ++k) {
      std::vector<double> fp(rows * 3), fv(rows * 3);
      for (std::size_t r = 0; r < rows; ++r) {
        for (int d = 0; d < 3; ++d) {
          fp[r * 3 + d] = history[r][kForceColumn + 6 * k + d];
          fv[r * 3 + d] = history[r][kForceColumn + 6 * k + 3 + d];
        }
      }
      w.WriteArray("forces/" + c.force_patches[k] + "/pressure", fp, {rows, 3}, "N", "pressure force on the patch");
      w.WriteArray("forces/" + c.force_patches[k] + "/viscous", fv, {rows, 3}, "N", "viscous force on the patch");
    }
    if (!captive_rows.empty()) WriteCaptiveHistory(w, captive_rows);
    if (!resistance_rows.empty()) {
      const std::size_t n = resistance_rows.size();
      const char* names[3] = {"resistance/C_T", "resistance/C_F", "resistance/C_P"};
      const char* what[3] = {"total resistance coefficient F.d / (rho U^2 S / 2) of the force patches",
                             "viscous (friction) part of C_T", "pressure part of C_T"};
      for (int j = 0; j < 3; ++j) {
        std::vector<double> v(n);
        for (std::size_t r = 0; r < n; ++r) v[r] = resistance_rows[r][j];
        w.WriteArray(names[j], v, {n}, "1", what[j]);
      }
      w.WriteArray("resistance/reference", std::vector<double>{c.resistance.speed, c.resistance.area, c.rho}, {3},
                   "m/s, m^2, kg/m^3", "reference speed U, area S and density rho of the coefficients");
    }
    if (c.steady.enabled()) {
      w.WriteArray("steady/change", std::vector<double>{steady.change()}, {1}, "1",
                   "relative range of the monitored force over the time.steady window at the last step");
      w.WriteArray("steady/converged", std::vector<double>{summary.steady_converged ? 1.0 : 0.0}, {1}, "1",
                   "1 when the force settled within the tolerance before time.end");
    }
    if (!turbulence_rows.empty()) {
      const std::size_t n = turbulence_rows.size();
      const char* names[4] = {"turbulence/residuals/k", "turbulence/residuals/omega", "turbulence/bounded/k",
                              "turbulence/bounded/omega"};
      const char* what[4] = {"initial normalized residual of k", "initial normalized residual of omega",
                             "cells the bound step lifted to the floor (k)",
                             "cells the bound step lifted to the floor (omega)"};
      for (int j = 0; j < 4; ++j) {
        std::vector<double> v(n);
        for (std::size_t r = 0; r < n; ++r) v[r] = turbulence_rows[r][j];
        w.WriteArray(names[j], v, {n}, "1", what[j]);
      }
      for (std::size_t k = 0; k < wall_rows.front().size(); ++k) {
        std::vector<double> v(n * 3);
        for (std::size_t r = 0; r < n; ++r) {
          v[3 * r] = wall_rows[r][k].y_plus_min;
          v[3 * r + 1] = wall_rows[r][k].y_plus_mean;
          v[3 * r + 2] = wall_rows[r][k].y_plus_max;
        }
        w.WriteArray("turbulence/y_plus/" + wall_rows.front()[k].patch, v, {n, 3}, "1",
                     "first-cell y+ on the wall patch: min, area-weighted mean, max");
      }
    }
    w.Commit();
  };

  const int total_steps = static_cast<int>(std::ceil((c.end_time - solver.time()) / c.dt - 1e-9));
  Progress::Options po;
  po.label = "kelvin run";
  po.enabled = options.progress;
  Progress progress(std::max(total_steps, 1), po);
  const auto start = std::chrono::steady_clock::now();
  const std::clock_t cpu_start = std::clock();
  for (int i = 0; i < total_steps; ++i) {
    const StepSummary s = solver.Step(resistance ? resistance->TimeStep(c.dt) : c.dt);
    summary.outer_iterations += s.outer_iterations;
    ++summary.steps;
    if (!s.finite) {
      summary.status = RunSummary::Status::kDiverged;
      summary.message = fmt::format(
          "diverged at step {} (t = {:.6g} s): non-finite residual or field (U residual {:.3g}, p residual {:.3g}, "
          "Courant {:.3g}); last good checkpoint: {}",
          s.step, s.time, s.initial_residual_U, s.initial_residual_p, s.courant_max,
          summary.last_checkpoint.empty() ? "none" : summary.last_checkpoint.string());
      break;
    }
    const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    const double cpu = static_cast<double>(std::clock() - cpu_start) / CLOCKS_PER_SEC;
    std::vector<double> row = {s.time, s.courant_max, s.initial_residual_U, s.initial_residual_p, s.continuity_error,
                               wall, static_cast<double>(s.outer_iterations),
                               static_cast<double>(s.pressure_iterations), cpu};
    for (const std::string& name : c.force_patches) {
      const auto [fp, fv] = PatchForce(solver, mesh.FindPatch(name), c.rho, nu);
      for (int d = 0; d < 3; ++d) row.push_back(fp[d]);
      for (int d = 0; d < 3; ++d) row.push_back(fv[d]);
    }
    if (c.resistance.enabled() || c.steady.enabled()) {
      // Summed pressure and viscous force of the force patches (the row holds
      // them per patch after kForceColumn).
      Vector3 fp = Vector3::Zero(), fv = Vector3::Zero();
      for (std::size_t k = 0; k < c.force_patches.size(); ++k) {
        for (int d = 0; d < 3; ++d) {
          fp[d] += row[kForceColumn + 6 * k + d];
          fv[d] += row[kForceColumn + 6 * k + 3 + d];
        }
      }
      if (c.resistance.enabled()) {
        const double q = 0.5 * c.rho * c.resistance.speed * c.resistance.speed * c.resistance.area;
        const double cp = fp.dot(c.resistance.direction) / q, cf = fv.dot(c.resistance.direction) / q;
        resistance_rows.push_back({cp + cf, cf, cp});
      }
      if (c.steady.enabled() && steady.Add(fp + fv)) summary.steady_converged = true;
      summary.steady_change = steady.change();
    }
    history.push_back(std::move(row));
    bool converged = false;
    if (resistance) {
      const auto [fp, fv] = PatchForce(solver, resistance->hull_patch(), c.rho, nu);
      converged = resistance->Record(solver, fp, fv);
    }
    if (c.motion && c.captive_length > 0.0) {
      captive_rows.push_back(MakeCaptiveSample(solver, *c.motion, force_patch_index, c.rho, nu,
                                            {c.rho, c.captive_length, c.captive_draft,
                                             c.motion->motion().options().speed}));
    }
    const bool last = i + 1 == total_steps || converged || summary.steady_converged;
    if ((last && c.vtu_interval >= 0) || (c.vtu_interval > 0 && solver.step() % c.vtu_interval == 0)) {
      write_fields();
    }
    if ((last && c.checkpoint_interval >= 0) ||
        (c.checkpoint_interval > 0 && solver.step() % c.checkpoint_interval == 0)) {
      summary.last_checkpoint = c.output_directory / "checkpoint.h5";
      WriteCheckpoint(summary.last_checkpoint, solver,
                      resistance ? resistance->CheckpointScalars() : CheckpointScalars{});
      write_history();
    }
    if (const TurbulenceModel* t = solver.turbulence()) {
      const TurbulenceSummary& ts = solver.turbulence_summary();
      turbulence_rows.push_back({ts.initial_residual_k, ts.initial_residual_omega, double(ts.bounded_k),
                                 double(ts.bounded_omega)});
      wall_rows.push_back(t->WallStats());
      if (ts.bounded_k + ts.bounded_omega > 0) {
        spdlog::warn("step {}: the bound step lifted {} k and {} omega cells to the floor", s.step, ts.bounded_k,
                     ts.bounded_omega);
      }
    }
    progress.Update(i + 1, fmt::format("step {} t={:.4g} Co={:.3g} U={:.2e} p={:.2e}", s.step, s.time,
                                       s.courant_max, s.initial_residual_U, s.initial_residual_p));
    if (converged || summary.steady_converged) break;
  }
  if (!history.empty()) write_history();
  progress.Finish(summary.status == RunSummary::Status::kCompleted ? "done" : "diverged");
  summary.time = solver.time();
  summary.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (summary.status == RunSummary::Status::kCompleted) {
    summary.message = fmt::format("completed {} steps to t = {:.6g} s; results in {}", summary.steps, summary.time,
                                  summary.output_directory.string());
    if (resistance && summary.steps > 0) {
      summary.message += "\n  " + resistance->Write(c.output_directory / "resistance.h5", solver);
    }
    if (c.steady.enabled()) {
      summary.message +=
          summary.steady_converged
              ? fmt::format("\n  steady: force settled (range {:.3g} of |F| over {} steps)", summary.steady_change,
                            c.steady.window)
              : fmt::format("\n  steady: NOT settled by time.end (range {:.3g} of |F| over {} steps, tolerance {:.3g})",
                            summary.steady_change, c.steady.window, c.steady.tolerance);
    }
    if (!resistance_rows.empty()) {
      const auto& r = resistance_rows.back();
      summary.message += fmt::format("\n  resistance: C_T {:.5e} = C_F {:.5e} + C_P {:.5e} (U {:.4g} m/s, S {:.5g} m^2)",
                                     r[0], r[1], r[2], c.resistance.speed, c.resistance.area);
    }
    if (!wall_rows.empty()) {
      for (const WallPatchStats& w : wall_rows.back()) {
        summary.message += fmt::format("\n  y+ on {}: min {:.3g}, mean {:.3g}, max {:.3g}", w.patch, w.y_plus_min,
                                       w.y_plus_mean, w.y_plus_max);
      }
    }
  }
  return summary;
}

}  // namespace kelvin::cfd
