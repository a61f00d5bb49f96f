#include "strand/model/DofMap.hpp"

#include <metis.h>

#include <algorithm>
#include <stdexcept>

namespace strand::model {
namespace {

// The block groups that couple DOFs, as CSR: every element's blocks (group by group), then every
// coupling (rigid body, joint, pulley) of the model. hubs false: without the couplings to free
// pulleys, whose blocks reach every element of a belt (the partition: as edges they pull METIS
// into cutting a belt loop many times; the interface-Schur solve takes their rows as hubs).
void blockGroups(const Model& model, std::vector<PetscInt>& ptr, std::vector<int>& blk, bool hubs = true) {
  ptr.assign(1, 0);
  blk.clear();
  size_t total = 0;
  for (const ElementGroup& g : model.groups()) total += g.blocks.size();
  blk.reserve(total);
  for (const ElementGroup& g : model.groups())
    for (int e = 0; e < g.size(); ++e) {
      blk.insert(blk.end(), g.blocksOf(e), g.blocksOf(e) + g.blocksPerElement);
      ptr.push_back(static_cast<PetscInt>(blk.size()));
    }
  for (const Coupling& c : model.couplings()) {
    if (!hubs && c.pulley >= 0) continue;
    blk.insert(blk.end(), c.blocks.begin(), c.blocks.end());
    ptr.push_back(static_cast<PetscInt>(blk.size()));
  }
}

// Rows of a CSR graph with sorted, unique entries: rows[r] lists the blocks sharing a group with r.
// Self-loops are kept (they are the diagonal block for preallocation) unless dropSelf.
void buildAdjacency(const std::vector<PetscInt>& gptr, const std::vector<int>& gblk, int nRows,
                    const std::vector<PetscInt>& rowOf, bool dropSelf, std::vector<PetscInt>& xadj,
                    std::vector<PetscInt>& adj, const std::vector<PetscInt>* colOf = nullptr) {
  const size_t nGroups = gptr.size() - 1;
  xadj.assign(nRows + 1, 0);
  for (size_t g = 0; g < nGroups; ++g)
    for (PetscInt a = gptr[g]; a < gptr[g + 1]; ++a)
      if (rowOf[gblk[a]] >= 0) xadj[rowOf[gblk[a]] + 1] += gptr[g + 1] - gptr[g];
  for (int r = 0; r < nRows; ++r) xadj[r + 1] += xadj[r];
  adj.assign(xadj[nRows], 0);
  std::vector<PetscInt> fill(xadj.begin(), xadj.end() - 1);
  for (size_t g = 0; g < nGroups; ++g)
    for (PetscInt a = gptr[g]; a < gptr[g + 1]; ++a) {
      const PetscInt r = rowOf[gblk[a]];
      if (r < 0) continue;
      for (PetscInt b = gptr[g]; b < gptr[g + 1]; ++b) adj[fill[r]++] = colOf ? (*colOf)[gblk[b]] : gblk[b];
    }
  // sort, unique and compact each row
  PetscInt out = 0;
  for (int r = 0; r < nRows; ++r) {
    const PetscInt lo = xadj[r], hi = xadj[r + 1];
    std::sort(adj.begin() + lo, adj.begin() + hi);
    const PetscInt start = out;
    for (PetscInt k = lo; k < hi; ++k) {
      if (k > lo && adj[k] == adj[k - 1]) continue;
      if (dropSelf && adj[k] == r) continue;  // only used without colOf (METIS graph)
      adj[out++] = adj[k];
    }
    xadj[r] = start;
  }
  xadj[nRows] = out;
  adj.resize(out);
}

std::vector<idx_t> metisPartition(const Model& model, const std::vector<PetscInt>& gptr, const std::vector<int>& gblk,
                                  int nParts) {
  const int nb = model.numBlocks();
  std::vector<idx_t> part(nb, 0);
  std::vector<PetscInt> identity(nb), xadj, adj;
  for (int b = 0; b < nb; ++b) identity[b] = b;
  buildAdjacency(gptr, gblk, nb, identity, true, xadj, adj);
  std::vector<idx_t> mx(xadj.begin(), xadj.end()), ma(adj.begin(), adj.end());
  idx_t nv = nb, ncon = 1, np = nParts, cut = 0;
  idx_t options[METIS_NOPTIONS];
  METIS_SetDefaultOptions(options);
  options[METIS_OPTION_SEED] = 1;  // deterministic partitions
  const int rc = METIS_PartGraphKway(&nv, &ncon, mx.data(), ma.data(), nullptr, nullptr, nullptr, &np,
                                     nullptr, nullptr, options, &cut, part.data());
  if (rc != METIS_OK) throw std::runtime_error("METIS_PartGraphKway failed with code " + std::to_string(rc));
  return part;
}

// Blocks that share an element or a coupling with a block of another part: the rows that the
// parallel direct solve calls the interface (InterfaceSchur.hpp).
std::vector<char> interfaceBlocks(const std::vector<PetscInt>& gptr, const std::vector<int>& gblk,
                                  const std::vector<int>& part) {
  std::vector<char> on(part.size(), 0);
  for (size_t g = 0; g + 1 < gptr.size(); ++g) {
    bool cut = false;
    for (PetscInt a = gptr[g]; a < gptr[g + 1]; ++a) cut = cut || part[gblk[a]] != part[gblk[gptr[g]]];
    if (cut)
      for (PetscInt a = gptr[g]; a < gptr[g + 1]; ++a) on[gblk[a]] = 1;
  }
  return on;
}

// A part whose interface blocks are exactly its first blocks in model order, and not its last: an
// end segment of a chain cut at its start. Numbered in reverse, its interface comes last, and the
// parallel direct solve's split sweeps (InterfaceSchurSweeps.cpp) take its vectors as they are
// instead of reordering b and x at every apply. Reversal keeps the band of the local block:
// |i - j| is unchanged.
bool interfaceIsPrefixOnly(const std::vector<int>& members, const std::vector<char>& onInterface) {
  size_t count = 0;
  for (int b : members) count += onInterface[b];
  if (count == 0 || count == members.size()) return false;
  const auto interface = [&](int b) { return onInterface[b] != 0; };
  const bool prefix = std::all_of(members.begin(), members.begin() + count, interface);
  const bool suffix = std::all_of(members.end() - count, members.end(), interface);
  return prefix && !suffix;
}

}  // namespace

DofMap::DofMap(MPI_Comm comm, const Model& model) : _comm(comm), _bs(model.dim()), _nGlobal(model.numBlocks()) {
  int rank = 0, size = 1;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &size);
  const int nb = model.numBlocks();
  std::vector<PetscInt> gptr;
  std::vector<int> gblk;
  blockGroups(model, gptr, gblk);
  // 1. partition on rank 0, broadcast
  std::vector<int> part(nb, 0);
  if (size > 1) {
    if (rank == 0) {
      std::vector<PetscInt> pptr;
      std::vector<int> pblk;
      blockGroups(model, pptr, pblk, false);
      const std::vector<idx_t> p = metisPartition(model, pptr, pblk, size);
      std::copy(p.begin(), p.end(), part.begin());
    }
    MPI_Bcast(part.data(), nb, MPI_INT, 0, comm);
  }
  // 2. contiguous renumbering: blocks of part 0 first, each part in model order or reversed
  std::vector<PetscInt> offset(size + 1, 0);
  for (int b = 0; b < nb; ++b) offset[part[b] + 1]++;
  for (int p = 0; p < size; ++p) offset[p + 1] += offset[p];
  _begin = offset[rank];
  _end = offset[rank + 1];
  _global.resize(nb);
  std::vector<std::vector<int>> members(size);
  for (int b = 0; b < nb; ++b) members[part[b]].push_back(b);
  const std::vector<char> onInterface = interfaceBlocks(gptr, gblk, part);
  for (int p = 0; p < size; ++p) {
    if (interfaceIsPrefixOnly(members[p], onInterface)) std::reverse(members[p].begin(), members[p].end());
    for (size_t i = 0; i < members[p].size(); ++i) _global[members[p][i]] = offset[p] + static_cast<PetscInt>(i);
  }
  // 3. local elements: those whose first block this rank owns, group by group; their ghosts
  const auto& groups = model.groups();
  for (int gi = 0; gi < static_cast<int>(groups.size()); ++gi) {
    const ElementGroup& group = groups[gi];
    LocalGroup local;
    local.group = gi;
    local.stride = group.blocksPerElement;
    for (int e = 0; e < group.size(); ++e) {
      const PetscInt g = _global[group.blocksOf(e)[0]];
      if (g >= _begin && g < _end) local.elements.push_back(e);
    }
    for (int e : local.elements)
      for (int k = 0; k < group.blocksPerElement; ++k) {
        const PetscInt g = _global[group.blocksOf(e)[k]];
        if (g < _begin || g >= _end) _ghosts.push_back(g);
      }
    _localGroups.push_back(std::move(local));
  }
  // couplings (rigid bodies, joints): those whose first block this rank owns
  const auto& couplings = model.couplings();
  for (int c = 0; c < static_cast<int>(couplings.size()); ++c) {
    const PetscInt g = _global[couplings[c].blocks[0]];
    if (g < _begin || g >= _end) continue;
    _localCouplings.push_back(c);
    for (int b : couplings[c].blocks)
      if (_global[b] < _begin || _global[b] >= _end) _ghosts.push_back(_global[b]);
  }
  std::sort(_ghosts.begin(), _ghosts.end());
  _ghosts.erase(std::unique(_ghosts.begin(), _ghosts.end()), _ghosts.end());
  for (LocalGroup& local : _localGroups) {
    const ElementGroup& group = groups[local.group];
    for (int e : local.elements)
      for (int k = 0; k < group.blocksPerElement; ++k) {
        const PetscInt g = _global[group.blocksOf(e)[k]];
        local.globalBlocks.push_back(g);
        local.localBlocks.push_back(localBlock(g));
      }
  }
  _cplOffset.assign(1, 0);
  for (int c : _localCouplings) {
    for (int b : couplings[c].blocks) {
      _cplGlobal.push_back(_global[b]);
      _cplLocal.push_back(localBlock(_global[b]));
    }
    _cplOffset.push_back(static_cast<PetscInt>(_cplGlobal.size()));
  }
  _coupledLocal.assign(_end - _begin + _ghosts.size(), 0);
  for (const Coupling& c : couplings)
    for (int b : c.blocks)
      if (const PetscInt lb = localBlock(_global[b]); lb >= 0) _coupledLocal[lb] = 1;
  // a body in contact too: its contact Jacobians (PulleyContacts) write whole element blocks as
  // elements come into contact, also against fixed pulleys (no coupling); the inserter must not
  // leave any of its blocks out of a matrix's first assembly
  for (const PulleyContactSet& set : model.contacts())
    for (int b : model.bodies()[set.body].nodeBlocks)
      if (const PetscInt lb = localBlock(_global[b]); lb >= 0) _coupledLocal[lb] = 1;
  // 4. exact preallocation of the owned block rows (every rank sees every element)
  std::vector<PetscInt> rowOf(nb, -1), xadj, adj;
  for (int b = 0; b < nb; ++b)
    if (_global[b] >= _begin && _global[b] < _end) rowOf[b] = _global[b] - _begin;
  buildAdjacency(gptr, gblk, static_cast<int>(_end - _begin), rowOf, false, xadj, adj, &_global);
  _dnnz.assign(_end - _begin, 0);
  _onnz.assign(_end - _begin, 0);
  for (PetscInt r = 0; r < _end - _begin; ++r) {
    if (xadj[r + 1] == xadj[r]) _dnnz[r] = 1;  // an isolated block still has its diagonal
    for (PetscInt k = xadj[r]; k < xadj[r + 1]; ++k) (adj[k] >= _begin && adj[k] < _end ? _dnnz[r] : _onnz[r])++;
  }
}

PetscInt DofMap::localBlock(PetscInt g) const {
  if (g >= _begin && g < _end) return g - _begin;
  auto it = std::lower_bound(_ghosts.begin(), _ghosts.end(), g);
  if (it == _ghosts.end() || *it != g) return -1;
  return (_end - _begin) + (it - _ghosts.begin());
}

PetscErrorCode DofMap::createVector(Vec* v) const {
  PetscFunctionBeginUser;
  if (!_prototype) {
    Vec p;
    PetscCall(VecCreateGhostBlock(_comm, _bs, ownedBlocks() * _bs, PETSC_DECIDE,
                                  static_cast<PetscInt>(_ghosts.size()), _ghosts.data(), &p));
    _prototype.reset(p, [](Vec x) { VecDestroy(&x); });
  }
  PetscCall(VecDuplicate(_prototype.get(), v));  // zero, like a new vector
  PetscFunctionReturn(0);
}

PetscErrorCode DofMap::sharesGhosts(Vec v, bool* shares) const {
  ISLocalToGlobalMapping mine, theirs;
  PetscFunctionBeginUser;
  *shares = false;
  if (!_prototype) PetscFunctionReturn(0);
  PetscCall(VecGetLocalToGlobalMapping(_prototype.get(), &mine));
  PetscCall(VecGetLocalToGlobalMapping(v, &theirs));
  // duplicates share the layout and with it the mapping object (PETSc's VecDuplicate_MPI), which
  // was created collectively: the pointer test gives the same answer on every rank. A vector that
  // only took the mapping (MatCreateVecs of a matrix given it) has no ghost slots: not ours.
  if (theirs != mine) PetscFunctionReturn(0);
  Vec local;
  PetscCall(VecGhostGetLocalForm(v, &local));
  *shares = local != nullptr;
  PetscCall(VecGhostRestoreLocalForm(v, &local));
  PetscFunctionReturn(0);
}

PetscErrorCode DofMap::createMatrix(Mat* A, const char* prefix, MatType defaultType) const {
  PetscFunctionBeginUser;
  PetscCall(MatCreate(_comm, A));
  PetscCall(MatSetSizes(*A, ownedBlocks() * _bs, ownedBlocks() * _bs, PETSC_DETERMINE, PETSC_DETERMINE));
  PetscCall(MatSetBlockSize(*A, _bs));
  PetscCall(MatSetType(*A, defaultType));
  if (prefix) PetscCall(MatSetOptionsPrefix(*A, prefix));
  PetscCall(MatSetFromOptions(*A));
  PetscCall(MatXAIJSetPreallocation(*A, _bs, _dnnz.data(), _onnz.data(), nullptr, nullptr));
  PetscCall(MatSetOption(*A, MAT_NEW_NONZERO_ALLOCATION_ERR, PETSC_TRUE));
  PetscFunctionReturn(0);
}

}  // namespace strand::model
