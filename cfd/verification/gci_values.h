// `kelvin gci --grids DIR --values FILE`: the GCI of values that were computed
// on each grid of a family by something other than one case file, e.g. a
// captive campaign run on each grid (tools/bench/dtc_drift_gci.py) or a
// derivative identified from each grid's campaign. FILE is YAML:
//
//   outputs:                        # one entry per quantity
//     Y_prime_10deg: [0.0492, 0.0488, 0.0471]   # grid 1 (finest), 2, 3
//     N_v: [-0.121, -0.118, -0.110]
//   settled: [true, true, false]    # optional: each grid's runs met their
//                                   # steady criterion (default all true)
//
// The grid sizes come from DIR/family.txt (ReadGridFamily); the values go
// through the same Celik et al. (2008) procedure as a case study
// (ComputeGciOutputs), and the report is the same (GciTable, WriteGciReport).
#pragma once

#include <filesystem>
#include <vector>

#include "cfd/verification/gci_study.h"

namespace kelvin::cfd {

// Reads FILE against the family's three finest grids. Throws ConfigError
// naming the file, the key and the value for a malformed entry (not three
// finite numbers, an empty outputs map, an unknown key).
GciStudy GciStudyFromValues(const std::vector<FamilyGrid>& family, const std::filesystem::path& values_file);

}  // namespace kelvin::cfd
