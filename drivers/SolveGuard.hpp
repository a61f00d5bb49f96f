// A PETSc error inside a solve ends the run like a divergence, not like a crash (issue 32 item 8:
// exit codes 59, 63, 76, 77, 91, 95 and a PETSc error stack for values the scene reader accepted).
//
// guardSolve runs `solve` with PETSc's error handler set to return quietly (no traceback), and
// returns the error's message if any rank failed. The caller then writes status = "diverged", keeps
// the output and exits with code 3 and a hint. The ranks agree on the outcome with a non-blocking
// reduction: an error that only some ranks raise leaves the others inside a collective call, and
// after kAgreeSeconds of waiting the failing rank prints the message and aborts with exit code 3
// (the output then keeps its last commit, OutputWriter.hpp).
#pragma once
#include <petscsys.h>

#include <functional>
#include <string>

namespace strand::drivers {

// "" when every rank's solve returned 0, else the first failing rank's PETSc message (same on all
// ranks). (A solver's setFromOptions runs through it too: drivers/Commands.hpp applyOptions, where
// an error is bad input.)
std::string guardSolve(MPI_Comm comm, const std::function<PetscErrorCode()>& solve);

}  // namespace strand::drivers
