#include "cfd/parallel/decompose.h"

#include <fmt/format.h>

#include <algorithm>
#include <tuple>

#include "cfd/parallel/petsc_halo.h"
#include "data/schema/errors.h"

namespace kelvin::cfd {
namespace {

struct LocalFace {
  int owner = 0;
  int neighbour = -1;
  std::vector<int> points;  // global point labels
  int global = 0;           // the face of the whole mesh
  signed char sign = 1;     // -1: oriented against it
};

std::vector<int> Reversed(std::span<const int> pts) {
  std::vector<int> r(pts.begin(), pts.end());
  std::reverse(r.begin() + 1, r.end());
  return r;
}

struct Ownership {
  std::vector<int> index_in_rank;  // local index of each cell on its owner
  std::vector<int> first_row;      // per rank
};

Ownership Owners(std::span<const int> cell_rank, int size) {
  Ownership o;
  o.index_in_rank.resize(cell_rank.size());
  std::vector<int> count(size, 0);
  for (std::size_t c = 0; c < cell_rank.size(); ++c) o.index_in_rank[c] = count[cell_rank[c]]++;
  o.first_row.assign(size, 0);
  for (int r = 1; r < size; ++r) o.first_row[r] = o.first_row[r - 1] + count[r - 1];
  return o;
}

// The faces between ranks (DomainPart::cross_roots, cross_leaves): a face's
// root is on the rank of its whole-mesh owner cell, numbered there in
// ascending whole-mesh face order, which every rank can count from the
// partition alone.
void CrossFaces(const Mesh& mesh, std::span<const int> cell_rank, int n_local_internal, DomainPart& part) {
  const auto owner = mesh.owner();
  const auto neighbour = mesh.neighbour();
  std::vector<int> counter(part.size, 0);
  std::vector<int> root_index(mesh.n_internal_faces(), -1);
  for (int g = 0; g < mesh.n_internal_faces(); ++g) {
    const int rp = cell_rank[owner[g]];
    if (rp != cell_rank[neighbour[g]]) root_index[g] = counter[rp]++;
  }
  part.cross_roots.assign(counter[part.rank], -1);
  std::vector<GhostSource> leaf_sources;
  for (int f = 0; f < n_local_internal; ++f) {
    const long long g = part.faces[f];
    if (root_index[g] < 0) continue;  // within one rank
    if (cell_rank[owner[g]] == part.rank) {
      KELVIN_CHECK(part.face_signs[f] > 0, "a face from an owned cell keeps its orientation");
      part.cross_roots[root_index[g]] = f;
    } else {
      KELVIN_CHECK(cell_rank[neighbour[g]] == part.rank && part.face_signs[f] < 0, "a leaf face is turned");
      part.cross_leaves.push_back(f);
      leaf_sources.push_back({cell_rank[owner[g]], root_index[g]});
    }
  }
  for (int f : part.cross_roots) KELVIN_CHECK(f >= 0, "every root face of the rank is a local face");
  part.cross_halo = std::make_shared<PetscHalo>(part.comm, static_cast<int>(part.cross_roots.size()), leaf_sources);
}

}  // namespace

LocalDomain Decompose(const Mesh& mesh, std::span<const int> cell_rank, MPI_Comm comm) {
  auto part = std::make_shared<DomainPart>();
  part->comm = comm;
  MPI_Comm_rank(comm, &part->rank);
  MPI_Comm_size(comm, &part->size);
  const int me = part->rank;
  const int nc = mesh.n_cells();
  KELVIN_CHECK(static_cast<int>(cell_rank.size()) == nc, "one rank per cell");
  for (int r : cell_rank) KELVIN_CHECK(r >= 0 && r < part->size, "cell ranks in [0, size)");
  part->n_global_cells = nc;
  part->n_global_faces = mesh.n_faces();
  part->n_global_internal_faces = mesh.n_internal_faces();
  const Ownership own = Owners(cell_rank, part->size);

  // Local cells: owned, then ghosts, each in ascending global order.
  std::vector<int> local_of(nc, -1);
  part->cells.reserve(std::count(cell_rank.begin(), cell_rank.end(), me));
  for (int c = 0; c < nc; ++c) {
    if (cell_rank[c] == me) {
      local_of[c] = static_cast<int>(part->cells.size());
      part->cells.push_back(c);
    }
  }
  part->n_owned = static_cast<int>(part->cells.size());
  if (part->n_owned == 0) {
    throw ConfigError(fmt::format("{}: rank {} of {} owns no cell; expected at least one cell per rank",
                                  mesh.source(), me, part->size));
  }
  const auto owner = mesh.owner();
  const auto neighbour = mesh.neighbour();
  std::vector<int> ghosts;
  for (int f = 0; f < mesh.n_internal_faces(); ++f) {
    const int P = owner[f], N = neighbour[f];
    if (cell_rank[P] == me && cell_rank[N] != me) ghosts.push_back(N);
    if (cell_rank[N] == me && cell_rank[P] != me) ghosts.push_back(P);
  }
  std::sort(ghosts.begin(), ghosts.end());
  ghosts.erase(std::unique(ghosts.begin(), ghosts.end()), ghosts.end());
  std::vector<GhostSource> sources;
  part->cells.reserve(part->cells.size() + ghosts.size());
  for (int g : ghosts) {
    local_of[g] = static_cast<int>(part->cells.size());
    part->cells.push_back(g);
    sources.push_back({cell_rank[g], own.index_in_rank[g]});
  }
  auto owned = [&](int local) { return local >= 0 && local < part->n_owned; };

  // Faces, in lists sized exactly first: the decomposition's transient sets
  // a rank's peak memory, and grown lists hold up to twice their size.
  std::vector<LocalFace> internal, processor;
  std::vector<std::vector<LocalFace>> patch_faces(mesh.patches().size());
  {
    std::size_t n_internal = 0, n_processor = 0;
    for (int f = 0; f < mesh.n_internal_faces(); ++f) {
      const int lp = local_of[owner[f]], ln = local_of[neighbour[f]];
      if (owned(lp) || owned(ln)) {
        ++n_internal;
      } else {
        n_processor += (lp >= 0) + (ln >= 0);
      }
    }
    for (std::size_t pi = 0; pi < mesh.patches().size(); ++pi) {
      const Patch& patch = mesh.patches()[pi];
      std::size_t n_patch = 0;
      for (int f = patch.start; f < patch.start + patch.size; ++f) {
        const int lp = local_of[owner[f]];
        if (lp >= 0) ++(owned(lp) ? n_patch : n_processor);
      }
      patch_faces[pi].reserve(n_patch);
    }
    internal.reserve(n_internal);
    processor.reserve(n_processor);
  }
  for (int f = 0; f < mesh.n_internal_faces(); ++f) {
    const int lp = local_of[owner[f]], ln = local_of[neighbour[f]];
    const auto pts = mesh.face(f);
    if (owned(lp) || owned(ln)) {
      if (lp < ln) {
        internal.push_back({lp, ln, std::vector<int>(pts.begin(), pts.end()), f, 1});
      } else {
        internal.push_back({ln, lp, Reversed(pts), f, -1});
      }
      continue;
    }
    if (lp >= 0) processor.push_back({lp, -1, std::vector<int>(pts.begin(), pts.end()), f, 1});
    if (ln >= 0) processor.push_back({ln, -1, Reversed(pts), f, -1});
  }
  for (std::size_t pi = 0; pi < mesh.patches().size(); ++pi) {
    const Patch& patch = mesh.patches()[pi];
    for (int f = patch.start; f < patch.start + patch.size; ++f) {
      const int lp = local_of[owner[f]];
      if (lp < 0) continue;
      const auto pts = mesh.face(f);
      (owned(lp) ? patch_faces[pi] : processor).push_back({lp, -1, std::vector<int>(pts.begin(), pts.end()), f, 1});
    }
  }
  std::sort(internal.begin(), internal.end(), [](const LocalFace& a, const LocalFace& b) {
    return std::tie(a.owner, a.neighbour) < std::tie(b.owner, b.neighbour);
  });

  // Points used by the local faces, renumbered in global order.
  std::vector<int> point_of(mesh.n_points(), -1);
  auto mark = [&](const std::vector<LocalFace>& faces) {
    for (const LocalFace& lf : faces) {
      for (int p : lf.points) point_of[p] = 0;
    }
  };
  mark(internal);
  mark(processor);
  for (const auto& pf : patch_faces) mark(pf);
  std::vector<Vector3> points;
  points.reserve(std::count_if(point_of.begin(), point_of.end(), [](int p) { return p >= 0; }));
  const bool placed = !mesh.placement_rotation().isIdentity() || !mesh.placement_translation().isZero();
  KELVIN_CHECK(!placed, "decompose the mesh in its body-fixed placement");
  for (int p = 0; p < mesh.n_points(); ++p) {
    if (point_of[p] < 0) continue;
    point_of[p] = static_cast<int>(points.size());
    points.push_back(mesh.points()[p]);
  }

  std::vector<std::vector<int>> faces;
  std::vector<int> owners, neighbours;
  std::vector<Patch> patches;
  std::size_t n_faces = internal.size() + processor.size();
  for (const auto& pf : patch_faces) n_faces += pf.size();
  part->faces.reserve(n_faces);
  part->face_signs.reserve(n_faces);
  owners.reserve(n_faces);
  neighbours.reserve(internal.size());
  faces.reserve(n_faces);
  // Each list's point labels are renumbered in place and handed over, and
  // the list is released once appended.
  auto append = [&](std::vector<LocalFace>& list) {
    for (LocalFace& lf : list) {
      for (int& p : lf.points) p = point_of[p];
      faces.push_back(std::move(lf.points));
      part->faces.push_back(lf.global);
      part->face_signs.push_back(lf.sign);
      owners.push_back(lf.owner);
      if (lf.neighbour >= 0) neighbours.push_back(lf.neighbour);
    }
    std::vector<LocalFace>().swap(list);
  };
  append(internal);
  for (std::size_t pi = 0; pi < mesh.patches().size(); ++pi) {
    Patch p = mesh.patches()[pi];
    p.start = static_cast<int>(faces.size());
    p.size = static_cast<int>(patch_faces[pi].size());
    patches.push_back(p);
    append(patch_faces[pi]);
  }
  patches.push_back({kProcessorPatch, PatchKind::kProcessor, static_cast<int>(faces.size()),
                     static_cast<int>(processor.size())});
  append(processor);

  LocalDomain out;
  out.mesh = std::make_unique<Mesh>(std::move(points), std::move(faces), std::move(owners), std::move(neighbours),
                                    std::move(patches),
                                    fmt::format("{} (rank {} of {})", mesh.source(), me, part->size));
  part->first_row = own.first_row[me];
  part->rows.resize(part->cells.size());
  for (std::size_t i = 0; i < part->cells.size(); ++i) {
    const long long c = part->cells[i];
    part->rows[i] = own.first_row[cell_rank[c]] + own.index_in_rank[c];
  }
  part->halo = std::make_shared<PetscHalo>(comm, part->n_owned, sources);
  CrossFaces(mesh, cell_rank, out.mesh->n_internal_faces(), *part);
  out.part = std::move(part);
  return out;
}

std::vector<double> GatherCells(const DomainPart& part, std::span<const double> local) {
  std::vector<double> mine(part.n_global_cells, 0.0), all(part.n_global_cells, 0.0);
  for (int i = 0; i < part.n_owned; ++i) mine[part.cells[i]] = local[i];
  MPI_Allreduce(mine.data(), all.data(), static_cast<int>(all.size()), MPI_DOUBLE, MPI_SUM, part.comm);
  return all;
}

}  // namespace kelvin::cfd
