// Run the `strand` executable from a test and capture its exit code and output.
#pragma once
#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>

namespace strand::testing {

struct CliResult {
  int exitCode = -1;
  std::string output;  // stdout and stderr together
};

inline std::string strandBinary() {
  const char* b = std::getenv("STRAND_BINARY");
  return b ? b : "strand";
}
inline std::string sourceDir() {
  const char* s = std::getenv("STRAND_SOURCE_DIR");
  return s ? s : ".";
}

// Runs `command` through the shell with PETSc options that keep error output short.
inline CliResult runCommand(const std::string& command) {
  CliResult r;
  FILE* p = popen((command + " 2>&1").c_str(), "r");
  if (!p) return r;
  std::array<char, 4096> buf;
  while (fgets(buf.data(), buf.size(), p)) r.output += buf.data();
  const int status = pclose(p);
  r.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return r;
}

// A fresh empty directory for one test.
inline std::filesystem::path scratchDir(const std::string& name) {
  auto d = std::filesystem::temp_directory_path() / ("strand-test-" + name + "-" + std::to_string(::getpid()));
  std::filesystem::remove_all(d);
  std::filesystem::create_directories(d);
  return d;
}

}  // namespace strand::testing
