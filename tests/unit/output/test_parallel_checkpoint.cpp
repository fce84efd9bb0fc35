// Checkpoints written by every rank together (each rank its block of u, V and last_increment,
// nothing gathered) hold exactly what one rank writes of the whole: every dataset's bytes and
// the same checksum; read back by every rank together, each gets its block and the rest whole;
// a flipped value is refused on every rank. Run on 1, 2 and 3 ranks (uneven blocks).
#include <gtest/gtest.h>
#include <hdf5.h>
#include <mpi.h>
#include <sys/stat.h>

#include <cstdint>
#include <string>
#include <vector>

#include "emcontact/error.hpp"
#include "emcontact/output/checkpoint.hpp"
#include "emcontact/output/parallel_hdf5.hpp"
#include "temp_dir.hpp"

namespace emc::output {
namespace {

using testing::TempDir;

/// A whole checkpoint of `values` per-node values (distinct, not round numbers).
Checkpoint whole(std::size_t values, bool increment) {
  Checkpoint c;
  c.step = 42;
  c.t = 0.1 + 0.2;
  c.dt = c.nominal_dt = 1.0 / 3.0;
  c.last_h = 1e-3 / 7;
  c.good_steps = 2;
  c.last_iterations = 4;
  c.newton_contraction = 2.5e-7 / 3;
  c.model = "nodes: 20\ntets: 30\n";
  for (std::size_t k = 0; k < values; ++k) {
    c.u.push_back(1.0 / (k + 3));
    c.V.push_back(-2.0 / (k + 7));
    if (increment) c.last_increment.push_back(1e-9 * k);
  }
  c.active = {4, 0, 17, 1.0 / 7, 2.0 / 7, 9, 1, 3, 0.25, 0.5};
  c.normal_force = {3.25, 1.0 / 9};
  c.state = {1, 0.6, -0.8, 1e-17, 0, 0, 0, 0, 0, 1};
  return c;
}

/// This rank's part: its block of the per-node values, the rest only on rank 0.
Checkpoint mine(const Checkpoint& c, std::size_t values) {
  const Block b =
      block_of(static_cast<long long>(values), rank_of(MPI_COMM_WORLD), ranks_of(MPI_COMM_WORLD));
  const auto cut = [&](const std::vector<double>& v) {
    return v.empty() ? v : std::vector<double>(v.begin() + b.first, v.begin() + b.first + b.count);
  };
  Checkpoint m;
  if (rank_of(MPI_COMM_WORLD) == 0) m = c;
  m.u = cut(c.u);
  m.V = cut(c.V);
  m.last_increment = cut(c.last_increment);
  return m;
}

std::vector<char> raw(const std::string& path, const char* name) {
  const hid_t file = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  const hid_t set = H5Dopen2(file, name, H5P_DEFAULT);
  const hid_t space = H5Dget_space(set);
  std::vector<char> bytes(static_cast<std::size_t>(H5Sget_simple_extent_npoints(space)) * 8);
  if (!bytes.empty()) H5Dread(set, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, bytes.data());
  H5Sclose(space);
  H5Dclose(set);
  H5Fclose(file);
  return bytes;
}

std::uint64_t stored_checksum(const std::string& path) {
  const hid_t file = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  const hid_t attr = H5Aopen(file, "checksum", H5P_DEFAULT);
  std::uint64_t v = 0;
  H5Aread(attr, H5T_NATIVE_UINT64, &v);
  H5Aclose(attr);
  H5Fclose(file);
  return v;
}

void expect_same_as_one_rank(std::size_t values, bool increment) {
  TempDir* tmp = rank_of(MPI_COMM_WORLD) == 0 ? new TempDir : nullptr;
  const std::string base = broadcast(MPI_COMM_WORLD, tmp ? tmp->path() : std::string());
  const Checkpoint c = whole(values, increment);
  {
    const Directory root_dir = rank_of(MPI_COMM_WORLD) == 0 ? Directory(base) : Directory();
    const Directory dir = shared_directory(MPI_COMM_WORLD, root_dir);
    write_checkpoint_collectively(MPI_COMM_WORLD, dir, "par.h5", mine(c, values), values);
  }
  if (rank_of(MPI_COMM_WORLD) == 0) {
    write_checkpoint(base + "/ser.h5", c);
    for (const char* set :
         {"scalars", "u", "V", "last_increment", "active", "normal_force", "state"})
      EXPECT_EQ(raw(base + "/par.h5", set), raw(base + "/ser.h5", set)) << set;
    EXPECT_EQ(stored_checksum(base + "/par.h5"), stored_checksum(base + "/ser.h5"));
    const Checkpoint r = read_checkpoint(base + "/par.h5");  // one rank, whole: its checksum
    EXPECT_EQ(r.u, c.u);
  }
  // every rank reads its block back
  CheckpointShape shape;
  shape.values = values;
  shape.max_entries = 2;
  const Checkpoint r = read_checkpoint_collectively(MPI_COMM_WORLD, base + "/par.h5", shape);
  const Checkpoint expected = mine(c, values);
  EXPECT_EQ(r.u, expected.u);
  EXPECT_EQ(r.V, expected.V);
  EXPECT_EQ(r.last_increment, expected.last_increment);
  EXPECT_EQ(r.active, c.active);
  EXPECT_EQ(r.state, c.state);
  EXPECT_EQ(r.model, c.model);
  EXPECT_EQ(r.scalars(), c.scalars());
  MPI_Barrier(MPI_COMM_WORLD);
  delete tmp;
}

TEST(ParallelCheckpoint, EveryRanksBlocksMakeTheSameFileAsOneRank) {
  expect_same_as_one_rank(61, true);
}

TEST(ParallelCheckpoint, WithoutLastIncrement) {
  expect_same_as_one_rank(30, false);
}

// the last value of u changed in the file: every rank refuses it with the same message
TEST(ParallelCheckpoint, AFlippedValueIsRefusedOnEveryRank) {
  TempDir* tmp = rank_of(MPI_COMM_WORLD) == 0 ? new TempDir : nullptr;
  const std::string base = broadcast(MPI_COMM_WORLD, tmp ? tmp->path() : std::string());
  const std::size_t values = 45;
  const Checkpoint c = whole(values, true);
  {
    const Directory root_dir = rank_of(MPI_COMM_WORLD) == 0 ? Directory(base) : Directory();
    write_checkpoint_collectively(MPI_COMM_WORLD, shared_directory(MPI_COMM_WORLD, root_dir),
                                  "c.h5", mine(c, values), values);
  }
  if (rank_of(MPI_COMM_WORLD) == 0) {
    const hid_t file = H5Fopen((base + "/c.h5").c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
    const hid_t set = H5Dopen2(file, "u", H5P_DEFAULT);
    std::vector<double> u = c.u;
    u.back() += 1e-12;
    H5Dwrite(set, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, u.data());
    H5Dclose(set);
    H5Fclose(file);
  }
  MPI_Barrier(MPI_COMM_WORLD);
  CheckpointShape shape;
  shape.values = values;
  shape.max_entries = 2;
  std::string what;
  try {
    read_checkpoint_collectively(MPI_COMM_WORLD, base + "/c.h5", shape);
  } catch (const Error& e) {
    what = e.what();
  }
  EXPECT_NE(what.find("the checksum does not match"), std::string::npos) << what;
  MPI_Barrier(MPI_COMM_WORLD);
  delete tmp;
}

}  // namespace
}  // namespace emc::output
