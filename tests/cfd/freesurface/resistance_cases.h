// Runs the resistance cases of data/cases/resistance with the `kelvin`
// program in a scratch directory, for the slow validation tests: grids are
// built with `kelvin mesh`, and each case's grid and results paths (relative
// to data/cases/resistance, under build/grids and results) are redirected
// into the scratch directory. With the environment variable `keep_variable`
// set to a directory, that directory is used and kept, and finished runs in
// it are reused.
#pragma once

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <memory>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "tests/test_utilities/test_utilities.h"

namespace kelvin::testing {

class ResistanceCases {
 public:
  explicit ResistanceCases(const char* keep_variable) {
    const char* keep = std::getenv(keep_variable);
    if (keep && *keep) {
      root_ = std::filesystem::path(keep);
      std::filesystem::create_directories(root_);
    } else {
      tmp_ = std::make_unique<ScopedTempDir>();
      root_ = tmp_->path();
    }
  }

  static std::filesystem::path Cases() { return SourceDir() / "data" / "cases" / "resistance"; }
  static std::string Kelvin() { return (ToolsDir() / "kelvin").string(); }
  const std::filesystem::path& root() const { return root_; }

  // Builds a grid once: kelvin mesh <mesh_case> -o root/grids/<name>.
  std::filesystem::path Grid(const std::string& mesh_case, const std::string& name) const {
    const std::filesystem::path dir = root_ / "grids" / name;
    if (!std::filesystem::exists(dir / "constant" / "polyMesh" / "owner")) {
      const auto r = RunCommand(Kelvin() + " mesh " + (Cases() / mesh_case).string() + " -o " + dir.string());
      EXPECT_EQ(r.exit_code, 0) << r.output;
    }
    return dir;
  }

  // Runs case <name>.yaml once, its grid build/grids/<grid_name> replaced by
  // `grid` and results/ by root/results/; returns the run's resistance.h5. A
  // variant (results under <name>_<variant>) has each text `edits` names
  // replaced in the case first.
  using Edits = std::vector<std::pair<std::string, std::string>>;
  std::filesystem::path Run(const std::string& name, const std::filesystem::path& grid, const std::string& grid_name,
                            const std::string& variant = "", const Edits& edits = {}) const {
    const std::filesystem::path out = root_ / "results" / (variant.empty() ? name : name + "_" + variant);
    const std::filesystem::path h5 = out / "resistance.h5";
    if (std::filesystem::exists(h5)) return h5;
    std::string text = ReadText(Cases() / (name + ".yaml"));
    auto replace = [&](const std::string& from, const std::string& to) {
      for (std::size_t at = text.find(from); at != std::string::npos; at = text.find(from, at + to.size())) {
        text.replace(at, from.size(), to);
      }
    };
    replace("../../../build/grids/" + grid_name, grid.string());
    replace("../../../results/", (root_ / "results").string() + "/");
    for (const auto& [from, to] : edits) {
      EXPECT_NE(text.find(from), std::string::npos) << name << ".yaml has no '" << from << "'";
      replace(from, to);
    }
    std::filesystem::create_directories(out);
    const std::filesystem::path file = out / (name + ".yaml");
    std::ofstream(file) << text;
    const auto r = RunCommand(Kelvin() + " run " + file.string() + " -o " + out.string() + " --no-progress");
    EXPECT_EQ(r.exit_code, 0) << r.output.substr(r.output.size() > 4000 ? r.output.size() - 4000 : 0);
    return h5;
  }

 private:
  std::unique_ptr<ScopedTempDir> tmp_;
  std::filesystem::path root_;
};

}  // namespace kelvin::testing
