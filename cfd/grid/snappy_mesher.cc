#include "cfd/grid/snappy_mesher.h"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <numbers>
#include <sstream>

#include "cfd/grid/spacing.h"
#include "cfd/mesh/poly_mesh_reader.h"
#include "data/schema/atomic_file.h"
#include "data/schema/errors.h"
#include "data/schema/file_status.h"

namespace kelvin::cfd {

namespace fs = std::filesystem;

namespace {

void RequirePositive(const char* key, double v) {
  if (!(v > 0) || !std::isfinite(v)) {
    throw ConfigError(fmt::format("snappy option '{}' = {}: expected a finite number > 0", key, v));
  }
}

void RequireRange(const char* key, int v, int lo, int hi) {
  if (v < lo || v > hi) {
    throw ConfigError(
        fmt::format("snappy option '{}' = {}: expected an integer in [{}, {}]", key, v, lo, hi));
  }
}

std::string Header(const char* object) {
  return fmt::format(
      "FoamFile\n{{\n    version     2.0;\n    format      ascii;\n    class       dictionary;\n   "
      " object      {};\n}}\n"
      "// Written by kelvin mesh.\n\n",
      object);
}

// The cell size at refinement `level`: length / base_cells_per_length / 2^level.
double SnappyLevelCell(const SnappyOptions& o, double length, int level) {
  return length / o.base_cells_per_length / std::pow(2.0, level);
}

std::string Vec(const Eigen::Vector3d& v) {
  return fmt::format("({:.9g} {:.9g} {:.9g})", v.x(), v.y(), v.z());
}

// Domain and boxes in ship axes.
struct Layout {
  Eigen::Vector3d min, max;
  Eigen::Vector3d near_min, near_max;  // near-hull box
  Eigen::Vector3d wake_min, wake_max;  // Kelvin wedge box
  std::array<int, 3> cells;
  Eigen::Vector3d inside;  // locationInMesh
  double length;
};

// Extent of the part of the hull below z = 0 (all of a submerged body).
void UnderwaterExtent(const TriangleSurface& hull, Eigen::Vector3d* lo, Eigen::Vector3d* hi) {
  *lo = hull.Max();
  *hi = hull.Min();
  for (const auto& v : hull.vertices) {
    if (v.z() > 0) continue;
    *lo = lo->cwiseMin(v);
    *hi = hi->cwiseMax(v);
  }
}

// The Kelvin wedge (half angle 19.47 deg) from just ahead of the bow: over
// half a length behind the stern and a tenth of a length deep, or, with
// waves, to the outlet, widened by the body's half beam and lambda / 6 deep.
void WakeBox(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi, const SnappyOptions& o,
             Layout& l) {
  const double L = l.length;
  const double x0 = hi.x() + 0.1 * L;
  const bool waves = o.wavelength > 0;
  const double x1 = waves ? l.min.x() : std::max(l.min.x(), lo.x() - 0.5 * L);
  const double beam = waves ? std::max(std::abs(lo.y()), std::abs(hi.y())) : 0.0;
  const double half = std::tan(19.47 * std::numbers::pi / 180.0) * (x0 - x1) + beam;
  const double depth = waves ? std::max(0.1 * L, o.wavelength / 6.0) : 0.1 * L;
  l.wake_min = Eigen::Vector3d(x1, std::max(l.min.y(), -half), std::max(l.min.z(), -depth));
  l.wake_max = Eigen::Vector3d(x0, std::min(l.max.y(), half), 0.0);
}

Layout MakeLayout(const TriangleSurface& hull, const SnappyOptions& o) {
  Eigen::Vector3d lo, hi;
  UnderwaterExtent(hull, &lo, &hi);
  Layout l;
  l.length = hi.x() - lo.x();
  if (!(l.length > 0))
    throw DataFileError(fmt::format("{}: no part of the hull lies below z = 0", hull.source));
  const double L = l.length;
  // Each extent: the option in hull lengths, or with waves at least the
  // stated number of wavelengths.
  const auto reach = [&](double lengths, double wavelengths) {
    return std::max(lengths * L, wavelengths * o.wavelength);
  };
  const double width = reach(o.half_width, SnappyOptions::kWaveHalfWidth);
  l.min = Eigen::Vector3d(lo.x() - reach(o.downstream, SnappyOptions::kWaveDownstream), -width,
                          -reach(o.depth, SnappyOptions::kWaveDepth));
  l.max = Eigen::Vector3d(hi.x() + reach(o.upstream, SnappyOptions::kWaveUpstream), width, 0.0);
  if (!(l.min.z() < lo.z()) || !(l.max.y() > hi.y()) || !(l.min.y() < lo.y())) {
    throw ConfigError(
        fmt::format("snappy domain (half_width {} L, depth {} L, L = {:.4g} m) does not contain "
                    "the hull of {} (lowest z = {:.4g} m, y from {:.4g} to {:.4g} m): expected "
                    "domain.depth and domain.half_width large enough",
                    o.half_width, o.depth, L, hull.source, lo.z(), lo.y(), hi.y()));
  }
  const double h = L / o.base_cells_per_length;
  const Eigen::Vector3d ext = l.max - l.min;
  for (int a = 0; a < 3; ++a) l.cells[a] = std::max(1, static_cast<int>(std::lround(ext[a] / h)));
  WakeBox(lo, hi, o, l);
  // Near the hull, up to z = 0: over a submerged body this is the explicit
  // refinement between the body and the free surface above it.
  l.near_min = Eigen::Vector3d(lo.x() - 0.1 * L, lo.y() - 0.05 * L, lo.z() - 0.05 * L);
  l.near_max = Eigen::Vector3d(hi.x() + 0.05 * L, hi.y() + 0.05 * L, 0.0);
  l.near_min = l.near_min.cwiseMax(l.min);
  // A point in the water away from every face: upstream, off the centreplane.
  l.inside = Eigen::Vector3d(0.5 * (hi.x() + l.max.x()) + 0.1234567 * h,
                             0.4321 * l.max.y() + 0.0123 * h, 0.6173 * l.min.z() + 0.0111 * h);
  return l;
}

double Seconds(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

std::string Tail(const fs::path& log, int lines) {
  std::ifstream in(log);
  std::vector<std::string> all;
  for (std::string s; std::getline(in, s);) all.push_back(s);
  std::string out;
  for (std::size_t i = all.size() > static_cast<std::size_t>(lines) ? all.size() - lines : 0;
       i < all.size(); ++i) {
    out += "    " + all[i] + "\n";
  }
  return out;
}

// Runs an OpenFOAM tool in the case directory with its log beside it.
double RunTool(const SnappyOptions& o, const fs::path& case_dir, const std::string& tool) {
  const std::string name = tool.substr(0, tool.find(' '));
  // Absolute paths: the command changes into the case directory, so a
  // relative `kelvin mesh -o DIR` must not be resolved a second time there.
  const fs::path dir = fs::absolute(case_dir);
  const fs::path log = dir / ("log." + name);
  if (!data::PathExists(o.openfoam_bashrc)) {
    throw DataFileError(
        fmt::format("{}: OpenFOAM environment not found (snappy option 'openfoam_bashrc'); install "
                    "Debian's openfoam package (tools/setup)",
                    o.openfoam_bashrc));
  }
  const std::string cmd =
      fmt::format("bash -c 'source \"{}\" >/dev/null 2>&1; cd \"{}\" && {} > \"{}\" 2>&1'",
                  o.openfoam_bashrc, dir.string(), tool, log.string());
  const auto t0 = std::chrono::steady_clock::now();
  const int status = std::system(cmd.c_str());
  const double s = Seconds(t0);
  if (status != 0) {
    throw DataFileError(fmt::format("{} failed (exit status {}); see {}; its last lines:\n{}", name,
                                    status, log.string(), Tail(log, 12)));
  }
  return s;
}

}  // namespace

void SnappyOptions::Validate() const {
  RequirePositive("upstream", upstream);
  RequirePositive("downstream", downstream);
  RequirePositive("half_width", half_width);
  RequirePositive("depth", depth);
  RequireRange("base_cells_per_length", base_cells_per_length, 2, 200);
  RequireRange("hull_level", hull_level, 0, 8);
  RequireRange("wake_level", wake_level, 0, 8);
  if (wake_level > hull_level) {
    throw ConfigError(
        fmt::format("snappy option 'wake_level' = {}: expected at most hull_level = {}", wake_level,
                    hull_level));
  }
  if (near_level != kAutoLevel && (near_level < wake_level || near_level > hull_level)) {
    throw ConfigError(fmt::format(
        "snappy option 'near_level' = {}: expected an integer in [wake_level, hull_level] = [{}, {}]",
        near_level, wake_level, hull_level));
  }
  for (std::size_t i = 0; i < boxes.size(); ++i) {
    const SnappyBox& b = boxes[i];
    if (!b.min.allFinite() || !b.max.allFinite() || (b.max - b.min).minCoeff() <= 0) {
      throw ConfigError(fmt::format(
          "snappy option 'boxes[{}]' min = {}, max = {}: expected finite corners with min < max in x, y and z",
          i, Vec(b.min), Vec(b.max)));
    }
    if (b.level < 0 || b.level > 8) {
      throw ConfigError(
          fmt::format("snappy option 'boxes[{}].level' = {}: expected an integer in [0, 8]", i, b.level));
    }
  }
  RequireRange("layers", layers, kAutoLayers, 50);
  if (!(final_layer_ratio >= 0 && final_layer_ratio <= 2) || !std::isfinite(final_layer_ratio)) {
    throw ConfigError(fmt::format(
        "snappy option 'final_layer_ratio' = {}: expected a number in [0, 2] (0: from y+)",
        final_layer_ratio));
  }
  if (!(expansion_ratio >= 1.0 && expansion_ratio <= 3.0)) {
    throw ConfigError(fmt::format(
        "snappy option 'expansion_ratio' = {}: expected a number in [1, 3]", expansion_ratio));
  }
  RequirePositive("y_plus", y_plus);
  if (!(reynolds >= 1e3) || !std::isfinite(reynolds)) {
    throw ConfigError(
        fmt::format("snappy option 'reynolds' = {}: expected a finite number >= 1000", reynolds));
  }
  if (!(wavelength >= 0) || !std::isfinite(wavelength)) {
    throw ConfigError(fmt::format(
        "snappy option 'wavelength' = {}: expected a finite length >= 0 (m; 0: no waves)",
        wavelength));
  }
  if (!(cells_per_wavelength >= 4 && cells_per_wavelength <= 100)) {
    throw ConfigError(
        fmt::format("snappy option 'cells_per_wavelength' = {}: expected a number in [4, 100]",
                    cells_per_wavelength));
  }
  if (!(feature_angle > 0 && feature_angle < 180)) {
    throw ConfigError(fmt::format(
        "snappy option 'feature_angle' = {}: expected degrees in (0, 180)", feature_angle));
  }
}

int SnappyLayerCount(const SnappyOptions& o, double length) {
  if (o.layers != SnappyOptions::kAutoLayers) return o.layers;
  const double first = FirstCellHeight(o.y_plus, o.reynolds, length);
  const double ratio = 0.5 * SnappyHullCell(o, length) / first;
  if (ratio <= 1.0) return 1;
  if (o.expansion_ratio <= 1.0 + 1e-9) return std::clamp(static_cast<int>(std::ceil(ratio)), 1, 50);
  return std::clamp(static_cast<int>(std::ceil(std::log(ratio) / std::log(o.expansion_ratio))) + 1,
                    1, 50);
}

int SnappyWakeLevel(const SnappyOptions& o, double length) {
  if (!(o.wavelength > 0)) return o.wake_level;
  const double base = length / o.base_cells_per_length,
               target = o.wavelength / o.cells_per_wavelength;
  const int level =
      std::max(o.wake_level, static_cast<int>(std::ceil(std::log2(base / target) - 1e-9)));
  if (level > o.hull_level) {
    throw ConfigError(fmt::format(
        "snappy option 'cells_per_wavelength' = {}: the free-surface cells (at most lambda / {} "
        "= {:.4g} m from base cells of {:.4g} m) need refinement level {}, above hull_level = "
        "{}; expected fewer cells per wavelength, or a higher hull_level or "
        "base_cells_per_length",
        o.cells_per_wavelength, o.cells_per_wavelength, target, base, level, o.hull_level));
  }
  return level;
}

double SnappyHullCell(const SnappyOptions& o, double length) { return SnappyLevelCell(o, length, o.hull_level); }

double SnappyFinalLayerRatio(const SnappyOptions& o, double length) {
  if (o.final_layer_ratio > 0) return o.final_layer_ratio;
  const int n = std::max(1, SnappyLayerCount(o, length));
  return FirstCellHeight(o.y_plus, o.reynolds, length) * std::pow(o.expansion_ratio, n - 1) /
         SnappyHullCell(o, length);
}

double SnappyFirstLayer(const SnappyOptions& o, double length) {
  const int n = std::max(1, SnappyLayerCount(o, length));
  return SnappyFinalLayerRatio(o, length) * SnappyHullCell(o, length) /
         std::pow(o.expansion_ratio, n - 1);
}

bool ReadSnappyLayerTable(const fs::path& log, const std::string& patch, double* layers,
                          double* thickness_percent) {
  std::ifstream in(log);
  bool found = false, in_table = false;
  for (std::string line; std::getline(in, line);) {
    // The final table follows the header "patch faces    layers   overall
    // thickness"; the one before layer addition says "avg thickness".
    if (line.find("overall thickness") != std::string::npos &&
        line.find("layers") != std::string::npos) {
      in_table = true;
      continue;
    }
    if (!in_table) continue;
    std::istringstream words(line);
    std::string name;
    long faces = 0;
    double n = 0, thickness = 0, percent = 0;
    if (words >> name && name == patch && words >> faces >> n >> thickness >> percent) {
      *layers = n;
      *thickness_percent = percent;
      found = true;
      in_table = false;
    }
  }
  return found;
}

std::vector<double> ReadSnappyFaceLayers(const fs::path& field, const std::string& patch, int faces) {
  std::ifstream in(field);
  if (!in) return {};
  std::stringstream buffer;
  buffer << in.rdbuf();
  const std::string text = buffer.str();
  auto fail = [&](const std::string& what) -> std::vector<double> {
    throw DataFileError(fmt::format("{}: {} (snappyHexMesh's per-face layer counts of patch '{}', {} faces)",
                                    field.string(), what, patch, faces));
  };
  const std::size_t boundary = text.find("boundaryField");
  if (boundary == std::string::npos) return fail("no boundaryField");
  // The patch entry: its name as a whole word followed by '{'.
  std::size_t at = boundary;
  for (;;) {
    at = text.find(patch, at + 1);
    if (at == std::string::npos) return fail("no entry for the patch");
    const std::size_t brace = text.find_first_not_of(" \t\r\n", at + patch.size());
    if (std::isspace(static_cast<unsigned char>(text[at - 1])) && brace != std::string::npos && text[brace] == '{')
      break;
  }
  const std::size_t value = text.find("value", at);
  if (value == std::string::npos) return fail("the patch entry has no value");
  std::istringstream words(text.substr(value + 5));
  std::string kind;
  words >> kind;
  if (kind == "uniform") {
    double n = 0;
    if (!(words >> n)) return fail("a uniform value that is not a number");
    return std::vector<double>(static_cast<std::size_t>(faces), n);
  }
  std::string type;
  long count = -1;
  char open = 0;
  if (kind != "nonuniform" || !(words >> type >> count >> open) || type != "List<scalar>" || open != '(')
    return fail("expected 'uniform <n>' or 'nonuniform List<scalar> <count> ( ... )'");
  if (count != faces) return fail(fmt::format("{} values, expected one per face", count));
  std::vector<double> layers(static_cast<std::size_t>(count));
  for (double& n : layers) {
    if (!(words >> n) || n < 0) return fail("a count that is not a non-negative number");
  }
  return layers;
}

void WriteSnappyCase(const TriangleSurface& hull, const SnappyOptions& o,
                     const fs::path& case_dir) {
  o.Validate();
  const Layout l = MakeLayout(hull, o);
  fs::create_directories(case_dir / "system");
  fs::create_directories(case_dir / "constant" / "triSurface");
  if (fs::exists(case_dir / "constant" / "polyMesh"))
    fs::remove_all(case_dir / "constant" / "polyMesh");
  WriteStl(hull, case_dir / "constant" / "triSurface" / "hull.stl");
  using data::WriteFileAtomically;

  WriteFileAtomically(
      case_dir / "system" / "controlDict",
      Header("controlDict") +
          "application snappyHexMesh;\nstartFrom startTime;\nstartTime 0;\nstopAt endTime;\n"
          "endTime 1;\ndeltaT 1;\nwriteControl timeStep;\nwriteInterval 1;\nwriteFormat ascii;\n"
          "writePrecision 12;\nwriteCompression off;\ntimeFormat general;\ntimePrecision 6;\n"
          "runTimeModifiable false;\n");
  WriteFileAtomically(
      case_dir / "system" / "fvSchemes",
      Header("fvSchemes") +
          "ddtSchemes { default steadyState; }\ngradSchemes { default Gauss linear; }\n"
          "divSchemes { default none; }\nlaplacianSchemes { default Gauss linear corrected; }\n"
          "interpolationSchemes { default linear; }\nsnGradSchemes { default corrected; }\n");
  WriteFileAtomically(case_dir / "system" / "fvSolution", Header("fvSolution"));

  // Background box: its top is the calm waterline z = 0.
  const Eigen::Vector3d& a = l.min;
  const Eigen::Vector3d& b = l.max;
  std::string bm = Header("blockMeshDict") + "scale 1;\nvertices\n(\n";
  const Eigen::Vector3d v[8] = {{a.x(), a.y(), a.z()}, {b.x(), a.y(), a.z()}, {b.x(), b.y(), a.z()},
                                {a.x(), b.y(), a.z()}, {a.x(), a.y(), b.z()}, {b.x(), a.y(), b.z()},
                                {b.x(), b.y(), b.z()}, {a.x(), b.y(), b.z()}};
  for (const auto& p : v) bm += "    " + Vec(p) + "\n";
  bm += fmt::format(
      ");\nblocks\n(\n    hex (0 1 2 3 4 5 6 7) ({} {} {}) simpleGrading (1 1 1)\n);\nedges "
      "();\nboundary\n(\n"
      "    freeSurface {{ type patch; faces ((4 5 6 7)); }}\n"
      "    inlet       {{ type patch; faces ((1 2 6 5)); }}\n"
      "    outlet      {{ type patch; faces ((0 4 7 3)); }}\n"
      "    side        {{ type patch; faces ((0 1 5 4) (3 7 6 2)); }}\n"
      "    bottom      {{ type patch; faces ((0 3 2 1)); }}\n);\nmergePatchPairs ();\n",
      l.cells[0], l.cells[1], l.cells[2]);
  WriteFileAtomically(case_dir / "system" / "blockMeshDict", bm);

  WriteFileAtomically(
      case_dir / "system" / "surfaceFeatureExtractDict",
      Header("surfaceFeatureExtractDict") +
          fmt::format("hull.stl\n{{\n    extractionMethod extractFromSurface;\n"
                      "    extractFromSurfaceCoeffs {{ includedAngle {:.6g}; }}\n"
                      "    subsetFeatures {{ nonManifoldEdges yes; openEdges yes; }}\n"
                      "    writeObj no;\n}}\n",
                      180.0 - o.feature_angle));

  const int wake_level = SnappyWakeLevel(o, l.length);
  const int near_level = o.near_level == SnappyOptions::kAutoLevel
                             ? (o.hull_level + wake_level + 1) / 2
                             : o.near_level;
  const int layers = SnappyLayerCount(o, l.length);
  std::string s = Header("snappyHexMeshDict");
  s += fmt::format("castellatedMesh true;\nsnap true;\naddLayers {};\n\n",
                   layers > 0 ? "true" : "false");
  s += "geometry\n{\n    hull.stl { type triSurfaceMesh; name hull; }\n";
  s += fmt::format("    nearHull {{ type searchableBox; min {}; max {}; }}\n", Vec(l.near_min),
                   Vec(l.near_max));
  s += fmt::format("    kelvinWake {{ type searchableBox; min {}; max {}; }}\n", Vec(l.wake_min),
                   Vec(l.wake_max));
  std::string box_levels;
  for (std::size_t i = 0; i < o.boxes.size(); ++i) {
    s += fmt::format("    userBox{} {{ type searchableBox; min {}; max {}; }}\n", i, Vec(o.boxes[i].min),
                     Vec(o.boxes[i].max));
    box_levels += fmt::format("        userBox{} {{ mode inside; levels ((1e15 {})); }}\n", i, o.boxes[i].level);
  }
  s += "}\n\n";
  s += fmt::format(
      "castellatedMeshControls\n{{\n    maxLocalCells 2000000;\n    maxGlobalCells 20000000;\n"
      "    minRefinementCells 0;\n    maxLoadUnbalance 0.10;\n    nCellsBetweenLevels 3;\n"
      "    features ( {{ file \"hull.eMesh\"; level {}; }} );\n"
      "    refinementSurfaces\n    {{\n        hull {{ level ({} {}); patchInfo {{ type wall; }} "
      "}}\n    }}\n"
      "    resolveFeatureAngle {:.6g};\n"
      "    refinementRegions\n    {{\n"
      "        nearHull {{ mode inside; levels ((1e15 {})); }}\n"
      "        kelvinWake {{ mode inside; levels ((1e15 {})); }}\n{}    }}\n"
      "    locationInMesh {};\n    allowFreeStandingZoneFaces true;\n}}\n\n",
      o.hull_level, o.hull_level, o.hull_level, o.feature_angle, near_level, wake_level, box_levels,
      Vec(l.inside));
  s += "snapControls\n{\n    nSmoothPatch 3;\n    tolerance 2.0;\n    nSolveIter 50;\n    "
       "nRelaxIter 5;\n"
       "    nFeatureSnapIter 10;\n    implicitFeatureSnap false;\n    explicitFeatureSnap true;\n"
       "    multiRegionFeatureSnap false;\n}\n\n";
  // Layers relative to the local cell size (final layer and minimum
  // thickness as fractions of it), extruded over every hull edge
  // (featureAngle 180) with smoothed surface normals and a lenient
  // thickness-to-medial-axis limit: on the DTC hull (level 5) this kept
  // 5.9 of 7 layers (89% of the thickness) where absolute sizes on the level
  // 4 grid kept 4.4 of 10.
  s += fmt::format(
      "addLayersControls\n{{\n    relativeSizes true;\n    layers {{ hull {{ nSurfaceLayers {}; "
      "}} }}\n"
      "    finalLayerThickness {:.6g};\n    expansionRatio {:.6g};\n    minThickness 0.05;\n"
      "    nGrow 0;\n"
      "    featureAngle 180;\n    slipFeatureAngle 30;\n    nRelaxIter 5;\n    "
      "nSmoothSurfaceNormals 3;\n"
      "    nSmoothNormals 3;\n    nSmoothThickness 10;\n    maxFaceThicknessRatio 0.5;\n"
      "    maxThicknessToMedialRatio 0.8;\n    minMedialAxisAngle 90;\n    nBufferCellsNoExtrude "
      "0;\n"
      "    nLayerIter 50;\n    nRelaxedIter 20;\n}}\n\n",
      std::max(layers, 1), SnappyFinalLayerRatio(o, l.length), o.expansion_ratio);
  // minTetQuality -1e30: the face-decomposition tet test guards OpenFOAM's
  // particle tracking, which kelvin does not use; kelvin's geometry is built
  // from face-centre pyramids (Mesh), which minVol keeps strictly positive.
  // With the tet test on (1e-15), the layer mover shrank the layers to
  // nothing wherever a snapped cell on the curved bow or stern failed it:
  // on the DTC it kept 84% of the layers over the hull area (grid 1); without it 97.6%.
  s += "meshQualityControls\n{\n    maxNonOrtho 65;\n    maxBoundarySkewness 20;\n    "
       "maxInternalSkewness 4;\n"
       "    maxConcave 80;\n    minVol 1e-13;\n    minTetQuality -1e30;\n    minArea -1;\n    "
       "minTwist 0.02;\n"
       "    minDeterminant 0.001;\n    minFaceWeight 0.05;\n    minVolRatio 0.01;\n    "
       "minTriangleTwist -1;\n"
       "    nSmoothScale 4;\n    errorReduction 0.75;\n    relaxed { maxNonOrtho 75; }\n}\n\n"
       "mergeTolerance 1e-6;\n"
       "writeFlags (layerFields);  // 0/nSurfaceLayers: the layers kept per face\n";
  WriteFileAtomically(case_dir / "system" / "snappyHexMeshDict", s);
}

namespace {

// The hull-area shares of the layers snappyHexMesh kept (SnappyRun).
void SummarizeFaceLayers(const Mesh& mesh, const fs::path& field, SnappyRun& r) {
  const int p = mesh.FindPatch("hull");
  if (p < 0 || r.layers <= 0) return;
  const Patch& patch = mesh.patches()[p];
  const std::vector<double> layers = ReadSnappyFaceLayers(field, "hull", patch.size);
  if (layers.empty()) return;
  double area = 0, weighted = 0, bare = 0;
  for (int i = 0; i < patch.size; ++i) {
    const double a = mesh.face_area_magnitudes()[patch.start + i];
    area += a;
    weighted += a * std::min(layers[i], static_cast<double>(r.layers));
    if (layers[i] < 0.5) bare += a;
  }
  r.layers_area_percent = 100.0 * weighted / (area * r.layers);
  r.area_without_layers_percent = 100.0 * bare / area;
}

}  // namespace

Mesh RunSnappy(const TriangleSurface& hull, const SnappyOptions& o, const fs::path& case_dir,
               SnappyRun* run) {
  WriteSnappyCase(hull, o, case_dir);
  SnappyRun r;
  r.seconds_block_mesh = RunTool(o, case_dir, "blockMesh");
  r.seconds_features = RunTool(o, case_dir, "surfaceFeatureExtract");
  r.seconds_snappy = RunTool(o, case_dir, "snappyHexMesh -overwrite");
  const double length = MakeLayout(hull, o).length;
  r.hull_cell = SnappyHullCell(o, length);
  r.first_layer_thickness = SnappyFirstLayer(o, length);
  r.final_layer_ratio = SnappyFinalLayerRatio(o, length);
  r.layers = SnappyLayerCount(o, length);
  r.wake_level = SnappyWakeLevel(o, length);
  r.wake_cell = SnappyLevelCell(o, length, r.wake_level);
  ReadSnappyLayerTable(case_dir / "log.snappyHexMesh", "hull", &r.layers_kept,
                       &r.thickness_kept_percent);
  Mesh mesh = ReadPolyMesh(case_dir / "constant" / "polyMesh");
  SummarizeFaceLayers(mesh, case_dir / "0" / "nSurfaceLayers", r);
  if (run) *run = r;
  return mesh;
}

}  // namespace kelvin::cfd
