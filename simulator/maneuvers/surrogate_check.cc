#include "simulator/maneuvers/surrogate_check.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <charconv>
#include <chrono>
#include <cmath>
#include <ctime>
#include <limits>
#include <set>
#include <utility>

#include "data/schema/atomic_file.h"
#include "data/schema/config.h"
#include "data/schema/errors.h"
#include "data/schema/file_status.h"
#include "data/schema/h5_file.h"
#include "simulator/maneuvers/identified_range.h"
#include "simulator/mmg/surrogate.h"

namespace kelvin::sim {

namespace {

namespace fs = std::filesystem;

constexpr double kDeg = M_PI / 180.0;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

constexpr const char* kToleranceForms =
    "<metric>=<number>% (relative to the reference), <metric>=<number><unit> (m, s, deg, deg/s, m/s: absolute), "
    "<metric>=<number> (absolute, nondimensional metrics) or <metric>=none";

MetricTolerance Relative(double percent) {
  return {MetricTolerance::Kind::kRelative, percent / 100.0, "", fmt::format("{:g}%", percent)};
}
MetricTolerance Absolute(double value, std::string unit) {
  return {MetricTolerance::Kind::kAbsolute, value, unit, fmt::format("{:g}{}", value, unit)};
}

std::string_view Trim(std::string_view s) {
  while (!s.empty() && s.front() == ' ') s.remove_prefix(1);
  while (!s.empty() && s.back() == ' ') s.remove_suffix(1);
  return s;
}

std::string Iso8601Now() {
  const std::time_t now = std::chrono::system_clock::to_time_t(std::chrono::system_clock::now());
  std::tm utc{};
  gmtime_r(&now, &utc);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", &utc);
  return buf;
}

// Execute time of a recorded maneuver: the first rudder execute, else the
// first sample past the approach phase, else the start.
double ExecuteTime(const ManeuverResult& r) {
  if (!r.execute_times.empty()) return r.execute_times.front();
  const auto& phases = r.trajectory.phases();
  for (std::size_t i = 0; i < phases.size(); ++i) {
    if (phases[i] != static_cast<int>(ManeuverPhase::kApproach)) return r.trajectory[i].t;
  }
  return r.trajectory[0].t;
}

TrackErrors CompareTracks(const ManeuverResult& ref, const ManeuverResult& sur) {
  TrackErrors e;
  const double t0r = ExecuteTime(ref), t0s = ExecuteTime(sur);
  const Trajectory& tr = ref.trajectory;
  const Trajectory& ts = sur.trajectory;
  const TrajectorySample o_r = tr.At(t0r), o_s = ts.At(t0s);
  const double span = std::min(tr[tr.size() - 1].t - t0r, ts[ts.size() - 1].t - t0s);
  // Position in axes of the position and heading at execute.
  auto local = [](const TrajectorySample& s, const TrajectorySample& o) {
    const double dx = s.x - o.x, dy = s.y - o.y;
    return std::pair{dx * std::cos(o.psi) + dy * std::sin(o.psi), -dx * std::sin(o.psi) + dy * std::cos(o.psi)};
  };
  auto add = [&](const TrajectorySample& a, double tau) {
    const TrajectorySample b = ts.At(t0s + tau);
    const auto [ar, cr] = local(a, o_r);
    const auto [as, cs] = local(b, o_s);
    e.time.push_back(tau);
    e.position_error.push_back(std::hypot(as - ar, cs - cr));
    e.heading_error.push_back((b.psi - o_s.psi) - (a.psi - o_r.psi));
  };
  for (std::size_t i = 0; i < tr.size(); ++i) {
    const double tau = tr[i].t - t0r;
    if (tau < 0) continue;
    if (tau > span) break;
    if (e.time.empty() && tau > 0) add(o_r, 0.0);  // an execute between samples starts the comparison
    add(tr[i], tau);
  }
  double int_p = 0, int_h = 0;
  for (std::size_t i = 0; i < e.time.size(); ++i) {
    e.max_position = std::max(e.max_position, e.position_error[i]);
    e.max_heading = std::max(e.max_heading, std::abs(e.heading_error[i]));
    if (i > 0) {
      const double dt = e.time[i] - e.time[i - 1];
      int_p +=
          0.5 * dt * (e.position_error[i] * e.position_error[i] + e.position_error[i - 1] * e.position_error[i - 1]);
      int_h += 0.5 * dt * (e.heading_error[i] * e.heading_error[i] + e.heading_error[i - 1] * e.heading_error[i - 1]);
    }
  }
  const double T = e.time.empty() ? 0 : e.time.back() - e.time.front();
  if (T > 0) {
    e.rms_position = std::sqrt(int_p / T);
    e.rms_heading = std::sqrt(int_h / T);
  } else {
    e.rms_position = e.max_position;
    e.rms_heading = e.max_heading;
  }
  return e;
}

const MetricRow* FindMetric(const std::vector<MetricRow>& rows, const std::string& name) {
  for (const MetricRow& m : rows) {
    if (m.name == name) return &m;
  }
  return nullptr;
}

void Judge(MetricComparison& c) {
  const bool both = c.reference && c.surrogate && std::isfinite(*c.reference) && std::isfinite(*c.surrogate);
  c.difference = both ? *c.surrogate - *c.reference : kNaN;
  c.relative = both && *c.reference != 0 ? c.difference / std::abs(*c.reference) : kNaN;
  if (!c.tolerance || c.tolerance->kind == MetricTolerance::Kind::kNone) return;
  c.allowed = c.tolerance->kind == MetricTolerance::Kind::kRelative
                  ? c.tolerance->value * (c.reference && std::isfinite(*c.reference) ? std::abs(*c.reference) : 0)
                  : c.tolerance->value;
  if (!both) {
    c.used = kInf;
  } else if (c.allowed > 0) {
    c.used = std::abs(c.difference) / c.allowed;
  } else {
    c.used = c.difference == 0 ? 0 : kInf;
  }
  c.verdict = c.used <= 1 ? MetricComparison::Verdict::kPass : MetricComparison::Verdict::kFail;
}

std::string Number(const std::optional<double>& v) { return v ? fmt::format("{:.6g}", *v) : "missing"; }
std::string Signed(double v, const char* suffix = "") {
  return std::isfinite(v) ? fmt::format("{:+.4g}{}", v, suffix) : "-";
}
std::string Percent(double rel) { return std::isfinite(rel) ? fmt::format("{:+.2f}%", 100 * rel) : "-"; }
std::string VerdictName(MetricComparison::Verdict v) {
  switch (v) {
    case MetricComparison::Verdict::kPass:
      return "pass";
    case MetricComparison::Verdict::kFail:
      return "FAIL";
    case MetricComparison::Verdict::kNone:
      return "";
  }
  return "";
}
std::string ToleranceText(const MetricComparison& c) {
  return c.tolerance && c.tolerance->kind != MetricTolerance::Kind::kNone ? c.tolerance->text : "";
}
std::string UnitSuffix(const std::string& unit) { return unit == "1" ? "" : " " + unit; }

const MetricComparison* Worst(const ManeuverCheck& m) {
  const MetricComparison* worst = nullptr;
  for (const MetricComparison& c : m.metrics) {
    if (c.verdict == MetricComparison::Verdict::kNone) continue;
    if (!worst || c.used > worst->used) worst = &c;
  }
  return worst;
}

std::string SummaryLine(const ManeuverCheck& m) {
  const MetricComparison* w = Worst(m);
  const double L = m.surrogate.Lpp;
  std::string s =
      fmt::format("{} against {}: {}", m.surrogate.spec.ToString(), m.reference.path, m.passed ? "pass" : "FAIL");
  if (w) {
    s += fmt::format("; worst {}: {} vs {}{} ({}{}, {}; tolerance {})", w->name, Number(w->surrogate),
                     Number(w->reference), UnitSuffix(w->unit), Signed(w->difference), UnitSuffix(w->unit),
                     Percent(w->relative), w->tolerance->text);
  }
  s += fmt::format("; track error max {:.3g} m ({:.3g} L), heading max {:.3g} deg", m.track.max_position,
                   m.track.max_position / L, m.track.max_heading / kDeg);
  return s;
}

std::string Stem(const fs::path& p) {
  std::string s = p.stem().string();
  for (char& c : s) {
    if (c == ':' || c == '/' || c == ' ') c = '_';
  }
  return s;
}

}  // namespace

CheckTolerances DefaultCheckTolerances() {
  return {{"advance", Relative(5)},
          {"tactical_diameter", Relative(5)},
          {"first_overshoot", Absolute(2, "deg")},
          {"second_overshoot", Absolute(2, "deg")}};
}

CheckTolerances ParseCheckTolerances(std::string_view text, CheckTolerances base, std::string_view option) {
  std::size_t start = 0;
  while (start <= text.size()) {
    const std::size_t comma = text.find(',', start);
    const std::string_view item =
        Trim(text.substr(start, comma == std::string_view::npos ? std::string_view::npos : comma - start));
    start = comma == std::string_view::npos ? text.size() + 1 : comma + 1;
    if (item.empty()) continue;
    auto bad = [&](const std::string& why) {
      throw ArgumentError(fmt::format("{} '{}': {}; expected {}", option, item, why, kToleranceForms));
    };
    const std::size_t eq = item.find('=');
    if (eq == std::string_view::npos) bad("no '='");
    const std::string name(Trim(item.substr(0, eq)));
    const std::string_view value = Trim(item.substr(eq + 1));
    if (name.empty()) bad("no metric name");
    MetricTolerance tol;
    if (value == "none") {
      tol = {MetricTolerance::Kind::kNone, 0, "", "none"};
    } else {
      double v = 0;
      const auto res = std::from_chars(value.data(), value.data() + value.size(), v);
      if (res.ec != std::errc() || value.empty()) bad(fmt::format("'{}' is not a number", value));
      if (!std::isfinite(v) || v < 0) bad(fmt::format("{} is not a tolerance (>= 0)", v));
      const std::string unit(
          Trim(std::string_view(res.ptr, static_cast<std::size_t>(value.data() + value.size() - res.ptr))));
      if (unit == "%") {
        tol = Relative(v);
      } else if (unit.empty() || unit == "m" || unit == "s" || unit == "deg" || unit == "deg/s" || unit == "m/s") {
        tol = Absolute(v, unit);
      } else {
        bad(fmt::format("unknown unit '{}'", unit));
      }
    }
    if (name == "overshoot") {
      base["first_overshoot"] = tol;
      base["second_overshoot"] = tol;
    } else {
      base[name] = tol;
    }
  }
  return base;
}

SurrogateCheck RunSurrogateCheck(const SurrogateCheckOptions& o) {
  if (!data::PathExists(o.derivatives)) {
    throw ArgumentError(fmt::format("derivative set {}: file not found", o.derivatives.string()));
  }
  if (!data::PathExists(o.ship)) throw ArgumentError(fmt::format("--ship {}: file not found", o.ship.string()));
  if (o.references.empty()) {
    throw ArgumentError("--against: no reference file given; expected one or more maneuver result files (HDF5)");
  }
  for (const fs::path& r : o.references) {
    if (!data::PathExists(r)) throw ArgumentError(fmt::format("--against {}: file not found", r.string()));
  }
  std::vector<ManeuverSpec> asked;
  for (const std::string& m : o.maneuvers) asked.push_back(ManeuverSpec::Parse(m));

  const DerivativeSet set = LoadDerivativeSet(o.derivatives);
  const ShipParameters file_ship = LoadShip(o.ship);
  const ShipParameters ship = SurrogateShip(file_ship, o.ship.string(), &set);
  const MmgModel<double> model(ship);

  SurrogateCheck check;
  check.derivatives_file = o.derivatives.string();
  check.ship_file = o.ship.string();
  check.set_name = set.name;
  check.integrator = o.integrator.method == SimulatorOptions::Method::kAdaptive ? "cvode" : "fixed";

  std::vector<ManeuverFile> refs;
  for (const fs::path& path : o.references) {
    ManeuverFile f = ReadManeuverResult(path);
    const ManeuverResult& r = f.result;
    if (r.ship_name != ship.name) {
      throw ArgumentError(fmt::format(
          "--against {}: attribute 'ship' = '{}': expected a maneuver of ship '{}', the ship of {}the ship file {}",
          path.string(), r.ship_name, ship.name,
          set.ship.empty() ? "" : fmt::format("the derivative set {} and of ", o.derivatives.string()),
          o.ship.string()));
    }
    if (std::abs(r.Lpp - ship.principal.Lpp) > 1e-9 * ship.principal.Lpp) {
      throw ArgumentError(
          fmt::format("--against {}: attribute 'Lpp' = {:g} m: expected the Lpp of the ship file {} "
                      "({:g} m), a reference at the ship file's scale",
                      path.string(), r.Lpp, o.ship.string(), ship.principal.Lpp));
    }
    if (!asked.empty()) {
      const std::string m = r.spec.ToString();
      const bool found =
          std::any_of(asked.begin(), asked.end(), [&](const ManeuverSpec& a) { return a.ToString() == m; });
      if (!found) {
        std::vector<std::string> names;
        for (const ManeuverSpec& a : asked) names.push_back(a.ToString());
        throw ArgumentError(
            fmt::format("--against {}: attribute 'maneuver' = '{}': expected the maneuver --maneuver "
                        "asks for ({})",
                        path.string(), m, fmt::join(names, ", ")));
      }
    }
    refs.push_back(std::move(f));
  }
  for (const ManeuverSpec& a : asked) {
    const std::string m = a.ToString();
    if (std::none_of(refs.begin(), refs.end(), [&](const ManeuverFile& f) { return f.result.spec.ToString() == m; })) {
      std::vector<std::string> have;
      for (const ManeuverFile& f : refs) have.push_back(fmt::format("{} ({})", f.path, f.result.spec.ToString()));
      throw ArgumentError(
          fmt::format("--maneuver {}: no reference file is of this maneuver; expected one among "
                      "--against: {}",
                      m, fmt::join(have, ", ")));
    }
  }

  // The surrogate runs.
  for (ManeuverFile& f : refs) {
    ManeuverCheck mc;
    RunOptions run;
    run.integrator = o.integrator;
    run.approach_speed = f.result.approach_speed;
    run.approach_rps = f.result.approach_rps;
    mc.surrogate = RunManeuver(model, f.result.spec, run);
    mc.surrogate.source = "surrogate";
    mc.self_propulsion_rps = SelfPropulsionRps(model, f.result.approach_speed);
    mc.reference = std::move(f);
    check.maneuvers.push_back(std::move(mc));
  }

  // Tolerances must name metrics of these maneuvers, in their units.
  std::set<std::string> all_metrics;
  std::map<std::string, std::string> units;
  for (const ManeuverCheck& mc : check.maneuvers) {
    for (const auto* rows : {&mc.surrogate.metrics, &mc.reference.result.metrics}) {
      for (const MetricRow& m : *rows) {
        all_metrics.insert(m.name);
        units.emplace(m.name, m.unit);
      }
    }
  }
  const CheckTolerances defaults = DefaultCheckTolerances();
  const std::vector<std::string> names(all_metrics.begin(), all_metrics.end());
  for (const auto& [name, tol] : o.tolerances) {
    const auto u = units.find(name);
    if (u == units.end()) {
      if (defaults.count(name)) continue;  // a default for maneuvers not checked here
      const auto guess = data::ClosestMatch(name, names);
      throw ArgumentError(fmt::format(
          "--tolerances '{}={}': no maneuver checked has a metric '{}'; its metrics: "
          "{}{}",
          name, tol.text, name, fmt::join(names, ", "), guess ? fmt::format(" (did you mean '{}'?)", *guess) : ""));
    }
    if (tol.kind != MetricTolerance::Kind::kAbsolute) continue;
    const bool ok = tol.unit == u->second || (tol.unit.empty() && u->second == "1");
    if (!ok) {
      throw ArgumentError(fmt::format("--tolerances '{}={}': {} is in {}; expected a percentage or a value in {}", name,
                                      tol.text, name, u->second == "1" ? "units of 1 (nondimensional)" : u->second,
                                      u->second == "1" ? "a bare number" : u->second));
    }
  }

  // Metric by metric.
  check.passed = true;
  std::vector<std::string> summary;
  for (ManeuverCheck& mc : check.maneuvers) {
    const auto& ref_rows = mc.reference.result.metrics;
    std::vector<std::string> order;
    for (const MetricRow& m : mc.surrogate.metrics) order.push_back(m.name);
    for (const MetricRow& m : ref_rows) {
      if (!FindMetric(mc.surrogate.metrics, m.name)) order.push_back(m.name);
    }
    bool any_verdict = false;
    for (const std::string& name : order) {
      MetricComparison c;
      c.name = name;
      const MetricRow* s = FindMetric(mc.surrogate.metrics, name);
      const MetricRow* r = FindMetric(ref_rows, name);
      const MetricRow* any = s ? s : r;
      c.unit = any->unit;
      c.description = any->description;
      if (s) c.surrogate = s->value;
      if (r) c.reference = r->value;
      if (const auto t = o.tolerances.find(name); t != o.tolerances.end()) c.tolerance = t->second;
      Judge(c);
      any_verdict = any_verdict || c.verdict != MetricComparison::Verdict::kNone;
      mc.metrics.push_back(std::move(c));
    }
    if (!any_verdict) {
      std::vector<std::string> with;
      for (const auto& [name, tol] : o.tolerances) {
        if (tol.kind != MetricTolerance::Kind::kNone) with.push_back(name);
      }
      throw ArgumentError(fmt::format(
          "--tolerances: none of the metrics of {} ({}) has a tolerance (tolerances are set for: {}); expected at "
          "least one, e.g. --tolerances {}=5%",
          mc.surrogate.spec.ToString(), mc.reference.path,
          with.empty() ? "none" : fmt::format("{}", fmt::join(with, ", ")),
          order.empty() ? "<metric>" : order.front()));
    }
    mc.track = CompareTracks(mc.reference.result, mc.surrogate);
    const std::string name = mc.surrogate.spec.ToString();
    for (const auto& [what, trajectory] :
         {std::pair{fmt::format("the {} reference of {}", mc.reference.source, name), &mc.reference.result.trajectory},
          std::pair{fmt::format("the surrogate's {}", name), &mc.surrogate.trajectory}}) {
      std::string w = ExtrapolationWarning(set, *trajectory, ship.principal.Lpp, what);
      if (!w.empty()) mc.warnings.push_back(std::move(w));
    }
    mc.passed = std::none_of(mc.metrics.begin(), mc.metrics.end(),
                             [](const MetricComparison& c) { return c.verdict == MetricComparison::Verdict::kFail; });
    mc.summary = SummaryLine(mc);
    check.passed = check.passed && mc.passed;
    summary.push_back(mc.summary);
  }

  std::vector<std::string> ref_names;
  for (const fs::path& p : o.references) ref_names.push_back(p.string());
  check.section.passed = check.passed;
  check.section.reference = fmt::format("{}", fmt::join(ref_names, ", "));
  check.section.date = o.date.empty() ? Iso8601Now() : o.date;
  check.section.summary = fmt::format("{}", fmt::join(summary, "\n"));
  return check;
}

std::string FormatCheckTable(const SurrogateCheck& check) {
  std::string s = fmt::format("kelvin check: derivative set {} ({}) in ship file {}\n", check.derivatives_file,
                              check.set_name.empty() ? "unnamed" : check.set_name, check.ship_file);
  for (const ManeuverCheck& m : check.maneuvers) {
    const ManeuverResult& r = m.reference.result;
    s += fmt::format(
        "\n{} against {} ({}): approach {:.4g} m/s, {:.5g} rps (the surrogate's self-propulsion: "
        "{:.5g} rps)\n",
        r.spec.ToString(), m.reference.path, m.reference.source, r.approach_speed, r.approach_rps,
        m.self_propulsion_rps);
    s += fmt::format("  {:<26} {:<6} {:>12} {:>12} {:>12} {:>10} {:>10} {}\n", "metric", "unit", "reference",
                     "surrogate", "difference", "relative", "tolerance", "verdict");
    for (const MetricComparison& c : m.metrics) {
      s += fmt::format("  {:<26} {:<6} {:>12} {:>12} {:>12} {:>10} {:>10} {}\n", c.name, c.unit, Number(c.reference),
                       Number(c.surrogate), Signed(c.difference), Percent(c.relative), ToleranceText(c),
                       VerdictName(c.verdict));
    }
    const TrackErrors& t = m.track;
    const double L = r.Lpp;
    s += fmt::format(
        "  track from execute ({} samples, {:.4g} s): position error max {:.4g} m ({:.4g} L), RMS {:.4g} "
        "m ({:.4g} L); heading error max {:.4g} deg, RMS {:.4g} deg\n",
        t.time.size(), t.time.empty() ? 0.0 : t.time.back(), t.max_position, t.max_position / L, t.rms_position,
        t.rms_position / L, t.max_heading / kDeg, t.rms_heading / kDeg);
    for (const std::string& w : m.warnings) s += fmt::format("  {}\n", w);
    s += fmt::format("  => {}\n", m.passed ? "PASS" : "FAIL");
  }
  s += fmt::format(
      "\ncheck {}: {} maneuver(s), {} failed\n", check.passed ? "PASSED" : "FAILED", check.maneuvers.size(),
      std::count_if(check.maneuvers.begin(), check.maneuvers.end(), [](const ManeuverCheck& m) { return !m.passed; }));
  return s;
}

fs::path SurrogateRunPath(const SurrogateCheck& check, std::size_t index, const fs::path& dir) {
  return dir / fmt::format("surrogate_{}_{}.h5", index, Stem(check.maneuvers.at(index).reference.path));
}

void WriteCheckReport(const SurrogateCheck& check, const fs::path& dir) {
  fs::create_directories(dir);
  // Markdown.
  std::string md = fmt::format("# Surrogate check of {}\n\n", check.derivatives_file);
  md += fmt::format("- derivative set: `{}` ({})\n- ship file: `{}`\n- date: {}\n- result: **{}**\n",
                    check.derivatives_file, check.set_name.empty() ? "unnamed" : check.set_name, check.ship_file,
                    check.section.date, check.passed ? "PASSED" : "FAILED");
  for (std::size_t i = 0; i < check.maneuvers.size(); ++i) {
    const ManeuverCheck& m = check.maneuvers[i];
    const ManeuverResult& r = m.reference.result;
    md += fmt::format("\n## {} against `{}` ({})\n\n", r.spec.ToString(), m.reference.path, m.reference.source);
    md += fmt::format(
        "Approach {:.4g} m/s at {:.5g} rps (the surrogate's self-propulsion at this speed: {:.5g} rps). "
        "Result: **{}**.\n\n",
        r.approach_speed, r.approach_rps, m.self_propulsion_rps, m.passed ? "pass" : "FAIL");
    md += "| metric | unit | reference | surrogate | difference | relative | tolerance | verdict |\n";
    md += "| --- | --- | ---: | ---: | ---: | ---: | ---: | --- |\n";
    for (const MetricComparison& c : m.metrics) {
      md += fmt::format("| {} | {} | {} | {} | {} | {} | {} | {} |\n", c.name, c.unit, Number(c.reference),
                        Number(c.surrogate), Signed(c.difference), Percent(c.relative), ToleranceText(c),
                        VerdictName(c.verdict));
    }
    const TrackErrors& t = m.track;
    const double L = r.Lpp;
    md += fmt::format("\nAlong the track, from the rudder execute ({} samples over {:.4g} s):\n\n", t.time.size(),
                      t.time.empty() ? 0.0 : t.time.back());
    md += "| error | max | RMS |\n| --- | ---: | ---: |\n";
    md += fmt::format("| position (m) | {:.4g} | {:.4g} |\n", t.max_position, t.rms_position);
    md += fmt::format("| position / Lpp | {:.4g} | {:.4g} |\n", t.max_position / L, t.rms_position / L);
    md += fmt::format("| heading (deg) | {:.4g} | {:.4g} |\n", t.max_heading / kDeg, t.rms_heading / kDeg);
    md += fmt::format("\nOverlay: `tools/plot_maneuver.py {} --overlay {}`\n", m.reference.path,
                      SurrogateRunPath(check, i, dir).string());
  }
  md += "\nTrack errors against time: `track_errors.h5`.\n";
  data::WriteFileAtomically(dir / "check_report.md", md);

  // Track errors.
  data::H5Writer h5(dir / "track_errors.h5");
  h5.SetAttribute("/", "kelvin_schema", "surrogate_check/1");
  h5.SetAttribute("/", "derivative_set", check.derivatives_file);
  h5.SetAttribute("/", "ship_file", check.ship_file);
  h5.SetAttribute("/", "passed", check.passed ? 1.0 : 0.0);
  h5.SetAttribute("/", "date", check.section.date);
  for (std::size_t i = 0; i < check.maneuvers.size(); ++i) {
    const ManeuverCheck& m = check.maneuvers[i];
    const TrackErrors& t = m.track;
    const std::string g = fmt::format("maneuver_{}", i);
    const double L = m.reference.result.Lpp;
    std::vector<double> over_L(t.position_error.size()), heading_deg(t.heading_error.size());
    for (std::size_t k = 0; k < over_L.size(); ++k) over_L[k] = t.position_error[k] / L;
    for (std::size_t k = 0; k < heading_deg.size(); ++k) heading_deg[k] = t.heading_error[k] / kDeg;
    h5.WriteArray(g + "/time", t.time, {t.time.size()}, "s", "time since the rudder execute");
    h5.WriteArray(g + "/position_error", t.position_error, {t.time.size()}, "m",
                  "distance between reference and surrogate midship, each in axes of its position and heading at "
                  "execute");
    h5.WriteArray(g + "/position_error_over_L", over_L, {t.time.size()}, "1", "position error / Lpp");
    h5.WriteArray(g + "/heading_error", heading_deg, {t.time.size()}, "deg",
                  "surrogate heading change - reference heading change since execute");
    h5.SetAttribute(g, "reference", m.reference.path);
    h5.SetAttribute(g, "reference_source", m.reference.source);
    h5.SetAttribute(g, "maneuver", m.surrogate.spec.ToString());
    h5.SetAttribute(g, "surrogate", SurrogateRunPath(check, i, dir).string());
    h5.SetAttribute(g, "max_position_error", t.max_position);
    h5.SetAttribute(g, "rms_position_error", t.rms_position);
    h5.SetAttribute(g, "max_heading_error_deg", t.max_heading / kDeg);
    h5.SetAttribute(g, "rms_heading_error_deg", t.rms_heading / kDeg);
    h5.SetAttribute(g, "passed", m.passed ? 1.0 : 0.0);
    h5.SetAttribute(g, "summary", m.summary);
  }
  h5.Commit();

  // The surrogate runs, in the maneuver schema.
  for (std::size_t i = 0; i < check.maneuvers.size(); ++i) {
    const ManeuverCheck& m = check.maneuvers[i];
    const fs::path path = SurrogateRunPath(check, i, dir);
    WriteManeuverResult(m.surrogate, path, check.integrator);
    data::H5Writer tag(path, data::H5Writer::Mode::kAppend);
    tag.SetAttribute("/", "derivative_set", check.derivatives_file);
    tag.SetAttribute("/", "reference", m.reference.path);
    tag.Commit();
  }
}

}  // namespace kelvin::sim
