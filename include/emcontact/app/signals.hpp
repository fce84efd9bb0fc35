#pragma once
// SIGTERM: during setup (nothing to keep yet) the run ends at once with a one-line message and
// exit code 1; from the time loop on it asks the loop to stop (time::stop_flag), which writes
// a checkpoint of the last accepted step and exits 1 with the --restart command.
namespace emc::app {

/// Installs the SIGTERM handler; `rank` 0 prints the setup message.
void install_sigterm_handler(int rank);
/// From now on SIGTERM stops the time loop (a checkpoint) instead of ending the run at once.
void sigterm_stops_time_loop();

}  // namespace emc::app
