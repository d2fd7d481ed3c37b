#include "cfd/parallel/domain_part.h"

#include <algorithm>

namespace kelvin::cfd {
namespace {

double Reduce(const DomainPart& part, double local, MPI_Op op) {
  if (!part.parallel()) return local;
  double global = 0.0;
  MPI_Allreduce(&local, &global, 1, MPI_DOUBLE, op, part.comm);
  return global;
}

}  // namespace

double DomainPart::Sum(double local) const { return Reduce(*this, local, MPI_SUM); }
double DomainPart::Max(double local) const { return Reduce(*this, local, MPI_MAX); }
double DomainPart::Min(double local) const { return Reduce(*this, local, MPI_MIN); }
bool DomainPart::All(bool local) const { return Min(local ? 1.0 : 0.0) > 0.5; }

int DomainPart::OwnedCell(long long global) const {
  // The owned cells are in ascending global order.
  const auto end = cells.begin() + n_owned;
  const auto it = std::lower_bound(cells.begin(), end, global);
  return it != end && *it == global ? static_cast<int>(it - cells.begin()) : -1;
}

}  // namespace kelvin::cfd
