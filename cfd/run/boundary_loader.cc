#include "cfd/run/boundary_loader.h"

#include <fmt/format.h>

#include <cmath>

#include "cfd/bc/curved_wall_pressure.h"
#include "cfd/bc/outlet_inlet.h"
#include "cfd/freesurface/linearized_free_surface.h"
#include "cfd/run/case_config.h"
#include "data/schema/errors.h"

namespace kelvin::cfd {
namespace {

// p: {type: linearizedFreeSurface, g, mesh_velocity, advection, linearization, beach: {width, strength, sides},
// waterline_patches, pressure_patch: {centre, radius, head}, kinematic_courant, limit_advection} on a patch in z = 0
// (see cfd/freesurface/linearized_free_surface.h).
// With a motion: section the mesh velocity is the rigid-body velocity of the
// moving grid, u_b = V + Omega x (x - c), in the earth frame the patch
// geometry is placed in each step (the kinematic condition advects eta
// relative to the moving mesh, docs/formulation.md section 3); the
// beach scales with the motion's forward speed.
std::unique_ptr<BoundaryCondition<double>> LoadFreeSurface(const ConfigNode& n, const Mesh& mesh, int patch,
                                                           const RigidMeshMotion* motion,
                                                           const FreeSurfaceOnRanks& ranks) {
  n.ExpectKeys({"type", "g", "mesh_velocity", "advection", "linearization", "beach", "waterline_patches",
                "pressure_patch", "kinematic_courant", "limit_advection"});
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
    u_b = Vector3(motion->body().nominal_speed(), 0.0, 0.0);
    o.mesh_velocity = [motion](const Vector3& x, double t) { return motion->PointVelocity(x, t); };
  }
  using Advection = LinearizedFreeSurfaceOptions::Advection;
  o.advection = GetEnum(n, "advection", o.advection,
                        {{"upwind", Advection::kUpwind},
                         {"linear_upwind", Advection::kLinearUpwind},
                         {"quick", Advection::kQuick}});
  using Linearization = LinearizedFreeSurfaceOptions::Linearization;
  o.linearization = GetEnum(n, "linearization", o.linearization,
                            {{"uniform_stream", Linearization::kUniformStream},
                             {"local_flow", Linearization::kLocalFlow}});
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
    return std::make_unique<LinearizedFreeSurface>(mesh, patch, std::move(o), ranks);
  } catch (const ConfigError& e) {
    n["type"].Fail(std::string("a patch that can carry the free surface; ") + e.what());
  }
}

}  // namespace

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
    return std::make_unique<FixedValue<Vector3>>(Vector3(0, 0, 0), PatchRole::kWall);
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

std::unique_ptr<BoundaryCondition<double>> LoadPressureBc(const ConfigNode& n, const Mesh& mesh, int patch,
                                                          const RigidMeshMotion* motion,
                                                          const FreeSurfaceOnRanks& ranks) {
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
  if (type == "curvedSlipWall") {
    n.ExpectKeys({"type"});
    return std::make_unique<CurvedWallPressure>(mesh, patch, ranks);
  }
  if (type == "linearizedFreeSurface") return LoadFreeSurface(n, mesh, patch, motion, ranks);
  n["type"].Fail(
      "one of fixedValue, zeroGradient, outletInlet, farField, empty, mixed, curvedSlipWall, linearizedFreeSurface");
}

}  // namespace kelvin::cfd
