#include "cfd/verification/gci_study.h"

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <sstream>

#include "cfd/run/run_case.h"
#include "data/schema/atomic_file.h"
#include "data/schema/config.h"
#include "data/schema/errors.h"
#include "data/schema/file_status.h"
#include "data/schema/h5_file.h"

namespace kelvin::cfd {
namespace {

namespace fs = std::filesystem;

const char* ConvergenceName(Convergence c) {
  return c == Convergence::kMonotonic ? "monotonic" : c == Convergence::kOscillatory ? "oscillatory" : "divergent";
}

// Short names of the outputs a case writes, and their datasets in history.h5.
const std::map<std::string, std::string>& KnownOutputs() {
  static const std::map<std::string, std::string> known = {
      {"C_T", "resistance/C_T"},     {"C_F", "resistance/C_F"},     {"C_P", "resistance/C_P"},
      {"X", "captive/X"},            {"Y", "captive/Y"},            {"N", "captive/N"},
      {"X_prime", "captive/X_prime"}, {"Y_prime", "captive/Y_prime"}, {"N_prime", "captive/N_prime"}};
  return known;
}

constexpr const char* kRunRecord = "run.yaml";

std::string ReadText(const fs::path& file) {
  std::ifstream in(file);
  if (!in) throw DataFileError(fmt::format("cannot read '{}'", file.string()));
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

void WriteRunRecord(const GridRunRecord& r, const fs::path& poly_mesh) {
  std::string t = "# kelvin gci: one grid's run of the case (a finished run is reused)\n";
  t += "status: completed\n";
  t += fmt::format("level: {}\ncells: {}\nh: {:.9g}\npoly_mesh: \"{}\"\n", r.level, r.cells, r.h, poly_mesh.string());
  t += fmt::format("steps: {}\nouter_iterations: {}\ncpu_seconds: {:.6g}\n", r.steps, r.outer_iterations,
                   r.cpu_seconds);
  t += fmt::format("steady: {}\nsteady_converged: {}\n", r.steady, r.steady_converged);
  data::WriteFileAtomically(r.directory / kRunRecord, t);
}

// A finished run of this grid, or false.
bool ReadRunRecord(GridRunRecord& r) {
  const fs::path file = r.directory / kRunRecord;
  if (!fs::exists(file) || !fs::exists(r.directory / "history.h5")) return false;
  const data::ConfigNode n = data::ConfigNode::LoadFile(file);
  if (n.Get<std::string>("status", "") != "completed") return false;
  if (std::lround(n.Get<double>("cells", -1.0)) != r.cells) return false;  // another grid was run here
  r.steps = n.Get<int>("steps", 0);
  r.outer_iterations = n.Get<int>("outer_iterations", 0);
  r.cpu_seconds = n.Get<double>("cpu_seconds", 0.0);
  r.steady = n.Get<bool>("steady", false);
  r.steady_converged = n.Get<bool>("steady_converged", false);
  return true;
}

}  // namespace

std::vector<std::string> SplitOutputNames(const std::vector<std::string>& args) {
  std::vector<std::string> names;
  for (const std::string& arg : args) {
    std::istringstream in(arg + ",");
    std::string item;
    while (std::getline(in, item, ',')) {
      const auto b = item.find_first_not_of(' '), e = item.find_last_not_of(' ');
      if (b == std::string::npos) {
        throw ArgumentError(fmt::format("--outputs '{}': an empty output name (expected e.g. C_T,X,Y)", arg));
      }
      names.push_back(item.substr(b, e - b + 1));
    }
  }
  if (names.empty()) throw ArgumentError("--outputs: name at least one output (e.g. C_T)");
  return names;
}

std::vector<FamilyGrid> ParseFamilyTable(const std::string& text, const std::string& source) {
  std::vector<FamilyGrid> grids;
  std::istringstream in(text);
  std::string line;
  int line_number = 0;
  bool header = false;
  while (std::getline(in, line)) {
    ++line_number;
    if (line.empty() || line[0] == '#') continue;
    if (!header) {
      if (line.rfind("grid cells h_m", 0) != 0) {
        throw DataFileError(fmt::format("{}:{}: expected the header 'grid cells h_m ...' of a grid family table "
                                        "(written by kelvin mesh --family), got '{}'",
                                        source, line_number, line));
      }
      header = true;
      continue;
    }
    std::istringstream row(line);
    FamilyGrid g;
    if (!(row >> g.level >> g.cells >> g.h) || g.cells <= 0 || !(g.h > 0.0) || !std::isfinite(g.h)) {
      throw DataFileError(fmt::format("{}:{}: expected 'level cells h_m ...' with cells > 0 and h_m > 0, got '{}'",
                                      source, line_number, line));
    }
    if (g.level != static_cast<int>(grids.size()) + 1) {
      throw DataFileError(fmt::format("{}:{}: grid level {} where level {} was expected (grid 1 finest, in order)",
                                      source, line_number, g.level, grids.size() + 1));
    }
    grids.push_back(g);
  }
  if (!header) throw DataFileError(fmt::format("{}: no grid family table (header 'grid cells h_m ...')", source));
  return grids;
}

std::vector<FamilyGrid> ReadGridFamily(const fs::path& dir, int family, double ratio_tolerance) {
  if (family < 3) {
    throw ArgumentError(fmt::format("--family {}: a GCI study needs three grids (--family 3)", family));
  }
  const fs::path table = dir / "family.txt";
  if (!data::IsExistingDirectory(dir)) {
    throw DataFileError(fmt::format("grid family directory '{}' does not exist (make it with kelvin mesh "
                                    "mesh.yaml --family {} -o DIR)",
                                    dir.string(), family));
  }
  if (!data::PathExists(table)) {
    throw DataFileError(fmt::format("'{}' is missing: '{}' is not a grid family written by kelvin mesh --family",
                                    table.string(), dir.string()));
  }
  std::vector<FamilyGrid> grids = ParseFamilyTable(ReadText(table), table.string());
  if (static_cast<int>(grids.size()) < family) {
    throw DataFileError(fmt::format("{}: lists {} grid(s), the study asks for {} (--family {})", table.string(),
                                    grids.size(), family, family));
  }
  grids.resize(family);
  for (FamilyGrid& g : grids) {
    g.poly_mesh = dir / fmt::format("grid{}", g.level) / "constant" / "polyMesh";
    if (!data::PathExists(g.poly_mesh / "owner")) {
      throw DataFileError(fmt::format("{}: grid {} is listed but '{}' holds no polyMesh", table.string(), g.level,
                                      g.poly_mesh.string()));
    }
  }
  for (std::size_t i = 1; i < grids.size(); ++i) {
    if (!(grids[i].h > grids[i - 1].h)) {
      throw DataFileError(fmt::format("{}: grid {} (h = {:.6g} m) is not coarser than grid {} (h = {:.6g} m)",
                                      table.string(), grids[i].level, grids[i].h, grids[i - 1].level,
                                      grids[i - 1].h));
    }
  }
  for (std::size_t i = 2; i < grids.size(); ++i) {
    const double r_fine = grids[i - 1].h / grids[i - 2].h, r_coarse = grids[i].h / grids[i - 1].h;
    if (std::abs(r_coarse / r_fine - 1.0) > ratio_tolerance) {
      throw DataFileError(fmt::format(
          "{}: non-constant refinement ratio: h{}/h{} = {:.4f} but h{}/h{} = {:.4f} (they may differ by at most "
          "{:.3g}%; make the family with kelvin mesh --family and a single family.ratio)",
          table.string(), grids[i - 1].level, grids[i - 2].level, r_fine, grids[i].level, grids[i - 1].level,
          r_coarse, 100 * ratio_tolerance));
    }
  }
  return grids;
}

double ExtractOutput(const fs::path& history, const std::string& name, int average) {
  if (average < 1) throw ArgumentError(fmt::format("--average {}: expected a number of steps >= 1", average));
  if (!data::PathExists(history)) {
    throw DataFileError(fmt::format("'{}' is missing (the run did not write its history)", history.string()));
  }
  const data::H5Reader h5(history);
  std::string dataset = name;
  int column = -1;
  if (const auto it = KnownOutputs().find(name); it != KnownOutputs().end()) {
    dataset = it->second;
  } else if (const auto colon = name.rfind(':'); colon != std::string::npos) {
    dataset = name.substr(0, colon);
    try {
      std::size_t used = 0;
      column = std::stoi(name.substr(colon + 1), &used);
      if (used != name.size() - colon - 1 || column < 0) throw std::invalid_argument("column");
    } catch (const std::exception&) {
      throw ArgumentError(fmt::format("output '{}': expected 'dataset:column' with a column index >= 0", name));
    }
  }
  if (!h5.Has(dataset)) {
    std::vector<std::string> offered;
    for (const auto& [short_name, path] : KnownOutputs()) {
      if (h5.Has(path)) offered.push_back(short_name);
    }
    throw DataFileError(fmt::format(
        "{}: no output '{}' (dataset '{}'); this run offers {} or any per-step dataset as name or name:column "
        "(C_T/C_F/C_P need output.resistance or a resistance section in the case, X/Y/N output.captive)",
        history.string(), name, dataset, offered.empty() ? std::string("none of the short names") : fmt::format("{}", fmt::join(offered, ", "))));
  }
  const data::Series s = h5.Read(dataset);
  if (column < 0) {
    if (s.cols != 1) {
      throw DataFileError(fmt::format("{}: '{}' has {} columns; name one as '{}:0' ... '{}:{}'", history.string(),
                                      dataset, s.cols, dataset, dataset, s.cols - 1));
    }
    column = 0;
  }
  if (static_cast<std::size_t>(column) >= s.cols) {
    throw DataFileError(fmt::format("{}: '{}' has {} column(s), no column {}", history.string(), dataset, s.cols,
                                    column));
  }
  if (s.rows < static_cast<std::size_t>(average)) {
    throw DataFileError(fmt::format("{}: '{}' has {} step(s), fewer than --average {}", history.string(), dataset,
                                    s.rows, average));
  }
  double sum = 0.0;
  for (std::size_t r = s.rows - average; r < s.rows; ++r) sum += s.at(r, column);
  const double v = sum / average;
  if (!std::isfinite(v)) throw DataFileError(fmt::format("{}: '{}' is not finite", history.string(), name));
  return v;
}

std::vector<GciOutputResult> ComputeGciOutputs(const std::vector<GridRunRecord>& grids,
                                               const std::vector<std::string>& outputs) {
  KELVIN_CHECK(grids.size() >= 3, "three grids");
  std::vector<GciOutputResult> results;
  for (std::size_t k = 0; k < outputs.size(); ++k) {
    GciOutputResult o;
    o.name = outputs[k];
    for (int g = 0; g < 3; ++g) o.phi[g] = grids[g].values.at(k);
    o.gci = ComputeGci(grids[0].h, grids[1].h, grids[2].h, o.phi[0], o.phi[1], o.phi[2]);
    results.push_back(o);
  }
  return results;
}

GciStudy RunGciStudy(const GciStudyOptions& options) {
  if (options.outputs.empty()) throw ArgumentError("--outputs: name at least one output (e.g. C_T)");
  if (options.average < 1) {
    throw ArgumentError(fmt::format("--average {}: expected a number of steps >= 1", options.average));
  }
  const std::vector<FamilyGrid> family = ReadGridFamily(options.grids, options.family, options.ratio_tolerance);
  const data::ConfigNode root = data::ConfigNode::LoadFile(options.case_file);
  if (!root["mesh"].Has("poly_mesh")) {
    root["mesh"].Fail("a poly_mesh entry (kelvin gci replaces it by each grid of the family)");
  }
  const CaseSettings settings = ReadCaseSettings(root, options.case_file.parent_path());
  const bool steady = settings.time.steady.has_value();  // the run stops on time.steady
  const fs::path runs = options.runs.empty() ? settings.output.directory / "gci" : options.runs;
  GciStudy study;
  for (const FamilyGrid& g : family) {
    GridRunRecord r;
    r.level = g.level;
    r.cells = g.cells;
    r.h = g.h;
    r.directory = runs / fmt::format("grid{}", g.level);
    study.grids.push_back(r);
  }
  // Coarse grids first: the cheap runs show a problem early.
  for (auto it = study.grids.rbegin(); it != study.grids.rend(); ++it) {
    GridRunRecord& r = *it;
    if (!options.rerun && ReadRunRecord(r)) {
      r.reused = true;
      spdlog::info("kelvin gci: grid {} ({} cells): reusing the finished run in {}", r.level, r.cells,
                   r.directory.string());
    } else {
      spdlog::info("kelvin gci: grid {} ({} cells): running in {}", r.level, r.cells, r.directory.string());
      fs::remove(r.directory / kRunRecord);
      RunOptions ro;
      ro.output_override = r.directory;
      ro.poly_mesh_override = family[r.level - 1].poly_mesh;
      ro.progress = options.progress;
      const RunSummary s = RunCase(options.case_file, ro);
      if (s.status != RunSummary::Status::kCompleted) {
        throw ModelError(fmt::format("kelvin gci: the run on grid {} {}", r.level, s.message));
      }
      r.steps = s.steps;
      r.outer_iterations = s.outer_iterations;
      r.steady = steady;
      r.steady_converged = s.steady_converged;
      const data::H5Reader h5(r.directory / "history.h5");
      const data::Series cpu = h5.Read("cpu_time");
      r.cpu_seconds = cpu.rows > 0 ? cpu.values.back() : 0.0;
      WriteRunRecord(r, family[r.level - 1].poly_mesh);
      spdlog::info("kelvin gci: grid {}: {}", r.level, s.message);
    }
    if (r.steady && !r.steady_converged) {
      spdlog::warn("kelvin gci: grid {}: the run had not met its steady criterion by time.end; its values carry "
                   "an iteration error",
                   r.level);
    }
  }
  for (GridRunRecord& r : study.grids) {
    for (const std::string& name : options.outputs) {
      r.values.push_back(ExtractOutput(r.directory / "history.h5", name, options.average));
    }
  }
  study.outputs = ComputeGciOutputs(study.grids, options.outputs);
  return study;
}

std::string GciTable(const GciStudy& study) {
  std::string t = "grid    cells        h (m)  steps  settled  CPU (s)  us/cell/iter";
  for (const GciOutputResult& o : study.outputs) t += fmt::format(" {:>14}", o.name);
  t += "\n";
  for (const GridRunRecord& r : study.grids) {
    const double per = r.outer_iterations > 0 && r.cells > 0 ? 1e6 * r.cpu_seconds / (double(r.cells) * r.outer_iterations) : 0.0;
    t += fmt::format("{:>4} {:>8} {:>12.6g} {:>6} {:>8} {:>8.1f} {:>13.2f}", r.level, r.cells, r.h, r.steps,
                     r.steady ? (r.steady_converged ? "yes" : "NO") : "-", r.cpu_seconds, per);
    for (double v : r.values) t += fmt::format(" {:>14.6e}", v);
    t += r.reused ? "  (reused)\n" : "\n";
  }
  t += "\noutput          r21     r32        R  convergence      p   extrapolated  GCI_fine  GCI_coarse  "
       "GCI32/(r21^p GCI21)\n";
  for (const GciOutputResult& o : study.outputs) {
    const GciResult& g = o.gci;
    t += fmt::format("{:<12} {:>7.4f} {:>7.4f} {:>8.4f}  {:<11} {:>6.3f} {:>14.6e} {:>8.3f}% {:>10.3f}%  {:>10.4f}\n",
                     o.name, g.r21, g.r32, g.R, ConvergenceName(g.convergence), g.p, g.phi_ext, 100 * g.gci21,
                     100 * g.gci32, g.asymptotic_ratio);
  }
  return t;
}

void WriteGciReport(const GciStudy& study, const fs::path& stem, const std::string& case_file) {
  fs::create_directories(stem.parent_path().empty() ? fs::path(".") : stem.parent_path());
  const std::size_t n = study.grids.size();
  // HDF5: grids/* per grid (fine first), outputs/<name>/* per output.
  data::H5Writer w(fs::path(stem.string() + ".h5"));
  std::vector<double> level, cells, h, steps, cpu, iters, settled;
  for (const GridRunRecord& r : study.grids) {
    level.push_back(r.level);
    cells.push_back(static_cast<double>(r.cells));
    h.push_back(r.h);
    steps.push_back(r.steps);
    cpu.push_back(r.cpu_seconds);
    iters.push_back(r.outer_iterations);
    settled.push_back(r.steady_converged ? 1.0 : 0.0);
  }
  w.WriteArray("grids/level", level, {n}, "1", "grid level (1 finest)");
  w.WriteArray("grids/cells", cells, {n}, "1", "cells");
  w.WriteArray("grids/h", h, {n}, "m", "representative cell size (V/N)^(1/3)");
  w.WriteArray("grids/steps", steps, {n}, "1", "time steps of the run");
  w.WriteArray("grids/outer_iterations", iters, {n}, "1", "PIMPLE outer iterations of the run");
  w.WriteArray("grids/cpu_time", cpu, {n}, "s", "process CPU time of the time loop");
  w.WriteArray("grids/steady_converged", settled, {n}, "1", "1 when the run met its steady criterion (time.steady or the resistance section)");
  for (const GciOutputResult& o : study.outputs) {
    const std::string g = "outputs/" + o.name;
    std::vector<double> values;
    for (const GridRunRecord& r : study.grids) values.push_back(r.values[&o - study.outputs.data()]);
    w.WriteArray(g + "/values", values, {n}, "", "output value per grid (fine first)");
    const GciResult& c = o.gci;
    const std::pair<const char*, double> scalars[] = {
        {"r21", c.r21},         {"r32", c.r32},         {"R", c.R},
        {"p", c.p},             {"extrapolated", c.phi_ext}, {"e_a21", c.e_a21},
        {"e_ext21", c.e_ext21}, {"gci_fine", c.gci21},  {"gci_coarse", c.gci32},
        {"asymptotic_ratio", c.asymptotic_ratio}};
    for (const auto& [key, value] : scalars) {
      w.WriteArray(g + "/" + key, std::vector<double>{value}, {1}, "", "Celik et al. (2008) GCI procedure");
    }
    w.SetAttribute(g, "convergence", ConvergenceName(c.convergence));
  }
  w.SetAttribute("/", "case", case_file);
  w.Commit();

  std::string y = fmt::format("# kelvin gci report (Celik et al. 2008, J. Fluids Eng. 130:078001)\ncase: \"{}\"\n",
                              case_file);
  y += "grids:\n";
  for (const GridRunRecord& r : study.grids) {
    y += fmt::format(
        "  - {{level: {}, cells: {}, h: {:.9g}, steps: {}, outer_iterations: {}, cpu_seconds: {:.6g}, "
        "steady_converged: {}, directory: \"{}\"}}\n",
        r.level, r.cells, r.h, r.steps, r.outer_iterations, r.cpu_seconds, r.steady_converged, r.directory.string());
  }
  y += "outputs:\n";
  for (std::size_t k = 0; k < study.outputs.size(); ++k) {
    const GciOutputResult& o = study.outputs[k];
    const GciResult& c = o.gci;
    y += fmt::format("  {}:\n    values: [{:.9g}, {:.9g}, {:.9g}]\n", o.name, o.phi[0], o.phi[1], o.phi[2]);
    y += fmt::format(
        "    r21: {:.6g}\n    r32: {:.6g}\n    R: {:.6g}\n    convergence: {}\n    p: {:.6g}\n"
        "    extrapolated: {:.9g}\n    e_a21: {:.6g}\n    e_ext21: {:.6g}\n    gci_fine: {:.6g}\n"
        "    gci_coarse: {:.6g}\n    asymptotic_ratio: {:.6g}\n",
        c.r21, c.r32, c.R, ConvergenceName(c.convergence), c.p, c.phi_ext, c.e_a21, c.e_ext21, c.gci21, c.gci32,
        c.asymptotic_ratio);
  }
  data::WriteFileAtomically(fs::path(stem.string() + ".yaml"), y);
}

}  // namespace kelvin::cfd
