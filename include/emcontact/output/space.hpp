#pragma once
// What a run will write to its output directory, against the room there: a run whose output
// cannot fit is refused before it starts, not stopped by a full disk after hours.
#include <cstdint>
#include <string>

#include "emcontact/output/parameters.hpp"

namespace emc::output {

/// The bytes a run writes, from the model's size and the number of steps it has left.
struct OutputSize {
  double frames = 0;       ///< fields_<step>.h5 files (Output/every)
  double frame_bytes = 0;  ///< one frame file and its grid in fields.xdmf
  double monitors = 0;     ///< monitors.csv
  double fixed = 0;        ///< mesh.h5, checkpoint.h5 and its temporary
  double total() const { return frames * frame_bytes + monitors + fixed; }
};

/// The estimate for `nodes` nodes, `tets` tetrahedra and `steps` steps of the nominal size (a
/// lower bound: step cuts only add steps).
OutputSize estimate_output(const Settings& s, long long nodes, long long tets, double steps);

/// The bytes free to this user on the file system of `path`, or of its nearest existing parent
/// when `path` does not exist yet; -1 if that cannot be told.
double free_bytes(const std::string& path);

/// "32.0 MB", "1.5 TB": a size for a message.
std::string format_bytes(double bytes);

/// Throws emc::Error when `need` exceeds `free` (free < 0: nothing known, nothing checked),
/// naming the directory, the estimate's parts and what to change.
void check_room(const std::string& dir, const OutputSize& need, double free, int every);

}  // namespace emc::output
