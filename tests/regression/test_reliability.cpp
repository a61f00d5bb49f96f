// requirement (issue 32): the `strand` command treats every file it reads as input and never loses
// a file it did not create. Checkpoint values are checked (finite, non-negative, consistent with the
// scene) before a restart; a refused restart touches no output; an output that is an input of the
// run, or an existing result without -overwrite, is refused; extreme but syntactically valid scenes
// end with exit code 2 or 3 and a message, never a PETSc abort; SIGTERM, SIGINT and SIGUSR1 stop a
// run after the current step with a checkpoint and exit code 4 (on 2 ranks too). Every case runs
// the real executable and checks its exit code, its message and the files it leaves.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>

#include "support/Cli.hpp"

using namespace strand::testing;
namespace fs = std::filesystem;

namespace {

void writeFile(const fs::path& p, const std::string& text) { std::ofstream(p) << text; }

[[maybe_unused]] std::string readText(const fs::path& p) {
  std::ifstream in(p);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

bool haveH5py() {
  static const bool have = runCommand("/usr/bin/python3 -c 'import h5py'").exitCode == 0;
  return have;
}

// Runs a Python snippet (Debian's python3 with h5py) written to `dir`, with `args`.
CliResult python(const fs::path& dir, const std::string& code, const std::string& args) {
  const fs::path script = dir / "snippet.py";
  writeFile(script, code);
  return runCommand("/usr/bin/python3 " + script.string() + " " + args);
}

std::string run(const std::string& args) { return strandBinary() + " " + args; }

// A short pendulum run (8 elements, 50 steps of 1 ms).
const char* kPendulum = R"(analysis: dynamic
dimension: 2
bodies:
  - name: rope
    element: AncfCable2d
    elements: 8
    geometry: {kind: line, start: [0, 0], end: [1, 0]}
    section: {E: 1e8, A: 1e-4, I: 1e-8, rho: 7850}
supports:
  - {body: rope, node: 0, type: pinned}
loads:
  gravity: [0, -9.81]
dynamics: {integrator: generalized_alpha, rho_inf: 0.9, dt: 1e-3, t_end: 0.05, output_every: 10}
)";

}  // namespace

// Item 5: a checkpoint's time, step, dt and state are input. Each damaged copy of a good
// checkpoint is refused with exit code 2 and a message naming the value, and no output is written.
// (Before: time -5, a NaN dt, a NaN or 1e300 step were accepted.)
TEST(Reliability, CheckpointValuesAreCheckedBeforeARestart) {
  if (!haveH5py()) GTEST_SKIP() << "needs python3-h5py to damage a checkpoint";
  const fs::path dir = scratchDir("ckpt-values");
  writeFile(dir / "p.yaml", kPendulum);
  auto r = runCommand(run("run " + (dir / "p.yaml").string() + " -o " + (dir / "p.h5").string() + " -checkpoint_every 20"));
  ASSERT_EQ(r.exitCode, 0) << r.output;
  ASSERT_TRUE(fs::exists(dir / "p.ckpt.h5"));
  const char* damage = R"PY(import sys, shutil, h5py, numpy as np
src, out, what = sys.argv[1], sys.argv[2], sys.argv[3]
shutil.copy(src, out)
with h5py.File(out, 'r+') as f:
    if what == 'X':
        x = f['X'][()]; x[3] = np.nan; del f['X']; f['X'] = x
    else:
        key, value = what.split('=')
        f.attrs[key] = float(value)
)PY";
  const std::pair<const char*, const char*> cases[] = {
      {"time=-5", "the checkpoint's time -5 s is negative"},
      {"dt=nan", "'dt' is nan, not a finite number"},
      {"step=nan", "'step' is nan, not a finite number"},
      {"step=1e300", "the checkpoint's step 1e+300 is not a step number"},
      {"step=7", "step 7 and t = 0.04"},  // the checkpoint is at step 40, t = 0.04 s
      {"energy_initial=inf", "'energy_initial' is inf, not a finite number"},
      {"X", "/X holds values that are not finite"},
  };
  int k = 0;
  for (const auto& [what, message] : cases) {
    const fs::path bad = dir / ("bad" + std::to_string(k) + ".ckpt.h5"), out = dir / ("r" + std::to_string(k) + ".h5");
    auto d = python(dir, damage, (dir / "p.ckpt.h5").string() + " " + bad.string() + " " + what);
    ASSERT_EQ(d.exitCode, 0) << d.output;
    auto x = runCommand(run("run " + (dir / "p.yaml").string() + " -restart " + bad.string() + " -o " + out.string()));
    EXPECT_EQ(x.exitCode, 2) << what << ": " << x.output;
    EXPECT_NE(x.output.find(bad.string() + ": -restart: " + message), std::string::npos) << what << ": " << x.output;
    EXPECT_FALSE(fs::exists(out)) << what;
    ++k;
  }
  fs::remove_all(dir);
}
