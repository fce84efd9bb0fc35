// Writes a sample output directory (mesh.h5, a few fields_*.h5, fields.xdmf, monitors.csv) for
// the Python checks, and prints write timings.
//   output_sample_writer DIR [K]   (K^3 cubes of 6 tets; K = 44 gives 511k tets)
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "emcontact/error.hpp"
#include "emcontact/output/fields.hpp"
#include "emcontact/output/monitors.hpp"
#include "fake_mesh.hpp"

namespace {

/// Fake monitors: a decaying kinetic energy traded for elastic energy, a slowly turning L.
void write_monitors(const std::string& path, int steps) {
  emc::output::MonitorWriter w(path);
  for (int s = 0; s <= steps; ++s) {
    emc::output::MonitorRow r;
    r.step = s;
    r.dt = 1e-3;
    r.time = s * r.dt;
    r.kinetic = 1.0 + std::cos(40.0 * r.time);
    r.elastic = 1.0 - std::cos(40.0 * r.time);
    r.potential = -0.1 * r.time;
    r.total = r.kinetic + r.elastic + r.potential;
    r.L = {std::sin(r.time), std::cos(r.time), 0.5};
    r.J = {0.0, 0.0, -1e-3 * s};
    r.active_contacts = s % 17;
    r.newton_iterations = 2 + s % 3;
    r.linear_iterations = 10 + s % 7;
    w.append(r);
    w.flush(false, 1.0);
  }
  w.flush(true);
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: %s DIR [K]\n", argv[0]);
    return 2;
  }
  const std::string dir = argv[1];
  const int k = argc > 2 ? std::atoi(argv[2]) : 4;
  try {
    const auto mesh = emc::output::testing::make_fake_mesh(k);
    emc::output::FieldWriter w(dir, mesh.X, mesh.tets, mesh.body);
    std::printf("%lld nodes, %lld tets: mesh.h5\n", mesh.num_nodes(), mesh.num_tets());
    for (long step : {0L, 10L, 20L}) {
      w.write(emc::output::testing::make_fake_frame(mesh, step));
      std::printf("frame %ld (fields h5 + xdmf)\n", step);
    }
    write_monitors(dir + "/monitors.csv", 2000);
    std::printf("monitors.csv, 2001 rows\n");
  } catch (const emc::Error& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 1;
  }
  return 0;
}
