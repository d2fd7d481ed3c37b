#include "cfd/mesh/box_mesh.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <tuple>

#include "cfd/mesh/mesh_builder.h"
#include "data/schema/errors.h"

namespace kelvin::cfd {

void BoxMeshOptions::Validate() const {
  for (int d = 0; d < 3; ++d) {
    if (!(max[d] > min[d])) {
      throw ConfigError(fmt::format("box mesh: max[{}] = {} must exceed min[{}] = {}", d, max[d], d, min[d]));
    }
    if (cells[d] < 1) throw ConfigError(fmt::format("box mesh: cells[{}] = {}; expected >= 1", d, cells[d]));
    if (!(grading[d] > 0)) {
      throw ConfigError(fmt::format("box mesh: grading[{}] = {}; expected > 0", d, grading[d]));
    }
  }
  if (!(perturbation >= 0.0 && perturbation < 0.45)) {
    throw ConfigError(fmt::format("box mesh: perturbation = {}; expected in [0, 0.45)", perturbation));
  }
  if (has_obstacle()) {
    for (int d = 0; d < 3; ++d) {
      if (obstacle_min[d] < 0 || obstacle_max[d] > cells[d]) {
        throw ConfigError(fmt::format("box mesh: obstacle blocks [{}, {}) along axis {}; expected within [0, {}]",
                                      obstacle_min[d], obstacle_max[d], d, cells[d]));
      }
    }
  }
}

bool BoxMeshOptions::has_obstacle() const {
  for (int d = 0; d < 3; ++d) {
    if (obstacle_max[d] <= obstacle_min[d]) return false;
  }
  return true;
}

namespace {

// Coordinates of n graded cells from a to b: last/first size = grading.
std::vector<double> GradedCoordinates(double a, double b, int n, double grading) {
  std::vector<double> sizes(n, 1.0);
  const double r = n > 1 ? std::pow(grading, 1.0 / (n - 1)) : 1.0;
  for (int i = 1; i < n; ++i) sizes[i] = sizes[i - 1] * r;
  double total = 0.0;
  for (double s : sizes) total += s;
  std::vector<double> x(n + 1, a);
  for (int i = 0; i < n; ++i) x[i + 1] = x[i] + (b - a) * sizes[i] / total;
  x[n] = b;
  return x;
}

}  // namespace

Mesh MakeBoxMesh(const BoxMeshOptions& opt) {
  opt.Validate();
  // Lattice: each block is split `split[d]` times along axis d.
  std::array<int, 3> split = {1, 1, 1};
  if (opt.polyhedral) {
    for (int d = 0; d < 3; ++d) split[d] = opt.cells[d] > 1 ? 2 : 1;
  }
  std::array<int, 3> n;  // lattice cells per axis
  std::array<std::vector<double>, 3> coord;
  for (int d = 0; d < 3; ++d) {
    n[d] = opt.cells[d] * split[d];
    const std::vector<double> blocks = GradedCoordinates(opt.min[d], opt.max[d], opt.cells[d], opt.grading[d]);
    coord[d].resize(n[d] + 1);
    for (int b = 0; b < opt.cells[d]; ++b) {
      for (int s = 0; s <= split[d]; ++s) {
        coord[d][b * split[d] + s] = blocks[b] + (blocks[b + 1] - blocks[b]) * s / split[d];
      }
    }
  }
  auto point_id = [&](int i, int j, int k) { return i + (n[0] + 1) * (j + (n[1] + 1) * k); };
  std::vector<Vector3> points((n[0] + 1) * (n[1] + 1) * (n[2] + 1));
  std::mt19937 rng(opt.seed);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  for (int k = 0; k <= n[2]; ++k) {
    for (int j = 0; j <= n[1]; ++j) {
      for (int i = 0; i <= n[0]; ++i) {
        Vector3 x(coord[0][i], coord[1][j], coord[2][k]);
        const std::array<int, 3> idx = {i, j, k};
        if (opt.perturbation > 0) {
          for (int d = 0; d < 3; ++d) {
            const double u = uniform(rng);
            // Only interior points move, and never along a single-cell axis.
            if (idx[d] > 0 && idx[d] < n[d]) {
              const double h = std::min(coord[d][idx[d]] - coord[d][idx[d] - 1], coord[d][idx[d] + 1] - coord[d][idx[d]]);
              x[d] += opt.perturbation * h * u;
            }
          }
        }
        points[point_id(i, j, k)] = x;
      }
    }
  }
  // Cell of each lattice cell: a block is one cell unless it is split.
  std::vector<int> cell_of(n[0] * n[1] * n[2]);
  auto lattice_id = [&](int i, int j, int k) { return i + n[0] * (j + n[1] * k); };
  int n_cells = 0;
  for (int bk = 0; bk < opt.cells[2]; ++bk) {
    for (int bj = 0; bj < opt.cells[1]; ++bj) {
      for (int bi = 0; bi < opt.cells[0]; ++bi) {
        const bool removed = opt.has_obstacle() && bi >= opt.obstacle_min[0] && bi < opt.obstacle_max[0] &&
                             bj >= opt.obstacle_min[1] && bj < opt.obstacle_max[1] &&
                             bk >= opt.obstacle_min[2] && bk < opt.obstacle_max[2];
        const bool refine = !removed && opt.polyhedral && (bi + bj + bk) % 2 == 0;
        const int block_cell = refine || removed ? -1 : n_cells++;
        for (int sk = 0; sk < split[2]; ++sk) {
          for (int sj = 0; sj < split[1]; ++sj) {
            for (int si = 0; si < split[0]; ++si) {
              cell_of[lattice_id(bi * split[0] + si, bj * split[1] + sj, bk * split[2] + sk)] =
                  refine ? n_cells++ : block_cell;
            }
          }
        }
      }
    }
  }
  // Unit lattice faces normal to axis d at lattice index (i, j, k), oriented +d.
  auto face_points = [&](int d, int i, int j, int k) -> std::vector<int> {
    switch (d) {
      case 0:
        return {point_id(i, j, k), point_id(i, j + 1, k), point_id(i, j + 1, k + 1), point_id(i, j, k + 1)};
      case 1:
        return {point_id(i, j, k), point_id(i, j, k + 1), point_id(i + 1, j, k + 1), point_id(i + 1, j, k)};
      default:
        return {point_id(i, j, k), point_id(i + 1, j, k), point_id(i + 1, j + 1, k), point_id(i, j + 1, k)};
    }
  };
  static const std::array<const char*, 6> kNames = {"xmin", "xmax", "ymin", "ymax", "zmin", "zmax"};
  MeshBuilder builder;
  for (int p = 0; p < 6; ++p) builder.AddPatch(kNames[p], opt.kinds[p]);
  constexpr int kObstacle = 6;
  if (opt.has_obstacle()) builder.AddPatch("obstacle", PatchKind::kWall);
  for (int d = 0; d < 3; ++d) {
    std::array<int, 3> ext = n;
    ext[d] += 1;
    for (int k = 0; k < ext[2]; ++k) {
      for (int j = 0; j < ext[1]; ++j) {
        for (int i = 0; i < ext[0]; ++i) {
          std::array<int, 3> lo = {i, j, k};
          const int plane = lo[d];
          std::vector<int> pts = face_points(d, i, j, k);
          if (plane == 0 || plane == n[d]) {
            std::array<int, 3> cell_idx = lo;
            if (plane == n[d]) cell_idx[d] -= 1;
            const int c = cell_of[lattice_id(cell_idx[0], cell_idx[1], cell_idx[2])];
            if (c < 0) continue;  // on the obstacle
            if (plane == 0) std::reverse(pts.begin(), pts.end());
            builder.AddBoundaryFace(2 * d + (plane == 0 ? 0 : 1), c, std::move(pts));
            continue;
          }
          std::array<int, 3> below = lo;
          below[d] -= 1;
          const int a = cell_of[lattice_id(below[0], below[1], below[2])];
          const int b = cell_of[lattice_id(lo[0], lo[1], lo[2])];
          if (a == b) continue;  // inside a block that is not split (or inside the obstacle)
          if (a < 0) {
            std::reverse(pts.begin(), pts.end());
            builder.AddBoundaryFace(kObstacle, b, std::move(pts));
            continue;
          }
          if (b < 0) {
            builder.AddBoundaryFace(kObstacle, a, std::move(pts));
            continue;
          }
          builder.AddInternalFace(a, b, std::move(pts));
        }
      }
    }
  }
  return std::move(builder).Build(std::move(points), "<box mesh>");
}

}  // namespace kelvin::cfd
