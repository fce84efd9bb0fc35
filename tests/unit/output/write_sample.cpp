// Writes a sample output directory (mesh.h5, a few fields_*.h5, fields.xdmf, monitors.csv) for
// the Python checks, and prints write timings.
//   output_sample_writer DIR [K]   (K^3 cubes of 6 tets; K = 44 gives 511k tets)
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "emcontact/error.hpp"
#include "emcontact/output/fields.hpp"
#include "emcontact/output/monitors.hpp"
#include "fake_mesh.hpp"

namespace {

/// Seconds since `t0` on the steady clock.
double since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

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
    auto t0 = std::chrono::steady_clock::now();
    emc::output::FieldWriter w(dir, mesh.X, mesh.tets, mesh.body);
    std::printf("%lld nodes, %lld tets: mesh.h5 %.3f s\n", mesh.num_nodes(), mesh.num_tets(),
                since(t0));
    for (long step : {0L, 10L, 20L}) {
      const auto frame = emc::output::testing::make_fake_frame(mesh, step);
      t0 = std::chrono::steady_clock::now();
      w.write(frame);
      std::printf("frame %ld (fields h5 + xdmf): %.3f s\n", step, since(t0));
    }
    t0 = std::chrono::steady_clock::now();
    write_monitors(dir + "/monitors.csv", 2000);
    std::printf("monitors.csv, 2001 rows: %.3f s\n", since(t0));
  } catch (const emc::Error& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 1;
  }
  return 0;
}
