// A Kokkos Tools library that times every labelled parallel_for, parallel_reduce and
// parallel_scan by name (wall time from dispatch to return, on the host) and writes, at
// Kokkos' finalize, one line per label: seconds, calls, label, slowest first. Load it into any
// run of the binary:
//
//   KOKKOS_PROFILE_LIBRARY=build/lib/libemc_kernel_timer.so EMC_KERNEL_TIMES=times.txt \
//     build/bin/emcontact inputs/drop.xml
//
// (without EMC_KERNEL_TIMES the table goes to stderr). perf/README.md "OpenMP threads" uses it
// to split contact's time into its kernels and what runs between them.
#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <string>
#include <utility>
#include <vector>

namespace {

using Clock = std::chrono::steady_clock;

struct Total {
  double seconds = 0;
  long calls = 0;
};

std::map<std::string, Total>& totals() {
  static std::map<std::string, Total> t;
  return t;
}

/// The kernels running now (host dispatch returns before the next starts; kept as a stack).
std::vector<std::pair<std::string, Clock::time_point>>& running() {
  static std::vector<std::pair<std::string, Clock::time_point>> r;
  return r;
}

void begin(const char* name, uint64_t* id) {
  *id = running().size();
  running().emplace_back(name, Clock::now());
}

void end(uint64_t id) {
  const auto now = Clock::now();
  auto& r = running();
  if (id >= r.size()) return;  // an end without its begin: nothing to time
  Total& t = totals()[r[id].first];
  t.seconds += std::chrono::duration<double>(now - r[id].second).count();
  ++t.calls;
  r.resize(id);
}

}  // namespace

extern "C" void kokkosp_init_library(int, uint64_t, uint32_t, void*) {}

extern "C" void kokkosp_finalize_library() {
  std::vector<std::pair<std::string, Total>> rows(totals().begin(), totals().end());
  std::sort(rows.begin(), rows.end(),
            [](const auto& a, const auto& b) { return a.second.seconds > b.second.seconds; });
  const char* path = std::getenv("EMC_KERNEL_TIMES");
  FILE* out = path ? std::fopen(path, "w") : stderr;
  if (!out) {
    std::fprintf(stderr, "emc_kernel_timer: cannot write EMC_KERNEL_TIMES = %s\n", path);
    return;
  }
  std::fprintf(out, "# seconds calls kernel\n");
  for (const auto& [name, t] : rows)
    std::fprintf(out, "%.6f %ld %s\n", t.seconds, t.calls, name.c_str());
  if (out != stderr) std::fclose(out);
}

extern "C" void kokkosp_begin_parallel_for(const char* name, uint32_t, uint64_t* id) {
  begin(name, id);
}
extern "C" void kokkosp_end_parallel_for(uint64_t id) {
  end(id);
}
extern "C" void kokkosp_begin_parallel_reduce(const char* name, uint32_t, uint64_t* id) {
  begin(name, id);
}
extern "C" void kokkosp_end_parallel_reduce(uint64_t id) {
  end(id);
}
extern "C" void kokkosp_begin_parallel_scan(const char* name, uint32_t, uint64_t* id) {
  begin(name, id);
}
extern "C" void kokkosp_end_parallel_scan(uint64_t id) {
  end(id);
}
