// Helpers shared by the CFD tests: fields with one condition per patch
// chosen by a callback, and the Ghia et al. (1982) reference table.
#pragma once

#include <filesystem>
#include <fstream>
#include <functional>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "cfd/field/field.h"
#include "cfd/run/run_case.h"
#include "cfd/solver/pimple_solver.h"
#include "data/schema/errors.h"
#include "tests/test_utilities/test_utilities.h"

namespace kelvin::cfd::testing {

template <typename T>
std::unique_ptr<CellField<T>> MakeField(const std::string& name, const Mesh& mesh,
                                        const std::function<std::unique_ptr<BoundaryCondition<T>>(const Patch&)>& bc) {
  std::vector<std::unique_ptr<BoundaryCondition<T>>> bcs;
  for (const Patch& p : mesh.patches()) bcs.push_back(bc(p));
  return std::make_unique<CellField<T>>(name, mesh, std::move(bcs));
}

// Writes a case file `case.yaml` into dir and returns its path.
inline std::filesystem::path WriteCase(const std::filesystem::path& dir, const std::string& text) {
  const std::filesystem::path p = dir / "case.yaml";
  std::ofstream(p) << text;
  return p;
}

// Running the case text fails with one ConfigError naming the case file and
// containing `part`.
inline void ExpectCaseConfigError(const std::string& text, const std::string& part) {
  kelvin::testing::ScopedTempDir tmp;
  RunOptions o;
  o.progress = false;
  try {
    RunCase(WriteCase(tmp.path(), text), o);
    ADD_FAILURE() << "expected a ConfigError with '" << part << "'";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find(part), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("case.yaml"), std::string::npos) << e.what();
  }
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
