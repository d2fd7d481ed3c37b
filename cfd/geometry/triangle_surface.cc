#include "cfd/geometry/triangle_surface.h"

#include <fmt/format.h>
#include <zlib.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <limits>
#include <map>
#include <sstream>
#include <unordered_map>

#include "cfd/geometry/hydrostatics.h"
#include "data/schema/atomic_file.h"
#include "data/schema/errors.h"
#include "data/schema/file_status.h"

namespace kelvin::cfd {

namespace fs = std::filesystem;

namespace {

[[noreturn]] void Fail(const fs::path& file, const std::string& what) {
  throw DataFileError(fmt::format("{}: {}", file.string(), what));
}

// The whole file, as bytes.
std::string ReadBytes(const fs::path& path) {
  if (!data::PathExists(path)) Fail(path, "file not found");
  if (data::IsExistingDirectory(path)) Fail(path, "is a directory; expected a surface file");
  std::ifstream in(path, std::ios::binary);
  if (!in) Fail(path, "cannot open");
  std::string raw(static_cast<std::size_t>(fs::file_size(path)), '\0');
  in.read(raw.data(), static_cast<std::streamsize>(raw.size()));
  if (!in) Fail(path, "read failed");
  return raw;
}

bool IsGzip(std::string_view raw) {
  return raw.size() >= 2 && static_cast<unsigned char>(raw[0]) == 0x1f && static_cast<unsigned char>(raw[1]) == 0x8b;
}

// Inflates gzip data, member after member (as gzread does for concatenated
// .gz files); bytes after the last member are ignored.
std::string Gunzip(const fs::path& file, const std::string& raw) {
  z_stream z{};
  if (inflateInit2(&z, 16 + MAX_WBITS) != Z_OK) Fail(file, "cannot start the gzip decoder");
  z.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(raw.data()));
  z.avail_in = static_cast<uInt>(std::min<std::size_t>(raw.size(), std::numeric_limits<uInt>::max()));
  std::string out;
  char buf[1 << 16];
  int rc = Z_OK;
  while (rc == Z_OK) {
    z.next_out = reinterpret_cast<Bytef*>(buf);
    z.avail_out = sizeof buf;
    rc = inflate(&z, Z_NO_FLUSH);
    out.append(buf, sizeof buf - z.avail_out);
    const char* rest = reinterpret_cast<const char*>(z.next_in);
    if (rc == Z_STREAM_END && IsGzip(std::string_view(rest, z.avail_in))) rc = inflateReset(&z);
  }
  const std::string why = z.msg ? z.msg : "unexpected end of data";
  inflateEnd(&z);
  if (rc != Z_STREAM_END) Fail(file, "corrupt or truncated gzip data (" + why + ")");
  return out;
}

std::string Decompressed(const fs::path& file, const std::string& raw) {
  return IsGzip(raw) ? Gunzip(file, raw) : raw;
}

// Welds vertices with identical coordinates.
class VertexWelder {
 public:
  explicit VertexWelder(TriangleSurface& s) : s_(s) {}
  int Add(const Eigen::Vector3d& p) {
    const Key k{p.x(), p.y(), p.z()};
    auto [it, inserted] = index_.try_emplace(k, static_cast<int>(s_.vertices.size()));
    if (inserted) s_.vertices.push_back(p);
    return it->second;
  }

 private:
  using Key = std::array<double, 3>;
  struct Hash {
    std::size_t operator()(const Key& k) const {
      std::size_t h = 1469598103934665603ull;
      for (double d : k) {
        std::uint64_t b;
        std::memcpy(&b, &d, sizeof b);
        h = (h ^ b) * 1099511628211ull;
      }
      return h;
    }
  };
  TriangleSurface& s_;
  std::unordered_map<Key, int, Hash> index_;
};

void CheckFinite(const fs::path& path, const Eigen::Vector3d& p, std::size_t tri, int corner) {
  if (!p.allFinite()) {
    Fail(path, fmt::format("triangle {} vertex {} has a non-finite coordinate ({}, {}, {}); expected finite numbers",
                           tri, corner, p.x(), p.y(), p.z()));
  }
}

TriangleSurface ParseBinaryStl(const fs::path& path, const std::string& data) {
  std::uint32_t n = 0;
  std::memcpy(&n, data.data() + 80, 4);
  const std::size_t need = 84 + 50 * static_cast<std::size_t>(n);
  if (data.size() != need) {
    Fail(path, fmt::format("binary STL declares {} triangles, which needs {} bytes, but the file has {} bytes "
                           "(truncated or not an STL)",
                           n, need, data.size()));
  }
  TriangleSurface s;
  s.source = path.string();
  VertexWelder weld(s);
  for (std::size_t t = 0; t < n; ++t) {
    const char* rec = data.data() + 84 + 50 * t;
    std::array<int, 3> tri{};
    for (int c = 0; c < 3; ++c) {
      float xyz[3];
      std::memcpy(xyz, rec + 12 + 12 * c, 12);
      const Eigen::Vector3d p(xyz[0], xyz[1], xyz[2]);
      CheckFinite(path, p, t, c);
      tri[c] = weld.Add(p);
    }
    s.triangles.push_back(tri);
  }
  return s;
}

TriangleSurface ParseAsciiStl(const fs::path& path, const std::string& data) {
  TriangleSurface s;
  s.source = path.string();
  VertexWelder weld(s);
  std::istringstream in(data);
  std::string line;
  int line_no = 0;
  std::array<int, 3> tri{};
  int corner = 0;
  bool in_loop = false;
  bool ended = false;
  while (std::getline(in, line)) {
    ++line_no;
    std::istringstream ls(line);
    std::string word;
    if (!(ls >> word)) continue;
    if (word == "vertex") {
      if (!in_loop || corner >= 3) {
        Fail(path, fmt::format("line {}: 'vertex' outside an 'outer loop' of three vertices", line_no));
      }
      std::string xs, ys, zs;
      if (!(ls >> xs >> ys >> zs)) Fail(path, fmt::format("line {}: expected 'vertex x y z', got '{}'", line_no, line));
      Eigen::Vector3d p;
      try {
        p = Eigen::Vector3d(std::stod(xs), std::stod(ys), std::stod(zs));
      } catch (const std::exception&) {
        Fail(path, fmt::format("line {}: expected three numbers after 'vertex', got '{} {} {}'", line_no, xs, ys, zs));
      }
      CheckFinite(path, p, s.triangles.size(), corner);
      tri[corner++] = weld.Add(p);
    } else if (word == "outer") {
      in_loop = true;
      corner = 0;
    } else if (word == "endloop") {
      if (corner != 3) {
        Fail(path, fmt::format("line {}: facet has {} vertices; expected 3", line_no, corner));
      }
      s.triangles.push_back(tri);
      in_loop = false;
    } else if (word == "endsolid") {
      ended = true;
    } else if (word != "solid" && word != "facet" && word != "endfacet") {
      Fail(path, fmt::format("line {}: unexpected '{}' in ASCII STL", line_no, word));
    }
  }
  if (in_loop || !ended) Fail(path, fmt::format("ASCII STL ends at line {} without 'endsolid' (truncated)", line_no));
  return s;
}

}  // namespace

Eigen::Vector3d TriangleSurface::Normal(std::size_t t) const {
  const auto& tr = triangles[t];
  return (vertices[tr[1]] - vertices[tr[0]]).cross(vertices[tr[2]] - vertices[tr[0]]);
}

double TriangleSurface::Area(std::size_t t) const { return 0.5 * Normal(t).norm(); }

Eigen::Vector3d TriangleSurface::Min() const {
  Eigen::Vector3d m = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
  for (const auto& v : vertices) m = m.cwiseMin(v);
  return m;
}

Eigen::Vector3d TriangleSurface::Max() const {
  Eigen::Vector3d m = Eigen::Vector3d::Constant(-std::numeric_limits<double>::infinity());
  for (const auto& v : vertices) m = m.cwiseMax(v);
  return m;
}

TriangleSurface ReadStl(const fs::path& path) { return ParseStl(ReadBytes(path), path); }

TriangleSurface ReadObj(const fs::path& path) { return ParseObj(ReadBytes(path), path); }

TriangleSurface ParseStl(const std::string& bytes, const fs::path& path) {
  const std::string data = Decompressed(path, bytes);
  if (data.empty()) Fail(path, "empty file; expected an STL surface");
  TriangleSurface s;
  const bool looks_ascii = data.compare(0, 5, "solid") == 0 &&
                           data.find("facet", 0) != std::string::npos;
  if (looks_ascii) {
    s = ParseAsciiStl(path, data);
  } else {
    if (data.size() < 84) {
      Fail(path, fmt::format("{} bytes is too short for a binary STL header (84 bytes)", data.size()));
    }
    s = ParseBinaryStl(path, data);
  }
  if (s.triangles.empty()) Fail(path, "no triangles; expected a hull surface");
  return s;
}

TriangleSurface ParseObj(const std::string& bytes, const fs::path& path) {
  const std::string data = Decompressed(path, bytes);
  TriangleSurface s;
  s.source = path.string();
  std::vector<Eigen::Vector3d> raw;
  std::istringstream in(data);
  std::string line;
  int line_no = 0;
  std::vector<std::array<int, 3>> faces;
  while (std::getline(in, line)) {
    ++line_no;
    std::istringstream ls(line);
    std::string word;
    if (!(ls >> word) || word[0] == '#') continue;
    if (word == "v") {
      std::string xs, ys, zs;
      if (!(ls >> xs >> ys >> zs)) Fail(path, fmt::format("line {}: expected 'v x y z', got '{}'", line_no, line));
      try {
        raw.emplace_back(std::stod(xs), std::stod(ys), std::stod(zs));
      } catch (const std::exception&) {
        Fail(path, fmt::format("line {}: expected three numbers after 'v', got '{} {} {}'", line_no, xs, ys, zs));
      }
      if (!raw.back().allFinite()) {
        Fail(path, fmt::format("line {}: vertex {} has a non-finite coordinate; expected finite numbers", line_no,
                               raw.size()));
      }
    } else if (word == "f") {
      std::vector<int> idx;
      std::string tok;
      while (ls >> tok) {
        const std::string head = tok.substr(0, tok.find('/'));
        int i = 0;
        try {
          i = std::stoi(head);
        } catch (const std::exception&) {
          Fail(path, fmt::format("line {}: face index '{}' is not an integer", line_no, tok));
        }
        const int n = static_cast<int>(raw.size());
        const int resolved = i > 0 ? i - 1 : n + i;  // negative: relative to the end
        if (i == 0 || resolved < 0 || resolved >= n) {
          Fail(path, fmt::format("line {}: face refers to vertex {} but {} vertices are defined", line_no, i, n));
        }
        idx.push_back(resolved);
      }
      if (idx.size() < 3) Fail(path, fmt::format("line {}: face has {} vertices; expected at least 3", line_no, idx.size()));
      for (std::size_t k = 1; k + 1 < idx.size(); ++k) faces.push_back({idx[0], idx[k], idx[k + 1]});
    }
  }
  if (faces.empty()) Fail(path, "no faces; expected a hull surface");
  VertexWelder weld(s);
  std::vector<int> map(raw.size(), -1);
  for (auto f : faces) {
    std::array<int, 3> t{};
    for (int c = 0; c < 3; ++c) {
      if (map[f[c]] < 0) map[f[c]] = weld.Add(raw[f[c]]);
      t[c] = map[f[c]];
    }
    s.triangles.push_back(t);
  }
  return s;
}

TriangleSurface ReadSurface(const fs::path& path) {
  std::string name = path.filename().string();
  std::transform(name.begin(), name.end(), name.begin(), [](unsigned char c) { return std::tolower(c); });
  if (name.ends_with(".gz")) name = name.substr(0, name.size() - 3);
  if (name.ends_with(".stl")) return ReadStl(path);
  if (name.ends_with(".obj")) return ReadObj(path);
  Fail(path, "unknown surface format; expected .stl, .stl.gz, .obj or .obj.gz");
}

void WeldIdenticalVertices(TriangleSurface& s) {
  TriangleSurface welded;
  welded.source = s.source;
  VertexWelder weld(welded);
  for (const auto& t : s.triangles) {
    std::array<int, 3> w{};
    for (int c = 0; c < 3; ++c) w[c] = weld.Add(s.vertices[t[c]]);
    if (w[0] != w[1] && w[1] != w[2] && w[0] != w[2]) welded.triangles.push_back(w);
  }
  s = std::move(welded);
}

void WriteStl(const TriangleSurface& s, const fs::path& path) {
  std::string out(80, '\0');
  const std::string header = "kelvin binary STL";
  std::memcpy(out.data(), header.data(), header.size());
  const auto n = static_cast<std::uint32_t>(s.triangles.size());
  out.append(reinterpret_cast<const char*>(&n), 4);
  for (std::size_t t = 0; t < s.triangles.size(); ++t) {
    const Eigen::Vector3d nrm = s.Normal(t).normalized();
    float rec[12];
    for (int k = 0; k < 3; ++k) rec[k] = static_cast<float>(nrm[k]);
    for (int c = 0; c < 3; ++c) {
      for (int k = 0; k < 3; ++k) rec[3 + 3 * c + k] = static_cast<float>(s.vertices[s.triangles[t][c]][k]);
    }
    out.append(reinterpret_cast<const char*>(rec), sizeof rec);
    out.append(2, '\0');
  }
  data::WriteFileAtomically(path, out);
}

std::string SurfaceCheck::Summary() const {
  return fmt::format("{} open edges ({} below the waterline), {} non-manifold edges, {} inconsistently oriented "
                     "edges, {} degenerate triangles, underwater volume {:.6g}{}",
                     open_edges, open_edges_below, non_manifold_edges, inconsistent_edges, degenerate_triangles,
                     underwater_volume, flipped ? " (normals pointed inward and were flipped)" : "");
}

SurfaceCheck CheckSurface(const TriangleSurface& s, double waterline_z) {
  SurfaceCheck c;
  // Each undirected edge: how often it is used, and how often in each direction.
  std::map<std::pair<int, int>, std::array<int, 2>> edges;
  const Eigen::Vector3d span = s.Max() - s.Min();
  const double tiny_area = 1e-14 * span.squaredNorm();
  for (std::size_t t = 0; t < s.triangles.size(); ++t) {
    const auto& tr = s.triangles[t];
    if (tr[0] == tr[1] || tr[1] == tr[2] || tr[0] == tr[2] || s.Area(t) <= tiny_area) ++c.degenerate_triangles;
    for (int e = 0; e < 3; ++e) {
      const int a = tr[e], b = tr[(e + 1) % 3];
      if (a == b) continue;
      auto& count = edges[{std::min(a, b), std::max(a, b)}];
      ++count[a < b ? 0 : 1];
    }
  }
  // Orientation from the immersed volume, which is defined even for a hull
  // that is open above the waterline (the waterplane closes it).
  {
    TriangleSurface shifted = s;
    for (auto& v : shifted.vertices) v.z() -= waterline_z;
    c.underwater_volume = UnderwaterVolume(shifted);
  }
  for (const auto& [key, count] : edges) {
    const int total = count[0] + count[1];
    if (total == 1) {
      ++c.open_edges;
      if (std::min(s.vertices[key.first].z(), s.vertices[key.second].z()) < waterline_z) ++c.open_edges_below;
    } else if (total > 2) {
      ++c.non_manifold_edges;
    } else if (count[0] == 2 || count[1] == 2) {
      ++c.inconsistent_edges;
    }
  }
  return c;
}

SurfaceCheck ValidateHull(TriangleSurface& s, double waterline_z, bool submerged_allowed) {
  const fs::path file = s.source;
  const SurfaceCheck c = CheckSurface(s, waterline_z);
  const Eigen::Vector3d lo = s.Min(), hi = s.Max();
  if (lo.z() >= waterline_z) {
    Fail(file, fmt::format("the hull lies entirely above the waterline (lowest z = {} >= waterline z = {}); check "
                           "geometry.waterline_z and the length unit",
                           lo.z(), waterline_z));
  }
  const bool submerged = hi.z() <= waterline_z;
  if (submerged && !submerged_allowed) {
    Fail(file, fmt::format("the hull lies entirely below the waterline (highest z = {} <= waterline z = {}); "
                           "expected a surface-piercing hull (check geometry.waterline_z and the length unit; for a "
                           "body meant to run fully submerged set geometry.submerged: true in the ship file)",
                           hi.z(), waterline_z));
  }
  if (submerged && c.open_edges > 0) {
    Fail(file, fmt::format("{} open edges on a fully submerged body; expected a closed surface ({})", c.open_edges,
                           c.Summary()));
  }
  if (c.degenerate_triangles > 0) {
    Fail(file, fmt::format("{} degenerate (zero-area) triangles; expected a clean surface ({})",
                           c.degenerate_triangles, c.Summary()));
  }
  if (c.inconsistent_edges > 0) {
    Fail(file, fmt::format("inconsistent normals: {} edges are traversed twice in the same direction; expected "
                           "consistently oriented triangles",
                           c.inconsistent_edges));
  }
  if (c.open_edges_below > 0) {
    Fail(file, fmt::format("{} open edges below the waterline; expected a watertight underwater hull ({})",
                           c.open_edges_below, c.Summary()));
  }
  if (c.underwater_volume < 0) {
    for (auto& t : s.triangles) std::swap(t[1], t[2]);
    SurfaceCheck flipped = c;
    flipped.underwater_volume = -c.underwater_volume;
    flipped.flipped = true;
    return flipped;
  }
  return c;
}

}  // namespace kelvin::cfd
