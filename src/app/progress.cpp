#include "emcontact/app/progress.hpp"

#include <unistd.h>

#include "emcontact/format.hpp"

namespace emc::app {

Progress::Progress(bool enabled, double end_time)
    : enabled_(enabled), tty_(isatty(fileno(stderr)) != 0), end_(end_time) {}

void Progress::update(long step, double t, double dt, int newton, double energy_error, int active,
                      bool dissipates) {
  if (!enabled_) return;
  std::string text = format(
      "step %7ld  t = %-11.5g (%5.1f%%)  dt = %-9.3g  newton %2d  "
      "|%s-E0|/(K+W+|Pi|) = %-9.2e  contacts %d",
      step, t, 100.0 * t / end_, dt, newton, dissipates ? "E+D" : "E", energy_error, active);
  if (tty_) {
    if (text.size() < width_) text.append(width_ - text.size(), ' ');  // over the last line
    width_ = text.size();
    std::fprintf(stderr, "\r%s", text.c_str());
    std::fflush(stderr);
  } else if (t >= next_report_ - 1e-12 * end_) {
    std::fprintf(stderr, "%s\n", text.c_str());
    next_report_ = t + 0.05 * end_;
  }
}

void Progress::finish() {
  if (enabled_ && tty_) std::fprintf(stderr, "\n");
}

}  // namespace emc::app
