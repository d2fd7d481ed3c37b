#include "cfd/geometry/surface_repair.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/orient_polygon_soup.h>
#include <CGAL/Polygon_mesh_processing/polygon_mesh_to_polygon_soup.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/Polygon_mesh_processing/repair_degeneracies.h>
#include <CGAL/Polygon_mesh_processing/repair_polygon_soup.h>
#include <CGAL/Polygon_mesh_processing/self_intersections.h>
#include <CGAL/Surface_mesh.h>
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <vector>

#include "data/schema/errors.h"

namespace kelvin::cfd {

namespace {

namespace PMP = CGAL::Polygon_mesh_processing;
using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_3;
using Mesh = CGAL::Surface_mesh<Point>;
using Polygon = std::vector<std::size_t>;

struct Soup {
  std::vector<Point> points;
  std::vector<Polygon> polygons;
};

Soup ToSoup(const TriangleSurface& s) {
  Soup soup;
  soup.points.reserve(s.vertices.size());
  for (const auto& v : s.vertices) soup.points.emplace_back(v.x(), v.y(), v.z());
  for (const auto& t : s.triangles) soup.polygons.push_back({std::size_t(t[0]), std::size_t(t[1]), std::size_t(t[2])});
  return soup;
}

// Back to a surface, with points of identical coordinates welded (orienting
// and meshing duplicate the points of non-manifold edges) and unused points
// dropped.
TriangleSurface FromSoup(const Soup& soup, const std::string& source) {
  TriangleSurface s;
  s.source = source;
  for (const Point& p : soup.points) s.vertices.emplace_back(p.x(), p.y(), p.z());
  for (const auto& poly : soup.polygons) {
    s.triangles.push_back({static_cast<int>(poly[0]), static_cast<int>(poly[1]), static_cast<int>(poly[2])});
  }
  WeldIdenticalVertices(s);
  return s;
}

class DisjointSets {
 public:
  explicit DisjointSets(std::size_t n) : parent_(n) { std::iota(parent_.begin(), parent_.end(), 0); }
  std::size_t Find(std::size_t i) {
    while (parent_[i] != i) i = parent_[i] = parent_[parent_[i]];
    return i;
  }
  // Keeps the smaller index as the representative, so its position stays.
  bool Join(std::size_t a, std::size_t b) {
    a = Find(a);
    b = Find(b);
    if (a == b) return false;
    parent_[std::max(a, b)] = std::min(a, b);
    return true;
  }

 private:
  std::vector<std::size_t> parent_;
};

// Merges vertices closer than `tolerance` (sweep along x) and the two ends of
// every edge shorter than `short_edge`; triangles that lose a corner go.
void MergeCloseVertices(TriangleSurface& s, double tolerance, double short_edge, RepairReport& r) {
  const std::size_t n = s.vertices.size();
  DisjointSets sets(n);
  std::vector<std::size_t> order(n);
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](auto a, auto b) { return s.vertices[a].x() < s.vertices[b].x(); });
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t j = i + 1; j < n && s.vertices[order[j]].x() - s.vertices[order[i]].x() <= tolerance; ++j) {
      if ((s.vertices[order[i]] - s.vertices[order[j]]).norm() <= tolerance && sets.Join(order[i], order[j])) {
        ++r.merged_vertices;
      }
    }
  }
  for (const auto& t : s.triangles) {
    for (int e = 0; e < 3; ++e) {
      const int a = t[e], b = t[(e + 1) % 3];
      if ((s.vertices[a] - s.vertices[b]).norm() < short_edge && sets.Join(a, b)) ++r.collapsed_edges;
    }
  }
  std::vector<std::array<int, 3>> kept;
  for (auto t : s.triangles) {
    for (int& c : t) c = static_cast<int>(sets.Find(c));
    if (t[0] != t[1] && t[1] != t[2] && t[0] != t[2]) {
      kept.push_back(t);
    } else {
      ++r.removed_triangles;
    }
  }
  s.triangles = std::move(kept);
}

// Height of a triangle over its longest edge (0 for a degenerate one).
double Height(const TriangleSurface& s, const std::array<int, 3>& t) {
  const Eigen::Vector3d& a = s.vertices[t[0]];
  const Eigen::Vector3d& b = s.vertices[t[1]];
  const Eigen::Vector3d& c = s.vertices[t[2]];
  const double longest = std::max({(b - a).norm(), (c - b).norm(), (a - c).norm()});
  return longest > 0 ? (b - a).cross(c - a).norm() / longest : 0.0;
}

std::size_t CountSlivers(const TriangleSurface& s, double short_edge) {
  std::size_t n = 0;
  for (const auto& t : s.triangles) n += Height(s, t) < short_edge ? 1 : 0;
  return n;
}

// A polygon reversed by orient_polygon_soup: same corners, opposite cycle.
bool Reversed(const Soup& before, const Polygon& a, const Soup& after, const Polygon& b) {
  auto same = [&](std::size_t i, std::size_t j) { return before.points[a[i]] == after.points[b[j]]; };
  for (int shift = 0; shift < 3; ++shift) {
    if (same(0, shift) && same(1, (shift + 2) % 3) && same(2, (shift + 1) % 3)) return true;
  }
  return false;
}

void Orient(TriangleSurface& s, RepairReport& r) {
  const Soup before = ToSoup(s);
  Soup after = before;
  PMP::orient_polygon_soup(after.points, after.polygons);
  std::size_t reversed = 0;
  for (std::size_t i = 0; i < after.polygons.size(); ++i) {
    reversed += Reversed(before, before.polygons[i], after, after.polygons[i]) ? 1 : 0;
  }
  // The outward sense is ValidateHull's: count the minority as flipped.
  r.reoriented_triangles = std::min(reversed, after.polygons.size() - reversed);
  s = FromSoup(after, s.source);
}

Mesh ToMesh(const TriangleSurface& s) {
  Soup soup = ToSoup(s);
  PMP::orient_polygon_soup(soup.points, soup.polygons);
  Mesh mesh;
  PMP::polygon_soup_to_polygon_mesh(soup.points, soup.polygons, mesh);
  return mesh;
}

void RemoveSlivers(TriangleSurface& s, double short_edge, RepairReport& r) {
  Mesh mesh = ToMesh(s);
  // Caps: an angle above 179 degrees with a height below short_edge are
  // flipped away; needles: edges below short_edge collapsed.
  const double cap_cosine = std::cos(179.0 * M_PI / 180.0);
  PMP::experimental::remove_almost_degenerate_faces(
      mesh, cap_cosine, 10.0, short_edge, CGAL::parameters::flip_triangle_height_threshold(short_edge));
  PMP::remove_degenerate_faces(mesh);
  mesh.collect_garbage();
  Soup soup;
  PMP::polygon_mesh_to_polygon_soup(mesh, soup.points, soup.polygons);
  const std::size_t before = CountSlivers(s, short_edge);
  s = FromSoup(soup, s.source);
  const std::size_t after = CountSlivers(s, short_edge);
  r.fixed_slivers += before > after ? before - after : 0;
}

// Orienting and meshing may turn the whole surface inside out; the sense the
// file had (by the sign of the immersed volume) is kept, so ValidateHull
// reports a flip only when the file itself was inward.
void KeepSense(double volume_before, double waterline_z, TriangleSurface& s) {
  if (CheckSurface(s, waterline_z).underwater_volume * volume_before >= 0) return;
  for (auto& t : s.triangles) std::swap(t[1], t[2]);
}

// Self-intersecting pairs; triangles that share a corner point are skipped
// (a rudder meeting the hull along a non-manifold edge touches, it does not
// cross).
void CheckSelfIntersections(const TriangleSurface& s, double waterline_z, RepairReport& r) {
  const Mesh mesh = ToMesh(s);
  std::vector<std::pair<Mesh::Face_index, Mesh::Face_index>> pairs;
  PMP::self_intersections(mesh, std::back_inserter(pairs));
  auto corners = [&](Mesh::Face_index f) {
    std::vector<Point> p;
    for (auto v : mesh.vertices_around_face(mesh.halfedge(f))) p.push_back(mesh.point(v));
    return p;
  };
  for (const auto& [f, g] : pairs) {
    const auto a = corners(f), b = corners(g);
    bool touch = false;
    for (const auto& p : a) touch = touch || std::find(b.begin(), b.end(), p) != b.end();
    if (touch) continue;
    auto lowest = [](const std::vector<Point>& p) {
      return std::min({p[0].z(), p[1].z(), p[2].z()});
    };
    if (lowest(a) < waterline_z && lowest(b) < waterline_z) {
      throw DataFileError(fmt::format(
          "{}: the surface intersects itself below the waterline, near ({:.6g}, {:.6g}, {:.6g}) (ship axes, m); "
          "expected a hull whose surfaces do not cross (repair it in the CAD tool: kelvin cannot tell which "
          "side is water)",
          s.source, a[0].x(), a[0].y(), a[0].z()));
    }
    ++r.self_intersections_above;
  }
}

double Diagonal(const TriangleSurface& s) { return (s.Max() - s.Min()).norm(); }

}  // namespace

bool RepairReport::Changed() const {
  return merged_vertices + collapsed_edges + removed_triangles + fixed_slivers + reoriented_triangles > 0;
}

std::string RepairReport::Summary() const {
  if (!Changed()) {
    return fmt::format("no change (merge tolerance {:.3g} m, short edge {:.3g} m)", merge_tolerance, short_edge);
  }
  return fmt::format(
      "{} near-duplicate vertices merged (within {:.3g} m), {} edges shorter than {:.3g} m collapsed, {} degenerate "
      "or duplicate triangles removed, {} slivers flipped or collapsed away, {} triangles re-oriented to agree with "
      "their neighbours",
      merged_vertices, merge_tolerance, collapsed_edges, short_edge, removed_triangles, fixed_slivers,
      reoriented_triangles);
}

TriangleSurface RepairSurface(const TriangleSurface& surface, const RepairOptions& o, RepairReport* report) {
  RepairReport r;
  const double diagonal = Diagonal(surface);
  r.merge_tolerance = o.merge_tolerance > 0 ? o.merge_tolerance : 1e-6 * diagonal;
  r.short_edge = o.short_edge > 0 ? o.short_edge : 1e-5 * diagonal;
  TriangleSurface s = surface;
  MergeCloseVertices(s, r.merge_tolerance, r.short_edge, r);
  {
    Soup soup = ToSoup(s);
    const std::size_t before = soup.polygons.size();
    PMP::repair_polygon_soup(soup.points, soup.polygons);
    r.removed_triangles += before - soup.polygons.size();
    s = FromSoup(soup, s.source);
  }
  const SurfaceCheck before = CheckSurface(s, o.waterline_z);
  if (before.inconsistent_edges > 0) Orient(s, r);
  if (CountSlivers(s, r.short_edge) > 0) RemoveSlivers(s, r.short_edge, r);
  KeepSense(before.underwater_volume, o.waterline_z, s);
  CheckSelfIntersections(s, o.waterline_z, r);
  if (report) *report = r;
  return s;
}

}  // namespace kelvin::cfd
