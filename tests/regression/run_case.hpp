#pragma once
// Runs a whole case in-process (the same code path as the emcontact binary) and returns its
// monitors. Output goes to a fresh directory gtest_runs/<out> of the test's working directory:
// never one of the out_<name> directories of the ctest cases beside it (a monitor case's run
// that another test overwrote before its 2-rank twin compared with it would fail that test).
#include <Tpetra_Core.hpp>
#include <filesystem>
#include <string>
#include <vector>

#include "emcontact/app/run.hpp"
#include "emcontact/output/monitors.hpp"

namespace emc::testing {

/// The output directory of an in-process run called `name` (its parent made if missing).
inline std::string run_directory(const std::string& name) {
  std::filesystem::create_directories("gtest_runs");
  return "gtest_runs/" + name;
}

inline std::vector<output::MonitorRow> run_case(const std::string& xml,
                                                std::vector<std::string> overrides,
                                                const std::string& name) {
  const std::string out = run_directory(name);
  app::Options o;
  o.input = std::string(EMC_TEST_DIR) + "/" + xml;
  o.overrides = std::move(overrides);
  o.output_dir = out;
  auto comm = Tpetra::getDefaultComm();
  if (comm->getRank() == 0) std::filesystem::remove_all(out);
  comm->barrier();
  app::run(o, comm);
  comm->barrier();
  return output::read_monitors(out + "/monitors.csv");
}

inline double norm3(const std::array<double, 3>& a) {
  return std::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
}

inline std::array<double, 3> diff3(const std::array<double, 3>& a, const std::array<double, 3>& b) {
  return {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
}

struct Drifts {
  double E = 0, L = 0, J = 0;  ///< max over the run of |q - q0| / |q0| (vector norms)
};

inline Drifts drifts(const std::vector<output::MonitorRow>& rows) {
  Drifts d;
  const auto& r0 = rows.front();
  for (const auto& r : rows) {
    d.E = std::max(d.E, std::fabs(r.total - r0.total) / std::fabs(r0.total));
    d.L = std::max(d.L, norm3(diff3(r.L, r0.L)) / norm3(r0.L));
    d.J = std::max(d.J, norm3(diff3(r.J, r0.J)) / norm3(r0.J));
  }
  return d;
}

}  // namespace emc::testing
