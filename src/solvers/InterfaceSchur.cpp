// The interface Schur-complement direct solve for chains (InterfaceSchur.hpp).
#include "strand/solvers/InterfaceSchur.hpp"

#include <petsc/private/pcimpl.h>
#include <petscksp.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <vector>

#include "solvers/InterfaceSchurData.hpp"

namespace strand::solvers {

namespace schur {

// x_G from the interface right-hand sides g of this rank (all ranks' gathered and solved).
PetscErrorCode interfaceSolve(const SchurData& d, MPI_Comm comm, const std::vector<PetscScalar>& g, bool transpose,
                              Eigen::VectorXd* x) {
  PetscFunctionBeginUser;
  // summed, not gathered: a rank taking the interior solve adds to other ranks' entries, and
  // every rank of the PC must call the same collective
  Eigen::VectorXd gAll = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(d.gamma.size()));
  for (size_t i = 0; i < g.size(); ++i) gAll[d.ownOffset + static_cast<Eigen::Index>(i)] = g[i];
  PetscCall(interfaceSolveSummed(d, comm, gAll, transpose, x));
  PetscFunctionReturn(0);
}

PetscErrorCode interfaceSolveSummed(const SchurData& d, MPI_Comm comm, Eigen::VectorXd& g, bool transpose,
                                    Eigen::VectorXd* x) {
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, g.data(), static_cast<PetscMPIInt>(g.size()), MPIU_SCALAR, MPI_SUM, comm));
  *x = transpose ? Eigen::VectorXd(d.schur.transpose().solve(g)) : Eigen::VectorXd(d.schur.solve(g));
  PetscFunctionReturn(0);
}

}  // namespace schur

namespace {

using schur::RowMajor;
using schur::SchurData;

SchurData* dataOf(PC pc) { return static_cast<SchurData*>(pc->data); }

PetscErrorCode clearLocalSolve(SchurData* d);

PetscErrorCode clear(SchurData* d) {
  PetscFunctionBeginUser;
  PetscCall(clearLocalSolve(d));
  d->built = false;
  PetscFunctionReturn(0);
}

// A row coupling to more than this many blocks of other ranks is a hub (SchurData::hubs): a chain's
// cut couples a block to the few blocks of one element across it.
constexpr PetscInt kHubBlocks = 16;

// The diagonal (own columns) and off-process blocks of the MPI matrix; on one rank the matrix
// itself and no off-process block. colmap (may be null): the global (block) column of each of
// Ao's columns.
PetscErrorCode localBlocks(Mat P, Mat* Ad, Mat* Ao, PetscBool* blocked, const PetscInt** colmap = nullptr) {
  PetscBool mpibaij, mpiaij, seqbaij, seqaij;
  PetscFunctionBeginUser;
  PetscObject o = reinterpret_cast<PetscObject>(P);
  PetscCall(PetscObjectTypeCompare(o, MATMPIBAIJ, &mpibaij));
  PetscCall(PetscObjectTypeCompare(o, MATMPIAIJ, &mpiaij));
  PetscCall(PetscObjectTypeCompare(o, MATSEQBAIJ, &seqbaij));
  PetscCall(PetscObjectTypeCompare(o, MATSEQAIJ, &seqaij));
  *Ao = nullptr;
  if (colmap) *colmap = nullptr;
  *blocked = static_cast<PetscBool>(mpibaij || seqbaij);
  if (mpibaij) PetscCall(MatMPIBAIJGetSeqBAIJ(P, Ad, Ao, colmap));
  else if (mpiaij) PetscCall(MatMPIAIJGetSeqAIJ(P, Ad, Ao, colmap));
  else if (seqbaij || seqaij) *Ad = P;
  else SETERRQ(PetscObjectComm(o), PETSC_ERR_SUP, "PC %s needs an AIJ or BAIJ matrix, not %s", kPcInterfaceSchur,
               o->type_name);
  PetscFunctionReturn(0);
}

// Interface rows: the hubs (block rows coupling to more than kHubBlocks blocks of other ranks) and
// the block rows with an entry in the off-process block outside the hubs' columns; and the
// interface of all ranks, in rank order (ownership is contiguous, so it is ascending).
PetscErrorCode findInterface(SchurData* d, Mat P) {
  Mat Ad, Ao;
  PetscBool blocked;
  const PetscInt* colmap;
  PetscInt rows, cols, bs;
  PetscFunctionBeginUser;
  PetscCall(localBlocks(P, &Ad, &Ao, &blocked, &colmap));
  PetscCall(MatGetBlockSize(P, &bs));
  PetscCall(MatGetLocalSize(P, &rows, &cols));
  d->rows = rows;
  MPI_Comm comm = PetscObjectComm(reinterpret_cast<PetscObject>(P));
  PetscMPIInt size, rank;
  PetscCallMPI(MPI_Comm_size(comm, &size));
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  PetscInt rstart, rend;
  PetscCall(MatGetOwnershipRange(P, &rstart, &rend));
  std::vector<char> onInterface(rows / bs, 0);
  PetscInt n = 0;
  const PetscInt *ia = nullptr, *ja = nullptr;
  PetscBool done;
  if (Ao) {
    PetscCall(MatGetRowIJ(Ao, 0, PETSC_FALSE, blocked, &n, &ia, &ja, &done));
    PetscCheck(done, PETSC_COMM_SELF, PETSC_ERR_SUP, "PC %s: no row structure of the off-process block",
               kPcInterfaceSchur);
  }
  const PetscInt rowsPerEntry = n > 0 ? rows / n : bs;  // bs for BAIJ's block rows, 1 for AIJ; a rank may own none
  const PetscInt colsPerEntry = blocked ? bs : 1;
  // hubs: the block rows reaching more than kHubBlocks off-process blocks (AIJ: entries over bs),
  // gathered from every rank as global block rows (ascending)
  std::vector<PetscInt> hubsHere;
  for (PetscInt r = 0; r < n; ++r)
    if ((ia[r + 1] - ia[r]) * colsPerEntry / bs > kHubBlocks) hubsHere.push_back(rstart / bs + r * rowsPerEntry / bs);
  hubsHere.erase(std::unique(hubsHere.begin(), hubsHere.end()), hubsHere.end());
  std::vector<PetscInt> hubs;
  if (size > 1) {
    const PetscMPIInt mineHubs = static_cast<PetscMPIInt>(hubsHere.size());
    std::vector<PetscMPIInt> hubCounts(size), hubOffsets(size, 0);
    PetscCallMPI(MPI_Allgather(&mineHubs, 1, MPI_INT, hubCounts.data(), 1, MPI_INT, comm));
    for (PetscMPIInt p = 1; p < size; ++p) hubOffsets[p] = hubOffsets[p - 1] + hubCounts[p - 1];
    hubs.resize(hubOffsets[size - 1] + hubCounts[size - 1]);
    PetscCallMPI(MPI_Allgatherv(hubsHere.data(), mineHubs, MPIU_INT, hubs.data(), hubCounts.data(), hubOffsets.data(),
                                MPIU_INT, comm));
  }
  d->hubs = !hubs.empty();
  // interface: the hubs, and the rows with an off-process entry outside the hubs' columns
  for (PetscInt b : hubsHere) onInterface[b - rstart / bs] = 1;
  for (PetscInt r = 0; r < n; ++r)
    for (PetscInt k = ia[r]; k < ia[r + 1]; ++k)
      if (!std::binary_search(hubs.begin(), hubs.end(), colmap[ja[k]] * colsPerEntry / bs)) {
        onInterface[r * rowsPerEntry / bs] = 1;
        break;
      }
  if (Ao) PetscCall(MatRestoreRowIJ(Ao, 0, PETSC_FALSE, blocked, &n, &ia, &ja, &done));
  // multiplier rows (a zero on the diagonal: a saddle point's constraint rows) join the interface,
  // whose dense Schur complement is factored with partial pivoting; the interior without them is
  // regular where the caller says so (setDirectSolverDefaults' regularInterior)
  {
    Vec diag;
    PetscCall(MatCreateVecs(Ad, nullptr, &diag));
    PetscCall(MatGetDiagonal(Ad, diag));
    const PetscScalar* a;
    PetscCall(VecGetArrayRead(diag, &a));
    d->multipliers = false;
    for (PetscInt r = 0; r < rows; ++r)
      if (a[r] == 0.0) onInterface[r / bs] = 1, d->multipliers = true;
    PetscCall(VecRestoreArrayRead(diag, &a));
    PetscCall(VecDestroy(&diag));
    PetscMPIInt mine = d->multipliers, any = 0;
    PetscCallMPI(MPI_Allreduce(&mine, &any, 1, MPI_INT, MPI_MAX, comm));
    d->anyMultipliers = any;
  }
  d->interface.clear();
  for (PetscInt r = 0; r < rows; ++r)
    if (onInterface[r / bs]) d->interface.push_back(r);

  std::vector<PetscInt> own(d->interface);
  for (PetscInt& r : own) r += rstart;
  const PetscMPIInt mine = static_cast<PetscMPIInt>(own.size());
  d->counts.assign(size, 0);
  d->offsets.assign(size, 0);
  PetscCallMPI(MPI_Allgather(&mine, 1, MPI_INT, d->counts.data(), 1, MPI_INT, comm));
  for (PetscMPIInt p = 1; p < size; ++p) d->offsets[p] = d->offsets[p - 1] + d->counts[p - 1];
  d->ownOffset = d->offsets[rank];
  d->gamma.assign(d->offsets[size - 1] + d->counts[size - 1], 0);
  PetscCallMPI(MPI_Allgatherv(own.data(), mine, MPIU_INT, d->gamma.data(), d->counts.data(), d->offsets.data(),
                              MPIU_INT, comm));
  PetscFunctionReturn(0);
}

PetscErrorCode createInteriorSolver(PC pc, SchurData* d) {
  const char* prefix;
  PC lu;
  PetscFunctionBeginUser;
  PetscCall(KSPCreate(PETSC_COMM_SELF, &d->interiorSolver));
  PetscCall(PCGetOptionsPrefix(pc, &prefix));
  PetscCall(KSPSetOptionsPrefix(d->interiorSolver, prefix));
  PetscCall(KSPAppendOptionsPrefix(d->interiorSolver, "schur_interior_"));
  PetscCall(KSPSetType(d->interiorSolver, KSPPREONLY));
  PetscCall(KSPGetPC(d->interiorSolver, &lu));
  PetscCall(PCSetType(lu, PCLU));
  // RCM keeps the band of cable chains: at 1e5 elements 3.3 instead of 3.9 kB per element and 2.4
  // instead of 3.0 s against the default nested dissection (docs/performance.md)
  PetscCall(PCFactorSetMatOrderingType(lu, MATORDERINGRCM));
  PetscCall(KSPSetFromOptions(d->interiorSolver));
  PetscFunctionReturn(0);
}

// Split sweeps: this rank's rows of S, row-major, |own interface| x |interface|: A_GG's columns of
// the other ranks' interface, and S00 = L_GG U_GG in the own ones.
PetscErrorCode ownSchurRows(SchurData* d, Mat P, std::vector<PetscScalar>* rows) {
  const PetscInt nG = static_cast<PetscInt>(d->gamma.size()), mine = static_cast<PetscInt>(d->interface.size());
  PetscInt rstart, rend;
  PetscFunctionBeginUser;
  rows->assign(mine * nG, 0.0);
  PetscCall(MatGetOwnershipRange(P, &rstart, &rend));
  for (PetscInt i = 0; i < mine; ++i) {
    PetscInt nc;
    const PetscInt* c;
    const PetscScalar* v;
    PetscCall(MatGetRow(P, rstart + d->interface[i], &nc, &c, &v));
    for (PetscInt k = 0; k < nc; ++k) {
      auto at = std::lower_bound(d->gamma.begin(), d->gamma.end(), c[k]);
      const bool own = c[k] >= rstart && c[k] < rend;
      if (at != d->gamma.end() && *at == c[k]) {
        if (!own) (*rows)[i * nG + (at - d->gamma.begin())] += v[k];
      } else if (!own)
        SETERRQ(PETSC_COMM_SELF, PETSC_ERR_ARG_WRONG,
                "PC %s needs a structurally symmetric matrix: row %d couples to column %d of another rank, "
                "which is not on the interface",
                kPcInterfaceSchur, static_cast<int>(rstart + d->interface[i]), static_cast<int>(c[k]));
    }
    PetscCall(MatRestoreRow(P, rstart + d->interface[i], &nc, &c, &v));
  }
  for (PetscInt i = 0; i < mine; ++i)
    for (PetscInt j = 0; j < mine; ++j) (*rows)[i * nG + d->ownOffset + j] += d->S00(i, j);
  PetscFunctionReturn(0);
}

// Interior solve: this rank's part of S (nG x nG, row-major; summed over the ranks by the caller):
// A_GG on its own interface rows, minus A_GI Z over the interface unknowns its interior touches.
// A hub row's entries in another rank's interior columns are sent to that rank (its A_GI). Keeps
// touch, agi, aig and Z.
PetscErrorCode interiorSchur(SchurData* d, Mat P, RowMajor* S) {
  const PetscInt nG = static_cast<PetscInt>(d->gamma.size()), mine = static_cast<PetscInt>(d->interface.size());
  MPI_Comm comm = PetscObjectComm(reinterpret_cast<PetscObject>(P));
  PetscMPIInt size;
  PetscInt rstart, rend;
  const PetscInt* ranges;
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_size(comm, &size));
  PetscCall(MatGetOwnershipRange(P, &rstart, &rend));
  PetscCall(MatGetOwnershipRanges(P, &ranges));
  S->setZero(nG, nG);
  d->agi.assign(nG, {});
  std::vector<std::vector<PetscInt>> sendRows(size), sendCols(size);  // (hub row, interior column) per owner
  std::vector<std::vector<PetscScalar>> sendValues(size);
  auto gammaIndex = [&](PetscInt global) {
    auto at = std::lower_bound(d->gamma.begin(), d->gamma.end(), global);
    return at != d->gamma.end() && *at == global ? static_cast<PetscInt>(at - d->gamma.begin()) : PetscInt(-1);
  };
  for (PetscInt i = 0; i < mine; ++i) {
    const PetscInt row = rstart + d->interface[i], gi = d->ownOffset + i;
    PetscInt nc;
    const PetscInt* c;
    const PetscScalar* v;
    PetscCall(MatGetRow(P, row, &nc, &c, &v));
    for (PetscInt k = 0; k < nc; ++k) {
      const PetscInt j = gammaIndex(c[k]);
      if (j >= 0) {
        (*S)(gi, j) += v[k];
      } else if (c[k] >= rstart && c[k] < rend) {
        d->agi[gi].emplace_back(c[k] - rstart, v[k]);
      } else {  // a hub's entry in another rank's interior
        const PetscMPIInt owner =
            static_cast<PetscMPIInt>(std::upper_bound(ranges, ranges + size + 1, c[k]) - ranges) - 1;
        sendRows[owner].push_back(row);
        sendCols[owner].push_back(c[k]);
        sendValues[owner].push_back(v[k]);
      }
    }
    PetscCall(MatRestoreRow(P, row, &nc, &c, &v));
  }
  if (d->hubs) {  // the hubs' entries in this rank's interior, from their owners (every rank takes the interior solve)
    std::vector<PetscMPIInt> sendCounts(size), recvCounts(size), sendOffsets(size, 0), recvOffsets(size, 0);
    for (PetscMPIInt p = 0; p < size; ++p) sendCounts[p] = static_cast<PetscMPIInt>(sendRows[p].size());
    PetscCallMPI(MPI_Alltoall(sendCounts.data(), 1, MPI_INT, recvCounts.data(), 1, MPI_INT, comm));
    for (PetscMPIInt p = 1; p < size; ++p) {
      sendOffsets[p] = sendOffsets[p - 1] + sendCounts[p - 1];
      recvOffsets[p] = recvOffsets[p - 1] + recvCounts[p - 1];
    }
    const PetscMPIInt total = recvOffsets[size - 1] + recvCounts[size - 1];
    std::vector<PetscInt> rowsOut, colsOut, rowsIn(total), colsIn(total);
    std::vector<PetscScalar> valuesOut, valuesIn(total);
    for (PetscMPIInt p = 0; p < size; ++p) {
      rowsOut.insert(rowsOut.end(), sendRows[p].begin(), sendRows[p].end());
      colsOut.insert(colsOut.end(), sendCols[p].begin(), sendCols[p].end());
      valuesOut.insert(valuesOut.end(), sendValues[p].begin(), sendValues[p].end());
    }
    PetscCallMPI(MPI_Alltoallv(rowsOut.data(), sendCounts.data(), sendOffsets.data(), MPIU_INT, rowsIn.data(),
                               recvCounts.data(), recvOffsets.data(), MPIU_INT, comm));
    PetscCallMPI(MPI_Alltoallv(colsOut.data(), sendCounts.data(), sendOffsets.data(), MPIU_INT, colsIn.data(),
                               recvCounts.data(), recvOffsets.data(), MPIU_INT, comm));
    PetscCallMPI(MPI_Alltoallv(valuesOut.data(), sendCounts.data(), sendOffsets.data(), MPIU_SCALAR, valuesIn.data(),
                               recvCounts.data(), recvOffsets.data(), MPIU_SCALAR, comm));
    for (PetscMPIInt k = 0; k < total; ++k) d->agi[gammaIndex(rowsIn[k])].emplace_back(colsIn[k] - rstart, valuesIn[k]);
  }
  // the touched interface unknowns; their columns' entries in the interior rows sit (structural
  // symmetry) in the rows named by their rows' interior columns
  d->touch.clear();
  d->aig.clear();
  for (PetscInt j = 0; j < nG; ++j) {
    if (d->agi[j].empty()) continue;
    d->touch.push_back(j);
    std::vector<std::pair<PetscInt, PetscScalar>> column;
    for (const auto& entry : d->agi[j]) {
      const PetscInt row = rstart + entry.first;
      PetscScalar a;
      PetscCall(MatGetValues(P, 1, &row, 1, &d->gamma[j], &a));
      column.emplace_back(entry.first, a);
    }
    d->aig.push_back(std::move(column));
  }
  const PetscInt nt = static_cast<PetscInt>(d->touch.size());
  d->Z.resize(d->rows, nt);
  for (PetscInt k = 0; k < nt; ++k) {  // column k of Z: A_II^{-1} A_IG e_touch[k]
    PetscScalar* w;
    PetscCall(VecSet(d->w, 0.0));
    PetscCall(VecGetArray(d->w, &w));
    for (const auto& [row, a] : d->aig[k]) w[row] = a;
    PetscCall(VecRestoreArray(d->w, &w));
    PetscCall(VecPlaceArray(d->y, d->Z.col(k).data()));
    PetscCall(KSPSolve(d->interiorSolver, d->w, d->y));
    PetscCall(VecResetArray(d->y));
  }
  for (PetscInt k1 = 0; k1 < nt; ++k1)
    for (const auto& [col, a] : d->agi[d->touch[k1]])
      for (PetscInt k2 = 0; k2 < nt; ++k2) (*S)(d->touch[k1], d->touch[k2]) -= a * d->Z(col, k2);
  PetscFunctionReturn(0);
}

// The interior solve's matrix, solver and work vectors (the split sweeps' LU is analyzed by
// splitSweepsFit). Without an interface (one rank) A_II is A_d itself.
PetscErrorCode prepareInteriorSolve(PC pc, SchurData* d, Mat Ad) {
  PetscFunctionBeginUser;
  PetscCall(createInteriorSolver(pc, d));
  if (!d->interface.empty()) PetscCall(MatDuplicate(Ad, MAT_DO_NOT_COPY_VALUES, &d->interiorBlock));
  PetscCall(MatCreateVecs(Ad, &d->w, &d->t));
  PetscCall(VecCreateSeqWithArray(PETSC_COMM_SELF, 1, d->rows, nullptr, &d->y));
  PetscFunctionReturn(0);
}

PetscErrorCode clearLocalSolve(SchurData* d) {
  PetscFunctionBeginUser;
  PetscCall(MatDestroy(&d->interiorBlock));
  PetscCall(KSPDestroy(&d->interiorSolver));
  for (Vec* v : {&d->w, &d->y, &d->t}) PetscCall(VecDestroy(v));
  d->lu = BandedBlockLu();
  d->work.clear();
  PetscFunctionReturn(0);
}

// A_II (A_d with the interface rows and columns replaced by the identity) factored (local; a
// failure is read after).
PetscErrorCode factorInterior(SchurData* d, Mat Ad) {
  PetscFunctionBeginUser;
  Mat interior = Ad;  // refactored when its values changed since the last factorization
  if (d->interiorBlock) {
    PetscCall(MatCopy(Ad, d->interiorBlock, SAME_NONZERO_PATTERN));
    PetscCall(MatZeroRowsColumns(d->interiorBlock, static_cast<PetscInt>(d->interface.size()), d->interface.data(),
                                 1.0, nullptr, nullptr));
    interior = d->interiorBlock;
  }
  PetscCall(KSPSetOperators(d->interiorSolver, interior, interior));
  PetscCall(KSPSetUp(d->interiorSolver));
  PetscFunctionReturn(0);
}

PCFailedReason localFailure(SchurData* d) {
  PC lu;
  PCFailedReason reason = PC_NOERROR;
  PetscCallAbort(PETSC_COMM_SELF, KSPGetPC(d->interiorSolver, &lu));
  PetscCallAbort(PETSC_COMM_SELF, PCGetFailedReason(lu, &reason));
  return reason;
}

PetscErrorCode apply(PC pc, Vec b, Vec x);

// Multiplier rows split off onto the interface need the rest of the matrix regular. Probe the
// solve once per factorization: b = A y for a fixed y, x = P^{-1} b, and the relative residual
// |A x - b| / |b|. A nearly singular interior (an ALE rope with free material coordinates: cond
// 1.5e12) left 1e-5 where a regular one leaves 1e-12 (meshes/link-and-cable.yaml: 3e-12); above
// 1e-8 the PC fails (a Newton failure that says so) instead of solving wrongly.
PetscErrorCode probeSaddlePoint(PC pc, SchurData* d, Mat P) {
  PetscFunctionBeginUser;
  Vec y, b, x;
  PetscCall(MatCreateVecs(P, &y, &b));
  PetscCall(VecDuplicate(y, &x));
  PetscInt lo, hi;
  PetscCall(VecGetOwnershipRange(y, &lo, &hi));
  PetscScalar* a;
  PetscCall(VecGetArray(y, &a));
  for (PetscInt i = lo; i < hi; ++i) a[i - lo] = 1.0 + 0.5 * std::sin(0.7 * static_cast<double>(i) + 0.3);
  PetscCall(VecRestoreArray(y, &a));
  PetscCall(MatMult(P, y, b));
  PetscCall(apply(pc, b, x));
  PetscCall(MatMult(P, x, y));  // y := A x
  PetscCall(VecAXPY(y, -1.0, b));
  PetscReal r, nb;
  PetscCall(VecNorm(y, NORM_INFINITY, &r));
  PetscCall(VecNorm(b, NORM_INFINITY, &nb));
  d->probeResidual = nb > 0.0 ? r / nb : 0.0;
  if (!(d->probeResidual <= schur::kSaddleProbeTolerance)) {
    d->failed = true;
    PetscCall(PCSetFailedReason(pc, PC_SUBPC_ERROR));
    PetscCall(PetscInfo(pc, "the matrix without its multiplier rows is nearly singular: probe residual %g; factor it "
                            "with MUMPS (-<prefix>pc_type lu -<prefix>pc_factor_mat_solver_type mumps)\n",
                        static_cast<double>(d->probeResidual)));
  }
  PetscCall(VecDestroy(&y));
  PetscCall(VecDestroy(&b));
  PetscCall(VecDestroy(&x));
  PetscFunctionReturn(0);
}

PetscErrorCode setUp(PC pc) {
  SchurData* d = dataOf(pc);
  Mat P = pc->pmat, Ad, Ao;
  PetscBool blocked;
  MPI_Comm comm = PetscObjectComm(reinterpret_cast<PetscObject>(pc));
  PetscFunctionBeginUser;
  PetscCall(PCSetFailedReason(pc, PC_NOERROR));
  if (d->built && pc->flag != SAME_NONZERO_PATTERN) PetscCall(clear(d));
  PetscCall(localBlocks(P, &Ad, &Ao, &blocked));
  if (!d->built) {
    PetscCall(findInterface(d, P));
    if (d->hubs) d->sweeps = false;  // an arrow, not a band: every rank takes the interior solve
    else if (d->multipliers) d->sweeps = false;  // no unpivoted trailing factors over a zero diagonal
    else PetscCall(schur::splitSweepsFit(d, Ad, blocked));
    if (!d->sweeps) PetscCall(prepareInteriorSolve(pc, d, Ad));
  }
  bool factored = true;
  if (d->sweeps) PetscCall(schur::factorSegment(d, Ad, &factored));
  // Local, no collective: the interior solve instead when the whole segment has a zero pivot (the
  // sweeps also pivot on the local Schur complement L_GG U_GG; A_II may still factor).
  if (d->sweeps && !factored) {
    PetscCall(clearLocalSolve(d));
    d->sweeps = false;
    d->sweepsRefused = true;
    PetscCall(prepareInteriorSolve(pc, d, Ad));
  }
  if (!d->sweeps) PetscCall(factorInterior(d, Ad));
  d->built = true;

  // a zero pivot on one rank fails the solve on all (the apply below is collective)
  const PCFailedReason reason = d->sweeps ? PC_NOERROR : localFailure(d);
  PetscMPIInt failedHere = reason != PC_NOERROR, failed;
  PetscCallMPI(MPI_Allreduce(&failedHere, &failed, 1, MPI_INT, MPI_MAX, comm));
  d->failed = failed;
  if (failed) {
    PetscCall(PCSetFailedReason(pc, failedHere ? reason : PC_SUBPC_ERROR));
    PetscFunctionReturn(0);
  }

  const PetscInt nG = static_cast<PetscInt>(d->gamma.size());
  PetscCheck(nG <= 4000, comm, PETSC_ERR_SUP,
             "PC %s: the interface has %d unknowns, too many for its dense Schur complement (this PC is for "
             "chains); use MUMPS (-pc_type lu -pc_factor_mat_solver_type mumps with the solver's prefix)",
             kPcInterfaceSchur, static_cast<int>(nG));
  // each rank's part, summed (a hub's rows take a part from every rank its row reaches): split
  // sweeps give their own rows, the interior solve its touched rows and columns
  RowMajor S = RowMajor::Zero(nG, nG);
  if (d->sweeps) {
    std::vector<PetscScalar> mine;
    PetscCall(ownSchurRows(d, P, &mine));
    std::copy(mine.begin(), mine.end(), S.data() + d->ownOffset * nG);
  } else {
    PetscCall(interiorSchur(d, P, &S));
  }
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, S.data(), static_cast<PetscMPIInt>(S.size()), MPIU_SCALAR, MPI_SUM, comm));
  d->schur.compute(S);
  // S is the same on every rank (summed above): a zero pivot of its LU (a singular matrix whose
  // zero row went onto the interface, e.g. a multiplier row without its constraint) fails all alike
  const auto pivots = d->schur.matrixLU().diagonal();
  for (Eigen::Index k = 0; k < pivots.size(); ++k)
    if (!(std::fabs(pivots[k]) > 0.0)) {
      d->failed = true;
      PetscCall(PCSetFailedReason(pc, PC_FACTOR_NUMERIC_ZEROPIVOT));
      break;
    }
  if (d->anyMultipliers && !d->failed) PetscCall(probeSaddlePoint(pc, d, P));
  PetscFunctionReturn(0);
}

// The local part of b with its interface entries zeroed, into w.
PetscErrorCode interiorPart(SchurData* d, const PetscScalar* b) {
  PetscScalar* w;
  PetscFunctionBeginUser;
  PetscCall(VecGetArray(d->w, &w));
  std::copy(b, b + d->rows, w);
  for (PetscInt r : d->interface) w[r] = 0.0;
  PetscCall(VecRestoreArray(d->w, &w));
  PetscFunctionReturn(0);
}

// y = A^{-1} b:  y_I = A_II^{-1} b_I;  S x_G = b_G - A_GI y_I;  x_I = y_I - Z x_G.
PetscErrorCode apply(PC pc, Vec b, Vec x) {
  SchurData* d = dataOf(pc);
  PetscFunctionBeginUser;
  if (d->failed) {
    PetscCall(VecSet(x, 0.0));
    PetscFunctionReturn(0);
  }
  const PetscInt mine = static_cast<PetscInt>(d->interface.size());
  const PetscScalar* bArray;
  PetscScalar* xArray;
  PetscCall(VecGetArrayRead(b, &bArray));
  if (d->sweeps) {
    PetscCall(VecGetArray(x, &xArray));
    PetscCall(schur::applySweeps(d, PetscObjectComm(reinterpret_cast<PetscObject>(pc)), bArray, xArray));
    PetscCall(VecRestoreArray(x, &xArray));
    PetscCall(VecRestoreArrayRead(b, &bArray));
    PetscFunctionReturn(0);
  }
  PetscCall(interiorPart(d, bArray));
  PetscCall(VecGetArray(x, &xArray));
  PetscCall(VecPlaceArray(d->y, xArray));
  PetscCall(KSPSolve(d->interiorSolver, d->w, d->y));  // zero on the interface rows
  PetscCall(VecResetArray(d->y));
  const PetscInt nt = static_cast<PetscInt>(d->touch.size());
  Eigen::VectorXd g = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(d->gamma.size())), xG;
  for (PetscInt i = 0; i < mine; ++i) g[d->ownOffset + i] = bArray[d->interface[i]];
  for (PetscInt k = 0; k < nt; ++k)
    for (const auto& [col, a] : d->agi[d->touch[k]]) g[d->touch[k]] -= a * xArray[col];
  PetscCall(VecRestoreArrayRead(b, &bArray));
  PetscCall(schur::interfaceSolveSummed(*d, PetscObjectComm(reinterpret_cast<PetscObject>(pc)), g, false, &xG));
  if (nt > 0) {
    Eigen::VectorXd xTouched(nt);
    for (PetscInt k = 0; k < nt; ++k) xTouched[k] = xG[d->touch[k]];
    Eigen::Map<Eigen::VectorXd>(xArray, d->Z.rows()) -= d->Z * xTouched;
  }
  for (PetscInt i = 0; i < mine; ++i) xArray[d->interface[i]] = xG[d->ownOffset + i];
  PetscCall(VecRestoreArray(x, &xArray));
  PetscFunctionReturn(0);
}

// y = A^{-T} b, every block transposed: y_I = A_II^{-T} b_I;  S^T x_G = b_G - A_IG^T y_I;
// x_I = A_II^{-T} (b_I - A_GI^T x_G), with A_IG and A_GI the touched interface unknowns' columns
// and rows in this rank's interior (aig, agi).
PetscErrorCode applyTranspose(PC pc, Vec b, Vec x) {
  SchurData* d = dataOf(pc);
  PetscFunctionBeginUser;
  if (d->failed) {
    PetscCall(VecSet(x, 0.0));
    PetscFunctionReturn(0);
  }
  const PetscInt mine = static_cast<PetscInt>(d->interface.size());
  const PetscScalar* bArray;
  PetscScalar* xArray;
  PetscCall(VecGetArrayRead(b, &bArray));
  PetscCall(VecGetArray(x, &xArray));
  if (d->sweeps) {
    PetscCall(schur::applyTransposeSweeps(d, PetscObjectComm(reinterpret_cast<PetscObject>(pc)), bArray, xArray));
    PetscCall(VecRestoreArray(x, &xArray));
    PetscCall(VecRestoreArrayRead(b, &bArray));
    PetscFunctionReturn(0);
  }
  const PetscInt nt = static_cast<PetscInt>(d->touch.size());
  PetscCall(VecPlaceArray(d->y, xArray));
  PetscCall(interiorPart(d, bArray));
  PetscCall(KSPSolveTranspose(d->interiorSolver, d->w, d->y));  // y_I
  Eigen::VectorXd g = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(d->gamma.size())), xG;
  for (PetscInt i = 0; i < mine; ++i) g[d->ownOffset + i] = bArray[d->interface[i]];
  for (PetscInt k = 0; k < nt; ++k)
    for (const auto& [row, a] : d->aig[k]) g[d->touch[k]] -= a * xArray[row];
  PetscCall(schur::interfaceSolveSummed(*d, PetscObjectComm(reinterpret_cast<PetscObject>(pc)), g, true, &xG));
  PetscScalar* w;  // b_I - A_GI^T x_G
  PetscCall(interiorPart(d, bArray));
  PetscCall(VecGetArray(d->w, &w));
  for (PetscInt k = 0; k < nt; ++k)
    for (const auto& [col, a] : d->agi[d->touch[k]]) w[col] -= a * xG[d->touch[k]];
  PetscCall(VecRestoreArray(d->w, &w));
  PetscCall(KSPSolveTranspose(d->interiorSolver, d->w, d->y));
  for (PetscInt i = 0; i < mine; ++i) xArray[d->interface[i]] = xG[d->ownOffset + i];
  PetscCall(VecResetArray(d->y));
  PetscCall(VecRestoreArray(x, &xArray));
  PetscCall(VecRestoreArrayRead(b, &bArray));
  PetscFunctionReturn(0);
}

PetscErrorCode setFromOptions(PC pc, PetscOptionItems* PetscOptionsObject) {
  SchurData* d = dataOf(pc);
  PetscBool allowed = d->sweepsAllowed ? PETSC_TRUE : PETSC_FALSE, set;
  PetscFunctionBeginUser;
  PetscOptionsHeadBegin(PetscOptionsObject, "Interface Schur complement (strand_interface_schur)");
  PetscCall(PetscOptionsBool("-pc_strand_interface_schur_split_sweeps",
                             "Solve a segment with its interface at one end by split sweeps of its LU", "InterfaceSchur.hpp",
                             allowed, &allowed, &set));
  PetscOptionsHeadEnd();
  if (set && static_cast<bool>(allowed) != d->sweepsAllowed) {
    d->sweepsAllowed = allowed;
    PetscCall(clear(d));
    pc->setupcalled = 0;  // rebuilt at the next PCSetUp, even for an unchanged operator
  }
  PetscFunctionReturn(0);
}

PetscErrorCode reset(PC pc) {
  PetscFunctionBeginUser;
  dataOf(pc)->sweepsRefused = false;  // options may have changed
  PetscCall(clear(dataOf(pc)));
  PetscFunctionReturn(0);
}

PetscErrorCode destroy(PC pc) {
  PetscFunctionBeginUser;
  PetscCall(clear(dataOf(pc)));
  delete dataOf(pc);
  pc->data = nullptr;
  PetscFunctionReturn(0);
}

PetscErrorCode view(PC pc, PetscViewer viewer) {
  SchurData* d = dataOf(pc);
  PetscBool ascii;
  PetscFunctionBeginUser;
  PetscCall(PetscObjectTypeCompare(reinterpret_cast<PetscObject>(viewer), PETSCVIEWERASCII, &ascii));
  if (!ascii || !d->built) PetscFunctionReturn(0);
  PetscCall(PetscViewerASCIIPrintf(viewer, "  interface Schur complement: %d interface unknowns\n",
                                   static_cast<int>(d->gamma.size())));
  if (d->probeResidual > 0.0)
    PetscCall(PetscViewerASCIIPrintf(viewer, "  multiplier rows on the interface: probe residual %.1e (limit %.0e)\n",
                                     d->probeResidual, schur::kSaddleProbeTolerance));
  PetscCall(PetscViewerASCIIPushSynchronized(viewer));
  PetscCall(PetscViewerASCIISynchronizedPrintf(
      viewer, "  [%d] interior unknowns %d, %s\n", static_cast<int>(PetscGlobalRank),
      static_cast<int>(d->rows - d->interface.size()),
      d->sweeps ? (d->reversed ? "split sweeps (blocks reversed)" : "split sweeps") : "interior solve with Z"));
  PetscCall(PetscViewerFlush(viewer));
  PetscCall(PetscViewerASCIIPopSynchronized(viewer));
  PetscFunctionReturn(0);
}

PetscErrorCode create(PC pc) {
  PetscFunctionBeginUser;
  pc->data = new SchurData();
  pc->ops->setup = setUp;
  pc->ops->apply = apply;
  pc->ops->applytranspose = applyTranspose;
  pc->ops->setfromoptions = setFromOptions;
  pc->ops->reset = reset;
  pc->ops->destroy = destroy;
  pc->ops->view = view;
  PetscFunctionReturn(0);
}

}  // namespace

PetscErrorCode InterfaceSchurRegister() {
  static bool registered = false;
  PetscFunctionBeginUser;
  if (!registered) PetscCall(PCRegister(kPcInterfaceSchur, create));
  registered = true;
  PetscFunctionReturn(0);
}

namespace {

// the data of a PC that must be strand_interface_schur
PetscErrorCode checkedData(PC pc, const SchurData** d) {
  PetscBool match;
  PetscFunctionBeginUser;
  PetscCall(PetscObjectTypeCompare(reinterpret_cast<PetscObject>(pc), kPcInterfaceSchur, &match));
  PetscCheck(match, PetscObjectComm(reinterpret_cast<PetscObject>(pc)), PETSC_ERR_ARG_WRONG, "PC is not %s",
             kPcInterfaceSchur);
  *d = dataOf(pc);
  PetscFunctionReturn(0);
}

}  // namespace

PetscErrorCode InterfaceSchurGetSizes(PC pc, PetscInt* interface, PetscInt* localInterior) {
  const SchurData* d = nullptr;
  PetscFunctionBeginUser;
  PetscCall(checkedData(pc, &d));
  *interface = static_cast<PetscInt>(d->gamma.size());
  *localInterior = d->rows - static_cast<PetscInt>(d->interface.size());
  PetscFunctionReturn(0);
}

PetscErrorCode InterfaceSchurProbeFailed(PC pc, PetscBool* failed) {
  PetscBool match;
  PetscFunctionBeginUser;
  *failed = PETSC_FALSE;
  PetscCall(PetscObjectTypeCompare(reinterpret_cast<PetscObject>(pc), kPcInterfaceSchur, &match));
  if (match) *failed = static_cast<PetscBool>(dataOf(pc)->probeResidual > schur::kSaddleProbeTolerance);
  PetscFunctionReturn(0);
}

PetscErrorCode InterfaceSchurGetSegmentSolve(PC pc, SegmentSolve* how) {
  const SchurData* d = nullptr;
  PetscFunctionBeginUser;
  PetscCall(checkedData(pc, &d));
  *how = !d->sweeps ? SegmentSolve::InteriorSolve : d->reversed ? SegmentSolve::ReversedSplitSweeps
                                                                 : SegmentSolve::SplitSweeps;
  PetscFunctionReturn(0);
}

}  // namespace strand::solvers
