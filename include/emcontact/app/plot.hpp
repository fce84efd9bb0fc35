#pragma once
// Output/plot: DIR/energies.png from DIR/monitors.csv with tools/plot_monitors.py.
#include <string>

namespace emc::app {

/// Runs the plot script as a child process with an argument vector (no shell, whatever `dir`
/// holds); waits for it. A failure only warns on stderr.
void plot_monitors(const std::string& dir);

}  // namespace emc::app
