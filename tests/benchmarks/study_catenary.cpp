// A long cable (tether) hanging between two level supports under gravity, solved statically, and
// its mid-span sag compared with the elastic catenary (tests/support/ElasticCatenary.hpp).
//   mpirun -n 2 study_catenary -n 100000 [-span 100]
// Scene: span S (default 100 m), unstretched length 1.01 S, steel wire rope (A = 2.83e-5 m^2,
// E = 2.1e11 Pa, rope-like bending stiffness I = 5e-13 m^4, rho = 7850 kg/m^3). Starts from the
// inextensible catenary of the same length (geometry kind: catenary). Prints one JSON line with
// the sag error, the wall time and the peak memory (the memory benchmark of the foundation issue
// is -n 1000000 -span 1000: a 1 km tether with 1 mm elements).
#include <petscsys.h>
#include <sys/resource.h>

#include <cmath>

#include "support/ElasticCatenary.hpp"
#include "support/Scenes.hpp"

using namespace strand;
using namespace strand::testing;

int main(int argc, char** argv) {
  PetscCall(PetscInitialize(&argc, &argv, nullptr, nullptr));
  PetscInt n = 1000;
  PetscReal span = 100.0;
  PetscCall(PetscOptionsGetInt(nullptr, nullptr, "-n", &n, nullptr));
  PetscCall(PetscOptionsGetReal(nullptr, nullptr, "-span", &span, nullptr));
  const double L0 = 1.01 * span, g = 9.81;
  const Section s{2.1e11, 2.83e-5, 5e-13, 7850.0};
  model::SceneDescription sc;
  sc.file = "(study_catenary)";
  sc.dimension = 3;
  model::BodyDesc b = straightBody("tether", 3, static_cast<int>(n), {0, 0, 0}, {span, 0, 0}, s);
  b.geometry.kind = model::GeometryKind::Catenary;
  b.geometry.length = L0;
  sc.bodies.push_back(b);
  pinEnds(sc, "tether");
  sc.loads.gravity = {0, 0, -g};
  PetscLogDouble t0, t1;
  PetscCall(PetscTime(&t0));
  std::string failure;
  {  // the problem's PETSc objects must go before PetscFinalize
  solvers::Problem p(PETSC_COMM_WORLD, sc);
  const auto q = solveStatic(p, 1, &failure);
  PetscCall(PetscTime(&t1));
  // mid-span point: node n/2 (n even) or the middle of the central element
  const model::Vec3 mid = nodePosition(p, q, 0, static_cast<int>(n / 2));
  const ElasticCatenary ref = elasticCatenary(L0, s.rho * s.A * g, s.E * s.A, span);
  struct rusage ru;
  getrusage(RUSAGE_SELF, &ru);
  PetscMPIInt size;
  PetscCallMPI(MPI_Comm_size(PETSC_COMM_WORLD, &size));
  PetscCall(PetscPrintf(PETSC_COMM_WORLD,
                        "{\"study\": \"catenary\", \"span_m\": %.6e, \"elements\": %d, \"ranks\": %d, \"converged\": %s, \"sag\": %.10f, "
                        "\"sag_elastic_catenary\": %.10f, \"relative_difference\": %.3e, \"H_elastic_catenary\": %.6f, "
                        "\"wall_time_s\": %.3f, \"max_rss_rank0_MB\": %.1f, \"bytes_per_element_rank0\": %.0f}\n",
                        span, static_cast<int>(n), size, failure.empty() ? "true" : "false", -mid[2], ref.midSag,
                        std::fabs(-mid[2] / ref.midSag - 1.0), ref.H, t1 - t0, ru.ru_maxrss / 1024.0, ru.ru_maxrss * 1024.0 / n));
  if (!failure.empty()) PetscCall(PetscPrintf(PETSC_COMM_WORLD, "# %s\n", failure.c_str()));
  }
  PetscCall(PetscFinalize());
  return failure.empty() ? 0 : 3;
}
