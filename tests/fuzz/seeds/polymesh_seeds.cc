// polyMesh seeds: two hexahedra side by side (12 points, 11 faces, patches
// inlet, outlet, walls) in ASCII (faceList and faceCompactList) and binary
// (label=32 and label=64), as single files and joined for polymesh_fuzzer.
#include <fmt/format.h>

#include <array>
#include <cstdint>
#include <cstring>
#include <vector>

#include "tests/fuzz/polymesh_input.h"
#include "tests/fuzz/seeds/seeds.h"

namespace kelvin::fuzz {
namespace {

namespace fs = std::filesystem;

constexpr int P(int i, int j, int k) { return i + 3 * (j + 2 * k); }

const std::vector<std::array<int, 4>> kFaces = {
    {P(1, 0, 0), P(1, 1, 0), P(1, 1, 1), P(1, 0, 1)},                                                 // internal
    {P(0, 0, 0), P(0, 0, 1), P(0, 1, 1), P(0, 1, 0)}, {P(2, 0, 0), P(2, 1, 0), P(2, 1, 1), P(2, 0, 1)},  // in, out
    {P(0, 0, 0), P(1, 0, 0), P(1, 0, 1), P(0, 0, 1)}, {P(1, 0, 0), P(2, 0, 0), P(2, 0, 1), P(1, 0, 1)},
    {P(0, 1, 0), P(0, 1, 1), P(1, 1, 1), P(1, 1, 0)}, {P(1, 1, 0), P(1, 1, 1), P(2, 1, 1), P(2, 1, 0)},
    {P(0, 0, 0), P(0, 1, 0), P(1, 1, 0), P(1, 0, 0)}, {P(1, 0, 0), P(1, 1, 0), P(2, 1, 0), P(2, 0, 0)},
    {P(0, 0, 1), P(1, 0, 1), P(1, 1, 1), P(0, 1, 1)}, {P(1, 0, 1), P(2, 0, 1), P(2, 1, 1), P(1, 1, 1)}};
const std::vector<int> kOwner = {0, 0, 1, 0, 1, 0, 1, 0, 1, 0, 1};

struct Format {
  bool binary;
  int label_bytes;
};

std::string Header(Format f, const char* cls, const char* object) {
  return fmt::format("FoamFile\n{{\n    version 2.0;\n    format {};\n{}    class {};\n    location \"constant/polyMesh\";\n"
                     "    object {};\n}}\n// * * * //\n\n",
                     f.binary ? "binary" : "ascii",
                     f.binary ? fmt::format("    arch \"LSB;label={};scalar=64\";\n", 8 * f.label_bytes) : "", cls,
                     object);
}

template <typename T>
void AppendRaw(std::string& out, T v) {
  char b[sizeof v];
  std::memcpy(b, &v, sizeof v);
  out.append(b, sizeof v);
}

std::string Labels(Format f, const std::vector<int>& v) {
  std::string out = fmt::format("{}\n(", v.size());
  for (int x : v) {
    if (!f.binary) out += fmt::format("{}{}", x, ' ');
    else if (f.label_bytes == 8) AppendRaw(out, static_cast<std::int64_t>(x));
    else AppendRaw(out, static_cast<std::int32_t>(x));
  }
  return out + ")\n";
}

std::string Points(Format f) {
  std::string out = Header(f, "vectorField", "points") + "12\n(";
  for (int n = 0; n < 12; ++n) {
    const std::array<double, 3> x = {double(n % 3), double((n / 3) % 2), double(n / 6)};
    if (!f.binary) out += fmt::format("({} {} {})\n", x[0], x[1], x[2]);
    else for (double c : x) AppendRaw(out, c);
  }
  return out + ")\n";
}

std::string Faces(Format f, bool compact) {
  if (!compact) {
    std::string out = Header(f, "faceList", "faces") + fmt::format("{}\n(\n", kFaces.size());
    for (const auto& q : kFaces) out += fmt::format("4({} {} {} {})\n", q[0], q[1], q[2], q[3]);
    return out + ")\n";
  }
  std::vector<int> offsets = {0}, labels;
  for (const auto& q : kFaces) {
    labels.insert(labels.end(), q.begin(), q.end());
    offsets.push_back(static_cast<int>(labels.size()));
  }
  return Header(f, "faceCompactList", "faces") + Labels(f, offsets) + "\n" + Labels(f, labels);
}

std::string Boundary() {
  return Header({false, 4}, "polyBoundaryMesh", "boundary") +
         "3\n(\n    inlet\n    {\n        type patch;\n        nFaces 1;\n        startFace 1;\n    }\n"
         "    outlet { type patch; inGroups 1(outlet); nFaces 1; startFace 2; }\n"
         "    walls { type wall; nFaces 8; startFace 3; }\n)\n";
}

cfd::PolyMeshText Mesh(Format f, bool compact) {
  return {Points(f), Faces(f, compact), Header(f, "labelList", "owner") + Labels(f, kOwner),
          Header(f, "labelList", "neighbour") + Labels(f, {1}), Boundary()};
}

}  // namespace

void WritePolyMeshSeeds(const fs::path& out) {
  const std::array<std::pair<const char*, cfd::PolyMeshText>, 4> meshes = {
      {{"ascii", Mesh({false, 4}, false)},
       {"ascii_compact", Mesh({false, 4}, true)},
       {"binary32", Mesh({true, 4}, true)},
       {"binary64", Mesh({true, 8}, true)}}};
  for (const auto& [name, m] : meshes) {
    WriteSeed(out / "polymesh", name, JoinPolyMesh(m));
    WriteSeed(out / "polymesh_points", name, m.points);
    WriteSeed(out / "polymesh_faces", name, m.faces);
    WriteSeed(out / "polymesh_labels", std::string(name) + "_owner", m.owner);
    WriteSeed(out / "polymesh_labels", std::string(name) + "_neighbour", m.neighbour);
  }
  WriteSeed(out / "polymesh_labels", "uniform", Header({false, 4}, "labelList", "owner") + "11{0}\n");
  WriteSeed(out / "polymesh_boundary", "boundary", Boundary());
}

}  // namespace kelvin::fuzz
