// PartitionOptions::Validate on its own: the case reader checks a case's
// `partition:` section without the partitioner (and the fuzzed case reader
// links it without PETSc).
#include <fmt/format.h>

#include <cmath>

#include "cfd/parallel/partition.h"
#include "data/schema/errors.h"

namespace kelvin::cfd {

void PartitionOptions::Validate() const {
  if (!(column_aspect >= 1.0) || !std::isfinite(column_aspect)) {
    throw ConfigError(fmt::format("partition.column_aspect = {}; expected a number >= 1", column_aspect));
  }
  if (!(imbalance > 0.0 && imbalance < 1.0)) {
    throw ConfigError(fmt::format("partition.imbalance = {}; expected in (0, 1)", imbalance));
  }
  if (min_cells_per_rank < 1) {
    throw ConfigError(fmt::format("partition.min_cells_per_rank = {}; expected at least 1", min_cells_per_rank));
  }
}

}  // namespace kelvin::cfd
