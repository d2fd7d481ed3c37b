// The captive sampler and the resistance monitor driven by a given solver
// state (no time step is solved): each gets face forces set by hand on the
// hull patch and a step record, and must return the sums, arms, axes and
// scales that follow in closed form from those forces and the mesh.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "cfd/run/captive_sampler.h"
#include "cfd/run/case_loader.h"
#include "cfd/run/resistance_monitor.h"
#include "data/schema/config.h"
#include "data/schema/h5_file.h"
#include "tests/test_utilities/test_utilities.h"

namespace kelvin::cfd {
namespace {

constexpr const char* kBox = R"(
mesh:
  box: {min: [-3, -2, -1], max: [3, 2, 0], cells: [12, 8, 2], obstacle: {min: [4, 3, 1], max: [8, 5, 2]}}
physics: {nu: 1.0e-2, rho: 998.0}
solution: {n_outer: 1}
boundary:
  xmax: {U: {type: fixedValue, value: [-1, 0, 0]}, p: {type: zeroGradient}}
  xmin: {U: {type: zeroGradient}, p: {type: fixedValue, value: 0}}
  ymin: {U: {type: slip}, p: {type: zeroGradient}}
  ymax: {U: {type: slip}, p: {type: zeroGradient}}
  zmin: {U: {type: slip}, p: {type: zeroGradient}}
  zmax: {U: {type: slip}, p: {type: zeroGradient}}
  obstacle: {U: {type: WALL}, p: {type: zeroGradient}}
)";

Case Load(const std::string& extra, const std::string& wall) {
  std::string text = std::string(kBox) + extra;
  text.replace(text.find("WALL"), 4, wall);
  return LoadCase(data::ConfigNode::LoadString(text, "monitors_test.yaml"), ".");
}

// The same force on every face of the patch.
PatchFaceForces Uniform(const Mesh& mesh, int patch, const Vector3& pressure, const Vector3& viscous) {
  const std::size_t n = static_cast<std::size_t>(mesh.patches()[patch].size);
  return {std::vector<Vector3>(n, pressure), std::vector<Vector3>(n, viscous)};
}

TEST(CaptiveSampler, ShipAxisLoadsOfAGivenForceField) {
  const Case c = Load(R"(reference: {speed: 1.5, direction: [-1, 0, 0], length: 2.0, draft: 0.5}
motion: {kind: static_drift, speed: 1.5, ramp_time: 0}
time: {dt: 0.1, end: 1}
output: {directory: out, forces: [obstacle], captive: true}
)",
                      "movingWallVelocity");
  const int hull = c.mesh->FindPatch("obstacle");
  const PrimeScales scales{998.0, 2.0, 0.5, 1.5};
  CaptiveSampler sampler(c, {hull}, scales);
  StepForces forces;
  forces.Set(hull, Uniform(*c.mesh, hull, Vector3(0, 1, 0), Vector3(0.5, 0, 0)));
  const StepSummary step;
  const SteadyStatus steady;
  History history;
  sampler.AfterStep(*c.solver, StepRecord{step, forces, steady}, history);
  ASSERT_EQ(sampler.samples().size(), 1u);
  const CaptiveSample& s = sampler.samples()[0];
  // At t = 0 with no drift the grid axes are the earth axes and the centre
  // is the origin: X = sum f_x, Y = -sum f_y (y to starboard), N = -sum (x f_y - y f_x).
  const Patch& p = c.mesh->patches()[hull];
  double sum_x = 0.0, sum_y = 0.0;
  for (int f = p.start; f < p.start + p.size; ++f) {
    sum_x += c.mesh->face_centres()[f].x();
    sum_y += c.mesh->face_centres()[f].y();
  }
  const double n = p.size;
  EXPECT_NEAR(s.loads.pressure.X, 0.0, 1e-12);
  EXPECT_NEAR(s.loads.pressure.Y, -n, 1e-12);
  EXPECT_NEAR(s.loads.pressure.N, -sum_x, 1e-12);
  EXPECT_NEAR(s.loads.viscous.X, 0.5 * n, 1e-12);
  EXPECT_NEAR(s.loads.viscous.Y, 0.0, 1e-12);
  EXPECT_NEAR(s.loads.viscous.N, 0.5 * sum_y, 1e-12);
  const double q = 0.5 * 998.0 * 2.0 * 0.5 * 1.5 * 1.5;
  EXPECT_NEAR(s.prime.X, 0.5 * n / q, 1e-12);
  EXPECT_NEAR(s.prime.Y, -n / q, 1e-12);
  EXPECT_NEAR(s.prime.N, (0.5 * sum_y - sum_x) / (q * 2.0), 1e-12);
}

// One recorded last step of a resistance monitor on `c` with the force
// `pressure` + `viscous` on every hull face; the report's summary.
std::string ReportOfOneStep(const Case& c, const Vector3& pressure, const Vector3& viscous) {
  ResistanceMonitor monitor(c);
  const int hull = c.mesh->FindPatch("obstacle");
  StepForces forces;
  forces.Set(hull, Uniform(*c.mesh, hull, pressure, viscous));
  StepSummary step;
  SteadyStatus steady;
  History history;
  StepRecord record{step, forces, steady};
  record.last = true;
  monitor.AfterStep(*c.solver, record, history);
  const std::vector<std::string> report = monitor.Finish(*c.solver);
  EXPECT_EQ(report.size(), 1u);
  return report.at(0);
}

TEST(ResistanceMonitor, SplitAndCoefficientsOfAGivenForceField) {
  kelvin::testing::ScopedTempDir tmp;
  const Case c = Load("reference: {speed: 2, direction: [-1, 0, 0], area: 3, length: 1.5}\n"
                      "time: {dt: 0.1, end: 1}\noutput: {directory: " + tmp.path().string() +
                          ", forces: [obstacle]}\nresistance: {hull: obstacle}\n",
                      "noSlip");
  ResistanceMonitor monitor(c);
  const int hull = c.mesh->FindPatch("obstacle");
  ASSERT_EQ(monitor.ForcePatches(), std::vector<int>{hull});
  StepForces forces;
  // Pressure 1 N and friction 0.25 N per face against the direction of the
  // flow past the hull (-x), and a side force that is no resistance.
  forces.Set(hull, Uniform(*c.mesh, hull, Vector3(-1, 0.3, 0), Vector3(-0.25, 0, 0)));
  StepSummary step;
  SteadyStatus steady;
  steady.enabled = true;
  steady.settled = true;
  steady.settled_step = 7;
  History history;
  StepRecord record{step, forces, steady};
  record.last = true;  // the report's hull faces are those of the last step
  monitor.AfterStep(*c.solver, record, history);
  const std::vector<std::string> report = monitor.Finish(*c.solver);
  ASSERT_EQ(report.size(), 1u);
  EXPECT_NE(report[0].find("converged at step 7"), std::string::npos) << report[0];
  const double n = c.mesh->patches()[hull].size;
  const data::H5Reader h(tmp.path() / "resistance.h5");
  EXPECT_DOUBLE_EQ(h.Read("R_P").at(0), n);
  EXPECT_DOUBLE_EQ(h.Read("R_F").at(0), 0.25 * n);
  EXPECT_DOUBLE_EQ(h.Read("R_T").at(0), 1.25 * n);
  const double q = 0.5 * 998.0 * 3.0 * 2.0 * 2.0;
  EXPECT_NEAR(h.Read("C_T").at(0), 1.25 * n / q, 1e-15);
  EXPECT_NEAR(h.Read("Fn").at(0), 2.0 / std::sqrt(9.81 * 1.5), 1e-12);
  EXPECT_NEAR(h.Read("Re").at(0), 2.0 * 1.5 / 1.0e-2, 1e-9);
  EXPECT_EQ(h.Read("converged").at(0), 1.0);
  const data::Series pf = h.Read("hull_faces/pressure_force");
  ASSERT_EQ(pf.rows, static_cast<std::size_t>(n));
  EXPECT_EQ(pf.at(0, 0), -1.0);
  EXPECT_EQ(pf.at(0, 1), 0.3);
}

// A turbulent case's friction is judged against ITTC-57: the ratio is in
// resistance.h5, and well off the line (0.6, as on a grid whose prism layers
// collapsed) the report says so loudly; near it (1.0) it does not.
TEST(ResistanceMonitor, FrictionFarFromIttc57IsALoudWarning) {
  for (double ratio : {0.6, 1.0}) {
    kelvin::testing::ScopedTempDir tmp;
    const Case c = Load("reference: {speed: 2, direction: [-1, 0, 0], area: 3, length: 1.5}\n"
                        "turbulence: {model: kOmegaSST, inflow: {intensity: 0.01, viscosity_ratio: 5, "
                        "reference_speed: 2}}\ntime: {dt: 0.1, end: 1}\noutput: {directory: " +
                            tmp.path().string() + ", forces: [obstacle]}\nresistance: {hull: obstacle}\n",
                        "noSlip");
    const double n = c.mesh->patches()[c.mesh->FindPatch("obstacle")].size;
    const double q = 0.5 * 998.0 * 3.0 * 2.0 * 2.0, re = 2.0 * 1.5 / 1.0e-2;
    const double c_f0 = 0.075 / std::pow(std::log10(re) - 2.0, 2);
    const std::string report = ReportOfOneStep(c, Vector3(-1, 0, 0), Vector3(-ratio * c_f0 * q / n, 0, 0));
    EXPECT_NEAR(data::H5Reader(tmp.path() / "resistance.h5").Read("C_F_over_ITTC57").at(0), ratio, 1e-12);
    EXPECT_EQ(report.find("WARNING: the friction on 'obstacle' is 0.60 of the ITTC-57 line") != std::string::npos,
              ratio < 0.9)
        << report;
  }
}

// The wave part against a double body on the same grid: R_W = R_P - R_P(double
// body) by coefficients. A ship's steady waves take energy from it, so a
// negative R_W beyond the steady tolerance of R_T (1e-3 without a steady:
// section) is a loud warning (the DTC's uniform-stream wave part was -3.4 N);
// a positive one, or one within the tolerance, is not.
TEST(ResistanceMonitor, NegativeWavePartIsALoudWarning) {
  kelvin::testing::ScopedTempDir tmp;
  const std::string reference = "reference: {speed: 2, direction: [-1, 0, 0], area: 3, length: 1.5}\n";
  // One monitor with a pressure force of `per_face` N per hull face against the flow; its summary and hull faces.
  auto report = [&](const std::string& directory, const std::string& resistance, double per_face) {
    const Case c = Load(reference + "time: {dt: 0.1, end: 1}\noutput: {directory: " + directory +
                            ", forces: [obstacle]}\nresistance: " + resistance + "\n",
                        "noSlip");
    const std::string text = ReportOfOneStep(c, Vector3(-per_face, 0, 0), Vector3(0, 0, 0));
    return std::make_pair(text, c.mesh->patches()[c.mesh->FindPatch("obstacle")].size);
  };
  const std::string db = (tmp.path() / "db").string();
  report(db, "{hull: obstacle}", 1.0);
  for (double per_face : {0.8, 0.9999, 1.2}) {
    const std::string out = (tmp.path() / fmt::format("fs{}", per_face)).string();
    const auto [text, n] = report(out, "{hull: obstacle, double_body: " + db + "/resistance.h5}", per_face);
    EXPECT_NEAR(data::H5Reader(std::filesystem::path(out) / "resistance.h5").Read("R_W").at(0), (per_face - 1.0) * n,
                1e-9 * n);
    EXPECT_EQ(text.find("WARNING: the free surface lowered the pressure resistance by") != std::string::npos,
              per_face < 0.9)
        << text;
  }
}

// A monitor asked for on a case that cannot provide it is one error naming the key.
TEST(ResistanceMonitor, CasesThatCannotProvideItAreErrors) {
  auto message = [](const std::string& extra, const std::string& wall) {
    try {
      Load(extra, wall);
    } catch (const ConfigError& e) {
      std::printf("%s\n", e.what());
      return std::string(e.what());
    }
    return std::string("no error");
  };
  const std::string time = "time: {dt: 0.1, end: 1}\n";
  EXPECT_NE(message(time + "output: {forces: [obstacle]}\nresistance: {hull: obstacle}\n", "noSlip")
                .find("a reference: {speed, direction} section"),
            std::string::npos);
  EXPECT_NE(message("reference: {speed: 1, direction: [-1, 0, 0]}\n" + time +
                        "output: {forces: [obstacle]}\nresistance: {hull: obstacle, free_surface: zmax}\n",
                    "noSlip")
                .find("resistance.free_surface"),
            std::string::npos);
  EXPECT_NE(message("reference: {speed: 1, direction: [-1, 0, 0], length: 1, draft: 1}\n" + time +
                        "output: {forces: [obstacle], captive: true}\n",
                    "noSlip")
                .find("a motion: section (ship-axis loads follow the body)"),
            std::string::npos);
}

}  // namespace
}  // namespace kelvin::cfd
