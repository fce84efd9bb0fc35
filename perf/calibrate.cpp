// The calibration of the benchmarks in CI (perf/check_baseline.py): a STREAM-triad loop
// a = b + s c over three arrays far larger than any core's last-level cache, timed in CPU
// seconds per sweep. Prints one JSON object: the median and the smallest of the sweeps' CPU
// times, the bytes moved per sweep and the bandwidth of the median sweep.
//
//     emc_calibrate [DOUBLES_PER_ARRAY [SWEEPS]]    (defaults: 2^24 = 128 MiB per array, 11)
#include <time.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

namespace {

double cpu_seconds() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return double(t.tv_sec) + 1e-9 * double(t.tv_nsec);
}

/// One triad sweep a = b + s c; returns its CPU seconds.
double triad(std::vector<double>& a, const std::vector<double>& b, const std::vector<double>& c,
             double s) {
  const double t0 = cpu_seconds();
  const std::size_t n = a.size();
  double* __restrict pa = a.data();
  const double* __restrict pb = b.data();
  const double* __restrict pc = c.data();
  for (std::size_t i = 0; i < n; ++i) pa[i] = pb[i] + s * pc[i];
  return cpu_seconds() - t0;
}

long positive_arg(int argc, char** argv, int i, long fallback) {
  if (argc <= i) return fallback;
  char* end = nullptr;
  const long v = std::strtol(argv[i], &end, 10);
  if (*end != '\0' || v <= 0) {
    std::fprintf(stderr, "emc_calibrate: argument %d '%s': a positive integer is allowed\n", i,
                 argv[i]);
    std::exit(1);
  }
  return v;
}

}  // namespace

int main(int argc, char** argv) {
  const long n = positive_arg(argc, argv, 1, 1L << 24);
  const long sweeps = positive_arg(argc, argv, 2, 11);
  // first touch here, outside the timed sweeps
  std::vector<double> a(n, 0.0), b(n, 1.0), c(n, 2.0);
  std::vector<double> t;
  for (long k = 0; k < sweeps; ++k) t.push_back(triad(a, b, c, 1.0 + 1e-3 * double(k)));
  double check = 0;  // uses the result, so that no sweep can be optimised away
  for (long i = 0; i < n; i += 4096) check += a[i];
  std::vector<double> sorted = t;
  std::sort(sorted.begin(), sorted.end());
  const double median = sorted[sorted.size() / 2];
  const double bytes = 3.0 * 8.0 * double(n);  // read b, c; write a (no write-allocate counted)
  std::printf(
      "{\"kernel\": \"triad\", \"doubles_per_array\": %ld, \"sweeps\": %ld, "
      "\"bytes_per_sweep\": %.0f, \"median_cpu_s\": %.9g, \"min_cpu_s\": %.9g, "
      "\"gbytes_per_s\": %.4g, \"checksum\": %.17g}\n",
      n, sweeps, bytes, median, sorted.front(), bytes / median * 1e-9, check);
  return 0;
}
