// Stop signals of batch jobs (Signals.hpp).
#include "Signals.hpp"

#include <signal.h>
#include <unistd.h>

#include <initializer_list>

namespace strand::drivers {

namespace {

volatile sig_atomic_t g_signal = 0;

void onSignal(int signal) {
  if (g_signal == SIGINT && signal == SIGINT) {  // the second Ctrl-C: stop now, as without a handler
    struct sigaction dfl {};
    dfl.sa_handler = SIG_DFL;
    sigaction(SIGINT, &dfl, nullptr);
    raise(SIGINT);
    return;
  }
  if (g_signal == 0) g_signal = signal;
  static const char kNote[] = "strand: stop requested; finishing the current step\n";
  if (write(STDERR_FILENO, kNote, sizeof kNote - 1) < 0) {
  }
}

}  // namespace

void installStopSignals() {
  struct sigaction sa {};
  sa.sa_handler = onSignal;
  sigemptyset(&sa.sa_mask);
  sa.sa_flags = SA_RESTART;  // blocking calls (MPI, file writes) continue; the solvers poll the flag
  for (int s : {SIGTERM, SIGINT, SIGUSR1}) sigaction(s, &sa, nullptr);
}

int stopSignal() { return g_signal; }

const char* signalName(int signal) {
  switch (signal) {
    case SIGTERM: return "SIGTERM";
    case SIGINT: return "SIGINT";
    case SIGUSR1: return "SIGUSR1";
    default: return "a signal";
  }
}

}  // namespace strand::drivers
