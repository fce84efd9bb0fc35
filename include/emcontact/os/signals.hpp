#pragma once
// SIGTERM, SIGINT and SIGHUP stop a run alike. During setup (nothing to keep yet) the run ends
// at once with a one-line message and exit code 1; from the time loop on the signal asks the
// loop to stop (time::stop_flag), which writes a checkpoint of the last accepted step and
// exits 1 with the --restart command. SIGINT and SIGHUP that the process started with ignored
// (a background job of a shell, nohup) stay ignored.
namespace emc::os {

/// Installs the handlers, first thing in main: a signal that comes before MPI has started is
/// held (ending the process inside MPI's start-up leaves its helper processes complaining)
/// until stop_handlers_ready.
void install_stop_handlers();
/// Once MPI has started: installs the handlers again (should MPI have replaced them); a held
/// signal ends the run now, and later ones at once, with the setup message (`rank` 0 prints it).
void stop_handlers_ready(int rank);
/// From now on the signals stop the time loop (a checkpoint) instead of ending the run at once.
void signals_stop_time_loop();
/// The run ends with an error being reported (exit `code`): a signal from now on ends it at
/// once with that code and says nothing (mpiexec stops the other ranks with SIGTERM as soon as
/// one has exited non-zero; rank 0's one line must stay the only one).
void signals_ending(int code);

}  // namespace emc::os
