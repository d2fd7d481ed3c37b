// The propeller tests' shared pieces: a uniform box, the solver of still
// water and of a uniform stream in it (no time step needed for the disk's
// updates), the KP505 open-water table and a Hough-Ordway disk of unit
// diameter.
#pragma once

#include <gtest/gtest.h>

#include <fstream>
#include <memory>
#include <sstream>
#include <string>

#include "cfd/mesh/box_mesh.h"
#include "cfd/propulsion/actuator_disk.h"
#include "cfd/propulsion/propeller.h"
#include "tests/cfd/cfd_test_support.h"

namespace kelvin::cfd::testing {

// A uniform box [-1, 1]^3 with n cells per axis, walls on no side.
inline Mesh UniformBox(int n) {
  BoxMeshOptions mo;
  mo.min = Vector3(-1, -1, -1);
  mo.max = Vector3(1, 1, 1);
  mo.cells = {n, n, n};
  mo.kinds.fill(PatchKind::kPatch);
  return MakeBoxMesh(mo);
}

// Slip walls, zero-gradient pressure, at rest.
inline std::unique_ptr<PimpleSolver> StillWater(const Mesh& mesh) {
  auto U = MakeField<Vector3>("U", mesh, [](const Patch&) -> std::unique_ptr<BoundaryCondition<Vector3>> {
    return std::make_unique<Slip>();
  });
  auto p = MakeField<double>("p", mesh, [](const Patch&) -> std::unique_ptr<BoundaryCondition<double>> {
    return std::make_unique<ZeroGradient<double>>();
  });
  return std::make_unique<PimpleSolver>(mesh, PhysicsOptions{}, SchemeOptions{}, PimpleOptions{}, std::move(U),
                                        std::move(p));
}

// KP505 (the KCS propeller) open-water table: NMRI data for SIMMAN 2008,
// data/reference/kp505_open_water.csv (J, K_T, 10 K_Q).
inline sim::OpenWaterCurve Kp505() {
  std::ifstream in(kelvin::testing::SourceDir() / "data/reference/kp505_open_water.csv");
  EXPECT_TRUE(in.good()) << "kp505_open_water.csv";
  sim::OpenWaterCurve c;
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#' || line[0] == 'J') continue;
    std::stringstream ss(line);
    std::string a, b, q;
    std::getline(ss, a, ',');
    std::getline(ss, b, ',');
    std::getline(ss, q, ',');
    c.J.push_back(std::stod(a));
    c.K_T.push_back(std::stod(b));
    c.K_Q.push_back(std::stod(q) / 10.0);
  }
  c.origin = "kp505_open_water.csv";
  return c;
}

inline ActuatorDiskOptions HoughOrdwayDisk() {
  ActuatorDiskOptions o;
  o.diameter = 1.0;
  o.hub_ratio = 0.2;
  o.thickness = 0.2;
  o.axis = -Vector3::UnitX();
  o.distribution = ActuatorDiskOptions::Distribution::kHoughOrdway;
  return o;
}

// U = (u, 0, 0) everywhere: no time step needed for Update.
inline std::unique_ptr<PimpleSolver> UniformFlow(const Mesh& mesh, double u) {
  auto solver = StillWater(mesh);
  for (Vector3& v : solver->U().values()) v = Vector3(u, 0, 0);
  return solver;
}

}  // namespace kelvin::cfd::testing
