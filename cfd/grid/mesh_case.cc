#include "cfd/grid/mesh_case.h"

#include <fmt/format.h>

#include <chrono>
#include <cmath>
#include <fstream>
#include <numbers>
#include <sstream>

#include "cfd/geometry/hull_intake.h"
#include "cfd/grid/mesh_writer.h"
#include "cfd/grid/spacing.h"
#include "data/schema/atomic_file.h"
#include "data/schema/config.h"
#include "data/schema/errors.h"
#include "data/schema/file_status.h"

namespace kelvin::cfd {

namespace fs = std::filesystem;
using data::ConfigNode;

namespace {

double Number(const ConfigNode& parent, std::string_view key, double fallback, double min,
              bool min_open = true) {
  auto child = parent.Find(key);
  if (!child) return fallback;
  const double v = child->As<double>();
  if (!std::isfinite(v) || (min_open ? !(v > min) : !(v >= min))) {
    child->Fail(fmt::format("a finite number {} {}", min_open ? ">" : ">=", min));
  }
  return v;
}

int Integer(const ConfigNode& parent, std::string_view key, int fallback, int min, int max) {
  auto child = parent.Find(key);
  if (!child) return fallback;
  const int v = child->As<int>();
  if (v < min || v > max) child->Fail(fmt::format("an integer in [{}, {}]", min, max));
  return v;
}

void ParseDomain(const ConfigNode& d, MeshCase& c) {
  d.ExpectKeys({"upstream", "downstream", "half_width", "depth"});
  c.structured.upstream = c.snappy.upstream = Number(d, "upstream", c.structured.upstream, 0.0);
  c.structured.downstream = c.snappy.downstream =
      Number(d, "downstream", c.structured.downstream, 0.0);
  c.structured.half_width = c.snappy.half_width =
      Number(d, "half_width", c.structured.half_width, 0.0);
  c.structured.depth = c.snappy.depth = Number(d, "depth", c.structured.depth, 0.0);
}

void ParseStructured(const ConfigNode& s, HullGridOptions& o) {
  s.ExpectKeys({"cells_hull", "cells_upstream", "cells_downstream", "cells_girth",
                "cells_below_keel", "cells_normal", "end_spacing", "free_surface_spacing",
                "keel_spacing"});
  o.cells_hull = Integer(s, "cells_hull", o.cells_hull, 2, 100000);
  o.cells_upstream = Integer(s, "cells_upstream", o.cells_upstream, 1, 100000);
  o.cells_downstream = Integer(s, "cells_downstream", o.cells_downstream, 1, 100000);
  o.cells_girth = Integer(s, "cells_girth", o.cells_girth, 2, 100000);
  o.cells_below_keel = Integer(s, "cells_below_keel", o.cells_below_keel, 1, 100000);
  o.cells_normal = Integer(s, "cells_normal", o.cells_normal, 2, 100000);
  o.end_spacing = Number(s, "end_spacing", o.end_spacing, 0.0);
  o.free_surface_spacing = Number(s, "free_surface_spacing", o.free_surface_spacing, 0.0);
  o.keel_spacing = Number(s, "keel_spacing", o.keel_spacing, 0.0);
}

Eigen::Vector3d Corner(const ConfigNode& box, std::string_view key) {
  const std::vector<double> v = box[key].As<std::vector<double>>();
  if (v.size() != 3) box[key].Fail(fmt::format("[x, y, z] in metres, got {} numbers", v.size()));
  return {v[0], v[1], v[2]};
}

// mesh.snappy.boxes: [{min: [x, y, z], max: [x, y, z], level: n}, ...]
std::vector<SnappyBox> ParseSnappyBoxes(const ConfigNode& list) {
  if (!list.IsSequence()) list.Fail("a list of boxes {min: [x, y, z], max: [x, y, z], level: n}");
  std::vector<SnappyBox> boxes;
  for (const ConfigNode& b : list.Items()) {
    b.ExpectKeys({"min", "max", "level"});
    const int level = b["level"].As<int>();
    if (level < 0 || level > 8) b["level"].Fail("an integer in [0, 8]");
    const SnappyBox box{Corner(b, "min"), Corner(b, "max"), level};
    if ((box.max - box.min).minCoeff() <= 0) {
      b["max"].Fail(fmt::format("a corner above min = [{}, {}, {}] in x, y and z, got [{}, {}, {}]", box.min.x(),
                                box.min.y(), box.min.z(), box.max.x(), box.max.y(), box.max.z()));
    }
    boxes.push_back(box);
  }
  return boxes;
}

void ParseSnappy(const ConfigNode& s, SnappyOptions& o) {
  s.ExpectKeys({"base_cells_per_length", "hull_level", "wake_level", "near_level", "layers",
                "expansion_ratio", "feature_angle", "boxes", "openfoam_bashrc"});
  o.base_cells_per_length = Integer(s, "base_cells_per_length", o.base_cells_per_length, 2, 200);
  o.hull_level = Integer(s, "hull_level", o.hull_level, 0, 8);
  o.wake_level = Integer(s, "wake_level", o.wake_level, 0, 8);
  if (o.wake_level > o.hull_level)
    s["wake_level"].Fail(fmt::format("at most hull_level = {}", o.hull_level));
  if (auto near = s.Find("near_level")) {
    const int n = near->As<int>();
    if (n < o.wake_level || n > o.hull_level)
      near->Fail(fmt::format("an integer in [wake_level, hull_level] = [{}, {}]", o.wake_level,
                             o.hull_level));
    o.near_level = n;
  }
  if (auto layers = s.Find("layers")) {
    if (layers->IsScalar() && layers->yaml().Scalar() == "auto") {
      o.layers = SnappyOptions::kAutoLayers;
    } else {
      const int n = layers->As<int>();
      if (n < 0 || n > 50) layers->Fail("'auto' or an integer in [0, 50]");
      o.layers = n;
    }
  }
  if (auto er = s.Find("expansion_ratio")) {
    o.expansion_ratio = er->As<double>();
    if (!(o.expansion_ratio >= 1.0 && o.expansion_ratio <= 3.0)) er->Fail("a number in [1, 3]");
  }
  if (auto fa = s.Find("feature_angle")) {
    o.feature_angle = fa->As<double>();
    if (!(o.feature_angle > 0.0 && o.feature_angle < 180.0))
      fa->Fail("an angle in degrees in (0, 180)");
  }
  if (auto boxes = s.Find("boxes")) o.boxes = ParseSnappyBoxes(*boxes);
  o.openfoam_bashrc = s.Get<std::string>("openfoam_bashrc", o.openfoam_bashrc);
}

void ParseSpheroid(const ConfigNode& node, MeshCase& c) {
  node.ExpectKeys({"length", "diameter", "depth"});
  c.spheroid = true;
  c.spheroid_shape.length = node.GetPositive("length");
  c.spheroid_shape.diameter = node.GetPositive("diameter");
  c.spheroid_shape.depth = node.GetPositive("depth");
  const auto [key, expected] = c.spheroid_shape.Problem();
  if (!key.empty()) node[key].Fail(expected);
}

// mesh.waves: the structured grid's far-field spacing, or the snappy
// domain and free-surface cells, from lambda = 2 pi Fn^2 L.
void ParseWaves(const ConfigNode& w, MeshCase& c) {
  w.ExpectKeys({"froude", "cells_per_wavelength"});
  const double froude = w.GetPositive("froude");
  if (c.method == MeshMethod::kStructured) {
    c.structured.wave_froude = froude;
    c.structured.cells_per_wave =
        Number(w, "cells_per_wavelength", c.structured.cells_per_wave, 0.0);
    return;
  }
  c.snappy.wavelength = 2.0 * std::numbers::pi * froude * froude * HullLength(c);
  c.snappy.cells_per_wavelength =
      Number(w, "cells_per_wavelength", c.snappy.cells_per_wavelength, 0.0);
  if (c.snappy.cells_per_wavelength < 4 || c.snappy.cells_per_wavelength > 100)
    w["cells_per_wavelength"].Fail("a number in [4, 100]");
}

}  // namespace

double HullLength(const MeshCase& c) {
  if (c.wigley) return c.wigley_length;
  if (c.spheroid) return c.spheroid_shape.length;
  return LoadHullPlacement(c.ship_file).Lpp;
}

MeshCase ParseMeshCase(const std::string& yaml_text, const std::string& source,
                       const fs::path& base_dir) {
  const ConfigNode root = ConfigNode::LoadString(yaml_text, source);
  if (!root.IsMap()) root.Fail("a map with sections 'mesh' and 'output'");
  root.ExpectKeys({"mesh", "output"});
  MeshCase c;
  c.source = source;
  const ConfigNode mesh = root["mesh"];
  mesh.ExpectKeys({"method", "hull", "flow", "y_plus", "domain", "structured", "snappy", "family", "waves"});

  const std::string method = mesh.Get<std::string>("method", "structured");
  if (method == "structured") {
    c.method = MeshMethod::kStructured;
  } else if (method == "snappy") {
    c.method = MeshMethod::kSnappy;
  } else {
    mesh["method"].Fail("'structured' or 'snappy'");
  }

  const ConfigNode hull = mesh["hull"];
  hull.ExpectKeys({"wigley", "ship", "spheroid"});
  if (int(hull.Has("wigley")) + int(hull.Has("ship")) + int(hull.Has("spheroid")) != 1) {
    hull.Fail(
        "exactly one of 'wigley' (the formula), 'spheroid' (a submerged body) or 'ship' (a ship "
        "file)");
  }
  double ship_nu = 0.0;
  if (auto w = hull.Find("wigley")) {
    w->ExpectKeys({"length", "beam", "draft"});
    c.wigley = true;
    c.wigley_length = w->GetPositive("length");
    c.wigley_beam = w->GetPositive("beam");
    c.wigley_draft = w->GetPositive("draft");
  } else if (auto sph = hull.Find("spheroid")) {
    ParseSpheroid(*sph, c);
  } else {
    const ConfigNode ship = hull["ship"];
    fs::path p = ship.As<std::string>();
    if (p.is_relative()) p = base_dir / p;
    if (!data::PathExists(p))
      ship.Fail("an existing ship file (relative paths start at the case file's folder)");
    c.ship_file = p;
    const ConfigNode sf = ConfigNode::LoadFile(p);
    if (auto principal = sf.Find("principal")) {
      if (auto nu = principal->Find("nu")) ship_nu = nu->As<double>();
    }
  }

  const ConfigNode flow = mesh["flow"];
  flow.ExpectKeys({"reynolds", "speed", "viscosity"});
  if (flow.Has("reynolds")) {
    if (flow.Has("speed") || flow.Has("viscosity")) {
      flow.Fail("either 'reynolds' or 'speed' (with 'viscosity' or the ship file's nu), not both");
    }
    c.reynolds = flow.GetPositive("reynolds");
    if (c.reynolds < 1e3) flow["reynolds"].Fail("a Reynolds number >= 1000");
  } else if (flow.Has("speed")) {
    const double speed = flow.GetPositive("speed");
    double nu = ship_nu;
    if (flow.Has("viscosity")) nu = flow.GetPositive("viscosity");
    if (!(nu > 0)) flow.Fail("'viscosity' (m^2/s): the hull has no ship file with principal.nu");
    c.reynolds = speed * HullLength(c) / nu;
  } else {
    flow.Fail("'reynolds', or 'speed' (m/s) with 'viscosity' (m^2/s)");
  }
  if (c.reynolds < 1e3)
    flow.Fail(fmt::format("a Reynolds number >= 1000 (got {:.4g})", c.reynolds));
  c.y_plus = Number(mesh, "y_plus", c.method == MeshMethod::kSnappy ? 60.0 : 1.0, 0.0);
  c.structured.y_plus = c.snappy.y_plus = c.y_plus;
  c.structured.reynolds = c.snappy.reynolds = c.reynolds;

  if (auto d = mesh.Find("domain")) ParseDomain(*d, c);
  if (auto s = mesh.Find("structured")) ParseStructured(*s, c.structured);
  if (auto s = mesh.Find("snappy")) ParseSnappy(*s, c.snappy);
  if (c.method == MeshMethod::kSnappy && c.wigley) {
    mesh["method"].Fail(
        "'structured' for the Wigley formula (the snappy path needs a ship file with a surface)");
  }
  if (c.method == MeshMethod::kStructured && c.spheroid) {
    mesh["method"].Fail(
        "'snappy' for a submerged spheroid (the structured grid needs a surface-piercing hull)");
  }
  if (auto w = mesh.Find("waves")) ParseWaves(*w, c);
  if (auto f = mesh.Find("family")) {
    f->ExpectKeys({"ratio", "layers"});
    c.family_ratio = Number(*f, "ratio", c.family_ratio, 1.0);
    if (c.family_ratio < 1.1 || c.family_ratio > 4.0)
      (*f)["ratio"].Fail("a refinement ratio in [1.1, 4]");
    if (auto l = f->Find("layers")) {
      const std::string v = l->As<std::string>();
      if (v == "similar") {
        c.family_layers = FamilyLayers::kSimilar;
      } else if (v == "first_layer") {
        c.family_layers = FamilyLayers::kSameFirstLayer;
      } else {
        l->Fail("'similar' (grid 1's layer count and relative thickness) or 'first_layer' (grid 1's first-layer "
                "height, the layer count from snappy.layers on each grid)");
      }
      if (c.method != MeshMethod::kSnappy) {
        l->Fail("no family.layers with mesh.method 'structured' (its family always scales the layers with the "
                "cells; 'similar' and 'first_layer' choose between the snappy path's two)");
      }
    }
  }

  const ConfigNode output = root["output"];
  output.ExpectKeys({"directory", "vtu"});
  fs::path dir = output.Get<std::string>("directory");
  if (dir.is_relative()) dir = base_dir / dir;
  c.output_directory = dir;
  c.write_vtu = output.Get<bool>("vtu", true);
  c.structured.Validate();
  c.snappy.Validate();
  return c;
}

MeshCase LoadMeshCase(const fs::path& path) {
  if (!data::PathExists(path)) throw ConfigError(fmt::format("{}: file not found", path.string()));
  std::ifstream in(path);
  std::ostringstream text;
  text << in.rdbuf();
  return ParseMeshCase(text.str(), path.string(), fs::absolute(path).parent_path());
}

namespace {

// The free-surface cells of a snappy grid sized for waves.
std::string SnappyWaveReport(const SnappyOptions& o, const SnappyRun& run) {
  if (!(o.wavelength > 0)) return "";
  return fmt::format(
      "waves: lambda = 2 pi Fn^2 L = {:.4g} m; free-surface (Kelvin wedge) box at level {}, "
      "cells {:.4g} m = lambda / {:.3g} (asked: at most lambda / {:.3g})\n",
      o.wavelength, run.wake_level, run.wake_cell, o.wavelength / run.wake_cell,
      o.cells_per_wavelength);
}

std::string GridReport(const MeshCase& c, const Mesh& mesh, const GridSummary& g,
                       const std::string& extra) {
  std::string r =
      fmt::format("kelvin mesh: {} (grid {}, {})\n", c.source, g.level,
                  c.method == MeshMethod::kStructured ? "built-in structured" : "snappyHexMesh");
  r += g.quality.Report();
  r += fmt::format("negative or zero volumes: {}\n", g.quality.min_volume > 0 ? "none" : "PRESENT");
  r += fmt::format("hull patch volume (below z = 0): {:.9g} m^3\n", g.hull_volume);
  r += fmt::format("y+ estimate (ITTC-57 C_F at Re = {:.4g}): min {:.3g} mean {:.3g} max {:.3g}\n",
                   c.reynolds, g.y_plus.min, g.y_plus.mean, g.y_plus.max);
  r += "estimated " + YPlusDistribution(g.y_plus.stats) + "\n";
  const std::string warning = YPlusWarning(g.y_plus.stats);
  if (!warning.empty()) r += warning + " (from the y+ estimate, before any run)\n";
  r += fmt::format("h = (V/N)^(1/3) = {:.6g} m\nmeshing time {:.3f} s\npatches:", g.h, g.seconds);
  for (const Patch& p : mesh.patches())
    r += fmt::format(" {}({} {})", p.name, PatchKindName(p.kind), p.size);
  r += "\n" + extra;
  return r;
}

}  // namespace

std::vector<GridSummary> RunMeshCase(const MeshCase& c, int family,
                                     const fs::path& output_override) {
  if (family < 1 || family > 6)
    throw ArgumentError(fmt::format("--family {}: expected 1 to 6 grids", family));
  const fs::path out = output_override.empty() ? c.output_directory : output_override;
  std::unique_ptr<HullSections> sections;
  TriangleSurface surface;
  std::string intake;  // the hull intake report, for quality.txt
  double length = 0;
  if (c.wigley) {
    sections = std::make_unique<WigleySections>(c.wigley_length, c.wigley_beam, c.wigley_draft);
    length = c.wigley_length;
  } else if (c.spheroid) {
    surface = SpheroidSurface(c.spheroid_shape);
    const SurfaceCheck check = ValidateHull(surface, 0.0, /*submerged_allowed=*/true);
    intake = fmt::format("  surface: {} ({} triangles, {} vertices)\n  check: {}\n", surface.source,
                         surface.triangles.size(), surface.vertices.size(), check.Summary());
  } else {
    HullPlacement placement = LoadHullPlacement(c.ship_file);
    if (!c.hull_file.empty()) placement.file = c.hull_file;
    const HullIntake in = TakeInHull(placement);
    surface = in.surface;
    intake = in.Report();
    for (const auto& w : in.warnings) fmt::print(stderr, "kelvin mesh: WARNING: {}\n", w);
    if (c.method == MeshMethod::kStructured && surface.Max().z() <= 0.0) {
      throw ConfigError(
          fmt::format("{}: mesh.method 'structured' with the fully submerged body of {}: expected "
                      "'snappy' (the structured grid's sections must reach the waterline)",
                      c.source, c.ship_file.string()));
    }
    if (c.method == MeshMethod::kStructured) sections = std::make_unique<SurfaceSections>(surface);
  }
  std::vector<GridSummary> grids;
  // snappy: grid 1's layer count and outermost-layer ratio for the family.
  int family_layers = c.snappy.layers;
  double family_final_ratio = c.snappy.final_layer_ratio;
  for (int g = 1; g <= family; ++g) {
    const double coarsen = std::pow(c.family_ratio, g - 1);
    GridSummary s;
    s.level = g;
    s.directory = family > 1 ? out / fmt::format("grid{}", g) : out;
    fs::create_directories(s.directory);
    std::string extra;
    const auto t0 = std::chrono::steady_clock::now();
    std::unique_ptr<Mesh> mesh;
    if (c.method == MeshMethod::kStructured) {
      const HullGridOptions o = c.structured.Coarsened(coarsen);
      HullGridInfo info;
      mesh = std::make_unique<Mesh>(MakeHullGrid(*sections, o, &info));
      s.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      length = sections->length();
      WritePolyMesh(*mesh, s.directory);
      extra += fmt::format(
          "target first cell height {:.4g} m (y+ {:.3g}); largest girth-line tilt {:.1f} deg\n",
          info.first_cell_height, o.y_plus, info.max_line_tilt_deg);
      if (c.wigley) {
        const double exact = 4.0 / 9.0 * c.wigley_length * c.wigley_beam * c.wigley_draft;
        extra +=
            fmt::format("Wigley volume 4/9 L B T = {:.9g} m^3; hull patch / exact - 1 = {:.3e}\n",
                        exact, HullPatchVolume(*mesh) / exact - 1.0);
      }
    } else {
      SnappyOptions o = c.snappy;
      o.base_cells_per_length =
          std::max(2, static_cast<int>(std::lround(c.snappy.base_cells_per_length / coarsen)));
      if (c.family_layers == FamilyLayers::kSimilar) {
        // The coarser grids keep grid 1's layers (count and thickness
        // relative to the cells), so the family stays geometrically similar:
        // the first-layer y+ grows with the cells, as in the structured family.
        o.layers = family_layers;
        o.final_layer_ratio = family_final_ratio;
      }  // else every grid sizes its layers from y_plus: the same first layer, more layers on coarser grids
      SnappyRun run;
      mesh = std::make_unique<Mesh>(RunSnappy(surface, o, s.directory, &run));
      family_layers = run.layers;
      family_final_ratio = run.final_layer_ratio;
      s.seconds = run.seconds_block_mesh + run.seconds_features + run.seconds_snappy;
      s.snappy = run;
      length = HullLength(c);
      extra += SnappyWaveReport(o, run);
      extra += fmt::format(
          "blockMesh {:.2f} s, surfaceFeatureExtract {:.2f} s, snappyHexMesh {:.2f} s\n"
          "base cells per length {}, hull cell {:.4g} m (level {})\n"
          "layers requested: {}, expansion {:.3g}, outermost {:.3g} of the hull cell, first layer "
          "{:.4g} m (first cell centre y+ {:.3g}; target {:.3g})\n",
          run.seconds_block_mesh, run.seconds_features, run.seconds_snappy,
          o.base_cells_per_length, run.hull_cell, o.hull_level, run.layers, o.expansion_ratio,
          run.final_layer_ratio, run.first_layer_thickness,
          YPlusAt(0.5 * run.first_layer_thickness, c.reynolds, length), o.y_plus);
      for (const SnappyBox& b : o.boxes) {
        extra += fmt::format("refinement box [{:.6g}, {:.6g}] x [{:.6g}, {:.6g}] x [{:.6g}, {:.6g}] m: level {}, "
                             "cells {:.4g} m\n",
                             b.min.x(), b.max.x(), b.min.y(), b.max.y(), b.min.z(), b.max.z(), b.level,
                             run.hull_cell * std::pow(2.0, o.hull_level - b.level));
      }
      if (run.layers_kept >= 0) {
        extra += fmt::format(
            "layers kept by snappyHexMesh: {:.2f} of {} per hull face on average, {:.1f}% of the "
            "requested thickness\n",
            run.layers_kept, run.layers, run.thickness_kept_percent);
      }
      if (run.layers_area_percent >= 0) {
        extra += fmt::format(
            "layers kept over the hull area: {:.1f}% of the requested count; {:.1f}% of the area "
            "has none\n",
            run.layers_area_percent, run.area_without_layers_percent);
      }
      extra +=
          fmt::format("hull surface volume below z = 0: {:.9g} m^3\n", UnderwaterVolume(surface));
    }
    s.quality = mesh->Quality();
    s.hull_volume = HullPatchVolume(*mesh);
    s.y_plus = EstimateYPlus(*mesh, c.reynolds, length);
    s.h = std::cbrt(s.quality.total_volume / s.quality.n_cells);
    if (c.write_vtu) WriteVtu(*mesh, s.directory / "mesh.vtu");
    if (!intake.empty()) extra += "hull intake:\n" + intake;
    s.report = GridReport(c, *mesh, s, extra);
    data::WriteFileAtomically(s.directory / "quality.txt", s.report);
    grids.push_back(std::move(s));
  }
  if (family > 1) {
    std::string t =
        fmt::format("# grid family of {} with refinement ratio r = {:.6g} (grid 1 finest)\n",
                    c.source, c.family_ratio);
    t += "grid cells h_m r_effective max_non_orthogonality_deg y_plus_mean\n";
    for (std::size_t g = 0; g < grids.size(); ++g) {
      const double r_eff = g == 0 ? 1.0 : grids[g].h / grids[g - 1].h;
      t += fmt::format("{} {} {:.6g} {:.4f} {:.3f} {:.3g}\n", grids[g].level,
                       grids[g].quality.n_cells, grids[g].h, r_eff,
                       grids[g].quality.max_non_orthogonality, grids[g].y_plus.mean);
    }
    data::WriteFileAtomically(out / "family.txt", t);
  }
  return grids;
}

}  // namespace kelvin::cfd
