// Checkpoint files: everything written (the entries' states too) is read back bit for bit; a
// checkpoint of the layout before the inexact Newton (6 scalars) still loads, with no
// contraction estimate; any other scalar count is refused naming the file.
#include <gtest/gtest.h>

#include <string>

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

}  // namespace
}  // namespace emc::output
