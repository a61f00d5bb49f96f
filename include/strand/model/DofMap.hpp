// Parallel layout of the DOF blocks (design section 5).
//
// Rank 0 partitions the block graph with METIS_PartGraphKway and broadcasts the parts; every rank
// renumbers the blocks so that each owns a contiguous range (in model order, or reversed when the
// part's interface to other parts is exactly its first blocks: an end segment of a chain then ends
// with its interface, see DofMap.cpp), takes the elements and couplings (rigid bodies, joints) whose
// first block it owns, and computes the exact block preallocation of its rows. All blocks have `dim`
// coordinates; an element has the blocks its kind lays out (Model::ElementGroup).
#pragma once
#include <petscmat.h>

#include <memory>
#include <type_traits>
#include <vector>

#include "strand/model/Model.hpp"

namespace strand::model {

class DofMap {
public:
  DofMap(MPI_Comm comm, const Model& model);

  MPI_Comm comm() const { return _comm; }
  PetscInt blockSize() const { return _bs; }
  PetscInt globalBlocks() const { return _nGlobal; }
  PetscInt ownedBegin() const { return _begin; }  // first owned block, global numbering
  PetscInt ownedEnd() const { return _end; }
  PetscInt ownedBlocks() const { return _end - _begin; }
  // model block -> global block (replicated on every rank)
  const std::vector<PetscInt>& globalBlock() const { return _global; }
  // The elements of one group (Model::groups()) that this rank assembles: their indices in the group
  // and, per element, `stride` ghosted-local and global block indices.
  struct LocalGroup {
    int group = 0;
    int stride = 0;
    std::vector<int> elements;
    std::vector<PetscInt> localBlocks, globalBlocks;
    int size() const { return static_cast<int>(elements.size()); }
    const PetscInt* localBlocksOf(int k) const { return &localBlocks[static_cast<size_t>(k) * stride]; }
    const PetscInt* globalBlocksOf(int k) const { return &globalBlocks[static_cast<size_t>(k) * stride]; }
  };
  // one per element group of the model, in its order
  const std::vector<LocalGroup>& localGroups() const { return _localGroups; }
  // couplings (indices into Model::couplings()) assembled by this rank, and their blocks:
  // local coupling k has blocks [couplingOffset()[k], couplingOffset()[k + 1]) of the two lists
  const std::vector<int>& localCouplings() const { return _localCouplings; }
  const std::vector<PetscInt>& couplingOffset() const { return _cplOffset; }
  const std::vector<PetscInt>& couplingLocalBlocks() const { return _cplLocal; }
  const std::vector<PetscInt>& couplingGlobalBlocks() const { return _cplGlobal; }
  // per ghosted-local block: 1 when a coupling of the model (rigid body, joint, contact with a free
  // pulley) holds it, or it belongs to a body in contact (ElementInserter never leaves it out)
  const std::vector<char>& coupledLocal() const { return _coupledLocal; }
  // ghosted-local index of a global block, or -1 when this rank neither owns nor ghosts it
  PetscInt localBlock(PetscInt globalBlock) const;

  // Ghosted block vector with this layout. All are duplicates of one vector, so they share its
  // local-to-global mapping and ghost scatter: sharesGhosts() tells such a vector in O(1), and the
  // assembler updates its ghosts in place instead of copying it (Assembler::beginLocal).
  PetscErrorCode createVector(Vec* v) const;
  // Whether v came from createVector() of this map (or is a duplicate of such a vector); the same
  // answer on every rank.
  PetscErrorCode sharesGhosts(Vec v, bool* shares) const;
  // Matrix with exact preallocation and MAT_NEW_NONZERO_ALLOCATION_ERR; of type defaultType unless
  // -<prefix>mat_type says otherwise. BAIJ (block = one node vector) is the memory-lean default.
  PetscErrorCode createMatrix(Mat* A, const char* prefix, MatType defaultType = MATBAIJ) const;

private:
  MPI_Comm _comm;
  PetscInt _bs = 0, _nGlobal = 0, _begin = 0, _end = 0;
  std::vector<PetscInt> _global, _ghosts;
  std::vector<LocalGroup> _localGroups;
  std::vector<int> _localCouplings;
  std::vector<PetscInt> _cplOffset, _cplLocal, _cplGlobal;
  std::vector<char> _coupledLocal;
  std::vector<PetscInt> _dnnz, _onnz;  // block preallocation of owned block rows
  // the vector createVector() duplicates, made on first use; shared by copies of the map
  mutable std::shared_ptr<std::remove_pointer_t<Vec>> _prototype;
};

}  // namespace strand::model
