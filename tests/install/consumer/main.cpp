// A consumer of the installed emcontact: a kernel of emcontact::kernels in a Kokkos loop and a
// function of emcontact::core. Prints "consumer: ok" and exits 0 when both give what they must.
#include <Kokkos_Core.hpp>
#include <cmath>
#include <cstdio>
#include <string>

#include "emcontact/app/run.hpp"
#include "kernels/tet4.hpp"

namespace {

// The tet (0,0,0), (2,0,0), (0,3,0), (0,0,4): V_e = 2 * 3 * 4 / 6 = 4 and N_1 = x / 2, so
// G_1 = (1/2, 0, 0) (docs/THEORY.md §1.1), computed in the default execution space.
bool tet_ok() {
  double volume = 0, g1x = 0;
  Kokkos::parallel_reduce(
      "consumer_tet", Kokkos::RangePolicy<>(0, 1),
      KOKKOS_LAMBDA(int, double& v, double& g) {
        const double X[4][3] = {{0, 0, 0}, {2, 0, 0}, {0, 3, 0}, {0, 0, 4}};
        double G[4][3];
        v += emc::kernels::tet_gradients(X, G);
        g += G[1][0];
      },
      volume, g1x);
  std::printf("kernels: V_e = %.17g, G_1,x = %.17g\n", volume, g1x);
  return std::abs(volume - 4) <= 1e-14 && std::abs(g1x - 0.5) <= 1e-15;
}

}  // namespace

int main(int argc, char** argv) {
  bool ok = false;
  Kokkos::initialize(argc, argv);
  ok = tet_ok();
  Kokkos::finalize();
  const std::string version = emc::app::version();
  std::printf("core: %s\n", version.c_str());
  ok = ok && version.rfind("emcontact ", 0) == 0;
  std::printf("consumer: %s\n", ok ? "ok" : "FAILED");
  return ok ? 0 : 1;
}
