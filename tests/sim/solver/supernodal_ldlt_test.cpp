#include "sim/solver/supernodal_ldlt.hpp"

#include <Eigen/Eigenvalues>
#include <Eigen/SparseCore>

#include <gtest/gtest.h>

#include <random>

using ligsim::sim::SupernodalLdlt;

namespace {

/// The lower triangle of a symmetric matrix with 3 x 3 blocks coupling the nodes of an
/// n x n x n grid to their 26 neighbours (the pattern of a stiffness matrix), random
/// entries, plus `shift` on the diagonal (large: positive definite; negative: indefinite).
Eigen::SparseMatrix<double> grid_matrix(int n, double shift, unsigned seed)
{
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> entry(-1.0, 1.0);
  auto node = [n](int i, int j, int k) { return (i * n + j) * n + k; };
  std::vector<Eigen::Triplet<double>> triplets;
  const int size = 3 * n * n * n;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      for (int k = 0; k < n; ++k)
        for (int di = 0; di <= 1; ++di)
          for (int dj = -1; dj <= 1; ++dj)
            for (int dk = -1; dk <= 1; ++dk) {
              const int a = node(i, j, k);
              if (i + di >= n || j + dj < 0 || j + dj >= n || k + dk < 0 || k + dk >= n)
                continue;
              const int b = node(i + di, j + dj, k + dk);
              if (b < a)
                continue;
              for (int p = 0; p < 3; ++p)
                for (int q = 0; q < 3; ++q) {
                  const int row = 3 * b + q;
                  const int column = 3 * a + p;
                  if (row >= column)
                    triplets.emplace_back(row, column, entry(random));
                }
            }
  for (int d = 0; d < size; ++d)
    triplets.emplace_back(d, d, shift);
  Eigen::SparseMatrix<double> lower(size, size);
  lower.setFromTriplets(triplets.begin(), triplets.end());
  lower.makeCompressed();
  return lower;
}

Eigen::MatrixXd dense(const Eigen::SparseMatrix<double>& lower)
{
  const Eigen::SparseMatrix<double> full = lower.selfadjointView<Eigen::Lower>();
  return Eigen::MatrixXd(full);
}

double relative_residual(const Eigen::SparseMatrix<double>& lower, const Eigen::VectorXd& x,
                         const Eigen::VectorXd& b)
{
  const Eigen::VectorXd Ax = lower.selfadjointView<Eigen::Lower>() * x;
  return (Ax - b).norm() / b.norm();
}

} // namespace

TEST(SupernodalLdlt, SolvesAPositiveDefiniteMatrixWithoutNegativePivots)
{
  const Eigen::SparseMatrix<double> A = grid_matrix(7, 30.0, 1);
  SupernodalLdlt ldlt;
  ldlt.analyze(A);
  ASSERT_TRUE(ldlt.factorize(A));
  EXPECT_EQ(ldlt.negative_pivots(), 0);
  const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(A.rows(), -1.0, 2.0);
  const Eigen::VectorXd x = ldlt.solve(b);
  EXPECT_LT(relative_residual(A, x, b), 1e-13);
  // The same as a dense solve.
  const Eigen::VectorXd reference = dense(A).llt().solve(b);
  EXPECT_LT((x - reference).norm(), 1e-12 * reference.norm());
  // Pivots multiply to the determinant (compared through logarithms).
  const double log_det = ldlt.pivots().array().log().sum();
  const double reference_log_det = dense(A).llt().matrixLLT().diagonal().array().log().sum() * 2;
  EXPECT_NEAR(log_det, reference_log_det, 1e-9 * std::abs(reference_log_det));
}

TEST(SupernodalLdlt, CountsTheNegativeEigenvaluesOfAnIndefiniteMatrix)
{
  for (double shift : {-1.0, 0.5, 2.0}) {
    const Eigen::SparseMatrix<double> A = grid_matrix(6, shift, 2);
    SupernodalLdlt ldlt;
    ldlt.analyze(A);
    ASSERT_TRUE(ldlt.factorize(A)) << "shift " << shift;
    const Eigen::VectorXd eigenvalues =
        Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(dense(A), Eigen::EigenvaluesOnly)
            .eigenvalues();
    const int negative = static_cast<int>((eigenvalues.array() < 0.0).count());
    EXPECT_GT(negative, 0);
    EXPECT_EQ(ldlt.negative_pivots(), negative) << "shift " << shift;
    const Eigen::VectorXd b = Eigen::VectorXd::Ones(A.rows());
    // No pivoting: accurate while no pivot is tiny; these matrices have none.
    EXPECT_LT(relative_residual(A, ldlt.solve(b), b), 1e-8) << "shift " << shift;
  }
}

TEST(SupernodalLdlt, RefactorisesNewValuesOnTheAnalysedPattern)
{
  const Eigen::SparseMatrix<double> first = grid_matrix(5, 30.0, 3);
  const Eigen::SparseMatrix<double> second = grid_matrix(5, 20.0, 4);
  SupernodalLdlt ldlt;
  ldlt.analyze(first);
  ASSERT_TRUE(ldlt.factorize(first));
  ASSERT_TRUE(ldlt.factorize(second));
  const Eigen::VectorXd b = Eigen::VectorXd::Ones(second.rows());
  EXPECT_LT(relative_residual(second, ldlt.solve(b), b), 1e-13);
}

TEST(SupernodalLdlt, SinglePrecisionSolvesToFloatAccuracyUntilTheNextFactorisation)
{
  const Eigen::SparseMatrix<double> A = grid_matrix(7, 30.0, 8);
  SupernodalLdlt ldlt;
  ldlt.analyze(A);
  ASSERT_TRUE(ldlt.factorize(A));
  const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(A.rows(), -1.0, 2.0);
  const Eigen::VectorXd exact = ldlt.solve(b);
  EXPECT_FALSE(ldlt.single_precision());
  ldlt.to_single_precision();
  ASSERT_TRUE(ldlt.single_precision());
  const Eigen::VectorXd single = ldlt.solve(b);
  // Float rounding (2^-24 = 6e-8) through a well-conditioned factor, but not double accuracy.
  EXPECT_LT(relative_residual(A, single, b), 1e-5);
  EXPECT_GT((single - exact).norm(), 1e-12 * exact.norm());
  EXPECT_EQ(ldlt.negative_pivots(), 0); // the pivots stay
  ASSERT_TRUE(ldlt.factorize(A));       // back to double precision
  EXPECT_FALSE(ldlt.single_precision());
  EXPECT_LT(relative_residual(A, ldlt.solve(b), b), 1e-13);
}

TEST(SupernodalLdlt, FactorsOfOnePatternShareTheLastAnalysis)
{
  const Eigen::SparseMatrix<double> first = grid_matrix(5, 30.0, 6);
  const Eigen::SparseMatrix<double> same_pattern = grid_matrix(5, 20.0, 7);
  const Eigen::SparseMatrix<double> other_pattern = grid_matrix(4, 30.0, 8);
  SupernodalLdlt a;
  a.analyze(first);
  SupernodalLdlt b;
  b.analyze(same_pattern);
  EXPECT_EQ(&a.symbolic(), &b.symbolic());
  SupernodalLdlt c;
  c.analyze(other_pattern);
  EXPECT_NE(&c.symbolic(), &a.symbolic());
  // The last analysis is the other pattern's now: a new factor of the first pattern analyses
  // it again, and every factor still solves its own matrix.
  SupernodalLdlt d;
  d.analyze(first);
  EXPECT_NE(&d.symbolic(), &a.symbolic());
  const std::vector<std::pair<SupernodalLdlt*, const Eigen::SparseMatrix<double>*>> cases = {
      {&a, &first}, {&b, &same_pattern}, {&c, &other_pattern}, {&d, &first}};
  for (const auto& [ldlt, matrix] : cases) {
    ASSERT_TRUE(ldlt->factorize(*matrix));
    const Eigen::VectorXd rhs = Eigen::VectorXd::LinSpaced(matrix->rows(), 1.0, 2.0);
    EXPECT_LT(relative_residual(*matrix, ldlt->solve(rhs), rhs), 1e-12);
  }
}

TEST(SupernodalLdlt, AZeroPivotFailsTheFactorisation)
{
  Eigen::SparseMatrix<double> A = grid_matrix(4, 30.0, 5);
  // Row and column 7 become zero: the matrix is singular with a zero pivot wherever 7 is
  // eliminated.
  for (int column = 0; column < A.outerSize(); ++column)
    for (Eigen::SparseMatrix<double>::InnerIterator it(A, column); it; ++it)
      if (it.row() == 7 || it.col() == 7)
        it.valueRef() = 0.0;
  SupernodalLdlt ldlt;
  ldlt.analyze(A);
  EXPECT_FALSE(ldlt.factorize(A));
  EXPECT_FALSE(ldlt.ok());
  EXPECT_EQ(ldlt.negative_pivots(), -1);
}
