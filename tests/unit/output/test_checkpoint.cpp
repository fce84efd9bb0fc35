// Checkpoint files: everything written (the entries' states too) is read back bit for bit; a
// checkpoint of the layout before the inexact Newton (6 scalars) still loads, with no
// contraction estimate; any other scalar count is refused naming the file; a dataset of another
// rank or length than the model needs is refused, naming it, before it is read.
#include <gtest/gtest.h>
#include <hdf5.h>

#include <string>
#include <vector>

#include "emcontact/error.hpp"
#include "emcontact/output/checkpoint.hpp"
#include "temp_dir.hpp"

namespace emc::output {
namespace {

using testing::TempDir;

TEST(Checkpoint, RoundTripIsBitwise) {
  TempDir dir;
  Checkpoint c;
  c.step = 123;
  c.t = 0.1 + 0.2;
  c.dt = 1.0 / 3.0;
  c.last_h = 1e-3 / 7;
  c.good_steps = 2;
  c.last_iterations = 4;
  c.newton_contraction = 2.5e-7 / 3;
  c.u = {1.0 / 3, -2e-300, 5};
  c.V = {0.1, 0.2, 0.3};
  c.last_increment = {7, 8, 9};
  c.active = {4, 0, 17, 1.0 / 7, 2.0 / 7};
  c.normal_force = {3.25};
  c.state = {1, 0.6, -0.8, 1e-17, 0};  // docs/THEORY.md §11.7: slip, direction, off
  write_checkpoint(dir / "c.h5", c);
  const Checkpoint r = read_checkpoint(dir / "c.h5");
  EXPECT_EQ(r.scalars(), c.scalars());
  EXPECT_EQ(r.u, c.u);
  EXPECT_EQ(r.V, c.V);
  EXPECT_EQ(r.last_increment, c.last_increment);
  EXPECT_EQ(r.active, c.active);
  EXPECT_EQ(r.normal_force, c.normal_force);
  EXPECT_EQ(r.state, c.state);
}

TEST(Checkpoint, OlderSixScalarLayoutLoadsOthersAreRefused) {
  Checkpoint c;
  c.set_scalars({10, 0.5, 1e-3, 1e-3, 1, 3}, "old.h5");
  EXPECT_EQ(c.step, 10);
  EXPECT_EQ(c.last_iterations, 3);
  EXPECT_EQ(c.newton_contraction, 0.0);
  try {
    c.set_scalars({10, 0.5, 1e-3}, "bad.h5");
    FAIL() << "3 scalars accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("bad.h5"), std::string::npos) << e.what();
  }
}

Checkpoint small_checkpoint() {
  Checkpoint c;
  c.step = 2;
  c.t = 0.02;
  c.dt = c.last_h = c.nominal_dt = 0.01;
  c.model = "nodes: 2\n";
  c.u = {1, 2, 3, 4, 5, 6};
  c.V = {0, 0, 0, 0, 0, 0};
  return c;
}

/// Replaces the dataset `name` of the file `path` by `dims` doubles (all 0).
void replace_dataset(const std::string& path, const char* name, std::vector<hsize_t> dims) {
  const hid_t file = H5Fopen(path.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
  ASSERT_GE(file, 0);
  ASSERT_GE(H5Ldelete(file, name, H5P_DEFAULT), 0);
  const hid_t space = H5Screate_simple(static_cast<int>(dims.size()), dims.data(), nullptr);
  const hid_t set =
      H5Dcreate2(file, name, H5T_IEEE_F64LE, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  hsize_t n = 1;
  for (hsize_t d : dims) n *= d;
  const std::vector<double> zeros(n, 0.0);
  EXPECT_GE(H5Dwrite(set, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, zeros.data()), 0);
  H5Dclose(set);
  H5Sclose(space);
  H5Fclose(file);
}

/// read_checkpoint(path, shape) throws an emc::Error naming `path` and containing `what`.
void expect_refused(const std::string& path, const CheckpointShape& shape,
                    const std::string& what) {
  try {
    read_checkpoint(path, shape);
    FAIL() << "accepted; expected: " << what;
  } catch (const Error& e) {
    const std::string msg = e.what();
    EXPECT_EQ(msg.rfind(path + ": ", 0), 0u) << msg;
    EXPECT_NE(msg.find(what), std::string::npos) << msg;
  }
}

TEST(Checkpoint, DatasetOfAnotherRankOrLengthIsRefusedBeforeReading) {
  TempDir dir;
  const std::string path = dir / "c.h5";
  CheckpointShape shape;
  shape.values = 6;
  write_checkpoint(path, small_checkpoint());
  EXPECT_EQ(read_checkpoint(path, shape).u, small_checkpoint().u);
  // the model's check comes before any dataset
  shape.check_model = [&](const std::string& m) {
    if (m != "nodes: 3\n") throw Error(path + ": another model");
  };
  expect_refused(path, shape, "another model");
  shape.check_model = nullptr;
  // the input's mesh needs another length
  shape.values = 9;
  expect_refused(path, shape, "the checkpoint dataset u has 6 values (allowed: 9, 3 per node");
  shape.values = 6;
  // as many values, in 2 dimensions (read as 2 values, they overflowed the vector)
  replace_dataset(path, "u", {2, 3});
  expect_refused(path, shape, "the checkpoint dataset u has 2 dimensions (allowed: 1");
  replace_dataset(path, "u", {2, 500000});  // more than the file holds
  expect_refused(path, shape, "the checkpoint dataset u has 2 dimensions");
  write_checkpoint(path, small_checkpoint());
  replace_dataset(path, "scalars", {1, 8});
  expect_refused(path, shape, "the checkpoint dataset scalars has 2 dimensions");
  write_checkpoint(path, small_checkpoint());
  replace_dataset(path, "active", {7});
  expect_refused(path, shape, "the checkpoint dataset active has 7 values (allowed: 5 per");
}

}  // namespace
}  // namespace emc::output
