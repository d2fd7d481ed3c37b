// The fixture of the free-running tests on the 1 m Wigley: the quickstart's
// captive grid meshed once per suite, the cases of data/cases/free_running
// with the ship file's path made absolute, runs in a temporary directory.
#pragma once

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "cfd/run/run_case.h"
#include "data/schema/h5_file.h"
#include "tests/test_utilities/test_utilities.h"

namespace kelvin::cfd::testing {

namespace fs = std::filesystem;

// The body's history columns of a run.
struct History {
  std::vector<double> t, u, v, x0, constraint_x, hull_y;
};

class FreeRunning : public ::testing::Test {
 public:
  static void SetUpTestSuite() {
    tmp_ = new kelvin::testing::ScopedTempDir();
    const fs::path src = kelvin::testing::SourceDir() / "data";
    grid_ = tmp_->path() / "grid";
    const auto r = kelvin::testing::RunCommand((kelvin::testing::ToolsDir() / "kelvin").string() + " mesh " +
                                               (src / "cases/captive_cfd/wigley_quick_mesh.yaml").string() +
                                               " -o " + grid_.string());
    ASSERT_EQ(r.exit_code, 0) << r.output;
    ship_ = src / "ships/wigley.yaml";
  }
  static void TearDownTestSuite() {
    delete tmp_;
    tmp_ = nullptr;
  }

  static std::string CaseText(const std::string& name) {
    std::string text =
        kelvin::testing::ReadText(kelvin::testing::SourceDir() / "data/cases/free_running" / (name + ".yaml"));
    Replace(text, "ship: ../../ships/wigley.yaml", "ship: " + ship_.string());
    return text;
  }
  static void Replace(std::string& text, const std::string& from, const std::string& to) {
    const auto at = text.find(from);
    ASSERT_NE(at, std::string::npos) << "the case no longer has '" << from << "'";
    text.replace(at, from.size(), to);
  }
  static RunSummary Run(const std::string& name, const std::string& text, const fs::path& restart = {}) {
    const fs::path dir = tmp_->path() / name;
    fs::create_directories(dir);
    std::ofstream(dir / "case.yaml") << text;
    RunOptions o;
    o.progress = false;
    o.poly_mesh_override = grid_ / "constant/polyMesh";
    o.output_override = dir / "out";
    o.restart = restart;
    return RunCase(dir / "case.yaml", o);
  }
  static History Read(const std::string& name) {
    const data::H5Reader h(tmp_->path() / name / "out/history.h5");
    History out;
    out.t = h.Read("time").values;
    const auto vel = h.Read("body/velocity").values, traj = h.Read("body/trajectory").values;
    const auto con = h.Read("body/constraint_load").values, hull = h.Read("body/hull_load").values;
    for (std::size_t i = 0; i < out.t.size(); ++i) {
      out.u.push_back(vel[3 * i]);
      out.v.push_back(vel[3 * i + 1]);
      out.x0.push_back(traj[3 * i]);
      out.constraint_x.push_back(con[3 * i]);
      out.hull_y.push_back(hull[3 * i + 1]);
    }
    return out;
  }

  static inline kelvin::testing::ScopedTempDir* tmp_ = nullptr;
  static inline fs::path grid_, ship_;
};

}  // namespace kelvin::cfd::testing
