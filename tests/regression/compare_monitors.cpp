// compare_monitors A.csv B.csv RTOL ATOL: every physical column of every row must agree,
// |a - b| <= ATOL + RTOL * max_rows |a| (the column's largest magnitude, or the vector's for
// the components of L, J and the centre of mass, so that values crossing zero are judged
// against their own scale). Prints the worst mismatch; exit 1 if any.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "emcontact/output/monitors.hpp"

using emc::output::MonitorRow;

namespace {

std::vector<double> physical(const MonitorRow& r) {
  return {r.time, r.kinetic, r.elastic, r.potential, r.total,  r.L[0],   r.L[1],
          r.L[2], r.J[0],    r.J[1],    r.J[2],      r.com[0], r.com[1], r.com[2]};
}
const char* kNames[] = {"time", "kinetic", "elastic", "potential", "total", "Lx",    "Ly",
                        "Lz",   "Jx",      "Jy",      "Jz",        "com_x", "com_y", "com_z"};

}  // namespace

int main(int argc, char** argv) {
  if (argc != 5) {
    std::fprintf(stderr, "usage: compare_monitors A.csv B.csv RTOL ATOL\n");
    return 2;
  }
  try {
    const auto a = emc::output::read_monitors(argv[1]);
    const auto b = emc::output::read_monitors(argv[2]);
    const double rtol = std::atof(argv[3]), atol = std::atof(argv[4]);
    if (a.size() != b.size()) {
      std::printf("row counts differ: %zu vs %zu\n", a.size(), b.size());
      return 1;
    }
    const std::size_t nc = physical(a[0]).size();
    std::vector<double> scale(nc, 0.0);
    for (const auto& r : a) {
      const auto v = physical(r);
      for (std::size_t c = 0; c < nc; ++c) scale[c] = std::max(scale[c], std::fabs(v[c]));
    }
    // the total energy is judged against its parts (it may start at zero)
    scale[4] = std::max({scale[1], scale[2], scale[3], scale[4]});
    // the components of a vector (L, J, centre of mass) share the vector's scale
    for (std::size_t first : {5, 8, 11}) {
      const double m = std::max({scale[first], scale[first + 1], scale[first + 2]});
      for (std::size_t c = first; c < first + 3; ++c) scale[c] = m;
    }
    double worst = 0;
    std::size_t wr = 0, wc = 0, first_row = a.size(), first_col = 0;
    int bad = 0;
    for (std::size_t k = 0; k < a.size(); ++k) {
      const auto va = physical(a[k]), vb = physical(b[k]);
      for (std::size_t c = 0; c < nc; ++c) {
        const double d = std::fabs(va[c] - vb[c]);
        const double rel = d / (atol + rtol * scale[c]);
        if (rel > worst) {
          worst = rel;
          wr = k;
          wc = c;
        }
        if (rel > 1 && first_row == a.size()) {
          first_row = k;
          first_col = c;
        }
        bad += rel > 1;
      }
    }
    const double d = std::fabs(physical(a[wr])[wc] - physical(b[wr])[wc]);
    std::printf(
        "%zu rows: worst %s at row %zu: |diff| %.3e = %.3g x allowed (scale %.3e); %d "
        "values out of tolerance\n",
        a.size(), kNames[wc], wr, d, worst, scale[wc], bad);
    if (bad) {  // where they part: a contact decision, or a Newton count, shows it
      const MonitorRow &ra = a[first_row], &rb = b[first_row];
      std::printf(
          "first out of tolerance: %s at row %zu (step %ld): %.17g vs %.17g; active contacts %d "
          "vs %d, Newton iterations %d vs %d, contact re-solves %d vs %d\n",
          kNames[first_col], first_row, ra.step, physical(ra)[first_col], physical(rb)[first_col],
          ra.active_contacts, rb.active_contacts, ra.newton_iterations, rb.newton_iterations,
          ra.contact_resolves, rb.contact_resolves);
    }
    return bad ? 1 : 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "compare_monitors: %s\n", e.what());
    return 2;
  }
}
