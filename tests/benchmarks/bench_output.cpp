// Cost of run output (issue 36 item 6), on the spin-up of meshes/spin-up.yaml (10 ANCF cable
// elements, 2D, 20,000 steps of 1e-3 s): three figures, each a ratio of two timings taken side by
// side in the same repetition, so that the machine's load changes both alike.
//   (a) frame_over_step: the cost of one frame of the 10-element beam written every step (gather,
//       centerline sampling, OutputWriter::writeFrame, and its share of the block commits and of
//       close()), timed inside a dynamics run, over the time of one step of the same run without
//       output (bench_dynamics' loop on the same scene). Target <= 1.
//   (b) every_step_over_end_only: `strand run` of the spin-up with output_every: 1 (20,001 frames)
//       over the same run with a frame at the start and the end only; process wall time. Target <= 2.
//   (c) run_over_bench: `strand run` of the spin-up as it is (the README's main job, output_every:
//       100), its time per step (the solve's "wall time" over the steps), over the time per step
//       of bench_dynamics' loop on the same scene in this process. Target <= 1.5.
// One JSON line per repetition and one summary line (median, min and max of each ratio over the
// repetitions). Options: -repeat N (default 5), -t_end T (default: the scene's 20 s),
// -strand PATH (default: this build's strand), -scene PATH (default: meshes/spin-up.yaml), -only_frames
// (part (a) alone, no `strand run`).
#include <petscsys.h>
#include <petsctime.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "strand/io/Frames.hpp"
#include "strand/io/OutputWriter.hpp"
#include "strand/io/SceneReader.hpp"
#include "strand/solvers/Dynamics.hpp"
#include "strand/solvers/Problem.hpp"

using namespace strand;
namespace fs = std::filesystem;

namespace {

double now() {
  PetscLogDouble t;
  PetscTime(&t);
  return t;
}

std::string readText(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// In this process: the spin-up integrated with a no-op callback (bench_dynamics' loop), or with a
// frame written every step. Returns seconds of the run; *frameSeconds gets the time spent in the
// frame path (plus close()), *steps the steps taken.
double integrate(const model::SceneDescription& scene, const std::string& out, double* frameSeconds, long* steps) {
  solvers::Problem p(PETSC_COMM_WORLD, scene);
  Vec X, V;
  PetscCallAbort(PETSC_COMM_WORLD, p.createInitialState(&X, &V));
  solvers::Dynamics dyn(p.assembler(), scene.dynamics);
  PetscCallAbort(PETSC_COMM_WORLD, dyn.setFromOptions());
  std::unique_ptr<io::OutputWriter> writer;
  const int samples = scene.output.samplesPerElement;
  if (!out.empty())
    writer = std::make_unique<io::OutputWriter>(PETSC_COMM_WORLD, out, io::RunInfo{scene.file, "dynamic", "bench", 2},
                                                io::bodyLayouts(p.model(), samples));
  double inFrames = 0.0;
  *steps = 0;
  solvers::Dynamics::StepCallback cb = [&](const solvers::DynamicsStep& st, Vec Xs, Vec) -> PetscErrorCode {
    *steps = st.step;
    if (writer) {
      const double t0 = now();
      std::vector<double> q;
      PetscCall(p.assembler().gatherToRoot(Xs, q));
      writer->writeFrame(st.time, io::makeFrames(p.model(), q, samples));
      inFrames += now() - t0;
    }
    return 0;
  };
  std::string failure;
  const double t0 = now();
  PetscCallAbort(PETSC_COMM_WORLD, dyn.run(X, V, cb, &failure));
  const double t1 = now();
  if (writer) {
    writer->close();
    inFrames += now() - t1;
  }
  if (!failure.empty()) std::fprintf(stderr, "bench_output: the spin-up failed: %s\n", failure.c_str());
  VecDestroy(&X);
  VecDestroy(&V);
  *frameSeconds = inFrames;
  return t1 - t0;
}

struct RunTiming {
  double process = 0.0, solve = 0.0;  // process wall time; the run's own "wall time" line
};

RunTiming strandRun(const std::string& strand, const fs::path& scene, const fs::path& dir, const std::string& tag) {
  const fs::path log = dir / (tag + ".log");
  const std::string cmd = "OMPI_MCA_ess_singleton_isolated=1 " + strand + " run " + scene.string() + " -o " +
                          (dir / (tag + ".h5")).string() + " -overwrite > " + log.string() + " 2>&1";
  const double t0 = now();
  const int rc = std::system(cmd.c_str());
  RunTiming r;
  r.process = now() - t0;
  const std::string text = readText(log);
  const auto at = text.find("wall time ");
  if (rc != 0 || at == std::string::npos) {
    std::fprintf(stderr, "bench_output: '%s' failed:\n%s\n", cmd.c_str(), text.c_str());
    std::exit(1);
  }
  r.solve = std::atof(text.c_str() + at + 10);
  return r;
}

struct Stats {
  double median, min, max;
};
Stats stats(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return {n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]), v.front(), v.back()};
}

std::string withOutputEvery(std::string text, const std::string& every) {
  const std::string key = "output_every: ";
  const auto at = text.find(key);
  if (at == std::string::npos) {
    std::fprintf(stderr, "bench_output: the scene has no '%s'\n", key.c_str());
    std::exit(1);
  }
  const auto end = text.find('\n', at);
  return text.replace(at, end - at, key + every);
}

}  // namespace

int main(int argc, char** argv) {
  PetscCall(PetscInitialize(&argc, &argv, nullptr, nullptr));
  PetscInt repeat = 5;
  PetscReal tEnd = 0.0;
  char strandBuf[PETSC_MAX_PATH_LEN] = STRAND_BINARY, sceneBuf[PETSC_MAX_PATH_LEN] = STRAND_SOURCE_DIR "/meshes/spin-up.yaml";
  PetscCall(PetscOptionsGetInt(nullptr, nullptr, "-repeat", &repeat, nullptr));
  PetscCall(PetscOptionsGetReal(nullptr, nullptr, "-t_end", &tEnd, nullptr));
  PetscCall(PetscOptionsGetString(nullptr, nullptr, "-strand", strandBuf, sizeof strandBuf, nullptr));
  PetscCall(PetscOptionsGetString(nullptr, nullptr, "-scene", sceneBuf, sizeof sceneBuf, nullptr));
  PetscBool onlyFrames = PETSC_FALSE;
  PetscCall(PetscOptionsGetBool(nullptr, nullptr, "-only_frames", &onlyFrames, nullptr));
  const fs::path dir = fs::temp_directory_path() / ("strand_bench_output_" + std::to_string(getpid()));
  fs::create_directories(dir);

  std::string text = readText(sceneBuf);
  if (tEnd > 0.0) {
    const auto at = text.find("t_end: ");
    text.replace(at, text.find('\n', at) - at, "t_end: " + std::to_string(tEnd));
  }
  const fs::path mainScene = dir / "main.yaml", everyScene = dir / "every.yaml", endScene = dir / "end.yaml";
  std::ofstream(mainScene) << text;
  std::ofstream(everyScene) << withOutputEvery(text, "1");
  std::ofstream(endScene) << withOutputEvery(text, "100000000");
  const model::SceneDescription scene = io::readScene(mainScene.string());

  std::vector<double> a, b, c;
  for (PetscInt rep = 0; rep < repeat; ++rep) {
    long steps = 0, framedSteps = 0;
    double none = 0.0, framed = 0.0;
    const double stepSeconds = integrate(scene, "", &none, &steps) / std::max(steps, 1L);
    const double framedRun = integrate(scene, (dir / "frames.h5").string(), &framed, &framedSteps);
    const double frameSeconds = framed / std::max(framedSteps, 1L);
    a.push_back(frameSeconds / stepSeconds);
    if (onlyFrames) {
      PetscCall(PetscPrintf(PETSC_COMM_WORLD,
                            "{\"bench\": \"output_frames\", \"rep\": %d, \"steps\": %ld, \"us_per_step\": %.2f, "
                            "\"us_per_frame\": %.2f, \"framed_run_us_per_step\": %.2f, "
                            "\"frame_over_step\": %.3f}\n",
                            static_cast<int>(rep), steps, 1e6 * stepSeconds, 1e6 * frameSeconds,
                            1e6 * framedRun / std::max(framedSteps, 1L), a.back()));
      continue;
    }
    const RunTiming main = strandRun(strandBuf, mainScene, dir, "main");
    const RunTiming every = strandRun(strandBuf, everyScene, dir, "every");
    const RunTiming end = strandRun(strandBuf, endScene, dir, "end");
    b.push_back(every.process / end.process);
    c.push_back(main.solve / std::max(steps, 1L) / stepSeconds);
    PetscCall(PetscPrintf(PETSC_COMM_WORLD,
                          "{\"bench\": \"output\", \"rep\": %d, \"steps\": %ld, \"us_per_step\": %.2f, "
                          "\"us_per_frame\": %.2f, \"framed_run_us_per_step\": %.2f, "
                          "\"frame_over_step\": %.3f, \"every_step_s\": %.3f, \"end_only_s\": %.3f, \"every_step_solve_s\": %.3f, "
                          "\"end_only_solve_s\": %.3f, \"every_step_over_end_only\": %.3f, "
                          "\"run_us_per_step\": %.2f, \"run_process_s\": %.3f, \"run_over_bench\": %.3f}\n",
                          static_cast<int>(rep), steps, 1e6 * stepSeconds, 1e6 * frameSeconds,
                          1e6 * framedRun / std::max(framedSteps, 1L), a.back(), every.process, end.process,
                          every.solve, end.solve, b.back(), 1e6 * main.solve / std::max(steps, 1L), main.process,
                          c.back()));
  }
  if (onlyFrames) {
    b = c = {0.0};
  }
  const Stats sa = stats(a), sb = stats(b), sc = stats(c);
  PetscCall(PetscPrintf(PETSC_COMM_WORLD,
                        "{\"bench\": \"output_summary\", \"repeat\": %d, "
                        "\"frame_over_step\": {\"median\": %.3f, \"min\": %.3f, \"max\": %.3f, \"target\": 1.0}, "
                        "\"every_step_over_end_only\": {\"median\": %.3f, \"min\": %.3f, \"max\": %.3f, \"target\": 2.0}, "
                        "\"run_over_bench\": {\"median\": %.3f, \"min\": %.3f, \"max\": %.3f, \"target\": 1.5}, "
                        "\"met\": %s}\n",
                        static_cast<int>(repeat), sa.median, sa.min, sa.max, sb.median, sb.min, sb.max, sc.median,
                        sc.min, sc.max, sa.median <= 1.0 && sb.median <= 2.0 && sc.median <= 1.5 ? "true" : "false"));
  fs::remove_all(dir);
  PetscCall(PetscFinalize());
  return 0;
}
