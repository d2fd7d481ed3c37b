#include "cfd/mesh/poly_mesh_reader.h"

#include <fmt/format.h>

#include <cctype>
#include <cstring>
#include <fstream>
#include <limits>
#include <optional>
#include <sstream>

#include "data/schema/errors.h"
#include "data/schema/file_status.h"

namespace kelvin::cfd {
namespace {

namespace fs = std::filesystem;

// One OpenFOAM file: header fields and a cursor over the body.
class FoamFile {
 public:
  FoamFile(const fs::path& path, std::string text) : path_(path), text_(std::move(text)) { ParseHeader(); }

  [[noreturn]] void Fail(const std::string& what) const {
    throw DataFileError(fmt::format("{}: {}", path_.string(), what));
  }
  [[noreturn]] void FailAt(const std::string& what) const {
    throw DataFileError(fmt::format("{}:{}: {}", path_.string(), LineAt(pos_), what));
  }
  bool binary() const { return binary_; }
  const std::string& class_name() const { return class_; }
  std::size_t label_bytes() const { return label_bytes_; }
  std::size_t scalar_bytes() const { return scalar_bytes_; }
  const fs::path& path() const { return path_; }

  void SkipSpace() {
    while (pos_ < text_.size()) {
      const char c = text_[pos_];
      if (std::isspace(static_cast<unsigned char>(c))) {
        ++pos_;
      } else if (c == '/' && pos_ + 1 < text_.size() && text_[pos_ + 1] == '/') {
        while (pos_ < text_.size() && text_[pos_] != '\n') ++pos_;
      } else if (c == '/' && pos_ + 1 < text_.size() && text_[pos_ + 1] == '*') {
        const std::size_t end = text_.find("*/", pos_ + 2);
        pos_ = end == std::string::npos ? text_.size() : end + 2;
      } else {
        break;
      }
    }
  }
  bool AtEnd() {
    SkipSpace();
    return pos_ >= text_.size();
  }
  char Peek() {
    SkipSpace();
    if (pos_ >= text_.size()) FailAt("file is truncated; expected more data");
    return text_[pos_];
  }
  void Expect(char c, const std::string& context) {
    if (Peek() != c) FailAt(fmt::format("expected '{}' {}, found '{}'", c, context, text_[pos_]));
    ++pos_;
  }
  std::string Word() {
    SkipSpace();
    const std::size_t start = pos_;
    while (pos_ < text_.size()) {
      const char c = text_[pos_];
      if (std::isspace(static_cast<unsigned char>(c)) || c == ';' || c == '(' || c == ')' || c == '{' || c == '}')
        break;
      ++pos_;
    }
    if (pos_ == start) FailAt(pos_ >= text_.size() ? "file is truncated; expected a word"
                                                   : fmt::format("expected a word, found '{}'", text_[pos_]));
    return text_.substr(start, pos_ - start);
  }
  long long Integer(const std::string& what) {
    SkipSpace();
    if (pos_ >= text_.size()) FailAt(fmt::format("file is truncated; expected {}", what));
    const char* begin = text_.c_str() + pos_;
    char* end = nullptr;
    const long long v = std::strtoll(begin, &end, 10);
    if (end == begin || (*end == '.' || *end == 'e' || *end == 'E')) {
      FailAt(fmt::format("expected {} (an integer), found '{}'", what, std::string(begin, std::min<std::size_t>(12, std::strlen(begin)))));
    }
    pos_ += static_cast<std::size_t>(end - begin);
    return v;
  }
  double Real(const std::string& what) {
    SkipSpace();
    if (pos_ >= text_.size()) FailAt(fmt::format("file is truncated; expected {}", what));
    const char* begin = text_.c_str() + pos_;
    char* end = nullptr;
    const double v = std::strtod(begin, &end);
    if (end == begin) FailAt(fmt::format("expected {} (a number), found '{}'", what, text_[pos_]));
    pos_ += static_cast<std::size_t>(end - begin);
    return v;
  }
  std::size_t remaining() const { return text_.size() - pos_; }
  // Raw bytes of a binary list body.
  const char* Bytes(std::size_t n, const std::string& what) {
    if (pos_ + n > text_.size()) {
      Fail(fmt::format("file is truncated in {}: expected {} bytes of binary data, found {}", what, n,
                       text_.size() - pos_));
    }
    const char* p = text_.data() + pos_;
    pos_ += n;
    return p;
  }
  long long LabelFromBytes(const char* p) const {
    if (label_bytes_ == 8) {
      std::int64_t v;
      std::memcpy(&v, p, 8);
      return v;
    }
    std::int32_t v;
    std::memcpy(&v, p, 4);
    return v;
  }
  double ScalarFromBytes(const char* p) const {
    if (scalar_bytes_ == 4) {
      float v;
      std::memcpy(&v, p, 4);
      return v;
    }
    double v;
    std::memcpy(&v, p, 8);
    return v;
  }
  // Skips a `key value;` entry or a `key { ... }` dictionary.
  void SkipEntryValue() {
    int depth = 0;
    while (true) {
      const char c = Peek();
      if (c == '{' || c == '(') ++depth;
      if (c == '}' || c == ')') --depth;
      ++pos_;
      if (depth == 0 && (c == ';' || c == '}')) return;
    }
  }
  // Reads `key value;` entries of a dictionary up to '}'.
  std::vector<std::pair<std::string, std::string>> Dictionary(const std::string& context) {
    Expect('{', context);
    std::vector<std::pair<std::string, std::string>> entries;
    while (Peek() != '}') {
      const std::string key = Word();
      if (Peek() == '{') {
        SkipEntryValue();
        continue;
      }
      SkipSpace();
      const std::size_t start = pos_;
      int depth = 0;
      while (true) {
        if (pos_ >= text_.size()) Fail(fmt::format("file is truncated in {}: entry '{}' has no ';'", context, key));
        const char c = text_[pos_];
        if (c == '(') ++depth;
        if (c == ')') --depth;
        if (c == ';' && depth == 0) break;
        ++pos_;
      }
      std::string value = text_.substr(start, pos_ - start);
      while (!value.empty() && std::isspace(static_cast<unsigned char>(value.back()))) value.pop_back();
      entries.emplace_back(key, value);
      ++pos_;
    }
    ++pos_;
    return entries;
  }

 private:
  void ParseHeader() {
    SkipSpace();
    if (text_.compare(pos_, 8, "FoamFile") != 0) {
      Fail("has no FoamFile header; expected an OpenFOAM file starting with 'FoamFile { ... }'");
    }
    pos_ += 8;
    for (const auto& [key, value] : Dictionary("FoamFile header")) {
      if (key == "format") {
        if (value == "binary") {
          binary_ = true;
        } else if (value != "ascii") {
          Fail(fmt::format("header format '{}'; expected ascii or binary", value));
        }
      } else if (key == "class") {
        class_ = value;
      } else if (key == "arch") {
        std::string a = value;
        if (!a.empty() && a.front() == '"') a = a.substr(1, a.size() - 2);
        if (a.find("label=64") != std::string::npos) label_bytes_ = 8;
        if (a.find("scalar=32") != std::string::npos) scalar_bytes_ = 4;
        if (a.find("MSB") != std::string::npos) Fail("arch is big-endian (MSB); expected LSB");
      }
    }
  }
  int LineAt(std::size_t pos) const {
    int line = 1;
    for (std::size_t i = 0; i < pos && i < text_.size(); ++i) line += text_[i] == '\n';
    return line;
  }

  fs::path path_;
  std::string text_;
  std::size_t pos_ = 0;
  bool binary_ = false;
  std::string class_;
  std::size_t label_bytes_ = 4;
  std::size_t scalar_bytes_ = 8;
};

// The text of one polyMesh file.
std::string ReadFoamText(const fs::path& path) {
  if (!data::PathExists(path)) {
    const std::string where = path.string();
    if (data::PathExists(where + ".gz")) {
      throw DataFileError(fmt::format("{}: is gzip-compressed ({}.gz); expected an uncompressed file (run "
                                      "foamFormatConvert or set writeCompression off)",
                                      where, path.filename().string()));
    }
    throw DataFileError(where + ": does not exist; expected an OpenFOAM polyMesh file");
  }
  std::ifstream in(path, std::ios::binary);
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// A uniform list `N{v}` of labels is only meaningful for a tiny mesh (every
// face owned by one cell, ...); longer ones are refused before they take the
// memory of N labels.
constexpr long long kMaxUniformLabels = 1 << 24;

// A list count that the rest of the file can hold: at least `entry_bytes`
// per entry, and at most the largest label kelvin stores (int).
void CheckCount(FoamFile& file, long long n, std::size_t entry_bytes, const std::string& what) {
  if (n < 0) file.FailAt(fmt::format("{} count is {}; expected >= 0", what, n));
  if (n > std::numeric_limits<int>::max()) {
    file.FailAt(fmt::format("{} count is {}; expected at most {} (kelvin's labels are 32-bit)", what, n,
                            std::numeric_limits<int>::max()));
  }
  if (static_cast<std::size_t>(n) > file.remaining() / entry_bytes) {
    file.FailAt(fmt::format("{} count is {} but only {} bytes follow; expected at least {} bytes per entry "
                            "(truncated file or wrong count)",
                            what, n, file.remaining(), entry_bytes));
  }
}

long long CheckLabel(FoamFile& file, long long v, long long i, const std::string& what) {
  if (v < std::numeric_limits<int>::min() || v > std::numeric_limits<int>::max()) {
    file.Fail(fmt::format("entry {} of {} is {}; expected a 32-bit label", i, what, v));
  }
  return v;
}

// A list of labels: `N ( a b c )`, `N{v}`, or binary `N(<bytes>)`.
std::vector<long long> ReadLabelList(FoamFile& file, const std::string& what) {
  const long long n = file.Integer(fmt::format("the number of {}", what));
  std::vector<long long> out;
  if (file.Peek() == '{') {
    if (n < 0 || n > kMaxUniformLabels) {
      file.FailAt(fmt::format("uniform list of {} {}; expected 0 to {} entries for a uniform list", n, what,
                              kMaxUniformLabels));
    }
    file.Expect('{', "");
    const long long v = CheckLabel(file, file.Integer(what), 0, what);
    file.Expect('}', fmt::format("after the uniform value of {}", what));
    out.assign(static_cast<std::size_t>(n), v);
    return out;
  }
  CheckCount(file, n, file.binary() ? file.label_bytes() : 2, what);
  out.reserve(static_cast<std::size_t>(n));
  file.Expect('(', fmt::format("to open the list of {} {}", n, what));
  if (file.binary() && n > 0) {
    const char* p = file.Bytes(static_cast<std::size_t>(n) * file.label_bytes(), what);
    for (long long i = 0; i < n; ++i) out.push_back(CheckLabel(file, file.LabelFromBytes(p + i * file.label_bytes()), i, what));
  } else {
    for (long long i = 0; i < n; ++i) {
      if (file.AtEnd() || file.Peek() == ')') {
        file.FailAt(fmt::format("list of {} ends after {} entries; expected {} (the count in the file)", what, i, n));
      }
      out.push_back(CheckLabel(file, file.Integer(fmt::format("entry {} of {}", i, what)), i, what));
    }
  }
  if (file.AtEnd()) file.Fail(fmt::format("file is truncated: the list of {} {} has no closing ')'", n, what));
  if (file.Peek() != ')') {
    file.FailAt(fmt::format("list of {} has more entries than its count {}; expected ')'", what, n));
  }
  file.Expect(')', "");
  return out;
}

std::vector<Vector3> ReadPoints(FoamFile file) {
  const long long n = file.Integer("the number of points");
  CheckCount(file, n, file.binary() ? 3 * file.scalar_bytes() : 7, "point");
  std::vector<Vector3> pts;
  pts.reserve(static_cast<std::size_t>(n));
  file.Expect('(', "to open the point list");
  if (file.binary() && n > 0) {
    const std::size_t s = file.scalar_bytes();
    const char* p = file.Bytes(static_cast<std::size_t>(n) * 3 * s, "points");
    for (long long i = 0; i < n; ++i) {
      pts.emplace_back(file.ScalarFromBytes(p + (3 * i) * s), file.ScalarFromBytes(p + (3 * i + 1) * s),
                       file.ScalarFromBytes(p + (3 * i + 2) * s));
    }
  } else {
    for (long long i = 0; i < n; ++i) {
      if (file.AtEnd() || file.Peek() == ')') {
        file.FailAt(fmt::format("point list ends after {} points; expected {} (the count in the file)", i, n));
      }
      file.Expect('(', fmt::format("to open point {}", i));
      Vector3 x;
      for (int d = 0; d < 3; ++d) x[d] = file.Real(fmt::format("coordinate {} of point {}", d, i));
      file.Expect(')', fmt::format("to close point {} (3 coordinates)", i));
      pts.push_back(x);
    }
  }
  if (file.AtEnd()) file.Fail(fmt::format("file is truncated: the list of {} points has no closing ')'", n));
  if (file.Peek() != ')') file.FailAt(fmt::format("point list has more entries than its count {}", n));
  file.Expect(')', "");
  return pts;
}

std::vector<std::vector<int>> ReadFaces(FoamFile file) {
  std::vector<std::vector<int>> faces;
  if (file.class_name() == "faceCompactList") {
    const std::vector<long long> offsets = ReadLabelList(file, "face offsets");
    const std::vector<long long> labels = ReadLabelList(file, "face point labels");
    if (offsets.empty()) return faces;
    if (offsets.back() != static_cast<long long>(labels.size())) {
      file.Fail(fmt::format("last face offset is {} but there are {} point labels; expected them to match",
                            offsets.back(), labels.size()));
    }
    for (std::size_t f = 0; f + 1 < offsets.size(); ++f) {
      if (offsets[f + 1] < offsets[f] || offsets[f] < 0 || offsets[f + 1] > offsets.back()) {
        file.Fail(fmt::format("face offsets of face {} are {} and {}; expected a non-decreasing list from 0 to the {} "
                              "point labels",
                              f, offsets[f], offsets[f + 1], labels.size()));
      }
      faces.emplace_back(labels.begin() + offsets[f], labels.begin() + offsets[f + 1]);
    }
    return faces;
  }
  if (file.binary()) file.Fail("binary faces must be a faceCompactList; found class " + file.class_name());
  const long long n = file.Integer("the number of faces");
  CheckCount(file, n, 4, "face");
  file.Expect('(', "to open the face list");
  faces.reserve(static_cast<std::size_t>(n));
  for (long long f = 0; f < n; ++f) {
    if (file.AtEnd() || file.Peek() == ')') {
      file.FailAt(fmt::format("face list ends after {} faces; expected {} (the count in the file)", f, n));
    }
    const long long m = file.Integer(fmt::format("the point count of face {}", f));
    file.Expect('(', fmt::format("to open face {}", f));
    std::vector<int> face;
    for (long long i = 0; i < m; ++i) {
      face.push_back(static_cast<int>(CheckLabel(file, file.Integer(fmt::format("point {} of face {}", i, f)), i,
                                                 fmt::format("face {}", f))));
    }
    file.Expect(')', fmt::format("to close face {} ({} points)", f, m));
    faces.push_back(std::move(face));
  }
  if (file.AtEnd()) file.Fail(fmt::format("file is truncated: the list of {} faces has no closing ')'", n));
  if (file.Peek() != ')') file.FailAt(fmt::format("face list has more entries than its count {}", n));
  file.Expect(')', "");
  return faces;
}

std::vector<Patch> ReadBoundary(FoamFile file) {
  const long long n = file.Integer("the number of patches");
  file.Expect('(', "to open the patch list");
  std::vector<Patch> patches;
  for (long long i = 0; i < n; ++i) {
    if (file.AtEnd() || file.Peek() == ')') {
      file.FailAt(fmt::format("patch list ends after {} patches; expected {} (the count in the file)", i, n));
    }
    Patch p;
    p.name = file.Word();
    std::optional<long long> n_faces, start;
    std::string type;
    for (const auto& [key, value] : file.Dictionary("patch " + p.name)) {
      if (key == "type") type = value;
      if (key == "nFaces" || key == "startFace") {
        char* end = nullptr;
        const long long v = std::strtoll(value.c_str(), &end, 10);
        if (end == value.c_str() || *end != '\0' || v < 0 || v > std::numeric_limits<int>::max()) {
          file.Fail(fmt::format("patch '{}': {} = '{}'; expected an integer from 0 to {}", p.name, key, value,
                                std::numeric_limits<int>::max()));
        }
        (key == "nFaces" ? n_faces : start) = v;
      }
    }
    if (!n_faces || !start || type.empty()) {
      file.Fail(fmt::format("patch '{}' lacks {}; expected type, nFaces and startFace", p.name,
                            type.empty() ? "type" : (!n_faces ? "nFaces" : "startFace")));
    }
    if (type == "patch") {
      p.kind = PatchKind::kPatch;
    } else if (type == "wall") {
      p.kind = PatchKind::kWall;
    } else if (type == "symmetryPlane" || type == "symmetry") {
      p.kind = PatchKind::kSymmetry;
    } else if (type == "empty") {
      p.kind = PatchKind::kEmpty;
    } else {
      file.Fail(fmt::format("patch '{}' has unknown type '{}'; expected one of patch, wall, symmetryPlane, "
                            "symmetry, empty",
                            p.name, type));
    }
    p.size = static_cast<int>(*n_faces);
    p.start = static_cast<int>(*start);
    patches.push_back(p);
  }
  file.Expect(')', fmt::format("to close the list of {} patches", n));
  return patches;
}

std::vector<int> ToInt(const std::vector<long long>& v) { return std::vector<int>(v.begin(), v.end()); }

// Every cell has at least four faces and a face at most two cells, so a cell
// label at or beyond the number of faces is an error (and would size the mesh's
// per-cell arrays from a stray number).
void CheckCellLabels(const std::vector<int>& cells, std::size_t n_faces, const fs::path& file,
                     const std::string& what) {
  for (std::size_t f = 0; f < cells.size(); ++f) {
    if (cells[f] >= 0 && static_cast<std::size_t>(cells[f]) >= n_faces) {
      throw DataFileError(fmt::format("{}: {} of face {} is cell {}; expected a cell index below the {} faces "
                                      "(a polyMesh has fewer cells than faces)",
                                      file.string(), what, f, cells[f], n_faces));
    }
  }
}

}  // namespace

std::vector<Vector3> ParsePolyMeshPoints(const std::string& text, const fs::path& file) {
  return ReadPoints(FoamFile(file, text));
}

std::vector<std::vector<int>> ParsePolyMeshFaces(const std::string& text, const fs::path& file) {
  return ReadFaces(FoamFile(file, text));
}

std::vector<int> ParsePolyMeshLabels(const std::string& text, const fs::path& file, const std::string& what) {
  FoamFile foam(file, text);
  return ToInt(ReadLabelList(foam, what));
}

std::vector<Patch> ParsePolyMeshBoundary(const std::string& text, const fs::path& file) {
  return ReadBoundary(FoamFile(file, text));
}

Mesh ReadPolyMesh(const fs::path& dir) {
  if (!data::IsExistingDirectory(dir)) {
    throw DataFileError(fmt::format("{}: not a directory; expected an OpenFOAM constant/polyMesh directory",
                                    dir.string()));
  }
  PolyMeshText text;
  for (auto [name, member] : {std::pair{"points", &PolyMeshText::points}, {"faces", &PolyMeshText::faces},
                              {"owner", &PolyMeshText::owner}, {"neighbour", &PolyMeshText::neighbour},
                              {"boundary", &PolyMeshText::boundary}}) {
    text.*member = ReadFoamText(dir / name);
  }
  return ParsePolyMesh(text, dir);
}

Mesh ParsePolyMesh(const PolyMeshText& text, const fs::path& dir) {
  std::vector<Vector3> points = ParsePolyMeshPoints(text.points, dir / "points");
  std::vector<std::vector<int>> faces = ParsePolyMeshFaces(text.faces, dir / "faces");
  std::vector<int> owner = ParsePolyMeshLabels(text.owner, dir / "owner", "owners");
  std::vector<int> neighbour = ParsePolyMeshLabels(text.neighbour, dir / "neighbour", "neighbours");
  std::vector<Patch> patches = ParsePolyMeshBoundary(text.boundary, dir / "boundary");

  const std::string where = (dir / "owner").string();
  if (owner.size() != faces.size()) {
    throw DataFileError(fmt::format("{}: {} owners but {} has {} faces; expected one owner per face", where,
                                    owner.size(), (dir / "faces").string(), faces.size()));
  }
  if (neighbour.size() > faces.size()) {
    throw DataFileError(fmt::format("{}: {} neighbours but only {} faces; expected at most one per face",
                                    (dir / "neighbour").string(), neighbour.size(), faces.size()));
  }
  CheckCellLabels(owner, faces.size(), dir / "owner", "owner");
  CheckCellLabels(neighbour, faces.size(), dir / "neighbour", "neighbour");
  for (std::size_t f = 0; f < faces.size(); ++f) {
    for (int p : faces[f]) {
      if (p < 0 || p >= static_cast<int>(points.size())) {
        throw DataFileError(fmt::format("{}: face {} uses point {}; expected an index in [0, {}) ({} points)",
                                        (dir / "faces").string(), f, p, points.size(),
                                        (dir / "points").string()));
      }
    }
  }
  // Patches must tile the boundary faces exactly.
  long long expected = static_cast<long long>(neighbour.size());
  for (const Patch& p : patches) {
    if (p.start != expected) {
      throw DataFileError(fmt::format("{}: patch '{}' has startFace {}; expected {} (right after the previous patch, "
                                      "the first boundary face is {})",
                                      (dir / "boundary").string(), p.name, p.start, expected, neighbour.size()));
    }
    expected += p.size;
  }
  if (expected != static_cast<long long>(faces.size())) {
    throw DataFileError(fmt::format("{}: the patches cover {} boundary faces; expected {} (faces {} minus internal "
                                    "faces {})",
                                    (dir / "boundary").string(), expected - neighbour.size(),
                                    faces.size() - neighbour.size(), faces.size(), neighbour.size()));
  }
  return Mesh(std::move(points), std::move(faces), std::move(owner), std::move(neighbour), std::move(patches),
              dir.string());
}

}  // namespace kelvin::cfd
