// Helpers shared by the CFD tests: fields with one condition per patch
// chosen by a callback, and the Ghia et al. (1982) reference table.
#pragma once

#include <fstream>
#include <functional>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "cfd/field/field.h"
#include "cfd/solver/pimple_solver.h"
#include "tests/test_utilities/test_utilities.h"

namespace kelvin::cfd::testing {

template <typename T>
std::unique_ptr<CellField<T>> MakeField(const std::string& name, const Mesh& mesh,
                                        const std::function<std::unique_ptr<BoundaryCondition<T>>(const Patch&)>& bc) {
  std::vector<std::unique_ptr<BoundaryCondition<T>>> bcs;
  for (const Patch& p : mesh.patches()) bcs.push_back(bc(p));
  return std::make_unique<CellField<T>>(name, mesh, std::move(bcs));
}

struct GhiaPoint {
  std::string section;  // u_vs_y or v_vs_x
  double coord;
  double re100, re400, re1000;
};

inline std::vector<GhiaPoint> LoadGhia() {
  std::ifstream in(kelvin::testing::SourceDir() / "data/reference/ghia1982_cavity.csv");
  std::vector<GhiaPoint> out;
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#' || line.rfind("section", 0) == 0) continue;
    std::stringstream ss(line);
    GhiaPoint g;
    std::string cell;
    std::getline(ss, g.section, ',');
    std::getline(ss, cell, ',');
    g.coord = std::stod(cell);
    std::getline(ss, cell, ',');
    g.re100 = std::stod(cell);
    std::getline(ss, cell, ',');
    g.re400 = std::stod(cell);
    std::getline(ss, cell, ',');
    g.re1000 = std::stod(cell);
    out.push_back(g);
  }
  return out;
}

}  // namespace kelvin::cfd::testing
