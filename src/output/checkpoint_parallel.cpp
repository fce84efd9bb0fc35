// Checkpoints written and read by every rank together (see checkpoint.hpp): each rank its
// block of u, V and last_increment, the checksum summed along the ranks in rank order (the
// same FNV sum, over the same bytes in the same order, as one rank's).
#include <mpi.h>

#include "checkpoint_meta.hpp"
#include "emcontact/error.hpp"
#include "emcontact/output/checkpoint.hpp"
#include "emcontact/output/parallel_hdf5.hpp"

namespace emc::output {

namespace {

constexpr int kTagSum = 4502;

/// Rank 0's sum h continued over every rank's values in rank order; on every rank.
std::uint64_t fnv_along(MPI_Comm comm, std::uint64_t h, const std::vector<double>& mine) {
  const int rank = rank_of(comm), ranks = ranks_of(comm);
  unsigned long long v = h;
  if (rank > 0) MPI_Recv(&v, 1, MPI_UNSIGNED_LONG_LONG, rank - 1, kTagSum, comm, MPI_STATUS_IGNORE);
  std::uint64_t x = v;
  detail::fnv_bytes(x, mine.data(), mine.size() * sizeof(double));
  v = x;
  if (rank + 1 < ranks) MPI_Send(&v, 1, MPI_UNSIGNED_LONG_LONG, rank + 1, kTagSum, comm);
  MPI_Bcast(&v, 1, MPI_UNSIGNED_LONG_LONG, ranks - 1, comm);
  return v;
}

/// The checksum (detail::checksum) of the checkpoint whose u, V and last_increment are the
/// ranks' blocks of `values` each (last_increment: none when `increment` is false) and whose
/// other parts are rank 0's; on every rank (collective).
std::uint64_t checksum_along(MPI_Comm comm, const Checkpoint& mine, unsigned long long values,
                             bool increment) {
  std::uint64_t h = detail::checksum_head(mine);  // rank 0's counts: it starts each chain
  for (const auto* v : {&mine.u, &mine.V, &mine.last_increment}) {
    detail::fnv_length(h, v == &mine.last_increment && !increment ? 0 : values);
    h = fnv_along(comm, h, *v);
  }
  detail::checksum_tail(h, mine);
  unsigned long long sum = h;
  MPI_Bcast(&sum, 1, MPI_UNSIGNED_LONG_LONG, 0, comm);
  return sum;
}

}  // namespace

void write_checkpoint_collectively(MPI_Comm comm, const Directory& dir, const std::string& name,
                                   const Checkpoint& mine, unsigned long long values) {
  if (ranks_of(comm) == 1) return write_checkpoint(dir, name, mine);
  const int rank = rank_of(comm);
  const Block b = block_of(static_cast<long long>(values), rank, ranks_of(comm));
  const bool increment = !all_ok(comm, mine.last_increment.empty());  // on any rank
  std::string error;
  for (const auto* v : {&mine.u, &mine.V, &mine.last_increment})
    if (v->size() != static_cast<std::size_t>(b.count) && !(v->empty() && !increment))
      error = "internal: a checkpoint block of " + std::to_string(v->size()) + " values, not " +
              std::to_string(b.count);
  error = first_error(comm, error);
  if (!error.empty()) throw Error(error);
  const std::uint64_t sum = checksum_along(comm, mine, values, increment);
  const std::string model = broadcast(comm, mine.model);
  const auto scalars = mine.scalars();
  const auto on_root = [&](const char* set, const std::vector<double>& v) {
    unsigned long long n = v.size();
    MPI_Bcast(&n, 1, MPI_UNSIGNED_LONG_LONG, 0, comm);
    return SlabDataset{set, H5T_IEEE_F64LE,    H5T_NATIVE_DOUBLE, n, 1,
                       0,   rank == 0 ? n : 0, v.data()};
  };
  const auto block = [&](const char* set, const std::vector<double>& v, bool present) {
    const unsigned long long n = present ? values : 0;
    return SlabDataset{set,
                       H5T_IEEE_F64LE,
                       H5T_NATIVE_DOUBLE,
                       n,
                       1,
                       static_cast<unsigned long long>(b.first),
                       present ? static_cast<unsigned long long>(b.count) : 0,
                       v.data()};
  };
  const std::vector<SlabDataset> sets = {
      on_root("scalars", scalars),    block("u", mine.u, true),
      block("V", mine.V, true),       block("last_increment", mine.last_increment, increment),
      on_root("active", mine.active), on_root("normal_force", mine.normal_force),
      on_root("state", mine.state)};
  const std::string path = dir.path(name);
  write_hdf5_collectively(comm, dir, name, sets, [&](hid_t file) {
    detail::write_string_attribute(file, "model", model, path);
    detail::write_u64_attribute(file, "checksum", sum, path);
  });
}

Checkpoint read_checkpoint_collectively(MPI_Comm comm, const std::string& path,
                                        const CheckpointShape& shape) {
  const int ranks = ranks_of(comm), rank = rank_of(comm);
  const Block b = block_of(static_cast<long long>(shape.values), rank, ranks);
  Checkpoint c;
  std::uint64_t stored = 0;
  bool increment = false;
  std::string error;
  try {
    c = detail::read_block(
        path, shape,
        {static_cast<unsigned long long>(b.first), static_cast<unsigned long long>(b.count)},
        stored, increment);
  } catch (const std::exception& e) {
    error = e.what();
    if (error.empty()) error = path + ": cannot read the checkpoint";
  }
  if (ranks == 1) {
    if (!error.empty()) throw Error(error);
    if (detail::checksum(c) != stored)
      throw Error(path + ": the checksum does not match the contents (the file is corrupt)");
    return c;
  }
  error = first_error(comm, error);  // a rank that cannot read its part stops every rank
  if (!error.empty()) throw Error(error);
  if (checksum_along(comm, c, shape.values, increment) != stored)
    throw Error(path + ": the checksum does not match the contents (the file is corrupt)");
  return c;
}

}  // namespace emc::output
