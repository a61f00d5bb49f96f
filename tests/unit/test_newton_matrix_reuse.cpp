// When the dynamics buy a new Newton matrix (NewtonMatrixReuse): the contraction rule and the
// ski-rental rule on the iterations a kept matrix costs beyond the 2 it needs at least.
//
// The solves here are fed as stopping-test histories: a kept matrix that contracts by 0.01 per
// iteration (below the contraction rule's 0.1, so only the rent can buy a new one).
//
// requirement: the first solve builds the matrix at its first iterate; a matrix is never bought
//   for the rent at a step's first iterate (the predictor's spurious forces, the header), but at
//   its second;
// requirement: solves of 2 iterations pay no rent and never buy;
// requirement: solves of 3 iterations pay 1 each: with price 8, 8 of them buy a matrix at the
//   next solve's second iterate; the rent starts again from 0;
// requirement: a bought matrix after which the next solve takes 2 iterations keeps the price; one
//   after which it still takes 3 doubles it (16, 32, then capped at 8 x 8 = 64), and a later one
//   that pays restores 8;
// requirement: the solve after a bought matrix is not judged when it rebuilt the matrix itself (new
//   Newton shifts) or when the buying solve failed and was retried with full Newton;
// requirement: price 0 never buys; the contraction rule still rebuilds.
#include <gtest/gtest.h>

#include <vector>

#include "strand/solvers/NewtonMatrixReuse.hpp"

using namespace strand::solvers;

namespace {

constexpr PetscReal kShiftA = 4e6, kShiftV = 2e3;

// One solve of n iterations; returns the iterates at which a matrix was (re)built.
std::vector<int> solve(NewtonMatrixReuse& reuse, int n, PetscReal contraction = 0.01, PetscReal shiftA = kShiftA) {
  NewtonFloor h;
  h.fnorm0 = 1.0;
  std::vector<int> built;
  for (int it = 0; it < n; ++it) {
    h.iteration = it;
    h.fnorm = it == 0 ? 1.0 : contraction;
    h.previousStep = 1.0;
    h.step = contraction;
    if (reuse.decideAt(it, h, shiftA, kShiftV)) built.push_back(it);
  }
  return built;
}

}  // namespace

TEST(NewtonMatrixReuse, TwoIterationSolvesKeepTheMatrix) {
  NewtonMatrixReuse reuse(0.1, 8.0);
  EXPECT_EQ(solve(reuse, 2), std::vector<int>{0});  // the first matrix
  for (int k = 0; k < 200; ++k) EXPECT_TRUE(solve(reuse, 2).empty()) << "solve " << k;
  EXPECT_EQ(reuse.rebuilds(), 1);
}

TEST(NewtonMatrixReuse, ExtraIterationsBuyAMatrixAtThePriceAtTheSecondIterate) {
  NewtonMatrixReuse reuse(0.1, 8.0);
  EXPECT_EQ(solve(reuse, 3), std::vector<int>{0});   // built here: no rent for this solve
  for (int k = 0; k < 8; ++k) EXPECT_TRUE(solve(reuse, 3).empty()) << "solve " << k;  // rent 1 each
  EXPECT_EQ(solve(reuse, 3), std::vector<int>{1});   // rent 8 = price: bought at the second iterate
  EXPECT_TRUE(solve(reuse, 2).empty());              // it paid (judged at the next solve's start)
  EXPECT_TRUE(solve(reuse, 3).empty());
  EXPECT_EQ(reuse.currentPrice(), 8.0);              // the price stays
  for (int k = 0; k < 6; ++k) EXPECT_TRUE(solve(reuse, 3).empty()) << "solve " << k;  // the rent from 0
  EXPECT_TRUE(solve(reuse, 3).empty());  // the 8th is paid at the next solve's start
  EXPECT_EQ(solve(reuse, 3), std::vector<int>{1});
  EXPECT_EQ(reuse.rebuilds(), 3);
}

TEST(NewtonMatrixReuse, AMatrixThatDoesNotPayDoublesThePrice) {
  NewtonMatrixReuse reuse(0.1, 8.0);
  solve(reuse, 3);
  for (int k = 0; k < 8; ++k) solve(reuse, 3);
  EXPECT_EQ(solve(reuse, 3), std::vector<int>{1});  // bought; the next solve still takes 3
  int sinceBuy = 0;
  std::vector<int> gaps;  // solves between buys
  for (int k = 0; k < 300 && gaps.size() < 4; ++k) {
    ++sinceBuy;
    if (!solve(reuse, 3).empty()) gaps.push_back(sinceBuy), sinceBuy = 0;
  }
  // 16 extra iterations, paid by the 16 solves after the bought one, buy at the 17th; then 32, and
  // 64 = kMaxPriceFactor x 8 twice
  EXPECT_EQ(gaps, (std::vector<int>{17, 33, 65, 65}));
  EXPECT_EQ(reuse.currentPrice(), 64.0);
  EXPECT_TRUE(solve(reuse, 2).empty());  // the last bought one pays at last (judged at the next start)
  solve(reuse, 2);
  EXPECT_EQ(reuse.currentPrice(), 8.0);
}

TEST(NewtonMatrixReuse, PriceZeroNeverBuysButTheContractionRuleRebuilds) {
  NewtonMatrixReuse reuse(0.1, 0.0);
  solve(reuse, 3);
  for (int k = 0; k < 100; ++k) EXPECT_TRUE(solve(reuse, 3).empty()) << "solve " << k;
  EXPECT_EQ(solve(reuse, 3, 0.5), (std::vector<int>{1, 2}));  // contracting by 0.5: stale at once
  EXPECT_EQ(reuse.rebuilds(), 3);
}

TEST(NewtonMatrixReuse, ASolveThatRebuiltItselfOrARetryIsNotJudged) {
  NewtonMatrixReuse reuse(0.1, 8.0);
  solve(reuse, 3);
  for (int k = 0; k < 8; ++k) solve(reuse, 3);
  EXPECT_EQ(solve(reuse, 3), std::vector<int>{1});                     // bought
  EXPECT_EQ(solve(reuse, 3, 0.01, 2.0 * kShiftA), std::vector<int>{0});  // a new step size: rebuilt at once
  EXPECT_TRUE(solve(reuse, 3, 0.01, 2.0 * kShiftA).empty());
  EXPECT_EQ(reuse.currentPrice(), 8.0);  // not doubled: the bought matrix was never used alone

  for (int k = 0; k < 7; ++k) EXPECT_TRUE(solve(reuse, 3, 0.01, 2.0 * kShiftA).empty()) << "solve " << k;
  EXPECT_EQ(solve(reuse, 3, 0.01, 2.0 * kShiftA), std::vector<int>{1});  // bought; say this solve failed
  EXPECT_TRUE(reuse.retryWithFullNewton());
  EXPECT_EQ(solve(reuse, 3, 0.01, 2.0 * kShiftA), (std::vector<int>{0, 1, 2}));  // the full-Newton retry
  solve(reuse, 3, 0.01, 2.0 * kShiftA);
  EXPECT_EQ(reuse.currentPrice(), 8.0);
}
