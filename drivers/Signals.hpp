// Batch signals (issue 32 item 12; docs/user-guide.md, "Files and signals"). Schedulers send SIGTERM
// before they kill a job, and often SIGUSR1 a set time before the limit (Slurm: --signal=USR1@120);
// a user presses Ctrl-C (SIGINT). On any of them a run finishes the step (or load step, or sweep
// point) it is in, writes its checkpoint (dynamics), marks the output status = "stopped" and exits
// with code 4, as -wall_time does. A second SIGINT ends the process at once (the output keeps its
// last commit, OutputWriter.hpp).
//
// PETSc installs its own handler for SIGTERM (it prints a stack and calls MPI_Abort: exit code 59);
// installStopSignals() replaces it for these three signals and must run after SlepcInitialize. The
// handler only records the signal (async-signal-safe); the solvers poll stopSignal() after each
// step and agree over the ranks (MPI_Allreduce), so every rank stops after the same step.
#pragma once

namespace strand::drivers {

void installStopSignals();

// The first stop signal received (SIGTERM, SIGINT or SIGUSR1), 0 if none.
int stopSignal();

// "SIGTERM", "SIGINT", "SIGUSR1".
const char* signalName(int signal);

}  // namespace strand::drivers
