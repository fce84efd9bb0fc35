#pragma once
// Output/plot: DIR/energies.png from DIR/monitors.csv with tools/plot_monitors.py.
#include "emcontact/output/open_directory.hpp"

namespace emc::os {

/// Runs the plot script as a child process with an argument vector (no shell, whatever the
/// directory's name holds) in the directory held by `dir` (fchdir: a rename of its name does
/// not redirect it); waits for it. It reads monitors.csv through a descriptor (/proc/self/fd)
/// and writes a fresh temporary, which becomes energies.png. A failure only warns on stderr,
/// with its cause (the script's last line of stderr, or the system's error).
void plot_monitors(const output::Directory& dir);

}  // namespace emc::os
