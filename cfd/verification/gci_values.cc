#include "cfd/verification/gci_values.h"

#include <fmt/format.h>

#include <cmath>
#include <string>

#include "data/schema/config.h"

namespace kelvin::cfd {
namespace {

std::vector<double> ThreeFinite(const data::ConfigNode& node) {
  const std::vector<double> v = node.As<std::vector<double>>();
  if (v.size() != 3) node.Fail(fmt::format("three values (grid 1, the finest, then 2 and 3); got {}", v.size()));
  for (double x : v) {
    if (!std::isfinite(x)) node.Fail("three finite numbers");
  }
  return v;
}

}  // namespace

GciStudy GciStudyFromValues(const std::vector<FamilyGrid>& family, const std::filesystem::path& values_file) {
  const data::ConfigNode root = data::ConfigNode::LoadFile(values_file);
  root.ExpectKeys({"outputs", "settled"});
  const data::ConfigNode outputs = root["outputs"];
  if (!outputs.IsMap() || outputs.size() == 0) outputs.Fail("a map of output name -> [grid 1, grid 2, grid 3]");
  std::vector<bool> settled(3, true);
  if (const auto s = root.Find("settled")) {
    const std::vector<data::ConfigNode> items = s->Items();
    if (items.size() != 3) s->Fail(fmt::format("three booleans (grid 1, 2, 3); got {}", items.size()));
    for (int g = 0; g < 3; ++g) settled[g] = items[g].As<bool>();
  }
  GciStudy study;
  for (int g = 0; g < 3; ++g) {
    GridRunRecord r;
    r.level = family.at(g).level;
    r.cells = family.at(g).cells;
    r.h = family.at(g).h;
    r.directory = family.at(g).poly_mesh.parent_path().parent_path();
    r.steady = true;
    r.steady_converged = settled[g];
    study.grids.push_back(r);
  }
  std::vector<std::string> names;
  for (const std::string& name : outputs.Keys()) {
    const std::vector<double> v = ThreeFinite(outputs[name]);
    for (int g = 0; g < 3; ++g) study.grids[g].values.push_back(v[g]);
    names.push_back(name);
  }
  study.outputs = ComputeGciOutputs(study.grids, names);
  return study;
}

}  // namespace kelvin::cfd
