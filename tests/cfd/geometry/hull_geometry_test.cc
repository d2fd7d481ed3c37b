// Hull surfaces and hydrostatics: the Wigley hull against its exact
// integrals, file formats (binary/ASCII/gzip STL, OBJ polygons), the DTC hull
// of Debian's openfoam-examples against its published particulars, and every
// bad-input path of the readers and hull checks.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <zlib.h>
#include <fmt/format.h>

#include <cmath>
#include <fstream>
#include <functional>
#include <set>

#include "cfd/geometry/hydrostatics.h"
#include "cfd/geometry/triangle_surface.h"
#include "data/schema/errors.h"
#include "tests/test_utilities/test_utilities.h"

namespace kelvin::cfd {
namespace {

using kelvin::testing::ScopedTempDir;
using ::testing::HasSubstr;

constexpr double kL = 4.0, kB = 0.4, kT = 0.25;

TriangleSurface Wigley(int nx = 240, int nz = 60) { return WigleySurface(kL, kB, kT, 0.5 * kT, nx, nz); }

// Wetted area of the exact Wigley surface below z = 0 by Gauss-Legendre
// quadrature of sqrt(1 + y_x^2 + y_z^2) over both sides.
double ExactWigleyWettedArea() {
  const double g[5] = {-0.9061798459386640, -0.5384693101056831, 0.0, 0.5384693101056831, 0.9061798459386640};
  const double w[5] = {0.2369268850561891, 0.4786286704993665, 0.5688888888888889, 0.4786286704993665,
                       0.2369268850561891};
  const int n = 400;
  double area = 0;
  for (int i = 0; i < n; ++i) {
    for (int k = 0; k < n; ++k) {
      for (int a = 0; a < 5; ++a) {
        for (int b = 0; b < 5; ++b) {
          const double x = kL * (i + 0.5 + 0.5 * g[a]) / n;
          const double z = -kT * (k + 0.5 + 0.5 * g[b]) / n;
          const double xi = 2 * (x - 0.5 * kL) / kL, zeta = z / kT;
          const double yx = 0.5 * kB * (-2 * xi * 2 / kL) * (1 - zeta * zeta);
          const double yz = 0.5 * kB * (1 - xi * xi) * (-2 * zeta / kT);
          area += 2 * std::sqrt(1 + yx * yx + yz * yz) * w[a] * w[b] * 0.25 * (kL / n) * (kT / n);
        }
      }
    }
  }
  return area;
}

TEST(WigleyHydrostaticsTest, MatchesExactIntegralsWithin0p1Percent) {
  TriangleSurface s = Wigley();
  const SurfaceCheck c = ValidateHull(s, 0.0);
  EXPECT_EQ(c.open_edges, 0u) << c.Summary();
  EXPECT_EQ(c.non_manifold_edges, 0u) << c.Summary();
  EXPECT_FALSE(c.flipped);
  const Hydrostatics h = ComputeHydrostatics(s, kL, kB, kT);
  // Exact: V = 4/9 L B T, A_wp = 2/3 L B, A_M = 2/3 B T, LCB = LCF = L/2.
  EXPECT_NEAR(h.volume / (4.0 / 9.0 * kL * kB * kT), 1.0, 1e-3);
  EXPECT_NEAR(h.Cb, 4.0 / 9.0, 4.0 / 9.0 * 1e-3);
  EXPECT_NEAR(h.waterplane_area / (2.0 / 3.0 * kL * kB), 1.0, 1e-3);
  EXPECT_NEAR(h.Cm, 2.0 / 3.0, 2.0 / 3.0 * 1e-3);
  // The triangulation's diagonals are not fore-aft symmetric, so the centres
  // carry an O(h^2) discretization error like the other integrals.
  EXPECT_NEAR(h.lcb, 0.5 * kL, 1e-3 * kL);
  EXPECT_NEAR(h.lcf, 0.5 * kL, 1e-3 * kL);
  EXPECT_NEAR(h.draft, kT, 1e-12);
  EXPECT_NEAR(h.wetted_area / ExactWigleyWettedArea(), 1.0, 1e-3);
  // Sectional area curve: A(x) = (2/3) B T (1 - (2x/L - 1)^2).
  for (const auto& [x, a] : h.sectional_areas) {
    const double xi = 2 * x / kL - 1;
    EXPECT_NEAR(a, 2.0 / 3.0 * kB * kT * (1 - xi * xi), 2e-3 * kB * kT) << "x = " << x;
  }
}

TEST(WigleyHydrostaticsTest, ConvergesAtSecondOrder) {
  // Halving the panel size cuts the volume error by about four.
  const double exact = 4.0 / 9.0 * kL * kB * kT;
  const double e1 = std::abs(ComputeHydrostatics(Wigley(40, 10), kL, kB, kT).volume - exact);
  const double e2 = std::abs(ComputeHydrostatics(Wigley(80, 20), kL, kB, kT).volume - exact);
  EXPECT_NEAR(std::log2(e1 / e2), 2.0, 0.15);
}

TEST(SurfaceFormatsTest, BinaryAsciiGzipAndObjAgree) {
  ScopedTempDir dir;
  const TriangleSurface s = Wigley(60, 16);
  const double v0 = UnderwaterVolume(s);
  std::set<int> used;
  for (const auto& t : s.triangles) used.insert(t.begin(), t.end());
  // Binary STL (float precision).
  WriteStl(s, dir / "w.stl");
  const TriangleSurface b = ReadSurface(dir / "w.stl");
  EXPECT_EQ(b.triangles.size(), s.triangles.size());
  EXPECT_EQ(b.vertices.size(), used.size());  // shared vertices welded
  EXPECT_NEAR(UnderwaterVolume(b), v0, 1e-6 * v0);
  // ASCII STL, gzip-compressed.
  {
    gzFile gz = gzopen((dir / "w.stl.gz").c_str(), "wb");
    gzprintf(gz, "solid wigley\n");
    for (const auto& t : s.triangles) {
      gzprintf(gz, " facet normal 0 0 0\n  outer loop\n");
      for (int c = 0; c < 3; ++c) {
        const auto& p = s.vertices[t[c]];
        gzprintf(gz, "   vertex %.17g %.17g %.17g\n", p.x(), p.y(), p.z());
      }
      gzprintf(gz, "  endloop\n endfacet\n");
    }
    gzprintf(gz, "endsolid wigley\n");
    gzclose(gz);
  }
  const TriangleSurface a = ReadSurface(dir / "w.stl.gz");
  EXPECT_EQ(a.vertices.size(), used.size());
  EXPECT_NEAR(UnderwaterVolume(a), v0, 1e-12 * v0);
  // OBJ with quadrilateral faces (relative and slash-separated indices).
  {
    std::ofstream obj(dir / "box.obj");
    obj << "# unit box, 0.5 below the waterline\n";
    obj << "v 0 0 -0.5\nv 1 0 -0.5\nv 1 1 -0.5\nv 0 1 -0.5\nv 0 0 0.5\nv 1 0 0.5\nv 1 1 0.5\nv 0 1 0.5\n";
    obj << "f 1 4 3 2\nf 5/1 6/1 7/1 8/1\nf 1 2 6 5\nf 2 3 7 6\nf 3 4 8 7\nf -8 -4 -1 -5\n";
  }
  TriangleSurface box = ReadSurface(dir / "box.obj");
  EXPECT_EQ(box.triangles.size(), 12u);
  ValidateHull(box, 0.0);
  EXPECT_NEAR(UnderwaterVolume(box), 0.5, 1e-15);
  EXPECT_NEAR(ComputeHydrostatics(box, 1, 1, 0.5).wetted_area, 3.0, 1e-15);
}

TEST(HullCheckTest, InwardNormalsAreFlippedAndRudderJunctionTolerated) {
  TriangleSurface s = Wigley(40, 10);
  for (auto& t : s.triangles) std::swap(t[1], t[2]);
  // A fin hanging from the keel: shares a keel edge with both hull sides
  // (a non-manifold junction, as a rudder joined to the hull).
  const auto& keel = s.triangles[0];
  int k0 = -1, k1 = -1;
  for (std::size_t t = 0; t < s.triangles.size() && k0 < 0; ++t) {
    for (int e = 0; e < 3; ++e) {
      const int a = s.triangles[t][e], b = s.triangles[t][(e + 1) % 3];
      if (s.vertices[a].z() == -kT && s.vertices[b].z() == -kT) {
        k0 = a;
        k1 = b;
        break;
      }
    }
  }
  (void)keel;
  ASSERT_GE(k0, 0);
  const int tip = static_cast<int>(s.vertices.size());
  s.vertices.push_back(0.5 * (s.vertices[k0] + s.vertices[k1]) - Eigen::Vector3d(0, 0, 0.05));
  s.triangles.push_back({k0, k1, tip});
  s.triangles.push_back({k1, k0, tip});
  const SurfaceCheck c = ValidateHull(s, 0.0);
  EXPECT_TRUE(c.flipped);
  EXPECT_GT(c.underwater_volume, 0.0);
  EXPECT_EQ(c.non_manifold_edges, 1u) << c.Summary();
  EXPECT_GT(UnderwaterVolume(s), 0.0);
}

// ------------------------------------------------------------ bad input

std::string ErrorOf(const std::function<void()>& f) {
  try {
    f();
  } catch (const DataFileError& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(BadSurfaceTest, TruncatedBinaryStl) {
  ScopedTempDir dir;
  const TriangleSurface s = Wigley(10, 4);
  WriteStl(s, dir / "w.stl");
  const std::size_t size = 84 + 50 * s.triangles.size();
  ASSERT_EQ(std::filesystem::file_size(dir / "w.stl"), size);
  std::filesystem::resize_file(dir / "w.stl", size - 20);
  EXPECT_THAT(ErrorOf([&] { ReadSurface(dir / "w.stl"); }),
              HasSubstr(fmt::format("binary STL declares {} triangles, which needs {} bytes, but the file has {} bytes",
                                    s.triangles.size(), size, size - 20)));
}

// A ship file's hull path that names a directory: before, the file size
// query threw a bare filesystem error.
TEST(BadSurfaceTest, DirectoryIsRefusedByName) {
  ScopedTempDir dir;
  std::filesystem::create_directory(dir / "hull.stl");
  EXPECT_THAT(ErrorOf([&] { ReadSurface(dir / "hull.stl"); }), HasSubstr("hull.stl: is a directory; expected a surface file"));
}

TEST(BadSurfaceTest, NanVertex) {
  ScopedTempDir dir;
  std::ofstream(dir / "nan.stl") << "solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 nan 0\n"
                                    "vertex 0 1 0\nendloop\nendfacet\nendsolid x\n";
  EXPECT_THAT(ErrorOf([&] { ReadSurface(dir / "nan.stl"); }),
              HasSubstr("nan.stl: triangle 0 vertex 1 has a non-finite coordinate"));
}

TEST(BadSurfaceTest, ZeroTriangles) {
  ScopedTempDir dir;
  std::ofstream(dir / "empty.stl") << "solid x\nendsolid x\n";
  // An ASCII file with no facet is read as binary and fails the size check;
  // a binary file declaring zero triangles is the explicit case.
  std::string bin(84, '\0');
  std::ofstream(dir / "zero.stl", std::ios::binary).write(bin.data(), 84);
  EXPECT_THAT(ErrorOf([&] { ReadSurface(dir / "zero.stl"); }), HasSubstr("zero.stl: no triangles"));
  EXPECT_THAT(ErrorOf([&] { ReadSurface(dir / "empty.stl"); }), HasSubstr("empty.stl: "));
}

TEST(BadSurfaceTest, TruncatedAsciiStl) {
  ScopedTempDir dir;
  std::ofstream(dir / "cut.stl") << "solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\n";
  EXPECT_THAT(ErrorOf([&] { ReadSurface(dir / "cut.stl"); }), HasSubstr("without 'endsolid' (truncated)"));
}

TEST(BadSurfaceTest, ObjIndexOutOfRangeAndUnknownFormat) {
  ScopedTempDir dir;
  std::ofstream(dir / "bad.obj") << "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n";
  EXPECT_THAT(ErrorOf([&] { ReadSurface(dir / "bad.obj"); }),
              HasSubstr("bad.obj: line 4: face refers to vertex 9 but 3 vertices are defined"));
  std::ofstream(dir / "hull.iges") << "x";
  EXPECT_THAT(ErrorOf([&] { ReadSurface(dir / "hull.iges"); }), HasSubstr("unknown surface format"));
  EXPECT_THAT(ErrorOf([&] { ReadSurface(dir / "none.stl"); }), HasSubstr("none.stl: file not found"));
}

TEST(BadHullTest, EntirelyAboveTheWaterline) {
  TriangleSurface s = Wigley(10, 4);
  for (auto& v : s.vertices) v.z() += 1.0;
  s.source = "high.stl";
  EXPECT_THAT(ErrorOf([&] { ValidateHull(s, 0.0); }), HasSubstr("high.stl: the hull lies entirely above the waterline"));
}

TEST(BadHullTest, OpenBelowTheWaterline) {
  TriangleSurface s = Wigley(10, 4);
  s.triangles.erase(s.triangles.begin());  // a hole at the keel
  s.source = "holed.stl";
  EXPECT_THAT(ErrorOf([&] { ValidateHull(s, 0.0); }),
              HasSubstr("holed.stl: 3 open edges below the waterline; expected a watertight underwater hull"));
}

TEST(BadHullTest, OpenAboveTheWaterlineIsAccepted) {
  TriangleSurface s = Wigley(10, 4);
  std::erase_if(s.triangles, [&](const auto& t) {
    return s.vertices[t[0]].z() > 0 && s.vertices[t[1]].z() > 0 && s.vertices[t[2]].z() > 0;
  });  // no deck, no topsides
  const SurfaceCheck c = ValidateHull(s, 0.0);
  EXPECT_GT(c.open_edges, 0u);
  EXPECT_EQ(c.open_edges_below, 0u);
}

TEST(BadHullTest, InconsistentNormals) {
  TriangleSurface s = Wigley(10, 4);
  std::swap(s.triangles[5][1], s.triangles[5][2]);
  s.source = "mixed.stl";
  EXPECT_THAT(ErrorOf([&] { ValidateHull(s, 0.0); }), HasSubstr("mixed.stl: inconsistent normals: 3 edges"));
}

TEST(BadHullTest, DegenerateTriangle) {
  TriangleSurface s = Wigley(10, 4);
  s.triangles.push_back({0, 0, 1});
  s.source = "sliver.stl";
  EXPECT_THAT(ErrorOf([&] { ValidateHull(s, 0.0); }), HasSubstr("sliver.stl: 1 degenerate (zero-area) triangles"));
}

TEST(DtcHullTest, DisplacementAndWettedAreaMatchPublishedValues) {
  // el Moctar, Shigunov & Zorn (2012), Ship Technology Research 59(3):
  // 173,467 m^3 and 22,032 m^2 at full scale, scaled by 1:59.407.
  const auto ship = kelvin::testing::SourceDir() / "data/ships/dtc.yaml";
  const HullPlacement p = LoadHullPlacement(ship);
  if (!std::filesystem::exists(p.file)) GTEST_SKIP() << p.file << " missing: install Debian's openfoam-examples";
  SurfaceCheck check;
  const TriangleSurface s = LoadHull(p, &check);
  const Hydrostatics h = ComputeHydrostatics(s, p.Lpp, p.B, p.T);
  std::printf("DTC hull: %s\n%s", check.Summary().c_str(), h.Report().c_str());
  const double lambda = 59.407;
  EXPECT_NEAR(h.volume / (173467.0 / (lambda * lambda * lambda)), 1.0, 0.005);
  EXPECT_NEAR(h.wetted_area / (22032.0 / (lambda * lambda)), 1.0, 0.005);
  EXPECT_NEAR(h.Cb, 0.661, 0.661 * 0.005);
}

TEST(HullPlacementTest, BadBowDirectionIsNamed) {
  ScopedTempDir dir;
  std::ofstream(dir / "s.yaml") << "ship: {name: X}\nprincipal: {Lpp: 1, B: 0.1, d: 0.05}\n"
                                   "geometry: {file: h.stl, length_unit: 1, waterline_z: 0, bow_direction: up}\n";
  try {
    LoadHullPlacement(dir / "s.yaml");
    FAIL();
  } catch (const ConfigError& e) {
    EXPECT_THAT(e.what(), HasSubstr("key 'geometry.bow_direction' = 'up': expected '+x' or '-x'"));
  }
}

}  // namespace
}  // namespace kelvin::cfd
