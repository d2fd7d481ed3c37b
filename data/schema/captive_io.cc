#include "data/schema/captive_io.h"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <fstream>
#include <map>
#include <sstream>

#include "data/schema/atomic_file.h"
#include "data/schema/errors.h"
#include "data/schema/file_status.h"
#include "data/schema/h5_file.h"

namespace kelvin::data {

namespace fs = std::filesystem;

namespace {

constexpr std::array<std::string_view, 3> kChannelUnits = {"N", "N", "N m"};
constexpr std::array<std::string_view, 3> kChannelDescriptions = {
    "surge force in ship axes", "sway force in ship axes", "yaw moment about midship"};

// Motion attributes in file order; the value is read into the member.
struct MotionAttribute {
  std::string_view key;
  double MotionParameters::*member;
  std::string_view units;
};
constexpr std::array<MotionAttribute, 7> kMotionAttributes = {
    {{"U", &MotionParameters::U, "m/s"},
     {"beta", &MotionParameters::beta, "rad"},
     {"y_a", &MotionParameters::y_a, "m"},
     {"psi_a", &MotionParameters::psi_a, "rad"},
     {"omega", &MotionParameters::omega, "rad/s"},
     {"r_prime", &MotionParameters::r_prime, "-"},
     {"t_ramp", &MotionParameters::t_ramp, "s"}}};

struct ShipAttribute {
  std::string_view key;
  double CaptiveShip::*member;
};
constexpr std::array<ShipAttribute, 7> kShipAttributes = {{{"Lpp", &CaptiveShip::Lpp},
                                                           {"B", &CaptiveShip::B},
                                                           {"d", &CaptiveShip::d},
                                                           {"rho", &CaptiveShip::rho},
                                                           {"mass", &CaptiveShip::mass},
                                                           {"x_G", &CaptiveShip::x_G},
                                                           {"I_zG", &CaptiveShip::I_zG}}};

std::string Trim(std::string_view s) {
  const auto b = s.find_first_not_of(" \t\r");
  if (b == std::string_view::npos) return {};
  const auto e = s.find_last_not_of(" \t\r");
  return std::string(s.substr(b, e - b + 1));
}

// Units spelled "N m", "N*m", "N.m", "Nm" all mean newton metre.
std::string NormalizeUnits(std::string_view units) {
  std::string u = Trim(units);
  if (u == "N*m" || u == "N.m" || u == "Nm" || u == "N·m") return "N m";
  return u;
}

bool ParseRigidBodyInertia(const std::string& value, const std::string& where) {
  if (value == "included") return true;
  if (value == "excluded") return false;
  throw DataFileError(
      fmt::format("{}: attribute 'rigid_body_inertia' = '{}': expected 'included' or 'excluded'",
                  where, value));
}

double ParseNumber(const std::string& text, const std::string& where) {
  std::size_t used = 0;
  double value = 0;
  try {
    value = std::stod(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used == 0 || Trim(text.substr(used)).size() != 0) {
    throw DataFileError(fmt::format("{}: '{}' is not a number", where, text));
  }
  return value;
}

}  // namespace

void WriteCampaignH5(const CaptiveCampaign& campaign, const fs::path& path) {
  H5Writer w(path);
  WriteCampaignH5(campaign, w);
  w.Commit();
}

void WriteCampaignH5(const CaptiveCampaign& campaign, H5Writer& w) {
  w.SetAttribute("/", "schema", kCaptiveSchema);
  w.SetAttribute("/", "description", campaign.description);
  w.SetAttribute("/ship", "name", campaign.ship.name);
  for (const ShipAttribute& a : kShipAttributes)
    w.SetAttribute("/ship", std::string(a.key), campaign.ship.*a.member);
  for (const CaptiveRun& run : campaign.runs) {
    const std::string g = "/runs/" + run.name;
    w.SetAttribute(g, "kind", MotionKindName(run.motion.kind));
    for (const MotionAttribute& a : kMotionAttributes)
      w.SetAttribute(g, std::string(a.key), run.motion.*a.member);
    w.SetAttribute(g, "rigid_body_inertia",
                   run.includes_rigid_body_inertia ? "included" : "excluded");
    if (run.settled >= 0) {
      w.SetAttribute(g, "t_settle", run.t_settle);
      w.SetAttribute(g, "settled", static_cast<double>(run.settled));
      w.SetAttribute(g, "settle_change", run.settle_change);
    }
    w.DeclareSeries(g + "/time", "s", "time from the start of the prescribed motion");
    w.Append(g + "/time", run.time);
    for (int c = 0; c < 3; ++c) {
      const std::string name = g + "/" + std::string(kChannelNames[c]);
      w.DeclareSeries(name, kChannelUnits[c], kChannelDescriptions[c]);
      w.Append(name, run.force[c]);
    }
  }
}

CaptiveCampaign ReadCampaignH5(const fs::path& path) {
  if (!data::PathExists(path)) throw DataFileError(fmt::format("{}: no such file", path.string()));
  const H5Reader r(path);
  const std::string src = path.string();
  if (!r.HasAttribute("/", "schema") || r.StringAttribute("/", "schema") != kCaptiveSchema) {
    throw DataFileError(fmt::format(
        "{}: attribute 'schema' = '{}': expected '{}' (a kelvin captive campaign)", src,
        r.HasAttribute("/", "schema") ? r.StringAttribute("/", "schema") : "", kCaptiveSchema));
  }
  CaptiveCampaign c;
  if (r.HasAttribute("/", "description")) c.description = r.StringAttribute("/", "description");
  if (!r.Has("/ship"))
    throw DataFileError(fmt::format("{}: group '/ship' (ship data) is missing", src));
  if (r.HasAttribute("/ship", "name")) c.ship.name = r.StringAttribute("/ship", "name");
  for (const ShipAttribute& a : kShipAttributes) {
    if (!r.HasAttribute("/ship", std::string(a.key))) {
      throw DataFileError(fmt::format("{}: ship attribute '{}' is missing", src, a.key));
    }
    c.ship.*a.member = r.NumberAttribute("/ship", std::string(a.key));
  }
  if (!r.Has("/runs")) throw DataFileError(fmt::format("{}: group '/runs' is missing", src));
  for (const std::string& name : r.List("/runs")) {
    const std::string g = "/runs/" + name;
    CaptiveRun run;
    run.name = name;
    const std::string where = fmt::format("{}: run '{}'", src, name);
    if (!r.HasAttribute(g, "kind")) throw DataFileError(where + ": attribute 'kind' is missing");
    run.motion.kind = ParseMotionKind(r.StringAttribute(g, "kind"), where);
    for (const MotionAttribute& a : kMotionAttributes) {
      if (r.HasAttribute(g, std::string(a.key)))
        run.motion.*a.member = r.NumberAttribute(g, std::string(a.key));
    }
    if (!r.HasAttribute(g, "rigid_body_inertia")) {
      throw DataFileError(where +
                          ": attribute 'rigid_body_inertia' ('included' or 'excluded') is missing");
    }
    run.includes_rigid_body_inertia =
        ParseRigidBodyInertia(r.StringAttribute(g, "rigid_body_inertia"), where);
    if (r.HasAttribute(g, "settled")) {
      const double settled = r.NumberAttribute(g, "settled");
      if (settled != 0.0 && settled != 1.0) {
        throw DataFileError(fmt::format("{}: attribute 'settled' = {}: expected 0 or 1", where, settled));
      }
      run.settled = static_cast<int>(settled);
      run.t_settle = r.HasAttribute(g, "t_settle") ? r.NumberAttribute(g, "t_settle") : 0.0;
      run.settle_change = r.HasAttribute(g, "settle_change") ? r.NumberAttribute(g, "settle_change") : 0.0;
      if (!std::isfinite(run.t_settle) || run.t_settle < 0.0) {
        throw DataFileError(fmt::format("{}: attribute 't_settle' = {}: expected a time >= 0 s", where, run.t_settle));
      }
    }
    auto read_channel = [&](std::string_view channel, std::string_view units) {
      const std::string ds = g + "/" + std::string(channel);
      if (!r.Has(ds))
        throw DataFileError(fmt::format("{}: channel '{}' is missing", where, channel));
      Series s = r.Read(ds);
      if (s.cols != 1) {
        throw DataFileError(
            fmt::format("{}: channel '{}' has {} columns; expected 1", where, channel, s.cols));
      }
      if (NormalizeUnits(s.units) != units) {
        throw DataFileError(fmt::format("{}: channel '{}' has units '{}'; expected '{}'", where,
                                        channel, s.units, units));
      }
      return std::move(s.values);
    };
    run.time = read_channel("time", "s");
    for (int ch = 0; ch < 3; ++ch)
      run.force[ch] = read_channel(kChannelNames[ch], kChannelUnits[ch]);
    c.runs.push_back(std::move(run));
  }
  ValidateCampaign(c, src);
  return c;
}

void WriteRunCsv(const CaptiveRun& run, const fs::path& path) {
  std::string out = "# kelvin captive run (data/schema/captive_schema.md)\n";
  out += fmt::format("# run: {}\n# kind: {}\n", run.name, MotionKindName(run.motion.kind));
  for (const MotionAttribute& a : kMotionAttributes) {
    out += fmt::format("# {}: {:.17g}\n", a.key, run.motion.*a.member);
  }
  out += fmt::format("# rigid_body_inertia: {}\n",
                     run.includes_rigid_body_inertia ? "included" : "excluded");
  out += "time [s],X [N],Y [N],N [N m]\n";
  for (std::size_t i = 0; i < run.time.size(); ++i) {
    out += fmt::format("{:.17g},{:.17g},{:.17g},{:.17g}\n", run.time[i], run.force[0][i],
                       run.force[1][i], run.force[2][i]);
  }
  WriteFileAtomically(path, out);
}

CaptiveRun ReadRunCsv(const fs::path& path) {
  std::ifstream in(path);
  if (!in) throw DataFileError(fmt::format("{}: cannot open file", path.string()));
  return ReadRunCsv(in, path);
}

CaptiveRun ReadRunCsv(std::istream& in, const fs::path& path) {
  const std::string src = path.string();
  CaptiveRun run;
  run.name = path.stem().string();
  std::map<std::string, std::pair<std::string, int>> attributes;  // key -> (value, line)
  std::string line;
  int line_no = 0;
  std::vector<int> column_of(4, -1);  // time, X, Y, N -> CSV column
  int columns = 0;
  bool header_seen = false;
  auto where = [&](int l) { return fmt::format("{}:{}: run '{}'", src, l, run.name); };
  while (std::getline(in, line)) {
    ++line_no;
    const std::string t = Trim(line);
    if (t.empty()) continue;
    if (t[0] == '#') {
      // '# key: value' with an identifier key is an attribute; any other
      // comment line is free text.
      const auto colon = t.find(':');
      if (colon == std::string::npos || header_seen) continue;
      const std::string key = Trim(std::string_view(t).substr(1, colon - 1));
      if (key.empty() || !std::all_of(key.begin(), key.end(), [](char ch) {
            return std::isalnum(static_cast<unsigned char>(ch)) || ch == '_';
          })) {
        continue;
      }
      const std::string value = Trim(std::string_view(t).substr(colon + 1));
      if (key == "run") {
        run.name = value;
      } else {
        attributes[key] = {value, line_no};
      }
      continue;
    }
    std::vector<std::string> cells;
    std::stringstream ss(t);
    std::string cell;
    while (std::getline(ss, cell, ',')) cells.push_back(Trim(cell));
    if (!header_seen) {
      header_seen = true;
      columns = static_cast<int>(cells.size());
      const std::array<std::string_view, 4> names = {"time", "X", "Y", "N"};
      const std::array<std::string_view, 4> units = {"s", "N", "N", "N m"};
      for (int c = 0; c < columns; ++c) {
        const std::string& h = cells[c];
        const auto open = h.find('['), close = h.rfind(']');
        const std::string name = Trim(h.substr(0, open));
        const auto it = std::find(names.begin(), names.end(), name);
        if (it == names.end()) {
          throw DataFileError(
              fmt::format("{}: unknown column '{}'; expected time [s], X [N], Y [N], N [N m]",
                          where(line_no), h));
        }
        const int idx = static_cast<int>(it - names.begin());
        const std::string u =
            (open == std::string::npos || close == std::string::npos || close < open)
                ? std::string()
                : NormalizeUnits(h.substr(open + 1, close - open - 1));
        if (u != units[idx]) {
          throw DataFileError(fmt::format("{}: channel '{}' has units '{}'; expected '{}'",
                                          where(line_no), name, u, units[idx]));
        }
        column_of[idx] = c;
      }
      for (int i = 0; i < 4; ++i) {
        if (column_of[i] < 0) {
          throw DataFileError(fmt::format("{}: channel '{}' is missing", where(line_no), names[i]));
        }
      }
      continue;
    }
    if (static_cast<int>(cells.size()) != columns) {
      throw DataFileError(fmt::format("{}: row has {} values; the header has {} columns",
                                      where(line_no), cells.size(), columns));
    }
    const std::array<std::string_view, 4> names = {"time", "X", "Y", "N"};
    for (int i = 0; i < 4; ++i) {
      const std::string& text = cells[column_of[i]];
      // NaN / inf parse as numbers here; ValidateCampaign rejects them by channel.
      const double value =
          ParseNumber(text, fmt::format("{}: channel '{}'", where(line_no), names[i]));
      if (i == 0) {
        run.time.push_back(value);
      } else {
        run.force[i - 1].push_back(value);
      }
    }
  }
  if (!header_seen)
    throw DataFileError(
        fmt::format("{}: run '{}': no header row 'time [s],X [N],Y [N],N [N m]'", src, run.name));
  auto attr = [&](const std::string& key) -> const std::pair<std::string, int>* {
    auto it = attributes.find(key);
    return it == attributes.end() ? nullptr : &it->second;
  };
  const auto* kind = attr("kind");
  if (!kind)
    throw DataFileError(
        fmt::format("{}: run '{}': header line '# kind: ...' is missing", src, run.name));
  run.motion.kind = ParseMotionKind(kind->first, where(kind->second));
  for (const MotionAttribute& a : kMotionAttributes) {
    if (const auto* v = attr(std::string(a.key))) {
      run.motion.*a.member =
          ParseNumber(v->first, fmt::format("{}: attribute '{}'", where(v->second), a.key));
    }
  }
  const auto* rbi = attr("rigid_body_inertia");
  if (!rbi) {
    throw DataFileError(fmt::format(
        "{}: run '{}': header line '# rigid_body_inertia: included|excluded' is missing", src,
        run.name));
  }
  run.includes_rigid_body_inertia = ParseRigidBodyInertia(rbi->first, where(rbi->second));
  for (const auto& entry : attributes) {
    const std::string& key = entry.first;  // a plain reference: clang 14 cannot capture a binding
    const auto& value = entry.second;
    const bool known = key == "kind" || key == "rigid_body_inertia" ||
                       std::any_of(kMotionAttributes.begin(), kMotionAttributes.end(),
                                   [&](const MotionAttribute& a) { return a.key == key; });
    if (!known) {
      throw DataFileError(
          fmt::format("{}: unknown header key '{}'; valid keys: run, kind, U, beta, y_a, psi_a, "
                      "omega, r_prime, t_ramp, rigid_body_inertia",
                      where(value.second), key));
    }
  }
  return run;
}

}  // namespace kelvin::data
