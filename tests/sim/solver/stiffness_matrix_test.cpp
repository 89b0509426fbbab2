#include "sim/mesh/quadratic_tet.hpp"
#include "sim/mesh/structured_mesh.hpp"
#include "sim/solver/stiffness_matrix.hpp"

#include "tests/sim/solver/cube_tension.hpp"

#include <gtest/gtest.h>

using namespace ligsim::sim;

namespace {

/// A deformed cube, bottom fixed, fibers along z: 10^3 hexes of linear tets (5,000: enough for
/// every worker of the parallel pass), or 5^3 of quadratic tets.
struct Deformed {
  explicit Deformed(bool quadratic = false)
      : body(quadratic ? HyperelasticBody(promote_to_quadratic(structured_cube_mesh(5, 1.0)),
                                          mcl_material(), fibers(), tet_quadrature(2))
                       : HyperelasticBody(structured_cube_mesh(10, 1.0), mcl_material(), fibers()))
      , mesh(body.mesh())
      , conditions(test::cube_tension(mesh, Eigen::Vector3d(0, 0, 0.01)))
      , dofs(body.node_count(), conditions, body.unreferenced_nodes())
      , x(body.rest_positions())
  {
    // A smooth stretch and shear, far from the rest state.
    for (int node = 0; node < body.node_count(); ++node) {
      const Eigen::Vector3d p = mesh.V.row(node).transpose();
      x.segment<3>(3 * node) += Eigen::Vector3d(0.1 * p.z() * p.z(), 0.05 * p.x(), 0.2 * p.z());
    }
  }
  static FiberField fibers()
  {
    FiberField a(1, 3);
    a << 0.0, 0.0, 1.03;
    return a;
  }

  HyperelasticBody body;
  ligsim::TetMesh mesh; ///< every node
  BoundaryConditions conditions;
  DofPartition dofs;
  Eigen::VectorXd x;
};

/// Checks the assembled matrix of `d` against its elements' stiffnesses, N nodes per element.
template <int N> void expect_the_parallel_pass_sums_the_element_stiffnesses(const Deformed& d)
{
  StiffnessMatrix K(d.body.elements(), d.dofs);
  K.set_zero();
  const double scale = 0.5;
  BodyEnergy energy;
  Eigen::VectorXd gradient;
  const int projected = K.add_elements(d.body, d.x, true, scale, &energy, &gradient);

  // Element by element, serially, into a free-DOF matrix of both triangles.
  const int n = d.dofs.free_count();
  std::vector<Eigen::Triplet<double>> entries;
  int reference_projected = 0;
  NodalEvaluation<N> evaluation;
  const ElementNodes& T = d.body.elements();
  for (Eigen::Index e = 0; e < d.body.element_count(); ++e) {
    reference_projected += d.body.element_hessian(d.x, e, true, evaluation) ? 1 : 0;
    for (int p = 0; p < 3 * N; ++p)
      for (int q = 0; q < 3 * N; ++q) {
        const int fp = d.dofs.free_index(3 * T(e, p / 3) + p % 3);
        const int fq = d.dofs.free_index(3 * T(e, q / 3) + q % 3);
        if (fp >= 0 && fq >= 0)
          entries.emplace_back(fp, fq, scale * evaluation.hessian(p, q));
      }
  }
  Eigen::SparseMatrix<double> reference(n, n);
  reference.setFromTriplets(entries.begin(), entries.end());
  EXPECT_EQ(projected, reference_projected);
  EXPECT_GT(projected, 0) << "the deformation should need some projections";
  const Eigen::SparseMatrix<double> assembled = K.matrix().selfadjointView<Eigen::Lower>();
  EXPECT_LT((assembled - reference).norm(), 1e-13 * reference.norm());

  // Energy and gradient exactly as the body's own pass gives them.
  Eigen::VectorXd expected_gradient;
  const BodyEnergy expected = d.body.energy_gradient(d.x, expected_gradient);
  EXPECT_EQ(energy.energy, expected.energy);
  EXPECT_EQ(gradient, expected_gradient);
}

} // namespace

TEST(StiffnessMatrix, TheParallelPassSumsTheElementStiffnesses)
{
  expect_the_parallel_pass_sums_the_element_stiffnesses<4>(Deformed());
}

TEST(StiffnessMatrix, TheParallelPassSumsQuadraticTetStiffnesses)
{
  const Deformed d(true);
  ASSERT_EQ(d.body.nodes_per_element(), 10);
  expect_the_parallel_pass_sums_the_element_stiffnesses<10>(d);
}

TEST(StiffnessMatrix, AnInvertedElementIsReportedAndLeftOut)
{
  Deformed d;
  // Push one node through the opposite face of the elements around it.
  d.x(3 * 555 + 2) -= 0.5;
  StiffnessMatrix K(d.body.elements(), d.dofs);
  K.set_zero();
  BodyEnergy energy;
  K.add_elements(d.body, d.x, false, 1.0, &energy, nullptr);
  const BodyEnergy expected = d.body.energy(d.x);
  EXPECT_FALSE(std::isfinite(energy.energy));
  EXPECT_EQ(energy.first_inverted, expected.first_inverted);
  EXPECT_GE(energy.first_inverted, 0);
}
