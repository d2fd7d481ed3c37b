#include "cfd/parallel/domain_part.h"

#include <algorithm>
#include <string>

#include "data/schema/errors.h"

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

void DomainPart::SumInPlace(std::span<double> values) const {
  if (!parallel() || values.empty()) return;
  MPI_Allreduce(MPI_IN_PLACE, values.data(), static_cast<int>(values.size()), MPI_DOUBLE, MPI_SUM, comm);
}

std::vector<double> AllGather(const DomainPart& part, std::span<const double> local) {
  if (!part.parallel()) return {local.begin(), local.end()};
  int n = static_cast<int>(local.size());
  std::vector<int> counts(part.size), offsets(part.size, 0);
  MPI_Allgather(&n, 1, MPI_INT, counts.data(), 1, MPI_INT, part.comm);
  for (int r = 1; r < part.size; ++r) offsets[r] = offsets[r - 1] + counts[r - 1];
  std::vector<double> all(static_cast<std::size_t>(offsets.back() + counts.back()));
  MPI_Allgatherv(local.data(), n, MPI_DOUBLE, all.data(), counts.data(), offsets.data(), MPI_DOUBLE, part.comm);
  return all;
}

void SyncCrossFaces(const DomainPart* part, std::span<double> face_values) {
  if (!part || !part->parallel()) return;
  const std::size_t roots = part->cross_roots.size();
  std::vector<double> buffer(roots + part->cross_leaves.size());
  for (std::size_t r = 0; r < roots; ++r) buffer[r] = face_values[part->cross_roots[r]];
  part->cross_halo->Update(std::span<double>(buffer));
  for (std::size_t l = 0; l < part->cross_leaves.size(); ++l) face_values[part->cross_leaves[l]] = -buffer[roots + l];
}

namespace {

MPI_Comm CommOf(const DomainPart* part) {
  return part && part->parallel() ? part->comm : MPI_COMM_NULL;
}

bool SeveralRanks(MPI_Comm comm) {
  int size = 1;
  if (comm != MPI_COMM_NULL) MPI_Comm_size(comm, &size);
  return size > 1;
}

// Runs `write`; what it throws (a DataFileError, or the file system's own)
// comes back as its message, empty when it returned.
std::string ErrorOf(const std::function<void()>& write) {
  try {
    write();
  } catch (const std::exception& e) {
    const std::string message = e.what();
    return message.empty() ? "a file could not be written" : message;
  }
  return {};
}

// Rank `root`'s `text` on every rank of `comm` (collective).
std::string FromRank(MPI_Comm comm, int root, std::string text) {
  int n = static_cast<int>(text.size());
  MPI_Bcast(&n, 1, MPI_INT, root, comm);
  text.resize(static_cast<std::size_t>(n));
  MPI_Bcast(text.data(), n, MPI_CHAR, root, comm);
  return text;
}

}  // namespace

void OnFirstRank(const DomainPart* part, const std::function<void()>& write) {
  OnFirstRank(CommOf(part), write);
}

void OnFirstRank(MPI_Comm comm, const std::function<void()>& write) {
  if (!SeveralRanks(comm)) {
    write();
    return;
  }
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  const std::string error = FromRank(comm, 0, rank == 0 ? ErrorOf(write) : std::string());
  if (!error.empty()) throw DataFileError(error);
}

void OnEveryRank(const DomainPart* part, const std::function<void()>& write) {
  const MPI_Comm comm = CommOf(part);
  if (!SeveralRanks(comm)) {
    write();
    return;
  }
  int rank = 0, size = 1;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &size);
  const std::string error = ErrorOf(write);
  // The first rank that failed tells every rank.
  int first = error.empty() ? size : rank;
  MPI_Allreduce(MPI_IN_PLACE, &first, 1, MPI_INT, MPI_MIN, comm);
  if (first < size) throw DataFileError(FromRank(comm, first, error));
}

std::string FromFirstRank(const DomainPart* part, std::string text) {
  return FromFirstRank(CommOf(part), std::move(text));
}

std::string FromFirstRank(MPI_Comm comm, std::string text) {
  return SeveralRanks(comm) ? FromRank(comm, 0, std::move(text)) : text;
}

OwnedEntries OwnEntries(const DomainPart* part, std::span<const int> whole_cells) {
  OwnedEntries out;
  for (std::size_t i = 0; i < whole_cells.size(); ++i) {
    const int local = part && part->parallel() ? part->OwnedCell(whole_cells[i]) : whole_cells[i];
    if (local < 0) continue;
    out.entries.push_back(static_cast<int>(i));
    out.cells.push_back(local);
  }
  return out;
}

int DomainPart::OwnedCell(long long global) const {
  // The owned cells are in ascending global order.
  const auto end = cells.begin() + n_owned;
  const auto it = std::lower_bound(cells.begin(), end, global);
  return it != end && *it == global ? static_cast<int>(it - cells.begin()) : -1;
}

}  // namespace kelvin::cfd
