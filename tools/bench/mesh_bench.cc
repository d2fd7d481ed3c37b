// Meshing benchmark (issue 5): time to mesh the Wigley hull at ~300k cells
// with the built-in hull-fitted generator, and the DTC with the snappyHexMesh
// path (blockMesh + surfaceFeatureExtract + snappyHexMesh, serial, Debian's
// OpenFOAM), in one run on this machine; reported as cells per second and
// their ratio, with the quality of both grids.
// Prints a Markdown section; with --write FILE it replaces the section
// between the mesh markers in FILE (BENCHMARKS.md).
#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "cfd/grid/hull_grid.h"
#include "cfd/grid/mesh_case.h"
#include "cfd/grid/mesh_writer.h"
#include "tools/bench/markdown_section.h"

namespace {

using Clock = std::chrono::steady_clock;
namespace fs = std::filesystem;

double Since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

}  // namespace

int main(int argc, char** argv) {
  std::string write_to;
  fs::path source = fs::path(__FILE__).parent_path().parent_path().parent_path();
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--write") && i + 1 < argc)
      write_to = argv[++i];
    else if (!std::strcmp(argv[i], "--source") && i + 1 < argc)
      source = argv[++i];
  }
  using namespace kelvin::cfd;
  // Built-in generator: Wigley L/B = 10, B/T = 1.6, Re 5e6, y+ 1, ~300k cells.
  const WigleySections wigley(2.5, 0.25, 0.15625);
  HullGridOptions o;
  o.cells_hull = 64;
  o.cells_upstream = 16;
  o.cells_downstream = 32;
  o.cells_girth = 24;
  o.cells_below_keel = 16;
  o.cells_normal = 34;
  std::vector<double> t;
  MeshQuality wq;
  for (int rep = 0; rep < 3; ++rep) {
    const auto t0 = Clock::now();
    const Mesh m = MakeHullGrid(wigley, o);
    t.push_back(Since(t0));
    if (rep == 0) wq = m.Quality();
  }
  std::sort(t.begin(), t.end());
  const double t_gen = t[1];
  const fs::path scratch = fs::temp_directory_path() / "kelvin_mesh_bench";
  fs::remove_all(scratch);
  const auto t1 = Clock::now();
  {
    const Mesh m = MakeHullGrid(wigley, o);
    WritePolyMesh(m, scratch / "wigley");
  }
  const double t_gen_write = Since(t1);

  // snappyHexMesh path on the DTC (the shipped case, its benchmark size).
  const MeshCase c = [&] {
    MeshCase mc = LoadMeshCase(source / "data/cases/mesh/dtc_snappy.yaml");
    mc.write_vtu = false;
    return mc;
  }();
  const auto t2 = Clock::now();
  const auto grids = RunMeshCase(c, 1, scratch / "dtc");
  const double t_snappy_total = Since(t2);
  const GridSummary& g = grids[0];
  fs::remove_all(scratch);

  const double rate_builtin = wq.n_cells / t_gen;
  const double rate_snappy = g.quality.n_cells / g.seconds;
  std::string md = "## Meshing (issue 5)\n\n";
  md +=
      "Produced by `build/release/tools/bench/mesh_bench --write BENCHMARKS.md` (one run; built-in "
      "generator median "
      "of 3; OpenFOAM v1912 tools from Debian, serial).\n\n";
  md += "| grid | cells | time (s) | cells/s | max non-orthogonality (deg) | max skewness |\n";
  md += "| --- | ---: | ---: | ---: | ---: | ---: |\n";
  md += fmt::format(
      "| Wigley, built-in hull-fitted generator (y+ 1 at Re 5e6) | {} | {:.3f} | {:.3g} | {:.1f} | "
      "{:.2f} |\n",
      wq.n_cells, t_gen, rate_builtin, wq.max_non_orthogonality, wq.max_skewness);
  md += fmt::format("| same, including writing the ASCII polyMesh | {} | {:.3f} | {:.3g} | | |\n",
                    wq.n_cells, t_gen_write, wq.n_cells / t_gen_write);
  md += fmt::format(
      "| DTC, snappyHexMesh path (blockMesh {:.2f} s + surfaceFeatureExtract {:.2f} s + "
      "snappyHexMesh {:.2f} s, hull level {}) | {} | {:.2f} | {:.3g} | {:.1f} | {:.2f} |\n",
      g.snappy.seconds_block_mesh, g.snappy.seconds_features, g.snappy.seconds_snappy,
      c.snappy.hull_level, g.quality.n_cells, g.seconds, rate_snappy,
      g.quality.max_non_orthogonality, g.quality.max_skewness);
  md += fmt::format(
      "\nRatio built-in / snappyHexMesh: {:.0f}x the cells per second. The whole `kelvin mesh` run "
      "for the DTC "
      "(writing the case, the tools, reading the polyMesh back, quality report) took {:.1f} s.\n\n",
      rate_builtin / rate_snappy, t_snappy_total);
  md += fmt::format(
      "DTC prism layers (relative to the hull cells): {} requested, first layer {:.3g} mm; "
      "snappyHexMesh kept {:.2f} per hull face on average, {:.1f}% of the requested thickness. "
      "y+ estimate on the hull (ITTC-57 u_tau): mean {:.0f}, max {:.0f}.\n\n",
      g.snappy.layers, 1e3 * g.snappy.first_layer_thickness, g.snappy.layers_kept,
      g.snappy.thickness_kept_percent, g.y_plus.mean, g.y_plus.max);
  {
    std::ifstream load("/proc/loadavg");
    double l1 = 0;
    if (load >> l1) {
      md += fmt::format(
          "Times are wall-clock seconds; the 1-minute load average at the end of the run was {:.1f} "
          "on 2 cores (the machine is shared), which slows both paths.\n\n",
          l1);
    }
  }
  fmt::print("{}", md);
  if (!write_to.empty()) kelvin::bench::ReplaceMarkdownSection(write_to, "mesh", md);
  return 0;
}
