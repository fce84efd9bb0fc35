// The output's size against the room in the output directory (space.hpp).
#include "emcontact/output/space.hpp"

#include <sys/stat.h>
#include <sys/statvfs.h>

#include <algorithm>
#include <cerrno>
#include <cmath>

#include "emcontact/error.hpp"
#include "emcontact/format.hpp"
#include "emcontact/output/atomic_file.hpp"

namespace emc::output {
namespace {

// Per frame beyond its values: HDF5's metadata for the 8 datasets of a frame file (4.1 kB
// measured with HDF5 1.10: 32784 bytes for 296 nodes and 920 tets) and the frame's grid in
// fields.xdmf (2.0 kB), rounded up.
constexpr double kFrameOverhead = 8e3;
// A monitors.csv row: 24 columns, 274 bytes a row measured on the tumbling box (%.17g).
constexpr double kRowBytes = 300;

}  // namespace

OutputSize estimate_output(const Settings& s, long long nodes, long long tets, double steps) {
  OutputSize o;
  const double n = static_cast<double>(nodes), e = static_cast<double>(tets);
  steps = std::max(0.0, std::ceil(steps));
  if (s.every > 0) o.frames = std::floor(steps / s.every) + 1;
  // displacement, velocity (3 per node), status, normal force, slip (1 per node), von Mises
  o.frame_bytes = 8 * (9 * n + e) + kFrameOverhead;
  o.monitors = (steps + 1) * kRowBytes;
  // mesh.h5 (coordinates, 4 node ids and a body id per tet); a checkpoint (u, V and the last
  // increment, 3 per node, and the contact state) written beside the one it replaces
  o.fixed = 8 * 3 * n + 36 * e + kFrameOverhead + 2 * (8 * 12 * n + kFrameOverhead);
  return o;
}

double free_bytes(const std::string& path) {
  std::string p = path.empty() ? "." : path;
  for (int up = 0; up < 256; ++up) {
    struct statvfs v {};
    if (::statvfs(p.c_str(), &v) == 0) return static_cast<double>(v.f_bavail) * v.f_frsize;
    if (errno != ENOENT && errno != ENOTDIR) return -1;
    const std::string parent = parent_directory(p);
    if (parent == p) return -1;
    p = parent;
  }
  return -1;
}

std::string format_bytes(double bytes) {
  static const char* units[] = {"B", "kB", "MB", "GB", "TB", "PB", "EB"};
  int u = 0;
  while (bytes >= 1000 && u < 6) {
    bytes /= 1000;
    ++u;
  }
  return format(u == 0 ? "%.0f %s" : "%.1f %s", bytes, units[u]);
}

void check_room(const std::string& dir, const OutputSize& need, double free, int every) {
  if (free < 0 || need.total() <= free) return;
  throw Error("output directory '" + dir + "': the run would write about " +
              format_bytes(need.total()) + " (" +
              (need.frames > 0
                   ? format("%.4g", need.frames) + " frames of " + format_bytes(need.frame_bytes) +
                         " with Output/every = " + std::to_string(every) + ", "
                   : std::string()) +
              "monitors.csv " + format_bytes(need.monitors) + ", mesh and checkpoint " +
              format_bytes(need.fixed) + "), more than the " + format_bytes(free) +
              " free there; allowed: output that fits (a larger Output/every, or 0 for no "
              "fields; a shorter Time/end) or a directory with room");
}

}  // namespace emc::output
