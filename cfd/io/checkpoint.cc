#include "cfd/io/checkpoint.h"

#include <fmt/format.h>

#include <algorithm>
#include <string>

#include "data/schema/errors.h"
#include "data/schema/h5_file.h"

namespace kelvin::cfd {
namespace {

std::vector<double> Flatten(const std::vector<Vector3>& v) {
  std::vector<double> out(v.size() * 3);
  for (std::size_t i = 0; i < v.size(); ++i) {
    for (int k = 0; k < 3; ++k) out[3 * i + k] = v[i][k];
  }
  return out;
}

std::vector<Vector3> Unflatten(const data::Series& s) {
  std::vector<Vector3> out(s.rows);
  for (std::size_t i = 0; i < s.rows; ++i) out[i] = Vector3(s.values[3 * i], s.values[3 * i + 1], s.values[3 * i + 2]);
  return out;
}

constexpr const char* kScalarNameChars = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789_";

// The names of a comma-separated list attribute, empty entries skipped.
std::vector<std::string> SplitNames(const std::string& names) {
  std::vector<std::string> out;
  std::size_t start = 0;
  while (start <= names.size()) {
    const std::size_t end = std::min(names.find(',', start), names.size());
    if (end > start) out.push_back(names.substr(start, end - start));
    start = end + 1;
  }
  return out;
}

}  // namespace

void WriteCheckpoint(const std::filesystem::path& path, const PimpleSolver& solver,
                     const CheckpointScalars& scalars, const CheckpointArrays& arrays) {
  WriteCheckpointState(path, solver.GetState(), solver.mesh().n_cells(), solver.mesh().n_faces(), scalars, arrays);
}

void WriteCheckpointState(const std::filesystem::path& path, const PimpleSolver::State& s, long long n_cells,
                          long long n_faces, const CheckpointScalars& scalars, const CheckpointArrays& arrays) {
  data::H5Writer w(path, data::H5Writer::Mode::kCreate);
  w.SetAttribute("/", "kind", "kelvin PIMPLE checkpoint");
  w.SetAttribute("/", "time", s.time);
  w.SetAttribute("/", "step", static_cast<double>(s.step));
  w.SetAttribute("/", "last_dt", s.last_dt);
  w.SetAttribute("/", "n_cells", static_cast<double>(n_cells));
  w.SetAttribute("/", "n_faces", static_cast<double>(n_faces));
  w.SetAttribute("/", "U_levels", static_cast<double>(s.U_old.size()));
  w.SetAttribute("/", "phi_levels", static_cast<double>(s.phi_old.size()));
  w.SetAttribute("/", "bc_states", static_cast<double>(s.bc_state.size()));
  w.WriteArray("U", Flatten(s.U), {s.U.size(), 3}, "m/s", "velocity");
  for (std::size_t l = 0; l < s.U_old.size(); ++l) {
    w.WriteArray(fmt::format("U_old/{}", l), Flatten(s.U_old[l]), {s.U_old[l].size(), 3}, "m/s", "old velocity");
  }
  w.WriteArray("p", s.p, {s.p.size()}, "m^2/s^2", "kinematic pressure");
  w.WriteArray("phi", s.phi, {s.phi.size()}, "m^3/s", "face volume flux");
  for (std::size_t l = 0; l < s.phi_old.size(); ++l) {
    w.WriteArray(fmt::format("phi_old/{}", l), s.phi_old[l], {s.phi_old[l].size()}, "m^3/s", "old face flux");
  }
  for (std::size_t b = 0; b < s.bc_state.size(); ++b) {
    if (!s.bc_state[b].empty()) {
      w.WriteArray(fmt::format("bc/{}", b), s.bc_state[b], {s.bc_state[b].size()}, "", "boundary condition state");
    }
  }
  if (!s.turbulence.empty()) {
    std::string names;
    for (const auto& [name, values] : s.turbulence) {
      names += (names.empty() ? "" : ",") + name;
      w.WriteArray("turbulence/" + name, values, {values.size()}, "", "turbulence model state");
    }
    w.SetAttribute("/", "turbulence_arrays", names);
  }
  if (!scalars.empty()) {
    std::string names;
    for (const auto& [name, value] : scalars) {
      KELVIN_CHECK(!name.empty() && name.find_first_not_of(kScalarNameChars) == std::string::npos,
                   "checkpoint scalar names are identifiers");
      names += (names.empty() ? "" : ",") + name;
      w.SetAttribute("/", "run_" + name, value);
    }
    w.SetAttribute("/", "run_scalars", names);
  }
  if (!arrays.empty()) {
    std::string names;
    for (const auto& [name, values] : arrays) {
      KELVIN_CHECK(!name.empty() && name.find_first_not_of(kScalarNameChars) == std::string::npos && !values.empty(),
                   "checkpoint arrays have identifier names and values");
      names += (names.empty() ? "" : ",") + name;
      w.WriteArray("run/" + name, values, {values.size()}, "", "run state");
    }
    w.SetAttribute("/", "run_arrays", names);
  }
  w.Commit();
}

namespace {

CheckpointScalars RunScalars(const data::H5Reader& r) {
  CheckpointScalars scalars;
  if (r.HasAttribute("/", "run_scalars")) {
    for (const std::string& name : SplitNames(r.StringAttribute("/", "run_scalars"))) {
      scalars[name] = r.NumberAttribute("/", "run_" + name);
    }
  }
  return scalars;
}

CheckpointArrays RunArrays(const data::H5Reader& r) {
  CheckpointArrays arrays;
  if (r.HasAttribute("/", "run_arrays")) {
    for (const std::string& name : SplitNames(r.StringAttribute("/", "run_arrays"))) {
      arrays[name] = r.Read("run/" + name).values;
    }
  }
  return arrays;
}

}  // namespace

CheckpointState ReadCheckpointState(const std::filesystem::path& path) {
  data::H5Reader r(path);
  CheckpointState c;
  c.n_cells = static_cast<long long>(r.NumberAttribute("/", "n_cells"));
  c.n_faces = static_cast<long long>(r.NumberAttribute("/", "n_faces"));
  PimpleSolver::State& s = c.state;
  s.time = r.NumberAttribute("/", "time");
  s.step = static_cast<int>(r.NumberAttribute("/", "step"));
  s.last_dt = r.NumberAttribute("/", "last_dt");
  s.U = Unflatten(r.Read("U"));
  const int u_levels = static_cast<int>(r.NumberAttribute("/", "U_levels"));
  for (int l = 0; l < u_levels; ++l) s.U_old.push_back(Unflatten(r.Read(fmt::format("U_old/{}", l))));
  s.p = r.Read("p").values;
  s.phi = r.Read("phi").values;
  const int phi_levels = static_cast<int>(r.NumberAttribute("/", "phi_levels"));
  for (int l = 0; l < phi_levels; ++l) s.phi_old.push_back(r.Read(fmt::format("phi_old/{}", l)).values);
  const int n_bc = static_cast<int>(r.NumberAttribute("/", "bc_states"));
  for (int b = 0; b < n_bc; ++b) {
    const std::string name = fmt::format("bc/{}", b);
    s.bc_state.push_back(r.Has(name) ? r.Read(name).values : std::vector<double>{});
  }
  if (r.HasAttribute("/", "turbulence_arrays")) {
    for (const std::string& name : SplitNames(r.StringAttribute("/", "turbulence_arrays"))) {
      s.turbulence.emplace_back(name, r.Read("turbulence/" + name).values);
    }
  }
  c.scalars = RunScalars(r);
  return c;
}

CheckpointScalars ReadCheckpoint(const std::filesystem::path& path, PimpleSolver& solver) {
  CheckpointState c = ReadCheckpointState(path);
  if (c.n_cells != solver.mesh().n_cells() || c.n_faces != solver.mesh().n_faces()) {
    throw DataFileError(fmt::format("{}: checkpoint has {} cells and {} faces; the mesh has {} and {}", path.string(),
                                    c.n_cells, c.n_faces, solver.mesh().n_cells(), solver.mesh().n_faces()));
  }
  try {
    solver.SetState(c.state);
  } catch (const DataFileError& e) {
    throw DataFileError(fmt::format("{}: {}", path.string(), e.what()));
  }
  return c.scalars;
}

CheckpointScalars ReadCheckpointScalars(const std::filesystem::path& path) {
  const data::H5Reader r(path);
  return RunScalars(r);
}

CheckpointArrays ReadCheckpointArrays(const std::filesystem::path& path) {
  const data::H5Reader r(path);
  return RunArrays(r);
}

}  // namespace kelvin::cfd
