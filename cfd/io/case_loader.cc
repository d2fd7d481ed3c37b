#include "cfd/io/case_loader.h"

#include <fmt/format.h>

#include <cmath>

#include "cfd/bc/outlet_inlet.h"
#include "cfd/freesurface/linearized_free_surface.h"
#include "cfd/freesurface/resistance.h"
#include "cfd/mesh/box_mesh.h"
#include "cfd/mesh/poly_mesh_reader.h"
#include "cfd/turbulence/k_omega_sst.h"
#include "data/schema/errors.h"

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

}  // namespace kelvin::cfd
