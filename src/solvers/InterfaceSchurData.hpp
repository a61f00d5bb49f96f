#pragma once
// The state of the PC strand_interface_schur (include/strand/solvers/InterfaceSchur.hpp), shared
// by its two ways to solve a rank's own segment:
//  - InterfaceSchur.cpp: the PC, the interface, and the *interior solve*: an LU of A_II (RCM
//    ordering) and Z = A_II^{-1} A_IG, kept; an apply is one solve plus a pass over Z.
//  - InterfaceSchurSweeps.cpp: the *split sweeps*, for a rank whose interface sits at one end of
//    its segment (every rank of a two-rank chain, the two end ranks of a longer one): an LU of the
//    whole local block with the interface last (BandedBlockLu.hpp); an apply is one forward and one
//    backward sweep with the interface solve in between, no Z.
#include <petscksp.h>

#include <Eigen/Dense>
#include <vector>

#include "solvers/BandedBlockLu.hpp"

namespace strand::solvers::schur {

using RowMajor = Eigen::Matrix<PetscScalar, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

inline constexpr double kSaddleProbeTolerance = 1e-8;

struct SchurData {
  bool built = false, failed = false;
  PetscInt rows = 0;                // local rows
  std::vector<PetscInt> interface;  // local rows on the interface, ascending
  KSP interiorSolver = nullptr;     // the LU of A_II (interior solve)
  Vec w = nullptr, t = nullptr;     // local work vectors (interior solve)
  Vec y = nullptr;                  // a local wrapper that borrows an array (interior solve)
  // the interface over all ranks: global rows (ascending), counts and offsets per rank
  std::vector<PetscInt> gamma;
  std::vector<PetscMPIInt> counts, offsets;
  PetscInt ownOffset = 0;
  Eigen::PartialPivLU<Eigen::MatrixXd> schur;

  // Interior solve. A_II as the local diagonal block with the interface rows and columns replaced
  // by the identity: no submatrix to extract, and its solution is zero on the interface rows.
  // None without an interface (one rank): A_II is A_d.
  Mat interiorBlock = nullptr;
  // The interface unknowns this rank's interior couples to (indices into gamma, ascending): its own,
  // and hubs of other ranks. For each: its row's entries in this rank's interior columns (A_GI,
  // local column and value; a hub's come from its owner) and its column's entries in this rank's
  // interior rows (A_IG, local row and value).
  std::vector<PetscInt> touch;
  std::vector<std::vector<std::pair<PetscInt, PetscScalar>>> agi, aig;
  // Z = A_II^{-1} A_IG (the touched columns; zero rows on the interface): the interior's response
  // to unit interface values, computed for S anyway; keeping it saves the second interior solve of
  // an apply
  Eigen::MatrixXd Z;
  // Hubs: block rows coupling to more than kHubBlocks blocks of other ranks (a free pulley's row
  // reaches every element of its belt). They are interface unknowns, and a row coupling to
  // another rank only through hub columns stays interior; then every rank takes the interior
  // solve (its local block is an arrow, not a band) and S is summed over the ranks.
  bool hubs = false;
  // Multiplier rows (a zero diagonal) on this rank's interface: its segment takes the interior
  // solve, whose A_II has them replaced by the identity and whose S is factored with pivoting (the
  // split sweeps' trailing factors would meet them unpivoted: 3e-12 relative residuals on one rank,
  // 2e-6 on two, on meshes/link-and-cable.yaml)
  bool multipliers = false;
  bool anyMultipliers = false;  // on some rank (the probe below is collective)
  double probeResidual = 0.0;  // of the last set-up's probe (InterfaceSchur.cpp, probeSaddlePoint)

  // Split sweeps. The LU of the whole local diagonal block A_d in factor order, the interface last:
  // A_d's order when the interface is at the end (DofMap numbers the end segments of a chain so),
  // else its blocks reversed. Own interface row i is row factorRow[i] in factor order. Allowed
  // unless -pc_strand_interface_schur_split_sweeps false; refused after a zero pivot of A_d.
  bool sweeps = false, reversed = false, sweepsRefused = false, sweepsAllowed = true;
  PetscInt bs = 1;
  BandedBlockLu lu;
  std::vector<PetscScalar> work;  // a local vector in factor order
  std::vector<PetscInt> factorRow;
  // With the interface last, the local block factors as L U, and this rank's part of the Schur
  // complement, A_GG - A_GI A_II^{-1} A_IG (own interface rows and columns), is L_GG U_GG.
  Eigen::MatrixXd Lgg, Ugg, S00;
};

// x_G (all ranks' interface) from this rank's interface right-hand sides g: gathered, then the
// redundant dense solve with S or S^T. Collective.
PetscErrorCode interfaceSolve(const SchurData& d, MPI_Comm comm, const std::vector<PetscScalar>& g, bool transpose,
                              Eigen::VectorXd* x);
// The same from each rank's part of the full right-hand side (all interface entries), summed.
PetscErrorCode interfaceSolveSummed(const SchurData& d, MPI_Comm comm, Eigen::VectorXd& g, bool transpose,
                                    Eigen::VectorXd* x);

// Split sweeps (InterfaceSchurSweeps.cpp). splitSweepsFit decides d->sweeps for this rank from the
// interface found and the structure of A_d (the local diagonal block), and analyzes that structure
// for the LU; factorSegment factors A_d's values (*factored = false at a zero pivot) and computes
// L_GG, U_GG and S00.
PetscErrorCode splitSweepsFit(SchurData* d, Mat Ad, PetscBool blocked);
PetscErrorCode factorSegment(SchurData* d, Mat Ad, bool* factored);
// x = A^{-1} b and x = A^{-T} b on this rank's rows (local arrays); collective.
PetscErrorCode applySweeps(SchurData* d, MPI_Comm comm, const PetscScalar* b, PetscScalar* x);
PetscErrorCode applyTransposeSweeps(SchurData* d, MPI_Comm comm, const PetscScalar* b, PetscScalar* x);

}  // namespace strand::solvers::schur
