// Kokkos' command-line options, checked before Kokkos parses them (kokkos_options.hpp).
#include "emcontact/app/kokkos_options.hpp"

#include <charconv>
#include <climits>
#include <cstring>

#include "emcontact/error.hpp"
#include "emcontact/input/echo.hpp"

namespace emc::app {
namespace {

/// An integer option of Kokkos' and the least value it takes; pairs: "INT[,INT]" (ndevices).
struct IntOption {
  const char* name;
  int least;
  bool pair;
};

// Kokkos 3.x reads the plain spellings too (deprecated); 3.7 renamed threads and device
constexpr IntOption kIntOptions[] = {
    {"--kokkos-threads", 1, false},
    {"--threads", 1, false},
    {"--kokkos-num-threads", 1, false},
    {"--kokkos-numa", 1, false},
    {"--numa", 1, false},
    {"--kokkos-device", 0, false},
    {"--device", 0, false},
    {"--kokkos-device-id", 0, false},
    {"--kokkos-ndevices", 1, true},
    {"--ndevices", 1, true},
    {"--kokkos-num-devices", 1, true},
};

/// `text` is a decimal integer in [least, INT_MAX].
bool is_int(const std::string& text, int least) {
  int v = 0;
  const char* first = text.data();
  const char* last = first + text.size();
  const auto res = std::from_chars(first, last, v);
  return !text.empty() && res.ec == std::errc() && res.ptr == last && v >= least;
}

bool valid_value(const IntOption& o, const std::string& value) {
  if (!o.pair) return is_int(value, o.least);
  const auto comma = value.find(',');
  if (comma == std::string::npos) return is_int(value, o.least);
  return is_int(value.substr(0, comma), o.least) && is_int(value.substr(comma + 1), 0);
}

}  // namespace

void check_kokkos_options(int argc, char** argv) {
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--set" || a == "--output" || a == "--restart") {
      ++i;  // a value, whatever it reads
      continue;
    }
    for (const IntOption& o : kIntOptions) {
      const std::size_t n = std::strlen(o.name);
      if (a.compare(0, n, o.name) != 0 || (a.size() > n && a[n] != '=')) continue;
      const std::string value = a.size() > n ? a.substr(n + 1) : "";
      if (valid_value(o, value)) break;
      throw InputError("Kokkos option \"" + input::echo(a) + "\": allowed: " + o.name + "=N, N " +
                       (o.least == 0 ? "an integer from 0" : "a whole number from 1") + " to " +
                       std::to_string(INT_MAX) +
                       (o.pair ? " (or N,SKIP: the device to skip)" : ""));
    }
  }
}

}  // namespace emc::app
