#include "cfd/mesh/poly_mesh_reader.h"

#include <fmt/format.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <functional>
#include <fstream>
#include <regex>
#include <sstream>

#include "cfd/mesh/box_mesh.h"
#include "data/schema/errors.h"
#include "tests/test_utilities/test_utilities.h"

namespace kelvin::cfd {
namespace {

namespace fs = std::filesystem;

std::string Header(const std::string& cls, const std::string& object, bool binary) {
  return "FoamFile\n{\n    version 2.0;\n    format " + std::string(binary ? "binary" : "ascii") +
         ";\n    arch \"LSB;label=32;scalar=64\";\n    class " + cls + ";\n    object " + object + ";\n}\n"
         "// * * * * * //\n\n";
}

// Writes `mesh` as an OpenFOAM polyMesh (ASCII faceList, or binary
// faceCompactList), the way OpenFOAM lays the files out.
void WritePolyMesh(const Mesh& mesh, const fs::path& dir, bool binary) {
  fs::create_directories(dir);
  auto labels = [&](std::ostream& os, const std::vector<int>& v) {
    os << v.size() << "\n(";
    if (binary) {
      os.write(reinterpret_cast<const char*>(v.data()), static_cast<std::streamsize>(v.size() * sizeof(int)));
    } else {
      os << "\n";
      for (int x : v) os << x << "\n";
    }
    os << ")\n";
  };
  {
    std::ofstream os(dir / "points", std::ios::binary);
    os << Header("vectorField", "points", binary) << mesh.n_points() << "\n(";
    if (binary) {
      for (const Vector3& p : mesh.points()) os.write(reinterpret_cast<const char*>(p.data()), 24);
    } else {
      os << "\n";
      os.precision(17);
      for (const Vector3& p : mesh.points()) os << "(" << p.x() << " " << p.y() << " " << p.z() << ")\n";
    }
    os << ")\n";
  }
  {
    std::ofstream os(dir / "faces", std::ios::binary);
    if (binary) {
      os << Header("faceCompactList", "faces", true);
      std::vector<int> offsets{0}, flat;
      for (const auto& f : mesh.faces()) {
        flat.insert(flat.end(), f.begin(), f.end());
        offsets.push_back(static_cast<int>(flat.size()));
      }
      labels(os, offsets);
      labels(os, flat);
    } else {
      os << Header("faceList", "faces", false) << mesh.n_faces() << "\n(\n";
      for (const auto& f : mesh.faces()) {
        os << f.size() << "(";
        for (std::size_t i = 0; i < f.size(); ++i) os << (i ? " " : "") << f[i];
        os << ")\n";
      }
      os << ")\n";
    }
  }
  {
    std::ofstream os(dir / "owner", std::ios::binary);
    os << Header("labelList", "owner", binary);
    labels(os, std::vector<int>(mesh.owner().begin(), mesh.owner().end()));
  }
  {
    std::ofstream os(dir / "neighbour", std::ios::binary);
    os << Header("labelList", "neighbour", binary);
    labels(os, std::vector<int>(mesh.neighbour().begin(), mesh.neighbour().end()));
  }
  {
    std::ofstream os(dir / "boundary");
    os << Header("polyBoundaryMesh", "boundary", false) << mesh.patches().size() << "\n(\n";
    for (const Patch& p : mesh.patches()) {
      os << "    " << p.name << "\n    {\n        type " << PatchKindName(p.kind) << ";\n        inGroups 1(wall);\n"
         << "        nFaces " << p.size << ";\n        startFace " << p.start << ";\n    }\n";
    }
    os << ")\n";
  }
}

using kelvin::testing::ReadText;
void WriteText(const fs::path& p, const std::string& s) {
  std::ofstream out(p, std::ios::binary);
  out << s;
}

Mesh SampleMesh() {
  BoxMeshOptions opt;
  opt.cells = {3, 4, 2};
  opt.perturbation = 0.15;
  opt.polyhedral = true;
  return MakeBoxMesh(opt);
}

void ExpectSameMesh(const Mesh& a, const Mesh& b) {
  ASSERT_EQ(a.n_cells(), b.n_cells());
  ASSERT_EQ(a.n_faces(), b.n_faces());
  ASSERT_EQ(a.patches().size(), b.patches().size());
  for (int c = 0; c < a.n_cells(); ++c) {
    EXPECT_DOUBLE_EQ(a.cell_volumes()[c], b.cell_volumes()[c]);
  }
  for (std::size_t p = 0; p < a.patches().size(); ++p) {
    EXPECT_EQ(a.patches()[p].name, b.patches()[p].name);
    EXPECT_EQ(a.patches()[p].kind, b.patches()[p].kind);
  }
}

TEST(PolyMeshReader, AsciiAndBinaryRoundTrip) {
  testing::ScopedTempDir tmp;
  const Mesh mesh = SampleMesh();
  WritePolyMesh(mesh, tmp / "ascii", false);
  WritePolyMesh(mesh, tmp / "binary", true);
  ExpectSameMesh(mesh, ReadPolyMesh(tmp / "ascii"));
  ExpectSameMesh(mesh, ReadPolyMesh(tmp / "binary"));
}

// Each malformed input gives one DataFileError naming the file and the
// problem.
class BadPolyMesh : public ::testing::Test {
 protected:
  void SetUp() override { WritePolyMesh(SampleMesh(), dir_, binary_); }
  void ExpectError(const std::string& file_part, const std::string& message_part) {
    try {
      ReadPolyMesh(dir_);
      FAIL() << "expected a DataFileError containing '" << message_part << "'";
    } catch (const DataFileError& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find(file_part), std::string::npos) << what;
      EXPECT_NE(what.find(message_part), std::string::npos) << what;
    }
  }
  testing::ScopedTempDir tmp_;
  fs::path dir_ = tmp_ / "polyMesh";
  bool binary_ = false;
};

TEST_F(BadPolyMesh, TruncatedAsciiPoints) {
  const std::string text = ReadText(dir_ / "points");
  WriteText(dir_ / "points", text.substr(0, text.size() / 2));
  ExpectError("points", "truncated");
}

TEST_F(BadPolyMesh, TruncatedBinaryFaces) {
  WritePolyMesh(SampleMesh(), dir_, true);
  const std::string text = ReadText(dir_ / "faces");
  WriteText(dir_ / "faces", text.substr(0, text.size() - 40));
  ExpectError("faces", "truncated");
}

TEST_F(BadPolyMesh, PointCountLargerThanTheList) {
  std::string text = ReadText(dir_ / "points");
  const Mesh mesh = SampleMesh();
  const std::string count = fmt::format("\n{}\n(", mesh.n_points());
  const std::size_t at = text.find(count);
  ASSERT_NE(at, std::string::npos);
  const std::string bigger = fmt::format("\n{}\n(", mesh.n_points() + 5);
  WriteText(dir_ / "points", text.substr(0, at) + bigger + text.substr(at + count.size()));
  ExpectError("points", fmt::format("expected {}", mesh.n_points() + 5));
}

TEST_F(BadPolyMesh, OwnerCountDoesNotMatchFaces) {
  const Mesh mesh = SampleMesh();
  std::vector<int> owner(mesh.owner().begin(), mesh.owner().end() - 1);
  std::ostringstream os;
  os << Header("labelList", "owner", false) << owner.size() << "\n(\n";
  for (int o : owner) os << o << "\n";
  os << ")\n";
  WriteText(dir_ / "owner", os.str());
  ExpectError("owner", "expected one owner per face");
}

TEST_F(BadPolyMesh, PointIndexOutOfRange) {
  std::string text = ReadText(dir_ / "faces");
  const std::size_t at = text.find("4(");
  ASSERT_NE(at, std::string::npos);
  text.replace(at, 3, "4(999999");
  WriteText(dir_ / "faces", text);
  ExpectError("faces", "999999");
}

TEST_F(BadPolyMesh, NegativeVolume) {
  // One cube whose faces all point inwards.
  testing::ScopedTempDir tmp;
  BoxMeshOptions opt;
  opt.cells = {1, 1, 1};
  const Mesh cube = MakeBoxMesh(opt);
  WritePolyMesh(cube, dir_, false);
  std::ostringstream os;
  os << Header("faceList", "faces", false) << cube.n_faces() << "\n(\n";
  for (const auto& f : cube.faces()) os << "4(" << f[3] << " " << f[2] << " " << f[1] << " " << f[0] << ")\n";
  os << ")\n";
  WriteText(dir_ / "faces", os.str());
  ExpectError("polyMesh", "cell 0 has volume -1");
}

// Found by polymesh_fuzzer: a stray owner label sized the mesh's cell arrays
// (6.7 GB for cell 1.6e9).
TEST_F(BadPolyMesh, CellLabelBeyondTheFaces) {
  const Mesh mesh = SampleMesh();
  std::vector<int> owner(mesh.owner().begin(), mesh.owner().end());
  owner.back() = 1600000000;
  std::ostringstream os;
  os << Header("labelList", "owner", false) << owner.size() << "\n(\n";
  for (int o : owner) os << o << "\n";
  os << ")\n";
  WriteText(dir_ / "owner", os.str());
  ExpectError("owner", "is cell 1600000000; expected a cell index below the");
}

TEST_F(BadPolyMesh, UnknownPatchType) {
  std::string text = ReadText(dir_ / "boundary");
  const std::size_t at = text.find("type wall");
  ASSERT_NE(at, std::string::npos);
  text.replace(at, 9, "type cyclicAMI");
  WriteText(dir_ / "boundary", text);
  ExpectError("boundary", "unknown type 'cyclicAMI'");
}

TEST_F(BadPolyMesh, PatchesDoNotTileTheBoundary) {
  std::string text = ReadText(dir_ / "boundary");
  const std::size_t at = text.rfind("nFaces ");
  ASSERT_NE(at, std::string::npos);
  WriteText(dir_ / "boundary", text.substr(0, at + 7) + "1" + text.substr(at + 7));
  ExpectError("boundary", "the patches cover");
}

TEST_F(BadPolyMesh, MissingFile) {
  fs::remove(dir_ / "neighbour");
  ExpectError("neighbour", "does not exist");
}

TEST_F(BadPolyMesh, NotAFoamFile) {
  WriteText(dir_ / "owner", "hello\n");
  ExpectError("owner", "FoamFile header");
}

// checkMesh prints "Total volume = V." and "Minimum face area = a. Maximum face
// area = b." and the cell volume range.
double Grab(const std::string& text, const std::string& pattern) {
  std::smatch m;
  if (!std::regex_search(text, m, std::regex(pattern))) return std::nan("");
  return std::stod(m[1]);
}

TEST(PolyMeshReader, BlockMeshAgreesWithCheckMesh) {
  if (!fs::exists("/usr/share/openfoam/etc/bashrc")) {
    GTEST_SKIP() << "OpenFOAM (Debian package 'openfoam') is not installed; skipping the blockMesh comparison";
  }
  for (const bool binary : {false, true}) {
    testing::ScopedTempDir tmp;
    fs::create_directories(tmp / "system");
    fs::create_directories(tmp / "constant");
    WriteText(tmp / "system" / "controlDict",
              Header("dictionary", "controlDict", false) +
                  "application blockMesh;\nstartTime 0;\nendTime 1;\ndeltaT 1;\nwriteControl timeStep;\n"
                  "writeInterval 1;\nwriteFormat " +
                  (binary ? "binary" : "ascii") + ";\nwritePrecision 17;\nwriteCompression off;\n");
    WriteText(tmp / "system" / "fvSchemes",
              Header("dictionary", "fvSchemes", false) +
                  "ddtSchemes { default Euler; }\ngradSchemes { default Gauss linear; }\n"
                  "divSchemes { default none; }\nlaplacianSchemes { default Gauss linear corrected; }\n"
                  "interpolationSchemes { default linear; }\nsnGradSchemes { default corrected; }\n");
    WriteText(tmp / "system" / "fvSolution", Header("dictionary", "fvSolution", false) + "solvers {}\n");
    // A graded, sheared hexahedral block: non-orthogonal cells of varying size.
    WriteText(tmp / "system" / "blockMeshDict",
              Header("dictionary", "blockMeshDict", false) +
                  "scale 1;\nvertices ( (0 0 0) (2 0 0) (2.5 1 0) (0.5 1 0) (0 0 0.7) (2 0 0.7) (2.5 1 0.7) (0.5 1 0.7) );\n"
                  "blocks ( hex (0 1 2 3 4 5 6 7) (12 9 5) simpleGrading (3 0.5 2) );\n"
                  "boundary ( inlet { type patch; faces ((0 4 7 3)); } outlet { type patch; faces ((1 2 6 5)); }\n"
                  " walls { type wall; faces ((0 1 5 4) (3 7 6 2) (0 3 2 1) (4 5 6 7)); } );\n");
    const std::string env = "bash -c 'source /usr/share/openfoam/etc/bashrc >/dev/null 2>&1; cd " + tmp.path().string();
    const auto block = testing::RunCommand(env + " && blockMesh'");
    ASSERT_EQ(block.exit_code, 0) << block.output;
    const auto check = testing::RunCommand(env + " && checkMesh'");
    ASSERT_EQ(check.exit_code, 0) << check.output;
    const Mesh mesh = ReadPolyMesh(tmp / "constant" / "polyMesh");
    const MeshQuality q = mesh.Quality();
    const double total = Grab(check.output, R"(Total volume = ([0-9.eE+-]+)\.?\s)");
    const double min_area = Grab(check.output, R"(Minimum face area = ([0-9.eE+-]+)\.)");
    const double max_area = Grab(check.output, R"(Maximum face area = ([0-9.eE+-]+)\.)");
    const double min_vol = Grab(check.output, R"(Min volume = ([0-9.eE+-]+)\.)");
    const double max_vol = Grab(check.output, R"(Max volume = ([0-9.eE+-]+)\.)");
    ASSERT_FALSE(std::isnan(total)) << check.output;
    // checkMesh prints 6 significant digits.
    EXPECT_NEAR(q.total_volume, total, 1e-5 * total);
    EXPECT_NEAR(q.total_volume, 1.4, 1e-12);  // parallelogram 2 x 1 base, 0.7 high
    EXPECT_NEAR(q.min_volume, min_vol, 1e-5 * min_vol);
    EXPECT_NEAR(q.max_volume, max_vol, 1e-5 * max_vol);
    const auto mags = mesh.face_area_magnitudes();
    EXPECT_NEAR(*std::min_element(mags.begin(), mags.end()), min_area, 1e-5 * min_area);
    EXPECT_NEAR(*std::max_element(mags.begin(), mags.end()), max_area, 1e-5 * max_area);
    EXPECT_EQ(mesh.n_cells(), 12 * 9 * 5);
    EXPECT_EQ(mesh.patches().size(), 3u);
    std::printf("%s blockMesh: kelvin volume %.9g vs checkMesh %.9g; face area [%.6g, %.6g] vs [%.6g, %.6g]\n",
                binary ? "binary" : "ascii", q.total_volume, total, *std::min_element(mags.begin(), mags.end()),
                *std::max_element(mags.begin(), mags.end()), min_area, max_area);
  }
}

// Defects the fuzz targets found (tests/fuzz/regressions), on single files.
std::string ParseError(const std::function<void()>& parse) {
  try {
    parse();
  } catch (const DataFileError& e) {
    return e.what();
  }
  return "(no DataFileError)";
}

TEST(PolyMeshFiles, FaceOffsetsBeyondTheLabelsAreAnError) {
  const std::string faces = Header("faceCompactList", "faces", false) + "3(0 9 4)\n4(0 1 2 3)\n";
  EXPECT_THAT(ParseError([&] { ParsePolyMeshFaces(faces, "faces"); }),
              ::testing::HasSubstr("face offsets of face 0 are 0 and 9; expected a non-decreasing list"));
}

TEST(PolyMeshFiles, ACountTheFileCannotHoldIsAnError) {
  const std::string points = Header("vectorField", "points", false) + "1000000000000\n((0 0 0))\n";
  EXPECT_THAT(ParseError([&] { ParsePolyMeshPoints(points, "points"); }),
              ::testing::HasSubstr("point count is 1000000000000; expected at most"));
  const std::string owner = Header("labelList", "owner", false) + "90000\n(0 1)\n";
  EXPECT_THAT(ParseError([&] { ParsePolyMeshLabels(owner, "owner", "owners"); }),
              ::testing::HasSubstr("owners count is 90000 but only"));
}

TEST(PolyMeshFiles, LabelsBeyond32BitsAreAnError) {
  const std::string owner = Header("labelList", "owner", false) + "2\n(0 4294967296)\n";
  EXPECT_THAT(ParseError([&] { ParsePolyMeshLabels(owner, "owner", "owners"); }),
              ::testing::HasSubstr("entry 1 of owners is 4294967296; expected a 32-bit label"));
  const std::string uniform = Header("labelList", "owner", false) + "2000000000{0}\n";
  EXPECT_THAT(ParseError([&] { ParsePolyMeshLabels(uniform, "owner", "owners"); }),
              ::testing::HasSubstr("uniform list of 2000000000 owners"));
}

TEST(PolyMeshFiles, NegativePatchSizesAreAnError) {
  const std::string boundary =
      Header("polyBoundaryMesh", "boundary", false) + "1\n(\nwalls { type wall; nFaces -5; startFace 3; }\n)\n";
  EXPECT_THAT(ParseError([&] { ParsePolyMeshBoundary(boundary, "boundary"); }),
              ::testing::HasSubstr("patch 'walls': nFaces = '-5'; expected an integer from 0 to"));
}

}  // namespace
}  // namespace kelvin::cfd
