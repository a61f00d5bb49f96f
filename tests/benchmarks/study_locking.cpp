// Locking study (issue 33): the linear tip deflection of a cantilever (L = 1 m, b = 0.1 m,
// steel, nu = 0.3) against Timoshenko beam theory, F L^3 / (3 E I) + F L / (k G A), for every 2D
// element kind and integration rule, L/h = 4, 10, 100, 1000, N = 1 .. 256 elements. The cable
// (AncfCable2d, Euler-Bernoulli) is shown beside the shear-deformable kinds: its error is the shear
// flexibility it leaves out, F L / (k G A) relative, which only thick beams notice.
// JSON lines: error against coordinates and against the wall time of the static solve (median of
// repeated solves, each building its solver; the model is built once).
// Rerun: cmake --build build --target study_locking && ./build/tests/benchmarks/study_locking
//        (the charts: cmake --build build --target validation-plots)
#include <petscsys.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "support/ShearBeams.hpp"

using namespace strand;
using namespace strand::testing;

namespace {

struct Variant {
  const char* kind;
  const char* rule;  // "" for the cable
};

model::SceneDescription scene(const Variant& v, int n, const RectangleSection& s) {
  if (std::string(v.rule).empty()) {
    Section c;
    c.E = s.E;
    c.A = s.area();
    c.I = s.inertia();
    c.rho = s.rho;
    return cantilever(2, n, 1.0, c);
  }
  return shearCantilever(v.kind, n, 1.0, s, v.rule);
}

}  // namespace

int main(int argc, char** argv) {
  PetscCall(PetscInitialize(&argc, &argv, nullptr, nullptr));
  const Variant variants[] = {{"AncfCable2d", ""},
                              {"AncfBeam2dShear", "full"},       {"AncfBeam2dShear", "reduced"},
                              {"AncfBeam2dShear", "selective"},  {"AncfBeam2dLinear", "full"},
                              {"AncfBeam2dLinear", "reduced"},   {"AncfBeam2dLinear", "selective"}};
  for (const Variant& v : variants)
    for (double Lh : {4.0, 10.0, 100.0, 1000.0})
      for (int n = 1; n <= 256; n *= 2) {
        RectangleSection s;
        s.height = 1.0 / Lh;
        auto sc = scene(v, n, s);
        const double F = 1e-7 * s.E * s.inertia();
        addTipLoad(sc, {0, -F, 0});
        solvers::Problem p(PETSC_COMM_WORLD, sc);
        std::vector<double> times;
        double w = 0.0;
        PetscLogDouble start, now;
        PetscCall(PetscTime(&start));
        do {
          PetscLogDouble t0, t1;
          PetscCall(PetscTime(&t0));
          const auto q = solveStatic(p, 1);
          PetscCall(PetscTime(&t1));
          times.push_back(t1 - t0);
          w = -nodePosition(p, q, 0, -1)[1];
          PetscCall(PetscTime(&now));
        } while (now - start < 0.2 && times.size() < 50);
        std::sort(times.begin(), times.end());
        const double exact = timoshenkoTipDeflection(F, 1.0, s);
        PetscCall(PetscPrintf(PETSC_COMM_WORLD,
                              "{\"study\": \"locking\", \"element\": \"%s\", \"integration\": \"%s\", \"L_over_h\": %d, "
                              "\"elements\": %d, \"dofs\": %d, \"tip_error\": %.6e, \"wall_s\": %.6e, \"label\": \"%s%s%s\"}\n",
                              v.kind, v.rule, static_cast<int>(Lh), n, p.model().numDofs(), std::fabs(w / exact - 1.0),
                              times[times.size() / 2], v.kind, *v.rule ? " " : "", v.rule));
      }
  PetscCall(PetscFinalize());
  return 0;
}
