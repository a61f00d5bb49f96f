// PETSc errors inside solves become divergences (SolveGuard.hpp).
#include "SolveGuard.hpp"

#include <unistd.h>

#include <cstdio>

#include "strand/core/Error.hpp"

namespace strand::drivers {

namespace {
constexpr double kAgreeSeconds = 60.0;
}

std::string guardSolve(MPI_Comm comm, const std::function<PetscErrorCode()>& solve) {
  PetscPushErrorHandler(PetscReturnErrorHandler, nullptr);
  const PetscErrorCode ierr = solve();
  PetscPopErrorHandler();
  std::string message;
  if (ierr) {
    const char* text = nullptr;
    char* specific = nullptr;
    PetscErrorMessage(ierr, &text, &specific);
    message = std::string(specific && *specific ? specific : text ? text : "unknown error") + " (PETSc error " +
              std::to_string(static_cast<int>(ierr)) + ")";
  }
  int rank, size;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &size);
  int first = ierr ? rank : size;  // the lowest failing rank speaks
  int agreed = size;
  MPI_Request request;
  MPI_Iallreduce(&first, &agreed, 1, MPI_INT, MPI_MIN, comm, &request);
  int done = 0;
  for (double waited = 0.0; !done; waited += 0.001) {
    MPI_Test(&request, &done, MPI_STATUS_IGNORE);
    if (done) break;
    if (ierr && waited > kAgreeSeconds) {  // the other ranks are stuck in a collective call
      std::fprintf(stderr, "strand: error on rank %d: the solve failed: %s; the other ranks did not stop, so the run "
                           "is aborted (the output keeps its last frame)\n", rank, message.c_str());
      MPI_Abort(comm, kExitDiverged);
    }
    usleep(1000);
  }
  if (agreed == size) return "";
  int length = static_cast<int>(message.size());
  MPI_Bcast(&length, 1, MPI_INT, agreed, comm);
  message.resize(length);
  MPI_Bcast(message.data(), length, MPI_CHAR, agreed, comm);
  return message;
}

}  // namespace strand::drivers
