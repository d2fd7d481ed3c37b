// Fully submerged bodies under the linearized free surface (issue #25,
// acceptance 5).
//
// Unit part (label unit): the analytic spheroid surface is closed with
// outward normals and the volume of the spheroid; the hull check refuses a
// body entirely below z = 0 unless the caller allows it, and then only a
// closed one; the snappy layout of a submerged body reaches the stated
// numbers of wavelengths and refines the free surface to the asked cells
// per wavelength; the mesh case's spheroid and waves keys, and their errors;
// the linear-theory wave resistance of a spheroid tends to Havelock's sphere.
//
// Run part (SubmergedSpheroidRun, label validation, about 2-3 minutes):
// `kelvin mesh` on data/cases/resistance/spheroid_mesh.yaml (snappyHexMesh),
// then `kelvin run` on spheroid_double_body.yaml and spheroid_fn050.yaml:
// the 5:1 spheroid L = 1 m, axis 0.25 m deep, Fn 0.5, under the linearized
// free surface to the steady criterion on the drag and eta. Checks:
// - the grid: the hull patch encloses the spheroid's volume within 3% (the
//   snapped surface of a coarse grid, 8 cells across the diameter);
// - both runs meet the steady criterion;
// - the centreline elevation is a trough over the body followed by a crest
//   (the flow speeds up over the body and the pressure, hence eta = p / rho g,
//   falls there), then a transverse wave train whose wavelength, from the
//   zero crossings between the body and the beach, is 2 pi U^2 / g within
//   7.5%: the discretization's phase error lengthens the wave by +4.5% at 12
//   and +3.3% at 16 faces per wavelength (measured on the Wigley pattern,
//   hull_kelvin_pattern_test.cc; this grid has 15.7), plus about 3% for
//   locating the crossings with linear interpolation on faces lambda / 15.7
//   wide over about two wavelengths;
// - no waves ahead: from a quarter wavelength ahead of the body, |eta| stays
//   below a quarter of the largest elevation behind it;
// - C_W = C_P - C_P(double body) > 0. It is printed against the linear
//   theory of the same problem (Neumann-Kelvin: the free-surface condition
//   linearized about the uniform stream, as LinearizedFreeSurface does):
//   the spheroid as its exact double-body singularities, a line of sources
//   of linearly varying strength between the foci, in Kelvin's wave
//   resistance integral for submerged sources (Havelock 1917, sphere as a
//   doublet; Havelock 1931, "The wave resistance of a spheroid", Proc. R.
//   Soc. Lond. A 131, 275-285). That theory leaves out the image of the body
//   in the free surface and viscosity, and this grid is coarse (the double
//   body's C_P, 2.7e-3, is mostly numerical), so the ratio is reported and
//   only checked to within a factor of two, a gross check of the level and
//   sign (measured 2026-12-02: R_W 4.06 N against 3.92 N, ratio 1.04, on
//   this single grid; no grid study).
// Set KELVIN_SUBMERGED_KEEP=dir to keep the grid and the runs.
#include <fmt/format.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <numbers>
#include <string>
#include <vector>

#include "cfd/geometry/hydrostatics.h"
#include "cfd/geometry/spheroid_surface.h"
#include "cfd/grid/mesh_case.h"
#include "cfd/grid/snappy_mesher.h"
#include "cfd/verification/steady_waves.h"
#include "data/schema/errors.h"
#include "data/schema/h5_file.h"
#include "tests/cfd/freesurface/resistance_cases.h"
#include "tests/test_utilities/test_utilities.h"

namespace kelvin::cfd {
namespace {

namespace fs = std::filesystem;
using kelvin::testing::ReadText;
using ::testing::HasSubstr;

constexpr double kPi = std::numbers::pi;
constexpr double kG = 9.81;

// The body of data/cases/resistance/spheroid_mesh.yaml.
constexpr SpheroidShape kSpheroid{1.0, 0.2, 0.25};

double SpheroidVolume(const SpheroidShape& s) {
  return kPi / 6.0 * s.length * s.diameter * s.diameter;
}

// Linear-theory (Neumann-Kelvin, deep water) wave resistance of a prolate
// spheroid moving along its axis at depth f, as its double-body
// singularities: sources of volume flux q(xi) = k xi per unit length between
// the foci +-c, whose dipole moment 2 k c^3 / 3 is the body's U (V + m11 /
// rho) = U 2 V / (2 - alpha0) (Lamb, Hydrodynamics, section 373), in the
// Kelvin integral for submerged sources
//   R = (rho k0^2 / pi) int_0^{pi/2} |A(theta)|^2 exp(-2 k0 f sec^2) sec^3 dtheta,
//   A = int q(xi) exp(i k0 xi sec theta) dxi,  k0 = g / U^2,
// (Michell's integral for a point source). A sphere (c -> 0) gives Havelock's
// R = 4 pi rho g k0^3 a^6 int sec^5 exp(-2 k0 f sec^2) dtheta.
double LinearWaveResistance(const SpheroidShape& s, double U, double rho) {
  const double a = 0.5 * s.length, b = 0.5 * s.diameter, k0 = kG / (U * U);
  const double volume = SpheroidVolume(s);
  double c = 0.0, alpha0 = 2.0 / 3.0;  // the sphere's
  if (a > b * (1 + 1e-12)) {
    const double e = std::sqrt(1.0 - b * b / (a * a));
    c = a * e;
    alpha0 = 2.0 * (1.0 - e * e) / (e * e * e) * (0.5 * std::log((1.0 + e) / (1.0 - e)) - e);
  }
  const double moment = U * 2.0 * volume / (2.0 - alpha0);
  const auto amplitude = [&](double p) {  // |A| at wavenumber p along x
    if (p * c < 1e-4) return p * moment;
    const double k = 3.0 * moment / (2.0 * c * c * c);
    return 2.0 * k * std::abs(std::sin(p * c) / (p * p) - c * std::cos(p * c) / p);
  };
  // theta -> t = tan(theta): sec^3 dtheta = sqrt(1 + t^2) dt; cut where the
  // exponential is e^-40.
  const double t_max = std::sqrt(20.0 / (k0 * s.depth));
  std::vector<double> x, w;
  GaussLegendre(400, x, w);
  double sum = 0.0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    const double t = 0.5 * t_max * (x[i] + 1.0), sec2 = 1.0 + t * t;
    const double A = amplitude(k0 * std::sqrt(sec2));
    sum += 0.5 * t_max * w[i] * A * A * std::exp(-2.0 * k0 * s.depth * sec2) * std::sqrt(sec2);
  }
  return rho * k0 * k0 / kPi * sum;
}

std::string ErrorOf(const std::function<void()>& f) {
  try {
    f();
  } catch (const std::exception& e) {
    return e.what();
  }
  return "(no error)";
}

// ------------------------------------------------------------- unit part

TEST(SubmergedBody, SpheroidSurfaceIsClosedOutwardAndHasTheSpheroidVolume) {
  TriangleSurface s = SpheroidSurface(kSpheroid);
  const SurfaceCheck c = CheckSurface(s, 0.0);
  EXPECT_EQ(c.open_edges, 0u);
  EXPECT_EQ(c.non_manifold_edges, 0u);
  EXPECT_EQ(c.inconsistent_edges, 0u);
  EXPECT_EQ(c.degenerate_triangles, 0u);
  // The inscribed polyhedron of 64 rings x 64 segments: the 64-gon alone
  // holds (64 / 2 pi) sin(2 pi / 64) = 99.84% of the circle's area.
  EXPECT_GT(c.underwater_volume, 0.0) << "normals point inward";
  EXPECT_NEAR(c.underwater_volume / SpheroidVolume(kSpheroid), 1.0, 5e-3);
  EXPECT_NEAR(s.Min().x(), 0.0, 1e-12);
  EXPECT_NEAR(s.Max().x(), 1.0, 1e-12);
  EXPECT_NEAR(s.Max().z(), -0.15, 1e-12);
  EXPECT_THAT(ErrorOf([] {
                SpheroidSurface({1.0, 0.2, 0.05});
              }),
              HasSubstr("spheroid 'depth' = 0.05: expected more than half the diameter"));
  EXPECT_THAT(ErrorOf([] {
                SpheroidSurface({1.0, 2.0, 5.0});
              }),
              HasSubstr("spheroid 'diameter' = 2: expected at most the length"));
}

TEST(SubmergedBody, HullCheckRefusesASubmergedBodyUnlessAllowedAndThenOnlyAClosedOne) {
  TriangleSurface s = SpheroidSurface(kSpheroid);
  s.source = "deep.stl";
  EXPECT_THAT(ErrorOf([&] { ValidateHull(s, 0.0); }),
              HasSubstr("deep.stl: the hull lies entirely below the waterline (highest z = -0.15 "
                        "<= waterline z = "
                        "0); expected a surface-piercing hull"));
  EXPECT_THAT(ErrorOf([&] { ValidateHull(s, 0.0); }), HasSubstr("geometry.submerged: true"));
  const SurfaceCheck c = ValidateHull(s, 0.0, true);
  EXPECT_FALSE(c.flipped);
  // Inward normals are flipped, as for a ship hull.
  TriangleSurface inward = s;
  for (auto& t : inward.triangles) std::swap(t[1], t[2]);
  EXPECT_TRUE(ValidateHull(inward, 0.0, true).flipped);
  EXPECT_GT(UnderwaterVolume(inward), 0.0);
  // A hole anywhere is refused: a submerged body has no deck to leave open.
  s.triangles.erase(s.triangles.begin() + 100);
  EXPECT_THAT(
      ErrorOf([&] { ValidateHull(s, 0.0, true); }),
      HasSubstr("deep.stl: 3 open edges on a fully submerged body; expected a closed surface"));
}

// A ship file for the spheroid written as an STL (file axes = ship axes).
fs::path WriteSpheroidShip(const fs::path& dir, const std::string& extra_geometry) {
  WriteStl(SpheroidSurface(kSpheroid), dir / "body.stl");
  std::ofstream(dir / "body.yaml")
      << "ship: {name: body}\nprincipal: {Lpp: 1.0, B: 0.2, d: 0.35}\n"
         "geometry: {file: body.stl, length_unit: 1.0, waterline_z: 0.0"
      << extra_geometry << "}\n";
  return dir / "body.yaml";
}

TEST(SubmergedBody, ShipFileSaysSubmergedOrTheBodyIsRefused) {
  kelvin::testing::ScopedTempDir dir;
  EXPECT_THAT(ErrorOf([&] { LoadHull(LoadHullPlacement(WriteSpheroidShip(dir.path(), ""))); }),
              HasSubstr("body.stl: the hull lies entirely below the waterline"));
  const HullPlacement p = LoadHullPlacement(WriteSpheroidShip(dir.path(), ", submerged: true"));
  EXPECT_TRUE(p.submerged);
  const TriangleSurface s = LoadHull(p);
  // The surface as written (binary STL: single-precision vertices).
  EXPECT_NEAR(UnderwaterVolume(s) / UnderwaterVolume(SpheroidSurface(kSpheroid)), 1.0, 1e-6);
  // No waterline: no waterplane and no centre of flotation.
  const Hydrostatics h = ComputeHydrostatics(s, 1.0, 0.2, 0.35);
  EXPECT_EQ(h.waterplane_area, 0.0);
  EXPECT_EQ(h.lcf, 0.0);
  EXPECT_NEAR(h.lcb, 0.5, 1e-6);
  EXPECT_NEAR(h.draft, 0.35, 1e-6);
  // The structured grid cannot take it: an error before any meshing.
  const std::string text = fmt::format(
      "mesh:\n  method: structured\n  hull: {{ship: {}}}\n  flow: {{reynolds: 1.0e6}}\noutput: "
      "{{directory: "
      "{}}}\n",
      (dir / "body.yaml").string(), (dir / "out").string());
  const MeshCase c = ParseMeshCase(text, "case.yaml", dir.path());
  EXPECT_THAT(ErrorOf([&] { RunMeshCase(c, 1); }),
              HasSubstr("mesh.method 'structured' with the fully submerged body"));
}

TEST(SubmergedBody, SnappyLayoutIsSizedByTheWavelength) {
  kelvin::testing::ScopedTempDir dir;
  SnappyOptions o;
  o.base_cells_per_length = 5;
  o.hull_level = 3;
  o.wake_level = 1;
  o.layers = 2;
  const double lambda = 2.0 * kPi * 0.25;  // Fn 0.5 on L = 1 m
  o.wavelength = lambda;
  o.cells_per_wavelength = 15;
  // Base cells 0.2 m: level 1 gives 0.1 m = lambda / 15.7.
  EXPECT_EQ(SnappyWakeLevel(o, 1.0), 1);
  WriteSnappyCase(SpheroidSurface(kSpheroid), o, dir.path());
  const std::string block = ReadText(dir / "system/blockMeshDict");
  // 3 lambda behind the aft end, 1 lambda ahead of the nose, 1.5 lambda to
  // the sides; 1 L deep (more than lambda / 2); top on z = 0.
  EXPECT_THAT(block,
              HasSubstr(fmt::format("({:.9g} {:.9g} {:.9g})", -3 * lambda, -1.5 * lambda, -1.0)));
  EXPECT_THAT(block,
              HasSubstr(fmt::format("({:.9g} {:.9g} {:.9g})", 1.0 + lambda, 1.5 * lambda, 0.0)));
  EXPECT_THAT(block, HasSubstr("freeSurface"));
  const std::string snappy = ReadText(dir / "system/snappyHexMeshDict");
  EXPECT_THAT(snappy, HasSubstr("kelvinWake { mode inside; levels ((1e15 1)); }"));
  // The wedge box reaches the outlet and lambda / 6 deep; the near box
  // spans the body up to z = 0.
  EXPECT_THAT(snappy, HasSubstr(fmt::format("kelvinWake {{ type searchableBox; min ({:.9g} ",
                                            -3 * lambda)));
  EXPECT_THAT(snappy, HasSubstr(fmt::format(" {:.9g}); max (1.1 ", -lambda / 6)));
  EXPECT_THAT(
      snappy,
      HasSubstr("nearHull { type searchableBox; min (-0.1 -0.15 -0.4); max (1.05 0.15 0);"));
  // Asking for 30 cells per wavelength needs level 2; 100 needs level 4,
  // above the hull level: refused, naming the key.
  o.cells_per_wavelength = 30;
  EXPECT_EQ(SnappyWakeLevel(o, 1.0), 2);
  o.cells_per_wavelength = 100;
  EXPECT_THAT(ErrorOf([&] { SnappyWakeLevel(o, 1.0); }),
              HasSubstr("snappy option 'cells_per_wavelength' = 100: the free-surface cells"));
  // Without waves the layout is the ship layout (lengths only).
  o.wavelength = 0;
  EXPECT_EQ(SnappyWakeLevel(o, 1.0), 1);
}

MeshCase Parse(const std::string& mesh_body) {
  const std::string text = "mesh:\n" + mesh_body + "output: {directory: out}\n";
  return ParseMeshCase(text, "case.yaml", kelvin::testing::SourceDir() / "data" / "cases" / "mesh");
}

TEST(SubmergedBody, MeshCaseNamesASpheroidAndSizesTheSnappyDomainByTheWaves) {
  const MeshCase c = Parse(
      "  method: snappy\n  hull: {spheroid: {length: 1.0, diameter: 0.2, depth: 0.25}}\n"
      "  flow: {speed: 1.566, viscosity: 1.0e-6}\n  waves: {froude: 0.5, cells_per_wavelength: "
      "15}\n");
  EXPECT_TRUE(c.spheroid);
  EXPECT_DOUBLE_EQ(HullLength(c), 1.0);
  EXPECT_NEAR(c.reynolds, 1.566e6, 1.0);
  EXPECT_NEAR(c.snappy.wavelength, 2.0 * kPi * 0.25, 1e-12);
  EXPECT_EQ(c.snappy.cells_per_wavelength, 15.0);
  EXPECT_THAT(
      ErrorOf([] {
        Parse(
            "  method: structured\n  hull: {spheroid: {length: 1.0, diameter: 0.2, depth: 0.25}}\n"
            "  flow: {reynolds: 1.0e6}\n");
      }),
      HasSubstr("key 'mesh.method' = 'structured': expected 'snappy' for a submerged spheroid"));
  EXPECT_THAT(
      ErrorOf([] {
        Parse(
            "  method: snappy\n  hull: {spheroid: {length: 1.0, diameter: 0.2, depth: 0.05}}\n"
            "  flow: {reynolds: 1.0e6}\n");
      }),
      HasSubstr("key 'mesh.hull.spheroid.depth' = '0.05': expected more than half the diameter"));
  EXPECT_THAT(ErrorOf([] {
                Parse(
                    "  method: snappy\n  hull: {spheroid: {length: 1, diameter: 0.2, depth: 0.25}, "
                    "ship: x}\n"
                    "  flow: {reynolds: 1.0e6}\n");
              }),
              HasSubstr("expected exactly one of 'wigley' (the formula), 'spheroid'"));
}

TEST(SubmergedBody, LinearWaveResistanceOfANearSphereIsHavelocksSphere) {
  const double U = 1.0, rho = 1000.0, a = 0.1, f = 0.25, k0 = kG / (U * U);
  // Havelock's sphere, by a plain midpoint rule in theta.
  double sum = 0.0;
  const int n = 20000;
  for (int i = 0; i < n; ++i) {
    const double th = 0.5 * kPi * (i + 0.5) / n, sec = 1.0 / std::cos(th);
    sum += 0.5 * kPi / n * std::pow(sec, 5) * std::exp(-2.0 * k0 * f * sec * sec);
  }
  const double sphere = 4.0 * kPi * rho * kG * std::pow(k0, 3) * std::pow(a, 6) * sum;
  EXPECT_NEAR(LinearWaveResistance({2 * a, 2 * a, f}, U, rho) / sphere, 1.0, 1e-6);
  // The line of sources of a nearly spherical spheroid (eccentricity 0.01)
  // acts as the sphere's doublet.
  EXPECT_NEAR(LinearWaveResistance({2 * a, 2 * a * std::sqrt(1 - 1e-4), f}, U, rho) / sphere, 1.0,
              1e-3);
  // The resistance falls with depth at least as exp(-2 k0 f).
  EXPECT_LT(LinearWaveResistance({1.0, 0.2, 0.5}, 1.566, rho),
            LinearWaveResistance({1.0, 0.2, 0.25}, 1.566, rho) *
                std::exp(-2.0 * k0 * 0.25 / (1.566 * 1.566)));
}

// -------------------------------------------------------------- run part

struct CentreLine {
  std::vector<double> x, eta;  // along the wave cut y = 0, x increasing
};

CentreLine ReadCut(const data::H5Reader& r) {
  CentreLine c;
  const std::vector<double> x = r.Read("wave_cuts/cut0/x").values,
                            eta = r.Read("wave_cuts/cut0/eta").values;
  for (std::size_t i = 0; i < x.size(); ++i) {
    if (std::isfinite(eta[i])) {
      c.x.push_back(x[i]);
      c.eta.push_back(eta[i]);
    }
  }
  return c;
}

TEST(SubmergedSpheroidRun, MeshesAndRunsToASteadyFreeSurfaceResult) {
  const kelvin::testing::ResistanceCases cases("KELVIN_SUBMERGED_KEEP");
  const fs::path grid = cases.Grid("spheroid_mesh.yaml", "spheroid_fn050");
  const std::string quality = ReadText(grid / "quality.txt");
  std::printf("%s\n", quality.c_str());
  EXPECT_THAT(quality, HasSubstr("negative or zero volumes: none"));
  const std::string tag = "hull patch volume (below z = 0): ";
  const std::size_t at = quality.find(tag);
  ASSERT_NE(at, std::string::npos);
  const double volume = std::stod(quality.substr(at + tag.size()));
  EXPECT_NEAR(volume / SpheroidVolume(kSpheroid), 1.0, 0.03) << "hull patch volume " << volume;

  const fs::path db = cases.Run("spheroid_double_body", grid, "spheroid_fn050");
  const fs::path h5 = cases.Run("spheroid_fn050", grid, "spheroid_fn050");
  ASSERT_TRUE(fs::exists(db) && fs::exists(h5));
  const data::H5Reader r(h5);
  EXPECT_EQ(data::H5Reader(db).Read("converged").at(0), 1.0) << "double body";
  EXPECT_EQ(r.Read("converged").at(0), 1.0) << "free surface";
  const double U = r.Read("speed").at(0), rho = r.Read("rho").at(0);
  const double lambda = 2.0 * kPi * U * U / kG;
  const double L = kSpheroid.length;

  // The centreline: trough over the body, crest behind it, then waves.
  const CentreLine c = ReadCut(r);
  ASSERT_GT(c.x.size(), 100u);
  const auto trough = std::min_element(c.eta.begin(), c.eta.end());
  const double x_trough = c.x[trough - c.eta.begin()];
  const auto crest = std::max_element(c.eta.begin(), trough);  // behind it (x smaller)
  const double x_crest = c.x[crest - c.eta.begin()];
  std::printf(
      "centreline: trough %.4f m at x = %.3f m, crest %.4f m at x = %.3f m (body from 0 to %.1f "
      "m)\n",
      *trough, x_trough, *crest, x_crest, L);
  EXPECT_LT(*trough, 0.0);
  EXPECT_GT(x_trough, -0.5 * lambda);
  EXPECT_LT(x_trough, L);
  EXPECT_GT(*crest, 0.0);
  EXPECT_GT(x_crest, x_trough - lambda);

  // Wavelength: zero crossings from the trough back to the beach.
  const std::vector<double> damping = r.Read("surface/damping").values,
                            sx = r.Read("surface/x").values, sy = r.Read("surface/y").values;
  double beach = -1e300;  // where the outlet beach starts on the centreline
  for (std::size_t i = 0; i < sx.size(); ++i) {
    if (damping[i] > 0.0 && sx[i] < 0.0 && std::abs(sy[i]) < 0.125 * lambda)
      beach = std::max(beach, sx[i]);
  }
  std::vector<double> crossings;
  for (std::size_t i = 0; i + 1 < c.x.size(); ++i) {
    const double x0 = c.x[i], x1 = c.x[i + 1], e0 = c.eta[i], e1 = c.eta[i + 1];
    if (x0 > beach && x1 < x_trough && e0 * e1 < 0.0)
      crossings.push_back(x0 + (x1 - x0) * e0 / (e0 - e1));
  }
  ASSERT_GE(crossings.size(), 3u) << "beach starts at x = " << beach;
  const double measured =
      2.0 * (crossings.back() - crossings.front()) / static_cast<double>(crossings.size() - 1);
  std::printf(
      "transverse wavelength %.4f m from %zu crossings between x = %.3f and %.3f m: %+.2f%% "
      "against "
      "2 pi U^2/g = %.4f m\n",
      measured, crossings.size(), crossings.front(), crossings.back(),
      100 * (measured / lambda - 1), lambda);
  EXPECT_NEAR(measured / lambda, 1.0, 0.075);

  // No waves ahead of the body.
  double peak = 0.0, upstream = 0.0;
  const double inlet = c.x.back();
  for (std::size_t i = 0; i < c.x.size(); ++i) {
    if (c.x[i] < L && c.x[i] > beach) peak = std::max(peak, std::abs(c.eta[i]));
    if (c.x[i] > L + 0.25 * lambda && c.x[i] < inlet)
      upstream = std::max(upstream, std::abs(c.eta[i]));
  }
  std::printf(
      "upstream (from lambda/4 ahead of the nose) max |eta| %.5f m = %.3f of the peak %.4f m "
      "behind\n",
      upstream, upstream / peak, peak);
  EXPECT_LT(upstream, 0.25 * peak);

  // Wave resistance.
  const double cw = r.Read("C_W").at(0), rw = r.Read("R_W").at(0);
  const double theory = LinearWaveResistance(kSpheroid, U, rho);
  const double q = 0.5 * rho * r.Read("wetted_area").at(0) * U * U;
  std::printf(
      "C_W = C_P - C_P(double body) = %.4e (R_W %.4f N); linear theory (Havelock's line sources, "
      "Neumann-Kelvin) R_W %.4f N, C_W %.4e: ratio %.3f. C_T %.4e, C_F %.4e, C_P %.4e, double body "
      "C_P "
      "%.4e; eta %.4f to %.4f m\n",
      cw, rw, theory, theory / q, rw / theory, r.Read("C_T").at(0), r.Read("C_F").at(0),
      r.Read("C_P").at(0), r.Read("C_P_double_body").at(0), r.Read("eta_min").at(0),
      r.Read("eta_max").at(0));
  EXPECT_GT(cw, 0.0);
  // A gross check only (a wrong free-surface level or sign would miss it by
  // far): within a factor of two of the linear theory.
  EXPECT_GT(rw / theory, 0.5);
  EXPECT_LT(rw / theory, 2.0);
}

}  // namespace
}  // namespace kelvin::cfd
