// Terminal or batch output (Terminal.hpp).
#include "Terminal.hpp"

#include <unistd.h>

#include <cstdio>
#include <fstream>
#include <string>

namespace strand::drivers {

namespace {

bool isLauncher(const std::string& name) {
  for (const char* l : {"mpirun", "mpiexec", "orterun", "prterun", "orted", "prted"})
    if (name == l) return true;
  return false;
}

// The target of /proc/<pid>/fd/1, "" if unreadable.
std::string stdoutOf(pid_t pid) {
  char target[256];
  const std::string link = "/proc/" + std::to_string(pid) + "/fd/1";
  const ssize_t n = readlink(link.c_str(), target, sizeof target - 1);
  return n > 0 ? std::string(target, static_cast<size_t>(n)) : "";
}

bool decide() {
  if (!isatty(fileno(stdout))) return false;
  const pid_t parent = getppid();
  std::string name;
  std::ifstream(("/proc/" + std::to_string(parent) + "/comm").c_str()) >> name;
  if (!isLauncher(name)) return true;  // run directly: the terminal is real
  const std::string out = stdoutOf(parent);
  return out.rfind("/dev/pts/", 0) == 0 || out.rfind("/dev/tty", 0) == 0;
}

}  // namespace

bool outputIsTerminal() {
  static const bool terminal = decide();
  return terminal;
}

void lineBufferBatchOutput() {
  if (!outputIsTerminal()) std::setvbuf(stdout, nullptr, _IOLBF, 0);
}

}  // namespace strand::drivers
