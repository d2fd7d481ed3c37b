#include "simulator/maneuvers/maneuver_file.h"

#include <fmt/format.h>

#include <cmath>

#include "data/schema/errors.h"
#include "data/schema/h5_file.h"

namespace kelvin::sim {

namespace {

[[noreturn]] void Fail(const std::filesystem::path& path, const std::string& what) {
  throw DataFileError(fmt::format("{}: {}", path.string(), what));
}

double PositiveAttribute(const data::H5Reader& h5, const std::string& name, const char* unit) {
  const double v = h5.NumberAttribute("/", name);
  if (!(v > 0) || !std::isfinite(v)) {
    Fail(h5.path(), fmt::format("attribute '{}' = {} {}: expected a positive number", name, v, unit));
  }
  return v;
}

data::H5Reader Open(const std::filesystem::path& path) {
  try {
    return data::H5Reader(path);
  } catch (const DataFileError& e) {
    throw DataFileError(fmt::format("{}; expected a maneuver result (HDF5, as kelvin simulate writes)", e.what()));
  }
}

}  // namespace

ManeuverFile ReadManeuverResult(const std::filesystem::path& path) {
  const data::H5Reader h5 = Open(path);
  ManeuverFile f;
  f.path = path.string();
  if (!h5.HasAttribute("/", "kelvin_schema")) {
    Fail(path, fmt::format("no attribute 'kelvin_schema': not a maneuver result (expected kelvin_schema = '{}', "
                           "as kelvin simulate writes)",
                           kManeuverSchema));
  }
  const std::string schema = h5.StringAttribute("/", "kelvin_schema");
  if (schema != kManeuverSchema) {
    Fail(path, fmt::format("attribute 'kelvin_schema' = '{}': not a maneuver result (expected '{}')", schema,
                           kManeuverSchema));
  }
  ManeuverResult& r = f.result;
  r.ship_name = h5.StringAttribute("/", "ship");
  const std::string maneuver = h5.StringAttribute("/", "maneuver");
  try {
    r.spec = ManeuverSpec::Parse(maneuver);
  } catch (const ArgumentError& e) {
    Fail(path, fmt::format("attribute 'maneuver': {}", e.what()));
  }
  if (h5.HasAttribute("/", "integrator")) f.integrator = h5.StringAttribute("/", "integrator");
  if (h5.HasAttribute("/", "source")) f.source = h5.StringAttribute("/", "source");
  r.Lpp = PositiveAttribute(h5, "Lpp", "m");
  r.approach_speed = PositiveAttribute(h5, "approach_speed", "m/s");
  r.approach_rps = PositiveAttribute(h5, "approach_rps", "1/s");

  static const char* const kColumns[] = {"time", "x", "y", "psi", "u", "v", "r", "rudder", "rps", "phase"};
  std::vector<data::Series> cols;
  for (const char* c : kColumns) {
    cols.push_back(h5.Read(std::string("trajectory/") + c));
    if (cols.back().values.size() != cols.front().values.size()) {
      Fail(path, fmt::format("'trajectory/{}' has {} values and 'trajectory/time' {}: expected one per time", c,
                             cols.back().values.size(), cols.front().values.size()));
    }
  }
  const std::size_t n = cols.front().values.size();
  if (n < 2) Fail(path, fmt::format("'trajectory/time' has {} samples: expected at least 2", n));
  for (std::size_t i = 0; i < n; ++i) {
    auto at = [&](int c) { return cols[static_cast<std::size_t>(c)].values[i]; };
    for (int c = 0; c < 10; ++c) {
      if (!std::isfinite(at(c))) {
        Fail(path, fmt::format("'trajectory/{}'[{}] = {}: expected a finite number", kColumns[c], i, at(c)));
      }
    }
    if (i > 0 && !(at(0) >= cols[0].values[i - 1])) {
      Fail(path, fmt::format("'trajectory/time'[{}] = {} s after {} s: expected non-decreasing times", i, at(0),
                             cols[0].values[i - 1]));
    }
    r.trajectory.Add({at(0), at(1), at(2), at(3), at(4), at(5), at(6), at(7), at(8)},
                     static_cast<int>(std::lround(at(9))));
  }
  if (h5.Has("execute_times")) r.execute_times = h5.Read("execute_times").values;

  if (h5.Has("metrics")) {
    for (const std::string& name : h5.List("metrics")) {
      const data::Series s = h5.Read("metrics/" + name);
      if (s.values.size() != 1) {
        Fail(path, fmt::format("'metrics/{}' has {} values: expected one", name, s.values.size()));
      }
      r.metrics.push_back({name, s.values[0], s.units, s.description});
    }
  }
  if (h5.Has("imo")) {
    constexpr std::string_view kPrefix = "IMO MSC.137(76): ", kSuffix = " [value, limit, pass]";
    for (const std::string& name : h5.List("imo")) {
      const data::Series s = h5.Read("imo/" + name);
      if (s.values.size() != 3) {
        Fail(path, fmt::format("'imo/{}' has {} values: expected [value, limit, pass]", name, s.values.size()));
      }
      std::string criterion = s.description;
      if (criterion.starts_with(kPrefix)) criterion.erase(0, kPrefix.size());
      if (criterion.ends_with(kSuffix)) criterion.erase(criterion.size() - kSuffix.size());
      r.verdicts.push_back({criterion, s.values[0], s.values[1], s.units, s.values[2] != 0});
    }
  }
  return f;
}

}  // namespace kelvin::sim
