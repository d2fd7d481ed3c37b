#include "cfd/parallel/state_layout.h"

#include <fmt/format.h>

#include <algorithm>
#include <limits>
#include <numeric>

#include "cfd/parallel/decompose.h"
#include "data/schema/errors.h"

namespace kelvin::cfd {
namespace {

// Sum over the ranks of each rank's contributions: `take(i)` says whether
// local entry i contributes, `global(i)` where it goes (and with what sign).
template <typename Take, typename Global>
std::vector<double> Reduce(const DomainPart& part, std::size_t n, const double* local, std::size_t n_local, int width,
                           Take take, Global global) {
  std::vector<double> sum(n * width, 0.0), count(n, 0.0);
  for (std::size_t i = 0; i < n_local; ++i) {
    if (!take(i)) continue;
    const auto [g, sign] = global(i);
    for (int k = 0; k < width; ++k) sum[g * width + k] += sign * local[i * width + k];
    count[g] += 1.0;
  }
  MPI_Allreduce(MPI_IN_PLACE, sum.data(), static_cast<int>(sum.size()), MPI_DOUBLE, MPI_SUM, part.comm);
  MPI_Allreduce(MPI_IN_PLACE, count.data(), static_cast<int>(count.size()), MPI_DOUBLE, MPI_SUM, part.comm);
  // A face between two ranks' cells comes from both (the same value).
  for (std::size_t g = 0; g < n; ++g) {
    for (int k = 0; k < width; ++k) sum[g * width + k] /= std::max(count[g], 1.0);
  }
  return sum;
}

template <typename T>
constexpr int Width() {
  return std::is_same_v<T, Vector3> ? 3 : 1;
}

template <typename T>
const double* Data(const std::vector<T>& v) {
  if constexpr (std::is_same_v<T, Vector3>) {
    return v.empty() ? nullptr : v.front().data();
  } else {
    return v.data();
  }
}

template <typename T>
std::vector<T> Unflatten(const std::vector<double>& flat) {
  std::vector<T> out(flat.size() / Width<T>());
  for (std::size_t i = 0; i < out.size(); ++i) {
    if constexpr (std::is_same_v<T, Vector3>) {
      out[i] = Vector3(flat[3 * i], flat[3 * i + 1], flat[3 * i + 2]);
    } else {
      out[i] = flat[i];
    }
  }
  return out;
}

template <typename T>
std::vector<T> GatherCellArray(const DomainPart& part, const std::vector<T>& local) {
  const auto flat = Reduce(
      part, part.n_global_cells, Data(local), local.size(), Width<T>(),
      [&](std::size_t i) { return static_cast<int>(i) < part.n_owned; },
      [&](std::size_t i) { return std::pair<long long, double>(part.cells[i], 1.0); });
  return Unflatten<T>(flat);
}

std::vector<double> GatherFaceArray(const DomainPart& part, const Mesh& mesh, const std::vector<double>& local) {
  return Reduce(
      part, part.n_global_faces, local.data(), local.size(), 1,
      [&](std::size_t f) { return mesh.owner()[f] < part.n_owned; },
      [&](std::size_t f) { return std::pair<long long, double>(part.faces[f], part.face_signs[f]); });
}

void Expect(std::size_t size, long long n, const char* what, const char* of) {
  if (static_cast<long long>(size) != n) {
    throw DataFileError(fmt::format("the state's {} has {} values; the decomposed mesh has {} {} (a checkpoint of "
                                    "another mesh?)",
                                    what, size, n, of));
  }
}

template <typename T>
std::vector<T> ScatterCells(const DomainPart& part, const std::vector<T>& global, const char* what) {
  Expect(global.size(), part.n_global_cells, what, "cells");
  std::vector<T> out(part.cells.size());
  for (std::size_t i = 0; i < out.size(); ++i) out[i] = global[part.cells[i]];
  return out;
}

std::vector<double> ScatterFaces(const DomainPart& part, const std::vector<double>& global, const char* what) {
  Expect(global.size(), part.n_global_faces, what, "faces");
  std::vector<double> out(part.faces.size());
  for (std::size_t f = 0; f < out.size(); ++f) out[f] = part.face_signs[f] * global[part.faces[f]];
  return out;
}

// The turbulence model's arrays over the boundary faces (the wall
// function's face viscosity); every other array is over the cells.
bool BoundaryArray(const std::string& name) { return name == "nut_wall"; }

std::vector<double> ScatterBoundaryArray(const DomainPart& part, const Mesh& mesh, const std::vector<double>& global,
                                         const std::string& name) {
  const long long gi = part.n_global_internal_faces;
  Expect(global.size(), part.n_global_faces - gi, name.c_str(), "boundary faces");
  const int ni = mesh.n_internal_faces();
  std::vector<double> out(mesh.n_boundary_faces(), 0.0);
  for (int b = 0; b < mesh.n_boundary_faces(); ++b) {
    const long long g = part.faces[b + ni] - gi;
    // A ghost's face inside the whole mesh (on the processor patch) has no boundary value.
    if (g >= 0) out[b] = global[g];
  }
  return out;
}

}  // namespace

// The faces on the processor patch are the ghosts' and are left out: every
// boundary face of the whole mesh is some rank's own.
std::vector<double> GatherBoundaryFaces(const DomainPart& part, const Mesh& mesh, const std::vector<double>& local) {
  const int ni = mesh.n_internal_faces();
  const long long gi = part.n_global_internal_faces;
  const int processor = mesh.FindPatch(kProcessorPatch);
  const Patch* proc = processor >= 0 ? &mesh.patches()[processor] : nullptr;
  auto on_processor = [&](std::size_t f) {
    return proc && static_cast<int>(f) >= proc->start && static_cast<int>(f) < proc->start + proc->size;
  };
  return Reduce(
      part, static_cast<std::size_t>(part.n_global_faces - gi), local.data(), local.size(), 1,
      [&](std::size_t b) { return !on_processor(b + ni); },
      [&](std::size_t b) { return std::pair<long long, double>(part.faces[b + ni] - gi, 1.0); });
}

std::vector<int> WholePatchIndices(const DomainPart* part, const Mesh& mesh, int patch) {
  const Patch& p = mesh.patches()[patch];
  std::vector<int> out(p.size);
  if (!part || !part->parallel()) {
    std::iota(out.begin(), out.end(), 0);
    return out;
  }
  // The patch's faces are contiguous in the whole mesh, each on one rank.
  double first = std::numeric_limits<double>::max();
  for (int f = p.start; f < p.start + p.size; ++f) first = std::min(first, static_cast<double>(part->faces[f]));
  const auto start = static_cast<long long>(part->Min(first));
  for (int i = 0; i < p.size; ++i) out[i] = static_cast<int>(part->faces[p.start + i] - start);
  return out;
}

std::vector<Vector3> GatherPatchFaces(const DomainPart* part, const Mesh& mesh, int patch,
                                      std::span<const Vector3> local) {
  const Patch& p = mesh.patches()[patch];
  KELVIN_CHECK(static_cast<int>(local.size()) == p.size, "one value per face of the patch");
  if (!part || !part->parallel()) return {local.begin(), local.end()};
  const std::vector<int> index = WholePatchIndices(part, mesh, patch);
  const auto n = static_cast<std::size_t>(part->Sum(p.size));
  const std::vector<double> sum = Reduce(
      *part, n, local.empty() ? nullptr : local.front().data(), local.size(), 3, [](std::size_t) { return true; },
      [&](std::size_t i) { return std::pair<long long, double>(index[i], 1.0); });
  std::vector<Vector3> out(n);
  for (std::size_t i = 0; i < n; ++i) out[i] = Vector3(sum[3 * i], sum[3 * i + 1], sum[3 * i + 2]);
  return out;
}

PimpleSolver::State GatherState(const DomainPart& part, const Mesh& mesh, const PimpleSolver::State& local) {
  PimpleSolver::State g;
  g.time = local.time;
  g.step = local.step;
  g.last_dt = local.last_dt;
  g.U = GatherCellArray(part, local.U);
  for (const auto& u : local.U_old) g.U_old.push_back(GatherCellArray(part, u));
  g.p = GatherCellArray(part, local.p);
  g.phi = GatherFaceArray(part, mesh, local.phi);
  for (const auto& phi : local.phi_old) g.phi_old.push_back(GatherFaceArray(part, mesh, phi));
  g.bc_state = local.bc_state;
  g.bc_state.pop_back();  // the processor patch's, of U ...
  g.bc_state.erase(g.bc_state.begin() + static_cast<long>(g.bc_state.size() / 2));  // ... and of p
  for (const auto& [name, values] : local.turbulence) {
    g.turbulence.emplace_back(name, BoundaryArray(name) ? GatherBoundaryFaces(part, mesh, values)
                                                        : GatherCellArray(part, values));
  }
  return g;
}

PimpleSolver::State ScatterState(const DomainPart& part, const Mesh& mesh, const PimpleSolver::State& global) {
  PimpleSolver::State s;
  s.time = global.time;
  s.step = global.step;
  s.last_dt = global.last_dt;
  s.U = ScatterCells(part, global.U, "U");
  for (const auto& u : global.U_old) s.U_old.push_back(ScatterCells(part, u, "U_old"));
  s.p = ScatterCells(part, global.p, "p");
  s.phi = ScatterFaces(part, global.phi, "phi");
  for (const auto& phi : global.phi_old) s.phi_old.push_back(ScatterFaces(part, phi, "phi_old"));
  // The conditions' own state (the free surface's eta) is over whole
  // patches on every rank already: each patch's as it is, for U then p,
  // and an empty one for the processor patch after each.
  const std::size_t patches = global.bc_state.size() / 2;
  for (std::size_t field = 0; field < 2; ++field) {
    const auto first = global.bc_state.begin() + static_cast<long>(field * patches);
    s.bc_state.insert(s.bc_state.end(), first, first + static_cast<long>(patches));
    s.bc_state.emplace_back();
  }
  for (const auto& [name, values] : global.turbulence) {
    s.turbulence.emplace_back(name, BoundaryArray(name) ? ScatterBoundaryArray(part, mesh, values, name)
                                                        : ScatterCells(part, values, name.c_str()));
  }
  return s;
}

}  // namespace kelvin::cfd
