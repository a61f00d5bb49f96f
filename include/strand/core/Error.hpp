// Errors and exit codes shared by every layer.
//
// Two kinds of failure, never blurred (exit codes: docs/user-guide.md, "The `strand` command"):
//  - InputError: the user's scene or options are wrong. The message names file, line, key and reason.
//  - SolveError: a solve diverged. The message names the time or load step and gives a hint.
// Internal invariants use assert(). Exceptions never cross a PETSc callback: the callbacks catch
// them (PetscCallCXX) and return an error code, and the drivers map them to exit codes.
#pragma once
#include <stdexcept>
#include <string>

namespace strand {

// 4: a run stopped at its wall-time limit (-wall_time) or by a stop signal (SIGTERM, SIGINT,
// SIGUSR1) after the current step, with a checkpoint (dynamics).
enum ExitCode : int {
  kExitSuccess = 0,
  kExitInternal = 1,
  kExitBadInput = 2,
  kExitDiverged = 3,
  kExitWallTime = 4,
  kExitStopped = 4
};

class InputError : public std::runtime_error {
public:
  using std::runtime_error::runtime_error;
};

class SolveError : public std::runtime_error {
public:
  using std::runtime_error::runtime_error;
};

}  // namespace strand
