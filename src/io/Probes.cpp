#include "strand/io/Probes.hpp"

#include <algorithm>
#include <cmath>

#include "strand/core/Error.hpp"

namespace strand::io {

namespace {
double dotOf(const model::Vec3& a, const model::Vec3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
}  // namespace

int Probes::slotOf(int block) {
  _blocks.push_back(block);
  return static_cast<int>(_blocks.size()) - 1;
}

int Probes::rigidSlots(int rigid) {
  const model::RigidBody& rb = _model.rigidBodies()[rigid];
  const int first = slotOf(rb.posBlock);
  for (int k = 1; k < rb.blocks(_dim); ++k) slotOf(rb.posBlock + k);
  return first;
}

Probes::Probes(const model::SceneDescription& scene, const model::Model& model, const model::DofMap& dofs)
    : _model(model), _dofs(dofs), _dim(model.dim()) {
  auto rigidIndex = [&](const std::string& name) {
    for (size_t r = 0; r < model.rigidBodies().size(); ++r)
      if (model.rigidBodies()[r].name == name) return static_cast<int>(r);
    return -1;
  };
  auto bodyIndex = [&](const std::string& name) {
    for (size_t b = 0; b < model.bodies().size(); ++b)
      if (model.bodies()[b].name == name) return static_cast<int>(b);
    return -1;
  };
  for (const model::ProbeDesc& d : scene.probes) {
    Probe p;
    p.name = d.name;
    p.kind = d.kind;
    p.force = d.force;
    std::vector<int> own;  // the blocks of the probe's body, to find the hub that turns it
    if (d.kind == model::ProbeDesc::Kind::RigidPoint) {
      const int r = rigidIndex(d.body);
      if (r < 0) throw InputError(d.mark.where() + ": no rigid body named '" + d.body + "'");
      p.rigidSlot = rigidSlots(r);
      p.point = d.point;
      own.push_back(model.rigidBodies()[r].posBlock);
    } else {
      const int bi = bodyIndex(d.body);
      if (bi < 0) throw InputError(d.mark.where() + ": no body named '" + d.body + "'");
      const model::Body& b = model.bodies()[bi];
      own = b.posBlock;
      if (d.kind == model::ProbeDesc::Kind::Node) {
        const int n = d.node < 0 ? b.elements : static_cast<int>(d.node);
        p.slots.push_back(slotOf(b.posBlock[n]));
        if (d.force)
          for (int i = 0; i < _dim; ++i)
            if (!model.fixedDofs()[b.posBlock[n] * _dim + i])
              throw InputError(d.mark.where() + ": node " + std::to_string(n) + " of body '" + b.name +
                               "' is not held by a support in every direction; a probe's force is a support's force");
      } else {  // element e and eta of the fraction along the body
        const double s = d.along * b.elements;
        const int e = std::min(static_cast<int>(std::floor(s)), b.elements - 1);
        p.body = bi;
        p.eta = s - e;
        // the element's blocks in order (positionOnBody's layout)
        for (int a = 0; a < 2 * b.blocksPerNode; ++a) p.slots.push_back(slotOf(b.nodeBlocks[e * b.blocksPerNode + a]));
      }
    }
    if (d.frame == "hub") {
      p.frame = FrameKind::Hub;
      const auto& hubs = model.hubMotions();
      for (size_t h = 0; h < hubs.size() && p.hub < 0; ++h)
        for (int blk : hubs[h].blocks)
          if (std::find(own.begin(), own.end(), blk) != own.end()) p.hub = static_cast<int>(h);
      if (p.hub < 0)
        throw InputError(d.frameMark.where() + ": no hub turns body '" + d.body +
                         "' (frame: hub is the frame of a support's hub on the probe's body)");
    } else if (d.frame != "world") {
      const int r = rigidIndex(d.frame);
      if (r < 0) throw InputError(d.frameMark.where() + ": no rigid body named '" + d.frame + "'");
      p.frame = FrameKind::Rigid;
      p.frameSlot = rigidSlots(r);
    }
    _probes.push_back(std::move(p));
  }
}

Probes::~Probes() {
  VecScatterDestroy(&_scatter);
  VecDestroy(&_local);
}

bool Probes::needForce() const {
  for (const Probe& p : _probes)
    if (p.force) return true;
  return false;
}

// The gathered blocks' values on rank 0 (slot-major, dim each); with addReference q0 is added
// (the solvers' X holds u = q - q0).
PetscErrorCode Probes::gather(Vec from, bool addReference, std::vector<double>* values) {
  PetscFunctionBeginUser;
  PetscMPIInt rank;
  PetscCallMPI(MPI_Comm_rank(_dofs.comm(), &rank));
  const PetscInt bs = _dofs.blockSize(), n = rank == 0 ? static_cast<PetscInt>(_blocks.size()) * bs : 0;
  if (!_scatter) {
    std::vector<PetscInt> idx;
    for (PetscInt k = 0; k < n; ++k) idx.push_back(_dofs.globalBlock()[_blocks[k / bs]] * bs + k % bs);
    IS is;
    PetscCall(ISCreateGeneral(PETSC_COMM_SELF, n, idx.data(), PETSC_COPY_VALUES, &is));
    PetscCall(VecCreateSeq(PETSC_COMM_SELF, n, &_local));
    PetscCall(VecScatterCreate(from, is, _local, nullptr, &_scatter));
    PetscCall(ISDestroy(&is));
  }
  PetscCall(VecScatterBegin(_scatter, from, _local, INSERT_VALUES, SCATTER_FORWARD));
  PetscCall(VecScatterEnd(_scatter, from, _local, INSERT_VALUES, SCATTER_FORWARD));
  values->assign(static_cast<size_t>(_blocks.size()) * _dim, 0.0);
  if (rank == 0) {
    const PetscScalar* a;
    PetscCall(VecGetArrayRead(_local, &a));
    const auto& q0 = _model.initialCoordinates();
    for (size_t s = 0; s < _blocks.size(); ++s)
      for (int i = 0; i < _dim; ++i)
        (*values)[s * _dim + i] = PetscRealPart(a[s * bs + i]) + (addReference ? q0[_blocks[s] * _dim + i] : 0.0);
    PetscCall(VecRestoreArrayRead(_local, &a));
  }
  PetscFunctionReturn(0);
}

// A rigid body's origin and axes from its gathered blocks at `slot` (position, then 2D: phi in
// component 0; 3D: the three body axes).
static void rigidFrame(int dim, int slot, const std::vector<double>& q, const std::vector<double>& v, model::Vec3* c,
                       model::Vec3* dc, model::Vec3* a, model::Vec3* da) {
  for (int i = 0; i < dim; ++i) {
    (*c)[i] = q[slot * dim + i];
    (*dc)[i] = v.empty() ? 0.0 : v[slot * dim + i];
  }
  if (dim == 2) {
    const double phi = q[(slot + 1) * 2], rate = v.empty() ? 0.0 : v[(slot + 1) * 2];
    const double co = std::cos(phi), si = std::sin(phi);
    a[0] = {co, si, 0.0};
    a[1] = {-si, co, 0.0};
    da[0] = {-si * rate, co * rate, 0.0};
    da[1] = {-co * rate, -si * rate, 0.0};
    a[2] = {0.0, 0.0, 1.0};
    da[2] = {0.0, 0.0, 0.0};
    return;
  }
  for (int k = 0; k < 3; ++k)
    for (int i = 0; i < 3; ++i) {
      a[k][i] = q[(slot + 1 + k) * 3 + i];
      da[k][i] = v.empty() ? 0.0 : v[(slot + 1 + k) * 3 + i];
    }
}

Probes::Frame Probes::frameOf(const Probe& p, double t, const std::vector<double>& q, const std::vector<double>& v) const {
  Frame f;
  for (int k = 0; k < 3; ++k) f.a[k][k] = 1.0;
  if (p.frame == FrameKind::Rigid) {
    rigidFrame(_dim, p.frameSlot, q, v, &f.c, &f.dc, f.a, f.da);
  } else if (p.frame == FrameKind::Hub) {  // the axes turned with the hub, and their rates
    const model::HubMotion& h = _model.hubMotions()[p.hub];
    f.c = h.center;
    for (int k = 0; k < 3; ++k) {
      model::Vec3 e{};
      e[k] = 1.0;
      f.a[k] = h.turn(e, t, &f.da[k]);
    }
  }
  return f;
}

void Probes::pointOf(const Probe& p, const std::vector<double>& q, const std::vector<double>& v, model::Vec3* x,
                     model::Vec3* xv) const {
  *x = {0, 0, 0};
  *xv = {0, 0, 0};
  const int d = _dim;
  if (p.kind == model::ProbeDesc::Kind::Node) {
    for (int i = 0; i < d; ++i) {
      (*x)[i] = q[p.slots[0] * d + i];
      (*xv)[i] = v.empty() ? 0.0 : v[p.slots[0] * d + i];
    }
  } else if (p.kind == model::ProbeDesc::Kind::Along) {
    const model::Body& b = _model.bodies()[p.body];
    const int perElement = static_cast<int>(p.slots.size());
    double w[elements::kMaxBlocksPerElement], qe[elements::kMaxBlocksPerElement * 3];
    for (int a = 0; a < perElement; ++a)
      for (int i = 0; i < d; ++i) qe[a * d + i] = q[p.slots[a] * d + i];
    b.info().interpolationAt(b.discretization, qe, p.eta, w);
    for (int a = 0; a < perElement; ++a)
      for (int i = 0; i < d; ++i) {
        (*x)[i] += w[a] * qe[a * d + i];
        if (!v.empty()) (*xv)[i] += w[a] * v[p.slots[a] * d + i];
      }
  } else {  // x = c + sum_k p_k a_k, v = dc/dt + sum_k p_k da_k/dt
    Frame r;
    rigidFrame(d, p.rigidSlot, q, v, &r.c, &r.dc, r.a, r.da);
    for (int i = 0; i < d; ++i) {
      (*x)[i] = r.c[i];
      (*xv)[i] = r.dc[i];
      for (int k = 0; k < d; ++k) {
        (*x)[i] += p.point[k] * r.a[k][i];
        (*xv)[i] += p.point[k] * r.da[k][i];
      }
    }
  }
}

PetscErrorCode Probes::write(OutputWriter& out, double t, Vec X, Vec V, Vec F) {
  PetscFunctionBeginUser;
  if (_probes.empty()) PetscFunctionReturn(0);
  std::vector<double> q, v, f;
  PetscCall(gather(X, true, &q));
  if (V) PetscCall(gather(V, false, &v));
  if (F) PetscCall(gather(F, false, &f));
  static const char* const kAxis[] = {"x", "y", "z"};
  for (const Probe& p : _probes) {
    model::Vec3 x, xv;
    pointOf(p, q, v, &x, &xv);
    const Frame fr = frameOf(p, t, q, v);
    model::Vec3 rel, relV;
    for (int i = 0; i < 3; ++i) {
      rel[i] = x[i] - fr.c[i];
      relV[i] = xv[i] - fr.dc[i];
    }
    const std::string stem = "probe_" + p.name + "_";
    for (int k = 0; k < _dim; ++k) PetscCallCXX(out.writeScalarSeries(stem + kAxis[k], dotOf(fr.a[k], rel)));
    if (V)
      for (int k = 0; k < _dim; ++k)
        PetscCallCXX(out.writeScalarSeries(stem + "v" + kAxis[k], dotOf(fr.da[k], rel) + dotOf(fr.a[k], relV)));
    if (F && p.force) {
      model::Vec3 force{0, 0, 0};
      for (int i = 0; i < _dim; ++i) force[i] = f[p.slots[0] * _dim + i];
      for (int k = 0; k < _dim; ++k) PetscCallCXX(out.writeScalarSeries(stem + "f" + kAxis[k], dotOf(fr.a[k], force)));
    }
  }
  PetscFunctionReturn(0);
}

}  // namespace strand::io
