// strand: the command-line entry point. Dispatches to one subcommand per file (drivers/*.cpp).
//
//   strand run SCENE [-o FILE] [PETSc options]    solve the scene's analysis, write HDF5 + XDMF
//   strand modes SCENE [-o FILE] [PETSc options]  natural frequencies (SLEPc) about the static state
//   strand sweep SCENE [-o FILE] [PETSc options]  modes along the scene's sweep, veering detection
//   strand plot KIND FILE [-o PNG]                charts (runs drivers/plot/strand_plot.py)
//   strand help [COMMAND]
//
// Exit codes: 0 success, 1 internal error, 2 bad input (scene or options), 3 solve diverged or
// failed, 4 stopped at the wall-time limit or by SIGTERM, SIGINT or SIGUSR1 (with a checkpoint).
#include <slepcsys.h>

#include <unistd.h>

#include <cstdio>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "Commands.hpp"
#include "Signals.hpp"
#include "Terminal.hpp"
#include "strand/core/Error.hpp"

namespace {

const char* kUsage =
    "strand - dynamics of flexible beams, belts, shafts and tethers (PETSc/SLEPc)\n"
    "\n"
    "Usage: strand <command> [SCENE] [options] [PETSc options]\n"
    "\n"
    "Commands:\n"
    "  run SCENE     solve the analysis the scene asks for (analysis: static | modes | dynamic)\n"
    "  modes SCENE   natural frequencies about the scene's static state (SLEPc)\n"
    "  sweep SCENE   modes along the scene's sweep (gamma, omega, mass ratio or location):\n"
    "                tracked loci, veering / crossing, mode shift; HDF5 + CSV\n"
    "  plot KIND ... charts from output files (campbell, nodes, lines, belt); `strand plot --help`\n"
    "  bench work-precision SCENE\n"
    "                integrators x step sizes against a reference: JSON lines + PNG chart\n"
    "  help [CMD]    this text, or the help of one command\n"
    "\n"
    "Exit codes: 0 success, 1 internal error, 2 bad input, 3 solve diverged or failed,\n"
    "4 stopped at the wall-time limit or by SIGTERM/SIGINT/SIGUSR1 (checkpoint written).\n"
    "Scenes are YAML files (docs/scene-reference.md); examples in meshes/.\n";

const char* kRunHelp =
    "strand run SCENE [-o FILE] [PETSc options]\n"
    "\n"
    "Solves the scene's analysis and writes FILE (default: the scene's output.file, else\n"
    "<scene stem>.h5 in the working directory) plus an XDMF file for ParaView.\n"
    "  analysis: static  SNES Newton with load stepping; options prefix -static_\n"
    "                    (e.g. -static_snes_monitor, -static_snes_rtol 1e-12, -static_pc_type lu)\n"
    "  analysis: modes   static solve (if the scene has loads), then SLEPc; prefix -modal_\n"
    "                    (e.g. -modal_eps_view, -modal_st_pc_factor_mat_solver_type mumps)\n"
    "  analysis: dynamic the scene's integrator: generalized_alpha / newmark / hht (our TS\n"
    "                    strand_alpha, fixed step, consistent start, joints), bdf (TSBDF order\n"
    "                    1-5, fixed or adaptive step), rk4 (TSRK), abm4 (explicit); prefix -dyn_\n"
    "                    (e.g. -dyn_ts_monitor, -dyn_snes_monitor); energies, time steps,\n"
    "                    Newton iterations and rejected steps in /series\n"
    "Options:\n"
    "  -o FILE           output file (with -restart the default gets the suffix _restart)\n"
    "  -checkpoint FILE  dynamic runs: checkpoint file (default <output stem>.ckpt.h5)\n"
    "  -checkpoint_every N  write the checkpoint every N steps\n"
    "  -wall_time S      stop after S seconds of integration: checkpoint, exit code 4\n"
    "  -restart FILE     continue a dynamic run from a checkpoint (any number of ranks)\n"
    "  -overwrite        replace an existing output (else an existing result is refused)\n"
    "  -output_commit_interval S  frames are buffered and committed to the output every S\n"
    "                    seconds (default 2; a kill loses at most the last S seconds)\n"
    "  -max_memory SIZE  refuse a scene whose memory estimate exceeds SIZE (e.g. 64G; default:\n"
    "                    what the host has)\n"
    "SIGTERM, SIGINT, SIGUSR1: finish the step, checkpoint, status = stopped, exit code 4\n"
    "  -log_view         PETSc performance summary (events Strand:*)\n"
    "Run under mpirun for parallel solves: mpirun -n 2 strand run SCENE\n";

const char* kModesHelp =
    "strand modes SCENE [-o FILE] [PETSc options]\n"
    "\n"
    "Like `strand run`, but always computes natural frequencies and mode shapes about the\n"
    "static state (the initial shape when the scene has no loads): K_T phi = omega^2 M phi on the\n"
    "unsupported DOFs, shift-and-invert about 0. The number of modes is modes.count in the scene.\n"
    "Frequencies go to stdout and to /modes in the output file.\n";

const char* kBenchHelp =
    "strand bench work-precision SCENE [-schemes LIST] [-dts LIST] [-reference SCHEME@DT] [-o STEM]\n"
    "\n"
    "Speed against accuracy of the time integrators on a dynamic scene: every scheme of -schemes\n"
    "(default generalized_alpha,newmark,bdf:2,rk4,abm4; with joints generalized_alpha,newmark,hht)\n"
    "at every step of -dts (default the scene's dt times 4, 2, 1, 1/2, 1/4), against a reference run\n"
    "(default rk4, or generalized_alpha:0.9 with joints, at the smallest dt / 8). Schemes:\n"
    "generalized_alpha[:rho_inf], newmark, hht[:alpha], bdf[:order], rk4, abm4.\n"
    "Error: the largest distance of a node (or rigid body) from the reference at t_end [m].\n"
    "Writes STEM_work_precision.jsonl (one JSON line per run; failed runs have error null) and\n"
    "STEM_work_precision.png (error against wall time, log-log); STEM defaults to the scene's stem.\n";

const char* kSweepHelp =
    "strand sweep SCENE [-o FILE] [PETSc options]\n"
    "\n"
    "Computes the modes at every point of the scene's `sweep` section: the steady state in the\n"
    "rotating frame (warm-started from the previous point), then the linearized modes (the scene's\n"
    "modes.method and modes.coriolis; prefix -modal_). Modes are tracked from point to point by\n"
    "the mass-weighted MAC; close approaches of neighbouring loci are reported as veering (the shapes\n"
    "mix and exchange: mode shift) or crossing (the shapes stay pure).\n"
    "Writes FILE (HDF5, group /sweep), <stem>.csv (one row per point) and <stem>_events.csv.\n"
    "Chart: strand plot campbell FILE -o campbell.png\n"
    "Dimensionless outputs: gamma = Omega sqrt(rho A L^4/EI), omega_bar = omega sqrt(rho A L^4/EI)\n"
    "of the first body.\n";

bool isHelp(const char* a) { return !std::strcmp(a, "-h") || !std::strcmp(a, "--help") || !std::strcmp(a, "-help"); }

const char* helpOf(const std::string& cmd) {
  return cmd == "run" ? kRunHelp : cmd == "modes" ? kModesHelp : cmd == "sweep" ? kSweepHelp : cmd == "bench" ? kBenchHelp : nullptr;
}

// `strand plot ...` hands its arguments to the plotting script (Python 3 with matplotlib and h5py).
// STRAND_PLOT_SCRIPT overrides the script's location (default: the source tree's copy).
int runPlot(int argc, char** argv) {
  const char* env = std::getenv("STRAND_PLOT_SCRIPT");
  std::string script = env && *env ? env : STRAND_PLOT_SCRIPT;
  if (access(script.c_str(), R_OK) != 0) {
    std::fprintf(stderr, "strand: plot script '%s' not found (set STRAND_PLOT_SCRIPT)\n", script.c_str());
    return strand::kExitInternal;
  }
  std::vector<char*> args{(char*)"/usr/bin/python3", script.data()};
  for (int i = 2; i < argc; ++i) args.push_back(argv[i]);
  args.push_back(nullptr);
  execv("/usr/bin/python3", args.data());  // Debian's python3 has matplotlib and h5py
  std::fprintf(stderr, "strand: cannot run /usr/bin/python3 for `strand plot`: %s\n", std::strerror(errno));
  return strand::kExitInternal;
}

}  // namespace

int main(int argc, char** argv) {
  // Help and usage errors are answered before MPI/PETSc start.
  if (argc < 2 || isHelp(argv[1])) {
    std::fputs(kUsage, stdout);
    return argc < 2 ? strand::kExitBadInput : strand::kExitSuccess;
  }
  const std::string cmd = argv[1];
  if (cmd == "plot") return runPlot(argc, argv);
  const char* cmdHelp = helpOf(cmd);
  if (cmd == "help") {
    const char* which = argc > 2 ? helpOf(argv[2]) : nullptr;
    if (argc > 2 && !std::strcmp(argv[2], "plot")) return runPlot(3, std::vector<char*>{argv[0], argv[2], (char*)"--help"}.data());
    std::fputs(which ? which : kUsage, stdout);
    return strand::kExitSuccess;
  }
  if (!cmdHelp) {
    std::fprintf(stderr, "strand: unknown command '%s'\n\n%s", cmd.c_str(), kUsage);
    return strand::kExitBadInput;
  }
  if (argc < 3 || isHelp(argv[2])) {
    std::fputs(cmdHelp, argc < 3 ? stderr : stdout);
    return argc < 3 ? strand::kExitBadInput : strand::kExitSuccess;
  }
  if (cmd == "bench") {
    if (std::strcmp(argv[2], "work-precision") != 0 || argc < 4) {
      std::fprintf(stderr, "strand: bench: unknown or incomplete benchmark\n\n%s", kBenchHelp);
      return strand::kExitBadInput;
    }
    if (SlepcInitialize(&argc, &argv, nullptr, nullptr)) return strand::kExitInternal;
    strand::drivers::installStopSignals();
    strand::drivers::lineBufferBatchOutput();
    const int code = strand::drivers::runWorkPrecision(argv[3]);
    SlepcFinalize();
    return code;
  }
  const char* scene = argv[2];
  // PETSc sees every argument; positional ones are ignored by its options parser.
  if (SlepcInitialize(&argc, &argv, nullptr, nullptr)) return strand::kExitInternal;
  strand::drivers::installStopSignals();  // after PETSc's own handlers (Signals.hpp)
  strand::drivers::lineBufferBatchOutput();
  const int code = cmd == "sweep" ? strand::drivers::runSweepScene(scene)
                   : strand::drivers::runScene(scene, cmd == "modes" ? strand::drivers::RunMode::ForceModes
                                                                     : strand::drivers::RunMode::SceneAnalysis);
  SlepcFinalize();
  return code;
}
