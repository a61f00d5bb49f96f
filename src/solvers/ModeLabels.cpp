#include "strand/solvers/ModeLabels.hpp"

#include <array>
#include <cmath>

namespace strand::solvers {

namespace {

using V3 = std::array<double, 3>;

V3 unit(V3 v) {
  const double n = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
  for (double& x : v) x /= n;
  return v;
}
double dot(const V3& a, const V3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
V3 cross(const V3& a, const V3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}

struct Direction {
  std::string name;
  V3 d;
};

// The axial direction and the two transverse ones with their names (see the header).
std::vector<Direction> directions(const model::Model& m) {
  const model::Body& b = m.bodies().front();
  const auto& q0 = m.initialCoordinates();
  const int D = m.dim();
  V3 a{0, 0, 0};
  for (int i = 0; i < D; ++i) a[i] = q0[b.posBlock.back() * D + i] - q0[b.posBlock.front() * D + i];
  a = unit(a);
  std::vector<Direction> out = {{"axial", a}};
  if (D == 2) {
    out.push_back({m.rotation().present ? "lead-lag" : "bending", {-a[1], a[0], 0.0}});
    return out;
  }
  if (m.rotation().present) {
    V3 f = m.rotation().axis;
    const double along = dot(f, a);
    for (int i = 0; i < 3; ++i) f[i] -= along * a[i];
    if (std::sqrt(dot(f, f)) > 1e-6) {
      f = unit(f);
      out.push_back({"flapwise", f});
      out.push_back({"lead-lag", unit(cross(a, f))});
      return out;
    }
  }
  // the global axis least aligned with a, made orthogonal to it, and the third direction
  int k = 0;
  for (int i = 1; i < 3; ++i)
    if (std::fabs(a[i]) < std::fabs(a[k])) k = i;
  V3 e{0, 0, 0};
  e[k] = 1.0;
  const double along = dot(e, a);
  for (int i = 0; i < 3; ++i) e[i] -= along * a[i];
  const V3 t1 = unit(e), t2 = unit(cross(a, t1));
  auto named = [](const V3& t) {
    int j = 0;
    for (int i = 1; i < 3; ++i)
      if (std::fabs(t[i]) > std::fabs(t[j])) j = i;
    return std::string("bending ") + "xyz"[j];
  };
  out.push_back({named(t1), t1});
  out.push_back({named(t2), t2});
  return out;
}

}  // namespace

PetscErrorCode labelModes(assembly::Assembler& assembler, Mat M, const ModalResult& result,
                          std::vector<ModeLabel>* labels) {
  PetscFunctionBeginUser;
  labels->assign(result.omega.size(), ModeLabel{});
  const model::Model& m = assembler.model();
  if (m.bodies().empty() || result.omega.empty()) PetscFunctionReturn(0);
  const int D = m.dim();
  const std::vector<Direction> dirs = directions(m);
  const int parts = static_cast<int>(dirs.size()) + 1;  // + the spin angles ("torsion")
  Vec part, Mpart;
  PetscCall(assembler.dofs().createVector(&part));
  PetscCall(VecDuplicate(part, &Mpart));
  for (size_t k = 0; k < result.omega.size(); ++k) {
    if (k < result.rigid.size() && result.rigid[k]) {
      (*labels)[k] = {"rigid", 1.0};
      continue;
    }
    std::vector<double> T(parts, 0.0);
    for (int im = 0; im < (result.shapesImag.empty() ? 1 : 2); ++im) {
      std::vector<double> x;
      PetscCall(assembler.toModelOrder(im == 0 ? result.shapes[k] : result.shapesImag[k], x));  // rank 0
      for (int p = 0; p < parts; ++p) {
        std::vector<double> y(x.size(), 0.0);
        for (const model::Body& b : m.bodies())
          for (int n = 0; n <= b.elements && !x.empty(); ++n)
            for (int kb = 0; kb < b.blocksPerNode; ++kb) {
              const int blk = b.block(n, kb);
              const elements::BlockRole role = b.info().layout[kb];
              if (role == elements::BlockRole::MaterialSpin) {
                if (p == parts - 1) y[blk * D + 1] = x[blk * D + 1];
                continue;
              }
              if (elements::isMaterialBlock(role) || p == parts - 1) continue;
              const V3& d = dirs[p].d;
              double s = 0.0;
              for (int i = 0; i < D; ++i) s += x[blk * D + i] * d[i];
              for (int i = 0; i < D; ++i) y[blk * D + i] = s * d[i];
            }
        PetscCall(assembler.fromModelOrder(y, part));
        PetscCall(MatMult(M, part, Mpart));
        PetscScalar t;
        PetscCall(VecDot(part, Mpart, &t));
        T[p] += PetscRealPart(t);
      }
    }
    double sum = 0.0;
    int best = 0;
    for (int p = 0; p < parts; ++p) {
      sum += T[p];
      if (T[p] > T[best]) best = p;
    }
    (*labels)[k] = {best == parts - 1 ? "torsion" : dirs[best].name, sum > 0.0 ? T[best] / sum : 0.0};
  }
  PetscCall(VecDestroy(&part));
  PetscCall(VecDestroy(&Mpart));
  PetscFunctionReturn(0);
}

}  // namespace strand::solvers
