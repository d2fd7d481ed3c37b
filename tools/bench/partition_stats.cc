// Halo volumes and message counts of the PT-Scotch partition (issue 23,
// acceptance 3): reads a polyMesh, renumbers it as the run layer does, and
// for each part count cuts it with PartitionCells on this one process. Per
// part it counts the owned cells, the ghost cells (the distinct cells of other
// parts that share an internal face with the part: what one halo exchange
// receives), the neighbour parts (the messages of one exchange) and the cut
// faces, and prints one JSON line per part count. No solver runs: the figures
// feed the paper estimate of tools/bench/scaling_estimate.py.
#include <CLI/CLI.hpp>
#include <fmt/format.h>
#include <mpi.h>

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <numeric>
#include <string>
#include <vector>

#include "cfd/mesh/poly_mesh_reader.h"
#include "cfd/parallel/partition.h"
#include "cfd/parallel/petsc_context.h"

namespace kelvin::cfd {
namespace {

struct PartStats {
  std::vector<double> owned, ghosts, neighbours, cut_faces;
};

// Sorted distinct (part, value) pairs, packed as part << 32 | value.
std::vector<std::uint64_t> Distinct(std::vector<std::uint64_t> keys) {
  std::sort(keys.begin(), keys.end());
  keys.erase(std::unique(keys.begin(), keys.end()), keys.end());
  return keys;
}

std::uint64_t Key(int part, int value) {
  return (static_cast<std::uint64_t>(part) << 32) | static_cast<std::uint32_t>(value);
}

// Adds one per key to the count of the key's part.
void CountPerPart(const std::vector<std::uint64_t>& keys, std::vector<double>& count) {
  for (std::uint64_t k : keys) count[k >> 32] += 1.0;
}

PartStats Stats(const Mesh& mesh, const std::vector<int>& part, int n_parts) {
  PartStats s;
  s.owned.assign(n_parts, 0.0);
  s.ghosts.assign(n_parts, 0.0);
  s.neighbours.assign(n_parts, 0.0);
  s.cut_faces.assign(n_parts, 0.0);
  for (int p : part) s.owned[p] += 1.0;
  std::vector<std::uint64_t> ghost_keys, neighbour_keys;
  for (int f = 0; f < mesh.n_internal_faces(); ++f) {
    const int a = mesh.owner()[f], b = mesh.neighbour()[f];
    const int pa = part[a], pb = part[b];
    if (pa == pb) continue;
    s.cut_faces[pa] += 1.0;
    s.cut_faces[pb] += 1.0;
    ghost_keys.push_back(Key(pa, b));
    ghost_keys.push_back(Key(pb, a));
    neighbour_keys.push_back(Key(pa, pb));
    neighbour_keys.push_back(Key(pb, pa));
  }
  CountPerPart(Distinct(std::move(ghost_keys)), s.ghosts);
  CountPerPart(Distinct(std::move(neighbour_keys)), s.neighbours);
  return s;
}

double Max(const std::vector<double>& v) { return *std::max_element(v.begin(), v.end()); }
double Mean(const std::vector<double>& v) { return std::accumulate(v.begin(), v.end(), 0.0) / v.size(); }

std::string List(const std::vector<double>& v) {
  std::string s = "[";
  for (std::size_t i = 0; i < v.size(); ++i) s += fmt::format("{}{:.0f}", i ? ", " : "", v[i]);
  return s + "]";
}

void Print(const Mesh& mesh, const PartitionSummary& summary, const PartStats& s, double seconds, bool per_part) {
  std::string line = fmt::format(
      "{{\"n_parts\": {}, \"cells\": {}, \"owned_max\": {:.0f}, \"owned_mean\": {:.1f}, \"ghosts_max\": {:.0f}, "
      "\"ghosts_mean\": {:.1f}, \"neighbours_max\": {:.0f}, \"neighbours_mean\": {:.2f}, \"ghosts_total\": {:.0f}, "
      "\"cut_faces\": {}, \"imbalance\": {:.4f}, \"partition_s\": {:.3f}",
      summary.n_parts, mesh.n_cells(), Max(s.owned), Mean(s.owned), Max(s.ghosts), Mean(s.ghosts),
      Max(s.neighbours), Mean(s.neighbours), std::accumulate(s.ghosts.begin(), s.ghosts.end(), 0.0),
      summary.cut_faces, summary.imbalance, seconds);
  if (per_part) {
    line += fmt::format(", \"owned\": {}, \"ghosts\": {}, \"neighbours\": {}", List(s.owned), List(s.ghosts),
                        List(s.neighbours));
  }
  std::printf("%s}\n", line.c_str());
  std::fflush(stdout);
}

int Run(const std::string& poly_mesh, const std::vector<int>& parts, bool per_part) {
  EnsurePetsc();
  Mesh mesh = ReadPolyMesh(poly_mesh);
  mesh.RenumberCells();
  PartitionOptions options;
  options.min_cells_per_rank = 1;  // the estimate wants the small counts too
  for (int n_parts : parts) {
    PartitionSummary summary;
    const double t0 = MPI_Wtime();
    const std::vector<int> part = PartitionCells(mesh, n_parts, MPI_COMM_SELF, options, &summary);
    const double seconds = MPI_Wtime() - t0;
    Print(mesh, summary, Stats(mesh, part, n_parts), seconds, per_part);
  }
  return 0;
}

}  // namespace
}  // namespace kelvin::cfd

int main(int argc, char** argv) {
  CLI::App app("halo volumes and message counts of the PT-Scotch partition of a polyMesh, per part count");
  std::string poly_mesh;
  std::vector<int> parts{8, 16, 32, 64, 128, 256};
  bool per_part = false;
  app.add_option("poly_mesh", poly_mesh, "constant/polyMesh directory")->required();
  app.add_option("--parts", parts, "part counts (comma-separated)")->delimiter(',')->check(CLI::Range(1, 1 << 20));
  app.add_flag("--per-part", per_part, "also print the owned, ghost and neighbour counts of every part");
  CLI11_PARSE(app, argc, argv);
  try {
    return kelvin::cfd::Run(poly_mesh, parts, per_part);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "partition_stats: %s\n", e.what());
    return 1;
  }
}
