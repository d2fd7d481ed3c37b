#include "cfd/run/case_loader.h"

#include "cfd/run/maneuver_pilot.h"
#include "cfd/run/propeller_actuator.h"
#include "cfd/run/rudder_actuator.h"

#include <fmt/format.h>
#include <malloc.h>

#include <algorithm>
#include <limits>

#include "cfd/freesurface/linearized_free_surface.h"
#include "cfd/mesh/box_mesh.h"
#include "cfd/mesh/poly_mesh_reader.h"
#include "cfd/parallel/decompose.h"
#include "cfd/run/boundary_loader.h"
#include "cfd/run/case_config.h"
#include "cfd/turbulence/k_omega_sst.h"
#include "data/schema/errors.h"

namespace kelvin::cfd {
namespace {

namespace fs = std::filesystem;

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

SchemeOptions LoadSchemes(const ConfigNode& root) {
  SchemeOptions schemes;
  if (root.Has("schemes")) {
    const ConfigNode s = root["schemes"];
    s.ExpectKeys({"time", "gradient", "limiter", "convection", "non_orthogonal_correction", "face_centre_correction",
                  "skew_correction", "curvature_correction"});
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
                                  {"linear", ConvectionScheme::kLinear},
                                  {"lust", ConvectionScheme::kLust}});
    schemes.non_orthogonal_correction = s.Get<bool>("non_orthogonal_correction", schemes.non_orthogonal_correction);
    schemes.skew_correction = s.Get<bool>("skew_correction", schemes.skew_correction);
    schemes.face_centre_correction = s.Get<bool>("face_centre_correction", schemes.face_centre_correction);
    schemes.curvature_correction = s.Get<bool>("curvature_correction", schemes.curvature_correction);
  }

  return schemes;
}

PimpleOptions LoadPimple(const ConfigNode& root) {
  PimpleOptions pimple;
  if (root.Has("solution")) {
    const ConfigNode s = root["solution"];
    s.ExpectKeys({"n_outer", "n_correctors", "n_non_orthogonal", "momentum_predictor", "relax", "residual_control",
                  "momentum", "pressure", "p_ref_cell", "p_ref_value"});
    pimple.n_outer = s.Get<int>("n_outer", pimple.n_outer);
    pimple.n_correctors = s.Get<int>("n_correctors", pimple.n_correctors);
    pimple.n_non_orthogonal = s.Get<int>("n_non_orthogonal", pimple.n_non_orthogonal);
    pimple.momentum_predictor = s.Get<bool>("momentum_predictor", pimple.momentum_predictor);
    if (s.Has("relax")) {
      const ConfigNode r = s["relax"];
      r.ExpectKeys({"U", "p", "U_final", "p_final"});
      pimple.relax_U = r.Get<double>("U", pimple.relax_U);
      pimple.relax_p = r.Get<double>("p", pimple.relax_p);
      pimple.relax_U_final = r.Get<double>("U_final", pimple.relax_U_final);
      pimple.relax_p_final = r.Get<double>("p_final", pimple.relax_p_final);
    }
    if (s.Has("residual_control")) {
      const ConfigNode r = s["residual_control"];
      r.ExpectKeys({"U", "p"});
      pimple.outer_tolerance_U = r.Get<double>("U", pimple.outer_tolerance_U);
      pimple.outer_tolerance_p = r.Get<double>("p", pimple.outer_tolerance_p);
    }
    if (s.Has("momentum")) pimple.momentum_solver = LoadSolver(s["momentum"], pimple.momentum_solver, false);
    if (s.Has("pressure")) {
      pimple.pressure_solver = LoadSolver(s["pressure"], pimple.pressure_solver, true);
      pimple.pressure_final_relative_tolerance =
          s["pressure"].Get<double>("final_relative_tolerance", pimple.pressure_final_relative_tolerance);
    }
    pimple.p_ref_cell = s.Get<int>("p_ref_cell", pimple.p_ref_cell);
    pimple.p_ref_value = s.Get<double>("p_ref_value", pimple.p_ref_value);
  }

  return pimple;
}

// `turbulence:` k-omega SST (or laminar) on the solver.
void LoadTurbulence(const ConfigNode& tn, const Mesh& mesh, double nu, PimpleSolver& solver,
                    std::shared_ptr<const DomainPart> part) {
  tn.ExpectKeys({"model", "inflow", "convection", "relax", "wall_omega", "solver"});
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
    so.relax = tn.Get<double>("relax", so.relax);
    so.wall_omega = GetEnum(tn, "wall_omega", so.wall_omega,
                            {{"sublayer", KOmegaSstOptions::WallOmega::kDiscreteSublayer},
                             {"point", KOmegaSstOptions::WallOmega::kPointValue}});
    // The k and omega solves: their tolerances and iteration limit (the method is BiCGStab with ILU(0)).
    if (tn.Has("solver")) {
      tn["solver"].ExpectKeys({"relative_tolerance", "absolute_tolerance", "max_iterations"});
      so.solver = LoadSolver(tn["solver"], so.solver, false);
    }
    ValidateAt(tn, [&] { so.Validate(); });
    // What each patch is to k and omega: the role its conditions state.
    const std::vector<TurbulencePatchRole> roles = TurbulencePatchRoles(solver.U(), solver.p());
    bool any_wall = false;
    for (TurbulencePatchRole r : roles) any_wall = any_wall || r == TurbulencePatchRole::kWall;
    if (!any_wall) tn["model"].Fail("a case with at least one wall patch (U: noSlip or movingWall) for kOmegaSST");
    solver.SetTurbulence(std::make_unique<KOmegaSst>(mesh, nu, so, roles, std::move(part)));
  }
}

// Velocity and pressure fields with a condition on every patch; every key
// must be a patch of the mesh.
struct Fields {
  std::unique_ptr<VectorField> U;
  std::unique_ptr<ScalarField> p;
};

Fields LoadBoundary(const ConfigNode& b, const Mesh& mesh, const RigidMeshMotion* motion,
                    const FreeSurfaceOnRanks& ranks) {
  std::vector<std::string> patch_names;
  for (const Patch& p : mesh.patches()) {
    if (p.kind != PatchKind::kProcessor) patch_names.push_back(p.name);
  }
  b.ExpectKeys(patch_names);
  std::vector<std::unique_ptr<BoundaryCondition<Vector3>>> u_bcs;
  std::vector<std::unique_ptr<BoundaryCondition<double>>> p_bcs;
  Fields f;
  for (const Patch& p : mesh.patches()) {
    if (p.kind == PatchKind::kProcessor) {
      // The ghost cells' outer faces on a rank: their values never reach an owned cell.
      u_bcs.push_back(std::make_unique<ZeroGradient<Vector3>>());
      p_bcs.push_back(std::make_unique<ZeroGradient<double>>());
      continue;
    }
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
    u_bcs.push_back(LoadVelocityBc(pn["U"], motion));
    p_bcs.push_back(LoadPressureBc(pn["p"], mesh, static_cast<int>(p_bcs.size()), motion, ranks));
    if (p_bcs.back()->type() == "linearizedFreeSurface" && u_bcs.back()->type() != "zeroGradient") {
      pn["U"]["type"].Fail("zeroGradient on a linearizedFreeSurface patch (its flux comes from the pressure equation)");
    }
    if (p_bcs.back()->type() == "curvedSlipWall" && u_bcs.back()->type() != "slip") {
      pn["U"]["type"].Fail("slip on a curvedSlipWall patch (its pressure gradient is an inviscid wall's)");
    }
  }
  f.U = std::make_unique<VectorField>("U", mesh, std::move(u_bcs));
  f.p = std::make_unique<ScalarField>("p", mesh, std::move(p_bcs));
  return f;
}

std::vector<int> ResolvePatches(const ConfigNode& node, const Mesh& mesh, const std::vector<std::string>& names) {
  std::vector<std::string> all;
  for (const Patch& p : mesh.patches()) all.push_back(p.name);
  std::vector<int> out;
  for (const std::string& name : names) {
    const int k = mesh.FindPatch(name);
    if (k < 0) node.Fail(fmt::format("patches of the mesh ({}); '{}' is not one", fmt::join(all, ", "), name));
    out.push_back(k);
  }
  return out;
}

LinearizedFreeSurface* FindFreeSurface(PimpleSolver& solver) {
  LinearizedFreeSurface* found = nullptr;
  for (int k = 0; k < solver.p().n_patches(); ++k) {
    if (auto* fs = dynamic_cast<LinearizedFreeSurface*>(&solver.p().bc(k))) found = fs;
  }
  return found;
}

// What the run-level sections ask of the built case.
void CheckRunSections(const ConfigNode& root, const Case& c) {
  const CaseSettings& s = c.settings;
  if (s.time.steady && c.force_patches.empty()) {
    for (SteadyQuantity q : s.time.steady->quantities) {
      if (q != SteadyQuantity::kEta) {
        const std::string expected = "output.forces naming the patches whose force decides when the run is steady";
        if (root["time"].Has("steady")) root["time"]["steady"]["quantities"].Fail(expected);
        throw ConfigError(fmt::format("{}: the steady criterion set for this run: expected {}", root.source(), expected));
      }
    }
  }
  if (s.time.steady) {
    for (SteadyQuantity q : s.time.steady->quantities) {
      if (q == SteadyQuantity::kEta && !c.free_surface) {
        root["time"]["steady"]["quantities"].Fail("no eta: the case has no linearizedFreeSurface patch");
      }
      if (q == SteadyQuantity::kShipLoads &&
          (!c.motion || !(s.reference.length > 0.0 || s.time.steady->ship_load_arm > 0.0))) {
        throw ConfigError(fmt::format(
            "{}: time.steady quantity ship_loads: expected a motion: section (the ship axes) and reference.length "
            "(the arm that scales N)",
            root.source()));
      }
      if (q == SteadyQuantity::kDrag && s.reference.speed == 0.0) {
        root["time"]["steady"]["quantities"].Fail("force instead of drag, or a reference: {speed, direction} section (the drag direction)");
      }
    }
  }
  if (s.time.rigid_lid_windows > 0.0 && !c.free_surface) {
    root["time"]["rigid_lid_windows"].Fail(
        "0 on a case without a linearizedFreeSurface patch (a double body has no lid to release)");
  }
  if (s.time.initial_velocity && s.reference.speed == 0.0) {
    root["time"]["initial_velocity"].Fail("a reference: {speed, direction} section (the initial velocity is speed * direction)");
  }
  if (s.output.captive) {
    const ConfigNode cap = root["output"]["captive"];
    if (!c.motion) cap.Fail("a motion: section (ship-axis loads follow the body)");
    if (c.force_patches.empty()) cap.Fail("output.forces naming the hull patches");
    if (s.reference.length == 0.0 || s.reference.draft == 0.0) {
      cap.Fail("reference.length and reference.draft (the prime-system scales)");
    }
  }
  if (s.resistance) {
    const ConfigNode r = root["resistance"];
    const ResistanceOptions& o = *s.resistance;
    if (s.reference.speed == 0.0) r.Fail("a reference: {speed, direction} section (the resistance is the force along direction)");
    if (c.mesh->FindPatch(o.hull_patch) < 0) r["hull"].Fail("a patch of the mesh");
    if (!o.free_surface_patch.empty()) {
      const int k = c.mesh->FindPatch(o.free_surface_patch);
      if (k < 0 || &c.solver->p().bc(k) != static_cast<const BoundaryCondition<double>*>(c.free_surface)) {
        r["free_surface"].Fail("a patch with a linearizedFreeSurface pressure");
      }
    }
    if (o.free_surface_patch.empty() && s.time.rigid_lid_windows > 0.0) {
      r.Fail("free_surface: time.rigid_lid_windows holds a free surface this resistance section does not name");
    }
  }
}

// Cuts the loaded whole mesh over the ranks of `comm` (more than one): the
// case then holds the rank's local mesh, and the whole one until it is set up.
void DecomposeCase(Case& c, MPI_Comm comm) {
  int size = 1;
  MPI_Comm_size(comm, &size);
  const std::vector<int> cell_rank = PartitionCells(*c.mesh, size, comm, c.settings.partition);
  LocalDomain local = Decompose(*c.mesh, cell_rank, comm);
  c.whole_mesh = std::move(c.mesh);
  c.mesh = std::move(local.mesh);
  c.part = std::move(local.part);
}

}  // namespace

double PatchArea(const Mesh& mesh, std::span<const int> patches) {
  double area = 0.0;
  for (int k : patches) {
    const Patch& p = mesh.patches()[k];
    for (int f = p.start; f < p.start + p.size; ++f) area += mesh.face_area_magnitudes()[f];
  }
  return area;
}

Case LoadCase(const ConfigNode& root, const fs::path& case_dir, const CaseOverrides& overrides) {
  Case c;
  c.settings = ReadCaseSettings(root, case_dir);
  CaseSettings& s = c.settings;
  if (!overrides.poly_mesh.empty() && !root["mesh"].Has("poly_mesh")) {
    root["mesh"].Fail("a poly_mesh entry (the grid is replaced by another grid of the family)");
  }
  c.mesh = LoadMesh(root["mesh"], case_dir, overrides.poly_mesh);
  if (overrides.ranks != MPI_COMM_NULL) {
    int size = 1;
    MPI_Comm_size(overrides.ranks, &size);
    if (size > 1) DecomposeCase(c, overrides.ranks);
  }
  const Mesh& mesh = *c.mesh;
  const Mesh& whole = c.whole_mesh ? *c.whole_mesh : mesh;
  if (overrides.motion && root.Has("motion")) root["motion"].Fail("no motion: section (the campaign sets it)");
  if (overrides.motion) {
    c.motion = std::make_unique<RigidMeshMotion>(*c.mesh, RigidMotion(*overrides.motion));
  } else if (root.Has("motion") && IsFreeMotion(root["motion"])) {
    c.free_running = LoadFreeRunning(root["motion"], case_dir, LoadSchemes(root).time == TimeScheme::kBackward);
    c.free_body = std::make_shared<FreeBody>(c.free_running->body);
    c.motion = std::make_unique<RigidMeshMotion>(*c.mesh, std::shared_ptr<const BodyKinematics>(c.free_body));
  } else if (root.Has("motion")) {
    c.motion = std::make_unique<RigidMeshMotion>(*c.mesh, RigidMotion(LoadMotionOptions(root["motion"])));
  }
  if (overrides.dt > 0.0) s.time.dt = overrides.dt;
  if (overrides.steady) s.time.steady = overrides.steady;
  // A harmonic motion with `periods` sets the end time.
  const double motion_end = c.motion && c.motion->prescribed() ? c.motion->prescribed()->options().EndTime() : 0.0;
  const ConfigNode t = root["time"];
  if (motion_end > 0.0 && t.Has("end")) t["end"].Fail("no end time: motion.periods sets it");
  if (overrides.end_time > 0.0) {
    s.time.end = overrides.end_time;
  } else if (motion_end > 0.0) {
    s.time.end = motion_end;
  } else if (!t.Has("end")) {
    t.Fail("an end time (s), or a harmonic motion with periods");
  }
  if (!overrides.output.empty()) s.output.directory = overrides.output;
  c.force_patches = ResolvePatches(root["output"].Has("forces") ? root["output"]["forces"] : root["output"], mesh,
                                   s.output.force_patches);
  if (s.reference.area == 0.0) s.reference.area = PatchArea(whole, c.force_patches);
  if (c.free_running) {
    const ConfigNode m = root["motion"];
    if (c.free_running->hull_patches.empty()) {
      if (c.force_patches.empty()) m.Fail("hull_patches, or output.forces naming the hull patches");
      c.hull_patches = c.force_patches;
    } else {
      c.hull_patches = ResolvePatches(m["hull_patches"], mesh, c.free_running->hull_patches);
    }
  }

  PhysicsOptions physics;
  physics.nu = s.nu;
  if (s.body_force) {
    const Vector3 g = *s.body_force;
    physics.source = [g](const Vector3&, double) { return g; };
  }
  Fields fields = LoadBoundary(root["boundary"], mesh, c.motion.get(), {c.whole_mesh.get(), c.part});
  // The propeller and the rudder find their cells on the body-fixed mesh (not
  // placed yet), on ranks the whole one; the rudder samples the flow behind
  // the propeller.
  if (auto propeller = LoadPropellerActuator(c, root)) c.actuators.push_back(std::move(propeller));
  if (auto rudder = LoadRudderActuator(c, root)) c.actuators.push_back(std::move(rudder));
  if (s.time.steady && s.time.steady->window_is_flow_through) {
    s.time.steady->criterion.window = FlowThroughTime(whole, s.reference);
  }
  // The whole mesh has served the set-up: it goes before the solver's fields
  // are allocated (its size would otherwise add to every rank's peak), and
  // the output is written in pieces, so no rank keeps it (rank 0 keeps its
  // quality report).
  if (c.part && c.part->rank == 0) c.whole_mesh_quality = c.whole_mesh->Quality().Report();
  c.whole_mesh.reset();
#ifdef __GLIBC__
  // The decomposition's many small temporaries (a point list per face) stay
  // resident in malloc's heap once freed; hand the free pages back (on 2 ranks
  // of a 373k-cell cube: 75 B per cell of peak memory, BENCHMARKS.md).
  if (c.part) malloc_trim(0);
#endif
  ValidateAt(root["solution"], [&] {
    c.solver = std::make_unique<PimpleSolver>(mesh, physics, LoadSchemes(root), LoadPimple(root), std::move(fields.U),
                                              std::move(fields.p), c.part);
  });
  if (c.motion) c.motion->Attach(*c.solver);
  if (root.Has("turbulence")) LoadTurbulence(root["turbulence"], mesh, s.nu, *c.solver, c.part);
  c.free_surface = FindFreeSurface(*c.solver);
  ValidateAt(t, [&] { s.time.Validate(); });
  CheckRunSections(root, c);
  c.maneuver = LoadManeuverPilot(root, c, s.output.directory, overrides.maneuver);
  return c;
}

Case LoadCaseFile(const fs::path& case_file, const CaseOverrides& overrides) {
  return LoadCase(ConfigNode::LoadFile(case_file), case_file.parent_path(), overrides);
}

double FlowThroughTime(const Mesh& mesh, const CaseReference& reference, const DomainPart* part) {
  // One flow-through: the extent of the mesh along the drag direction / speed.
  double lo = std::numeric_limits<double>::max(), hi = -lo;
  for (const Vector3& x : mesh.points()) {
    lo = std::min(lo, x.dot(reference.direction));
    hi = std::max(hi, x.dot(reference.direction));
  }
  if (part && part->parallel()) {
    lo = part->Min(lo);
    hi = part->Max(hi);
  }
  return (hi - lo) / reference.speed;
}

}  // namespace kelvin::cfd
