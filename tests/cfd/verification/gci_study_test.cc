// `kelvin gci` on synthetic data: the family table and its checks, output
// extraction from a run history, the study over finished (reused) runs whose
// outputs follow a known power law of h, the same from a values file
// (--values), the report files, and the single clear error of each bad
// input, also through the command line.
#include "cfd/verification/gci_study.h"
#include "cfd/verification/gci_values.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <fmt/format.h>

#include <fstream>
#include <sstream>

#include "data/schema/errors.h"
#include "data/schema/h5_file.h"
#include "tests/test_utilities/test_utilities.h"

namespace kelvin::cfd {
namespace {

namespace fs = std::filesystem;
using kelvin::testing::RunCommand;
using kelvin::testing::ScopedTempDir;
using ::testing::HasSubstr;

void Write(const fs::path& p, const std::string& text) {
  fs::create_directories(p.parent_path());
  std::ofstream(p) << text;
}

// The output of a synthetic case: phi(h) = 0.004 + 0.05 h^2 (observed order
// 2, limit 0.004), with a small oscillation in the steps before the last.
double Phi(double h) { return 0.004 + 0.05 * h * h; }

// A family directory as `kelvin mesh --family` writes it (the polyMesh files
// only need to exist here: the runs are reused, never started).
void WriteFamily(const fs::path& dir, const std::vector<double>& h, bool with_meshes = true) {
  std::string t = "# grid family of case.yaml with refinement ratio r = 1.41421 (grid 1 finest)\n"
                  "grid cells h_m r_effective max_non_orthogonality_deg y_plus_mean\n";
  for (std::size_t g = 0; g < h.size(); ++g) {
    t += fmt::format("{} {} {} 1.41 40.0 50\n", g + 1, static_cast<long>(std::lround(125.0 / std::pow(h[g], 3))),
                     h[g]);
    if (with_meshes) Write(dir / fmt::format("grid{}", g + 1) / "constant/polyMesh/owner", "");
  }
  Write(dir / "family.txt", t);
}

// A finished run of grid `level`: history.h5 with 10 steps and run.yaml.
void WriteRun(const fs::path& dir, int level, long cells, double h) {
  data::H5Writer w(dir / "history.h5");
  const std::size_t n = 10;
  std::vector<double> ct(n), cf(n), fp(3 * n), cpu(n), x(n);
  for (std::size_t i = 0; i < n; ++i) {
    const double wobble = (i + 2 < n) ? 1e-3 * ((i % 2) ? 1 : -1) : 0.0;
    ct[i] = Phi(h) + wobble;
    cf[i] = 0.8 * Phi(h);
    for (int d = 0; d < 3; ++d) fp[3 * i + d] = 10.0 * d + h;
    cpu[i] = 0.5 * (i + 1);
    x[i] = -2.0 * Phi(h);
  }
  w.WriteArray("resistance/C_T", ct, {n}, "1", "");
  w.WriteArray("resistance/C_F", cf, {n}, "1", "");
  w.WriteArray("forces/hull/pressure", fp, {n, 3}, "N", "");
  w.WriteArray("cpu_time", cpu, {n}, "s", "");
  w.WriteArray("captive/X", x, {n}, "N", "");
  w.Commit();
  Write(dir / "run.yaml", fmt::format("status: completed\nlevel: {}\ncells: {}\nh: {}\nsteps: 10\n"
                                      "outer_iterations: 10\ncpu_seconds: 5\nsteady: true\nsteady_converged: true\n",
                                      level, cells, h));
}

const std::vector<double> kH = {0.1, 0.1414, 0.2};

TEST(GciStudyTest, SplitsOutputLists) {
  EXPECT_EQ(SplitOutputNames({"C_T, X", "Y"}), (std::vector<std::string>{"C_T", "X", "Y"}));
  EXPECT_EQ(SplitOutputNames({"forces/hull/pressure:0"}), (std::vector<std::string>{"forces/hull/pressure:0"}));
  EXPECT_THROW(SplitOutputNames({"C_T,,X"}), ArgumentError);
  EXPECT_THROW(SplitOutputNames({""}), ArgumentError);
  EXPECT_THROW(SplitOutputNames({}), ArgumentError);
}

TEST(GciStudyTest, ParsesTheFamilyTableOfKelvinMesh) {
  const auto grids = ParseFamilyTable(
      "# grid family\ngrid cells h_m r_effective max_non_orthogonality_deg y_plus_mean\n"
      "1 164864 0.0911754 1.0000 48.788 31\n2 57200 0.129754 1.4231 48.612 43.8\n3 20608 0.182351 1.4054 48.3 62\n",
      "family.txt");
  ASSERT_EQ(grids.size(), 3u);
  EXPECT_EQ(grids[1].level, 2);
  EXPECT_EQ(grids[1].cells, 57200);
  EXPECT_DOUBLE_EQ(grids[2].h, 0.182351);
  try {
    ParseFamilyTable("grid cells h_m\n1 100 0.1\n3 50 0.2\n", "f.txt");
    FAIL() << "levels out of order accepted";
  } catch (const DataFileError& e) {
    EXPECT_THAT(e.what(), HasSubstr("f.txt:3: grid level 3 where level 2 was expected"));
  }
  EXPECT_THROW(ParseFamilyTable("cells h\n1 100 0.1\n", "f.txt"), DataFileError);
  EXPECT_THROW(ParseFamilyTable("grid cells h_m\n1 100 -0.1\n", "f.txt"), DataFileError);
  EXPECT_THROW(ParseFamilyTable("# only a comment\n", "f.txt"), DataFileError);
}

// Each bad family gives one error naming the file and what is wrong.
TEST(GciStudyTest, BadFamiliesGiveOneClearError) {
  ScopedTempDir tmp;
  auto message = [](auto&& f) -> std::string {
    try {
      f();
    } catch (const InputError& e) {
      return e.what();
    }
    return "no error";
  };
  EXPECT_THAT(message([&] { ReadGridFamily(tmp / "fam", 2); }), HasSubstr("needs three grids"));
  EXPECT_THAT(message([&] { ReadGridFamily(tmp / "missing", 3); }), HasSubstr("does not exist"));
  fs::create_directories(tmp / "empty");
  EXPECT_THAT(message([&] { ReadGridFamily(tmp / "empty", 3); }), HasSubstr("family.txt' is missing"));
  WriteFamily(tmp / "two", {0.1, 0.1414});
  EXPECT_THAT(message([&] { ReadGridFamily(tmp / "two", 3); }), HasSubstr("lists 2 grid(s), the study asks for 3"));
  WriteFamily(tmp / "nomesh", kH);
  fs::remove_all(tmp / "nomesh/grid3");
  EXPECT_THAT(message([&] { ReadGridFamily(tmp / "nomesh", 3); }), HasSubstr("grid 3 is listed but"));
  WriteFamily(tmp / "ratio", {0.1, 0.1414, 0.25});
  EXPECT_THAT(message([&] { ReadGridFamily(tmp / "ratio", 3); }),
              HasSubstr("non-constant refinement ratio: h2/h1 = 1.4140 but h3/h2 = 1.7680"));
  // Within the tolerance (the effective ratios of a family differ a little
  // because cell counts are rounded): accepted.
  WriteFamily(tmp / "ok", {0.1, 0.1423, 0.2}, true);
  EXPECT_EQ(ReadGridFamily(tmp / "ok", 3).size(), 3u);
}

TEST(GciStudyTest, ExtractsNamedOutputsFromARunHistory) {
  ScopedTempDir tmp;
  WriteRun(tmp.path(), 1, 100, 0.1);
  const fs::path h = tmp / "history.h5";
  EXPECT_DOUBLE_EQ(ExtractOutput(h, "C_T"), Phi(0.1));
  // The mean over the last 4 steps includes the +-1e-3 oscillation of two.
  EXPECT_NEAR(ExtractOutput(h, "C_T", 4), Phi(0.1), 1e-15);
  EXPECT_NEAR(ExtractOutput(h, "C_T", 3), Phi(0.1) + 1e-3 / 3, 1e-15);
  EXPECT_DOUBLE_EQ(ExtractOutput(h, "X"), -2.0 * Phi(0.1));
  EXPECT_DOUBLE_EQ(ExtractOutput(h, "forces/hull/pressure:2"), 20.1);
  EXPECT_DOUBLE_EQ(ExtractOutput(h, "cpu_time"), 5.0);
  auto message = [&](const std::string& name, int average = 1) -> std::string {
    try {
      ExtractOutput(h, name, average);
    } catch (const InputError& e) {
      return e.what();
    }
    return "no error";
  };
  EXPECT_THAT(message("C_P"), HasSubstr("no output 'C_P' (dataset 'resistance/C_P'); this run offers C_F, C_T, X"));
  EXPECT_THAT(message("forces/hull/pressure"), HasSubstr("has 3 columns; name one as 'forces/hull/pressure:0'"));
  EXPECT_THAT(message("forces/hull/pressure:3"), HasSubstr("no column 3"));
  EXPECT_THAT(message("forces/hull/pressure:x"), HasSubstr("expected 'dataset:column'"));
  EXPECT_THAT(message("C_T", 11), HasSubstr("has 10 step(s), fewer than --average 11"));
  EXPECT_THAT(message("C_T", 0), HasSubstr("--average 0"));
  EXPECT_THROW(ExtractOutput(tmp / "nothere.h5", "C_T"), DataFileError);
}

// The whole study over finished runs: values, GCI of a known power law,
// table and report files.
TEST(GciStudyTest, ReusesFinishedRunsAndReportsTheGci) {
  ScopedTempDir tmp;
  WriteFamily(tmp / "grids", kH);
  Write(tmp / "case.yaml", "mesh: {poly_mesh: grids/grid1/constant/polyMesh}\nphysics: {nu: 1.0e-6}\nboundary: {}\n"
                           "time: {dt: 1, end: 10}\n"
                           "output: {directory: results}\n");
  const auto grids = ReadGridFamily(tmp / "grids", 3);
  for (const FamilyGrid& g : grids) {
    WriteRun(tmp / "results/gci" / fmt::format("grid{}", g.level), g.level, g.cells, g.h);
  }
  GciStudyOptions o;
  o.case_file = tmp / "case.yaml";
  o.grids = tmp / "grids";
  o.outputs = {"C_T", "C_F", "X"};
  o.progress = false;
  const GciStudy study = RunGciStudy(o);
  ASSERT_EQ(study.grids.size(), 3u);
  for (const GridRunRecord& r : study.grids) {
    EXPECT_TRUE(r.reused);
    EXPECT_TRUE(r.steady_converged);
    EXPECT_EQ(r.outer_iterations, 10);
  }
  ASSERT_EQ(study.outputs.size(), 3u);
  const GciResult& ct = study.outputs[0].gci;
  EXPECT_EQ(ct.convergence, Convergence::kMonotonic);
  EXPECT_NEAR(ct.p, 2.0, 1e-8);
  EXPECT_NEAR(ct.phi_ext, 0.004, 1e-12);
  EXPECT_NEAR(study.outputs[1].gci.phi_ext, 0.0032, 1e-12);
  EXPECT_NEAR(study.outputs[2].gci.phi_ext, -0.008, 1e-12);
  // GCI_fine = 1.25 |phi1 - phi2| / phi1 / (r21^p - 1).
  const double r21 = kH[1] / kH[0];
  EXPECT_NEAR(ct.gci21, 1.25 * (Phi(kH[1]) - Phi(kH[0])) / Phi(kH[0]) / (r21 * r21 - 1), 1e-10);
  const std::string table = GciTable(study);
  EXPECT_THAT(table, HasSubstr("(reused)"));
  EXPECT_THAT(table, HasSubstr("monotonic"));
  EXPECT_THAT(table, HasSubstr("GCI_fine"));

  WriteGciReport(study, tmp / "report/gci", "case.yaml");
  const data::H5Reader h5(tmp / "report/gci.h5");
  EXPECT_NEAR(h5.Read("outputs/C_T/p").at(0), 2.0, 1e-8);
  EXPECT_NEAR(h5.Read("outputs/C_T/values").at(2), Phi(0.2), 1e-15);
  EXPECT_EQ(h5.Read("grids/cells").rows, 3u);
  EXPECT_EQ(h5.StringAttribute("outputs/C_T", "convergence"), "monotonic");
  std::ifstream yaml(tmp / "report/gci.yaml");
  std::ostringstream buffer;
  buffer << yaml.rdbuf();
  const std::string text = buffer.str();
  EXPECT_THAT(text, HasSubstr("convergence: monotonic"));
  EXPECT_THAT(text, HasSubstr("gci_fine:"));

  // A case whose mesh is not a poly_mesh cannot take the family's grids.
  Write(tmp / "box.yaml", "mesh: {box: {max: [1, 1, 1], cells: [2, 2, 2]}}\ntime: {dt: 1, end: 1}\n");
  o.case_file = tmp / "box.yaml";
  try {
    RunGciStudy(o);
    FAIL() << "box case accepted";
  } catch (const ConfigError& e) {
    EXPECT_THAT(e.what(), HasSubstr("poly_mesh"));
  }
}

// The command line: the table on stdout, and exit code 2 (arguments) or 1
// (files) with one message for bad input.
TEST(GciStudyTest, CommandLine) {
  ScopedTempDir tmp;
  WriteFamily(tmp / "grids", kH);
  Write(tmp / "case.yaml", "mesh: {poly_mesh: grids/grid1/constant/polyMesh}\nphysics: {nu: 1.0e-6}\nboundary: {}\n"
                           "time: {dt: 1, end: 10}\n"
                           "output: {directory: results}\n");
  const auto grids = ReadGridFamily(tmp / "grids", 3);
  for (const FamilyGrid& g : grids) {
    WriteRun(tmp / "results/gci" / fmt::format("grid{}", g.level), g.level, g.cells, g.h);
  }
  const std::string kelvin = (kelvin::testing::ToolsDir() / "kelvin").string();
  const std::string base = kelvin + " gci " + (tmp / "case.yaml").string() + " --no-progress";
  auto ok = RunCommand(base + " --grids " + (tmp / "grids").string() + " --outputs C_T,C_F --report " +
                       (tmp / "rep").string() + " 2>&1");
  ASSERT_EQ(ok.exit_code, 0) << ok.output;
  EXPECT_THAT(ok.output, HasSubstr("GCI_fine"));
  EXPECT_THAT(ok.output, HasSubstr("C_F"));
  EXPECT_TRUE(fs::exists(tmp / "rep.h5"));
  EXPECT_TRUE(fs::exists(tmp / "rep.yaml"));

  auto bad_family = RunCommand(base + " --grids " + (tmp / "grids").string() + " --family 2 2>&1");
  EXPECT_EQ(bad_family.exit_code, 2) << bad_family.output;
  EXPECT_THAT(bad_family.output, HasSubstr("needs three grids"));
  auto missing = RunCommand(base + " --grids " + (tmp / "nogrids").string() + " 2>&1");
  EXPECT_EQ(missing.exit_code, 1) << missing.output;
  EXPECT_THAT(missing.output, HasSubstr("does not exist"));
  auto bad_output = RunCommand(base + " --grids " + (tmp / "grids").string() + " --outputs C_Q 2>&1");
  EXPECT_EQ(bad_output.exit_code, 1) << bad_output.output;
  EXPECT_THAT(bad_output.output, HasSubstr("no output 'C_Q'"));
}

// --values: values computed elsewhere on each grid give the same GCI as the
// runs' outputs (phi = 0.004 + 0.05 h^2: p = 2, limit 0.004), the settled
// flags reach the report, and each malformed entry is one clear error.
TEST(GciStudyTest, ValuesFileGivesTheSameGciAsTheRuns) {
  ScopedTempDir tmp;
  WriteFamily(tmp / "grids", kH);
  const auto grids = ReadGridFamily(tmp / "grids", 3);
  Write(tmp / "values.yaml", fmt::format("outputs:\n  Y_prime: [{:.17g}, {:.17g}, {:.17g}]\n  twice: [{:.17g}, "
                                         "{:.17g}, {:.17g}]\nsettled: [true, true, false]\n",
                                         Phi(kH[0]), Phi(kH[1]), Phi(kH[2]), 2 * Phi(kH[0]), 2 * Phi(kH[1]),
                                         2 * Phi(kH[2])));
  const GciStudy study = GciStudyFromValues(grids, tmp / "values.yaml");
  ASSERT_EQ(study.outputs.size(), 2u);
  EXPECT_EQ(study.outputs[0].name, "Y_prime");
  EXPECT_EQ(study.outputs[0].gci.convergence, Convergence::kMonotonic);
  EXPECT_NEAR(study.outputs[0].gci.p, 2.0, 1e-8);
  EXPECT_NEAR(study.outputs[0].gci.phi_ext, 0.004, 1e-12);
  EXPECT_NEAR(study.outputs[1].gci.phi_ext, 0.008, 1e-12);
  EXPECT_TRUE(study.grids[1].steady_converged);
  EXPECT_FALSE(study.grids[2].steady_converged);
  EXPECT_THAT(GciTable(study), HasSubstr("NO"));

  const auto message = [&](const std::string& text) {
    Write(tmp / "bad.yaml", text);
    try {
      GciStudyFromValues(grids, tmp / "bad.yaml");
    } catch (const ConfigError& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  EXPECT_THAT(message("outputs:\n  Y: [1, 2]\n"), HasSubstr("'outputs.Y'"));
  EXPECT_THAT(message("outputs:\n  Y: [1, 2]\n"), HasSubstr("three values"));
  EXPECT_THAT(message("outputs:\n  Y: [1, .nan, 2]\n"), HasSubstr("finite"));
  EXPECT_THAT(message("outputs:\n  Y: [1, 2, 3]\nsettled: [true]\n"), HasSubstr("three booleans"));
  EXPECT_THAT(message("outputs: {}\n"), HasSubstr("a map of output name"));
  EXPECT_THAT(message("output:\n  Y: [1, 2, 3]\n"), HasSubstr("unknown key 'output'"));

  const std::string kelvin = (kelvin::testing::ToolsDir() / "kelvin").string();
  const std::string base = kelvin + " gci --grids " + (tmp / "grids").string() + " --values " +
                           (tmp / "values.yaml").string();
  auto ok = RunCommand(base + " --report " + (tmp / "rep").string() + " 2>&1");
  ASSERT_EQ(ok.exit_code, 0) << ok.output;
  EXPECT_THAT(ok.output, HasSubstr("Y_prime"));
  const data::H5Reader h5(tmp / "rep.h5");
  EXPECT_NEAR(h5.Read("outputs/Y_prime/p").at(0), 2.0, 1e-8);
  auto no_report = RunCommand(base + " 2>&1");
  EXPECT_EQ(no_report.exit_code, 2) << no_report.output;
  EXPECT_THAT(no_report.output, HasSubstr("--report"));
  // The values file names its outputs: a run's --outputs would be ignored, so it is refused.
  auto with_outputs = RunCommand(base + " --report " + (tmp / "rep").string() + " --outputs C_T 2>&1");
  EXPECT_NE(with_outputs.exit_code, 0) << with_outputs.output;
  EXPECT_THAT(with_outputs.output, HasSubstr("--outputs"));
  auto neither = RunCommand(kelvin + " gci --grids " + (tmp / "grids").string() + " 2>&1");
  EXPECT_EQ(neither.exit_code, 2) << neither.output;
  EXPECT_THAT(neither.output, HasSubstr("either a case file or --values"));
}

}  // namespace
}  // namespace kelvin::cfd
