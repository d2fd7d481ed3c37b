// `kelvin gci case.yaml --family 3 --grids DIR`: the grid-convergence study
// of a case file on a grid family written by `kelvin mesh --family N` (DIR
// holds family.txt and grid1 ... gridN, grid 1 finest). The case runs on each
// grid (its mesh.poly_mesh replaced by DIR/grid<g>/constant/polyMesh, output
// in RUNS/grid<g>); a grid whose run already finished (RUNS/grid<g>/run.yaml
// says completed) is reused. Chosen scalar outputs of the three finest grids
// go through ComputeGci (Celik et al. 2008): R, observed order p, Richardson
// extrapolation, GCI_fine (GCI21), GCI_coarse (GCI32) and the asymptotic-range
// check GCI32 / (r21^p GCI21).
//
// Output names: C_T, C_F, C_P (output.resistance of the case), X, Y, N and
// X_prime, Y_prime, N_prime (output.captive), or any dataset of history.h5
// with one value per step, `name` or `name:column` for a multi-column one
// (e.g. forces/hull/pressure:0). The value is the mean over the last
// `average` steps.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "cfd/verification/gci.h"

namespace kelvin::cfd {

struct FamilyGrid {
  int level = 1;  // 1 = finest
  long cells = 0;
  double h = 0.0;  // (V / N)^(1/3), m
  std::filesystem::path poly_mesh;  // <dir>/grid<level>/constant/polyMesh
};

// Parses family.txt (the table `kelvin mesh --family` writes). `source` names
// the file in messages. Throws DataFileError for a malformed table.
std::vector<FamilyGrid> ParseFamilyTable(const std::string& text, const std::string& source);

// Reads DIR/family.txt and checks that it lists at least `family` grids
// (>= 3), levels 1..family in order with growing h, that each grid's polyMesh
// exists, and that the refinement ratios h2/h1 and h3/h2 agree within
// `ratio_tolerance` (relative). Returns the `family` finest grids.
std::vector<FamilyGrid> ReadGridFamily(const std::filesystem::path& dir, int family,
                                       double ratio_tolerance = 0.05);

// The value of output `name` in a run's history.h5 (mean over the last
// `average` steps). Throws DataFileError naming the file, the output and the
// outputs it offers.
double ExtractOutput(const std::filesystem::path& history, const std::string& name, int average = 1);

// "C_T,X" "Y" -> C_T, X, Y (command-line lists, comma-separated or repeated;
// spaces around names dropped). Throws ArgumentError for an empty name.
std::vector<std::string> SplitOutputNames(const std::vector<std::string>& args);

struct GciStudyOptions {
  std::filesystem::path case_file;
  std::filesystem::path grids;  // family directory
  int family = 3;
  std::vector<std::string> outputs = {"C_T"};
  std::filesystem::path runs;   // default: <output.directory of the case>/gci
  std::filesystem::path report; // default: <runs>/gci (writes .h5 and .yaml)
  int average = 1;
  bool rerun = false;           // run every grid again even if finished
  bool progress = true;
  double ratio_tolerance = 0.05;
};

struct GridRunRecord {
  int level = 1;
  long cells = 0;
  double h = 0.0;
  std::filesystem::path directory;
  bool reused = false;
  int steps = 0;
  int outer_iterations = 0;
  double cpu_seconds = 0.0;      // process CPU time of the time loop
  bool steady_converged = false; // the steady criterion met (false also when not asked)
  bool steady = false;           // the case has time.steady or a resistance section
  std::vector<double> values;    // one per output
};

struct GciOutputResult {
  std::string name;
  double phi[3] = {0, 0, 0};  // fine, medium, coarse
  GciResult gci;
};

struct GciStudy {
  std::vector<GridRunRecord> grids;  // fine first
  std::vector<GciOutputResult> outputs;
};

// Checks the arguments (ArgumentError), the family (DataFileError) and the
// case, runs or reuses each grid's run, and computes the GCI of each output.
GciStudy RunGciStudy(const GciStudyOptions& options);

// The GCI of each output from values already on three grids (used by
// RunGciStudy; separate for tests).
std::vector<GciOutputResult> ComputeGciOutputs(const std::vector<GridRunRecord>& grids,
                                               const std::vector<std::string>& outputs);

// Text table of the grids and of the GCI per output.
std::string GciTable(const GciStudy& study);

// Writes <stem>.h5 and <stem>.yaml atomically (grids, values and GCI per
// output).
void WriteGciReport(const GciStudy& study, const std::filesystem::path& stem, const std::string& case_file);

}  // namespace kelvin::cfd
