// The block LU of a chain segment (BandedBlockLu.hpp).
#include "solvers/BandedBlockLu.hpp"

#include <algorithm>
#include <type_traits>

namespace strand::solvers {

namespace {

template <int BS>
using Block = Eigen::Matrix<PetscScalar, BS, BS>;
template <int BS>
using Piece = Eigen::Matrix<PetscScalar, BS, 1>;

// D^{-1} in place; false when D is singular (an exact zero pivot, as PETSc's BAIJ LU reports) or
// its inverse overflows.
template <int BS>
bool invertInPlace(PetscScalar* d) {
  Eigen::Map<Block<BS>> D(d);
  Block<BS> inverse;
  if constexpr (BS <= 4) {  // Eigen's closed forms for fixed sizes up to 4
    bool invertible;
    PetscScalar det;
    D.computeInverseAndDetWithCheck(inverse, det, invertible, 0.0);
    if (!invertible) return false;
  } else {
    Eigen::PartialPivLU<Block<BS>> lu(D);
    if (lu.determinant() == 0.0) return false;
    inverse = lu.inverse();
  }
  if (!inverse.allFinite()) return false;
  D = inverse;
  return true;
}

}  // namespace

PetscErrorCode BandedBlockLu::analyze(Mat A, bool reversed) {
  PetscInt n;
  const PetscInt *ia, *ja;
  PetscBool done;
  PetscFunctionBeginUser;
  PetscCall(MatGetBlockSize(A, &_bs));
  PetscCheck(supports(_bs), PETSC_COMM_SELF, PETSC_ERR_SUP, "banded block LU: no kernel for blocks of %d",
             static_cast<int>(_bs));
  PetscCall(MatGetRowIJ(A, 0, PETSC_FALSE, PETSC_TRUE, &n, &ia, &ja, &done));
  PetscCheck(done, PETSC_COMM_SELF, PETSC_ERR_SUP, "banded block LU: no block row structure");
  _n = n;
  const auto position = [&](PetscInt r) { return reversed ? n - 1 - r : r; };
  _first.resize(n);
  _last.resize(n);
  for (PetscInt i = 0; i < n; ++i) _first[i] = _last[i] = i;  // the diagonal block always
  for (PetscInt r = 0; r < n; ++r)
    for (PetscInt k = ia[r]; k < ia[r + 1]; ++k) {
      const PetscInt i = position(r), j = position(ja[k]);
      _first[i] = std::min(_first[i], j);
      _last[i] = std::max(_last[i], j);
    }
  for (PetscInt i = 0; i < n; ++i)  // U's fill: row i's U part reaches as far as the rows it combines
    for (PetscInt k = _first[i]; k < i; ++k) _last[i] = std::max(_last[i], _last[k]);
  _lowerStart.assign(n + 1, 0);
  _upperStart.assign(n + 1, 0);
  for (PetscInt i = 0; i < n; ++i) {
    _lowerStart[i + 1] = _lowerStart[i] + i - _first[i];
    _upperStart[i + 1] = _upperStart[i] + _last[i] - i + 1;
  }
  _lower.assign(static_cast<size_t>(_lowerStart[n] * _bs * _bs), 0.0);
  _upper.assign(static_cast<size_t>(_upperStart[n] * _bs * _bs), 0.0);
  _slot.resize(ia[n]);
  for (PetscInt r = 0; r < n; ++r)
    for (PetscInt k = ia[r]; k < ia[r + 1]; ++k) _slot[k] = block(position(r), position(ja[k]));
  // the blocks no entry of A fills (the fill, and absent diagonal blocks): zeroed at a factorization
  std::vector<char> filled(_lowerStart[n] + _upperStart[n], 0);
  const auto indexOf = [this, n](const PetscScalar* p) {  // the block's number, L's then U's
    const bool lower = p >= _lower.data() && p < _lower.data() + _lower.size();
    return (lower ? p - _lower.data() : p - _upper.data()) / (_bs * _bs) + (lower ? 0 : _lowerStart[n]);
  };
  for (PetscScalar* p : _slot) filled[indexOf(p)] = 1;
  _fill.clear();
  for (PetscInt i = 0; i < n; ++i)
    for (PetscInt j = _first[i]; j <= _last[i]; ++j)
      if (!filled[indexOf(block(i, j))]) _fill.push_back(block(i, j));
  PetscCall(MatRestoreRowIJ(A, 0, PETSC_FALSE, PETSC_TRUE, &n, &ia, &ja, &done));
  PetscFunctionReturn(0);
}

// Doolittle by block rows, in place on the profile (the header's reference):
//   L_ij = (A_ij - sum_{k<j} L_ik U_kj) U_jj^{-1}  for first(i) <= j < i,
//   U_ij =  A_ij - sum_{k<i} L_ik U_kj            for i <= j <= last(i),
// with U_kj = 0 outside row k's profile (j > last(k)).
template <int BS>
PetscInt BandedBlockLu::factorBlocks() {
  using Map = Eigen::Map<Block<BS>>;
  const auto at = [this](PetscInt i, PetscInt j) { return Map(block(i, j)); };
  for (PetscInt i = 0; i < _n; ++i) {
    const PetscInt first = _first[i];
    for (PetscInt j = first; j < i; ++j) {
      Map lij = at(i, j);
      for (PetscInt k = first; k < j; ++k)
        if (j <= _last[k]) lij.noalias() -= at(i, k) * at(k, j);
      lij = (lij * at(j, j)).eval();  // U_jj is held inverted
    }
    for (PetscInt j = i; j <= _last[i]; ++j) {
      Map uij = at(i, j);
      for (PetscInt k = first; k < i; ++k)
        if (j <= _last[k]) uij.noalias() -= at(i, k) * at(k, j);
    }
    if (!invertInPlace<BS>(block(i, i))) return i;
  }
  return -1;
}

template <int BS>
void BandedBlockLu::forwardBlocks(const PetscScalar* b, PetscScalar* y) const {
  using Matrix = Eigen::Map<const Block<BS>>;
  using Vector = Eigen::Map<const Piece<BS>>;
  const PetscScalar* l = _lower.data();  // row after row
  for (PetscInt i = 0; i < _n; ++i) {     // y_i = b_i - sum_{j<i} L_ij y_j
    Piece<BS> yi = Vector(b + BS * i);
    for (PetscInt j = _first[i]; j < i; ++j, l += BS * BS) yi.noalias() -= Matrix(l) * Vector(y + BS * j);
    Eigen::Map<Piece<BS>>(y + BS * i) = yi;
  }
}

template <int BS>
void BandedBlockLu::backwardBlocks(const PetscScalar* y, PetscScalar* x) const {
  using Matrix = Eigen::Map<const Block<BS>>;
  using Vector = Eigen::Map<const Piece<BS>>;
  for (PetscInt i = _n - 1; i >= 0; --i) {  // x_i = U_ii^{-1} (y_i - sum_{j>i} U_ij x_j)
    const PetscScalar* u = &_upper[BS * BS * _upperStart[i]];  // U_ii^{-1}, then U_i,i+1 ...
    Piece<BS> r = Vector(y + BS * i);
    for (PetscInt j = i + 1; j <= _last[i]; ++j) r.noalias() -= Matrix(u + BS * BS * (j - i)) * Vector(x + BS * j);
    Eigen::Map<Piece<BS>>(x + BS * i).noalias() = Matrix(u) * r;
  }
}

// A^T = U^T L^T: U^T z = b by ascending rows, then L^T x = z by descending rows, each row's result
// subtracted from the later rows it reaches (row storage read column-wise).
template <int BS>
void BandedBlockLu::solveTransposeBlocks(PetscScalar* x) const {
  using Matrix = Eigen::Map<const Block<BS>>;
  using Vector = Eigen::Map<Piece<BS>>;
  for (PetscInt i = 0; i < _n; ++i) {
    const Piece<BS> z = Matrix(block(i, i)).transpose() * Vector(x + BS * i);
    Vector(x + BS * i) = z;
    for (PetscInt j = i + 1; j <= _last[i]; ++j) Vector(x + BS * j).noalias() -= Matrix(block(i, j)).transpose() * z;
  }
  for (PetscInt i = _n - 1; i >= 0; --i) {
    const Piece<BS> xi = Vector(x + BS * i);
    for (PetscInt j = _first[i]; j < i; ++j) Vector(x + BS * j).noalias() -= Matrix(block(i, j)).transpose() * xi;
  }
}

// The kernel for the block size (supports()).
template <typename Call>
auto BandedBlockLu::dispatch(PetscInt bs, const Call& call) {
  switch (bs) {
    case 1: return call(std::integral_constant<int, 1>{});
    case 2: return call(std::integral_constant<int, 2>{});
    case 3: return call(std::integral_constant<int, 3>{});
    case 4: return call(std::integral_constant<int, 4>{});
    case 5: return call(std::integral_constant<int, 5>{});
    default: return call(std::integral_constant<int, 6>{});
  }
}

PetscErrorCode BandedBlockLu::factor(Mat A, PetscInt* zeroPivot) {
  PetscScalar* a;
  PetscFunctionBeginUser;
  const PetscInt bs2 = _bs * _bs;
  for (PetscScalar* p : _fill) std::fill(p, p + bs2, 0.0);
  PetscCall(MatSeqBAIJGetArray(A, &a));
  for (size_t k = 0; k < _slot.size(); ++k) std::copy(a + bs2 * k, a + bs2 * (k + 1), _slot[k]);
  PetscCall(MatSeqBAIJRestoreArray(A, &a));
  *zeroPivot = dispatch(_bs, [this](auto bs) { return factorBlocks<decltype(bs)::value>(); });
  PetscFunctionReturn(0);
}

void BandedBlockLu::forward(const PetscScalar* b, PetscScalar* y) const {
  dispatch(_bs, [&](auto bs) { forwardBlocks<decltype(bs)::value>(b, y); });
}

void BandedBlockLu::backward(const PetscScalar* y, PetscScalar* x) const {
  dispatch(_bs, [&](auto bs) { backwardBlocks<decltype(bs)::value>(y, x); });
}

void BandedBlockLu::solveTransposeInPlace(PetscScalar* x) const {
  dispatch(_bs, [&](auto bs) { solveTransposeBlocks<decltype(bs)::value>(x); });
}

void BandedBlockLu::trailingFactors(PetscInt m, Eigen::MatrixXd* L, Eigen::MatrixXd* U) const {
  const PetscInt bs = _bs, i0 = _n - m / bs;
  L->setIdentity(m, m);
  U->setZero(m, m);
  for (PetscInt i = i0; i < _n; ++i)
    for (PetscInt j = std::max(_first[i], i0); j <= _last[i]; ++j) {
      const Eigen::Map<const Eigen::MatrixXd> b(block(i, j), bs, bs);
      auto to = (j < i ? L : U)->block((i - i0) * bs, (j - i0) * bs, bs, bs);
      if (j == i) to = b.inverse();  // held inverted
      else to = b;
    }
}

}  // namespace strand::solvers
