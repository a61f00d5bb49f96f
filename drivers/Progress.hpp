// One progress line: rewritten in place on a terminal, plain lines in batch jobs (rank 0 only).
// With a completed fraction (time stepping), a batch job gets a line every 5 % only. Terminal or
// batch is decided by where rank 0's output really goes (Terminal.hpp: under mpirun the rank's
// stdout is a pseudo-terminal even when the log is a file), and batch lines are flushed.
#pragma once
#include <petscsys.h>
#include <unistd.h>

#include <cstdio>
#include <string>

#include "Terminal.hpp"

namespace strand::drivers {

class Progress {
public:
  explicit Progress(MPI_Comm comm) {
    int rank;
    MPI_Comm_rank(comm, &rank);
    _active = rank == 0;
    _tty = _active && outputIsTerminal();
  }
  void update(const std::string& line, double fraction = -1.0) {
    if (!_active) return;
    if (!_tty && fraction >= 0.0) {
      if (fraction < _nextMark && fraction < 1.0) return;
      while (_nextMark <= fraction) _nextMark += 0.05;
    }
    if (_tty) {
      std::printf("\r\033[K%s", line.c_str());
      std::fflush(stdout);
      _open = true;
    } else {
      std::printf("%s\n", line.c_str());
      std::fflush(stdout);  // a killed batch job keeps its progress
    }
  }
  void finish() {
    if (_open) std::printf("\n");
    _open = false;
  }

private:
  bool _active = false, _tty = false, _open = false;
  double _nextMark = 0.0;
};

}  // namespace strand::drivers
