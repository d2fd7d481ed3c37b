#include "cfd/campaign/appendage_run.h"

#include <fmt/format.h>
#include <yaml-cpp/yaml.h>

#include <cmath>

#include "cfd/run/propeller_actuator.h"
#include "cfd/run/rudder_actuator.h"
#include "data/schema/errors.h"

namespace kelvin::cfd {
namespace {

constexpr double kDeg = M_PI / 180.0;

// The campaign's case file with the run's free body (every degree of
// freedom held), propeller and rudder sections.
data::ConfigNode AppendageCaseText(const data::CampaignFile& f, const data::AppendageTest& t) {
  const data::ConfigNode original = data::ConfigNode::LoadFile(f.cfd.case_file);
  if (original.Has("motion")) original["motion"].Fail("no motion: section (the campaign sets it)");
  for (const char* key : {"propeller", "rudder", "maneuver"}) {
    if (original.Has(key)) original[key].Fail(fmt::format("no {}: section (tests.appendages sets it)", key));
  }
  YAML::Node root = YAML::Clone(original.yaml());
  const std::filesystem::path ship = std::filesystem::absolute(f.appendages->ship_file);
  YAML::Node motion;
  motion["kind"] = "free";
  motion["ship"] = ship.string();
  motion["centre"] = std::vector<double>(f.cfd.centre.begin(), f.cfd.centre.end());
  motion["free"] = std::vector<std::string>{};
  motion["initial"]["u"] = t.u;
  motion["initial"]["v"] = t.v;
  motion["initial"]["r"] = t.r;
  motion["ramp_time"] = f.cfd.steady_ramp;
  root["motion"] = motion;
  root["propeller"]["rate"]["n"] = t.n;
  root["propeller"]["swirl"] = f.appendages->swirl;
  root["rudder"]["angle_deg"] = t.delta / kDeg;
  const data::AppendageDesign& d = *f.appendages;
  if (d.propeller_thickness > 0) root["propeller"]["thickness"] = d.propeller_thickness;
  if (d.rudder_sample_distance > 0) root["rudder"]["sample_distance"] = d.rudder_sample_distance;
  return data::ConfigNode::LoadString(YAML::Dump(root), f.cfd.case_file.string() + " (with " + t.name + ")");
}

}  // namespace

Case LoadAppendageCase(const data::CampaignFile& f, const data::AppendageTest& test, CaseOverrides overrides) {
  KELVIN_CHECK(f.appendages.has_value(), "a campaign with tests.appendages");
  overrides.motion.reset();
  return LoadCase(AppendageCaseText(f, test), f.cfd.case_file.parent_path(), overrides);
}

AppendageSampler::AppendageSampler(const Case& c, const FreeRunningCoupler& coupler) : coupler_(coupler) {
  for (const auto& a : c.actuators) {
    if (auto* p = dynamic_cast<const PropellerActuator*>(a.get())) propeller_ = p;
    if (auto* r = dynamic_cast<const RudderActuator*>(a.get())) rudder_ = r;
  }
  KELVIN_CHECK(propeller_ && rudder_, "an appendage case with a propeller and a rudder (LoadAppendageCase)");
}

void AppendageSampler::AfterStep(const PimpleSolver& solver, const StepRecord&, History&) {
  const PlanarLoad h = coupler_.hull_loads().Total(), a = coupler_.actuator_load();
  const PropellerState& p = propeller_->last();
  const RudderState& r = rudder_->last();
  rows_.push_back({solver.time(), h.X + a.X, h.Y + a.Y, h.N + a.N, p.T, p.U_A, p.J, p.K_T, r.F_N, r.u_R, r.v_R});
}

void AppendageSampler::AddCheckpointArrays(CheckpointArrays& arrays) const {
  std::vector<double> flat;
  for (const auto& row : rows_) flat.insert(flat.end(), row.begin(), row.end());
  arrays["appendage_samples"] = std::move(flat);
}

void AppendageSampler::RestoreArrays(const CheckpointArrays& arrays) {
  const auto it = arrays.find("appendage_samples");
  if (it == arrays.end() || it->second.size() % kFields != 0) {
    throw DataFileError(fmt::format("the checkpoint has no appendage_samples of {} values per step; the run is a "
                                    "captive run with the propeller and rudder",
                                    kFields));
  }
  rows_.clear();
  for (std::size_t i = 0; i < it->second.size(); i += kFields) {
    std::array<double, kFields> row;
    std::copy_n(it->second.begin() + static_cast<std::ptrdiff_t>(i), kFields, row.begin());
    rows_.push_back(row);
  }
}

data::AppendageRun AppendageSampler::Mean(const data::AppendageTest& test, double from) const {
  std::array<double, kFields> sum{};
  int count = 0;
  for (const auto& row : rows_) {
    if (row[0] < from) continue;
    for (std::size_t k = 0; k < kFields; ++k) sum[k] += row[k];
    ++count;
  }
  KELVIN_CHECK(count > 0, "samples after the start of the averaging window");
  for (double& x : sum) x /= count;
  data::AppendageRun r;
  r.name = test.name;
  r.u = test.u, r.v = test.v, r.r = test.r, r.delta = test.delta, r.n = test.n;
  r.X = sum[1], r.Y = sum[2], r.N = sum[3], r.T = sum[4], r.U_A = sum[5], r.J = sum[6], r.K_T = sum[7];
  r.F_N = sum[8], r.u_R = sum[9], r.v_R = sum[10];
  return r;
}

}  // namespace kelvin::cfd
