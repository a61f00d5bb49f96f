// Where rank 0's output really goes (issue 32 item 13). Under mpirun, Open MPI gives every rank a
// pseudo-terminal for stdout even when mpirun's own stdout is a file, so isatty() said "terminal"
// and a redirected log got the live progress line redrawn at every step. Here the launcher's stdout
// decides: when this process runs under mpirun (its parent is mpirun, mpiexec, orterun, prterun or
// an orted) and stdout is a terminal, the parent's stdout (/proc/<ppid>/fd/1) must be one too.
#pragma once

namespace strand::drivers {

// True when rank 0's progress should be one line redrawn in place, false for plain lines.
bool outputIsTerminal();

// Batch output (not a terminal): stdout line-buffered, so that a killed run keeps every line it
// printed (block buffering lost them). Call once, before printing.
void lineBufferBatchOutput();

}  // namespace strand::drivers
