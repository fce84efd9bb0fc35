#pragma once
#include <cstdio>
#include <string>

namespace emc::app {

/// The one-line progress display on rank 0: rewritten in place on a terminal, otherwise
/// printed as a plain line about every 5% of the run.
class Progress {
 public:
  Progress(bool enabled, double end_time);
  /// energy_error: |E + D - E0| / |E0|, labelled E + D once friction has dissipated (D > 0)
  void update(long step, double t, double dt, int newton, double energy_error, int active,
              bool dissipates);
  void finish();

 private:
  bool enabled_, tty_;
  double end_, next_report_ = 0;
  std::size_t width_ = 0;
};

}  // namespace emc::app
