#pragma once
// DIR/monitors.csv: one row per accepted step (docs/THEORY.md §1.9). Rank 0 only.
#include <array>
#include <string>
#include <vector>

#include "emcontact/output/atomic_file.hpp"
#include "emcontact/output/open_directory.hpp"

namespace emc::output {

struct MonitorRow {
  long step = 0;
  double time = 0;
  double kinetic = 0, elastic = 0, potential = 0, total = 0;
  std::array<double, 3> L{}, J{};
  int active_contacts = 0;
  int newton_iterations = 0;
  // extra columns, after the fixed ones
  double dt = 0;
  int linear_iterations = 0;
  std::array<double, 3> com{};      ///< centre of mass (sum M x / sum M)
  double gap_min = 0, gap_max = 0;  ///< g_N at n+1 of the active slave nodes (0 if none)
  int contact_resolves = 0;         ///< extra solves of the step for activation/release (§6)
  double normal_force_min =
      0;                  ///< smallest f_N of the active nodes at the accepted solve (0 if none)
  double dissipated = 0;  ///< energy dissipated by friction since t = 0 (docs/THEORY.md §11.2)
};

/// The fixed header: step,time,kinetic,elastic,potential,total,Lx,Ly,Lz,Jx,Jy,Jz,
/// active_contacts,newton_iterations, then
/// dt,linear_iterations,com_x,com_y,com_z,gap_min,gap_max,contact_resolves,normal_force_min,
/// dissipated.
std::string monitor_header();
std::string format_row(const MonitorRow& r);  ///< %.17g for doubles: round-trips exactly

class MonitorWriter {
 public:
  /// The file `name` of `dir` (monitors.csv): the first flush() replaces it atomically (the
  /// header and the rows so far), later ones append the new rows.
  MonitorWriter(Directory dir, std::string name);
  /// The same for `path`, its directory opened by name.
  explicit MonitorWriter(const std::string& path);
  void append(const MonitorRow& r);
  /// Writes the rows appended since the last write if `force` or if at least `min_seconds`
  /// passed since then; `force` also syncs the file to disk (before a checkpoint, at the end).
  void flush(bool force = true, double min_seconds = 1.0);
  /// Rows appended so far.
  long rows() const { return rows_; }

 private:
  Directory dir_;
  std::string name_;
  GrowingFile file_;
  long rows_ = 0;
  double last_write_ = -1e300;  // steady-clock seconds of the last write
  std::string pending_;         // the rows not yet written (the header before the first write)
};

/// Reads a monitors.csv written by MonitorWriter (for tests and tools); throws on bad format.
std::vector<MonitorRow> read_monitors(const std::string& path);

}  // namespace emc::output
