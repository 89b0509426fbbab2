#include "common/error.hpp"
#include "sim/mesh/node_selection.hpp"
#include "sim/mesh/structured_mesh.hpp"
#include "sim/mesh/tet_shape.hpp"
#include "sim/verify/febio_reference.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <limits>
#include <set>

using namespace ligsim::sim;

namespace {

std::set<std::array<int, 4>> sorted_tets(const ligsim::Tetrahedra& T)
{
  std::set<std::array<int, 4>> tets;
  for (Eigen::Index e = 0; e < T.rows(); ++e) {
    std::array<int, 4> tet = {T(e, 0), T(e, 1), T(e, 2), T(e, 3)};
    std::sort(tet.begin(), tet.end());
    tets.insert(tet);
  }
  return tets;
}

double total_volume(const ligsim::TetMesh& mesh)
{
  double volume = 0.0;
  for (const TetShape& shape : compute_rest_shapes(mesh))
    volume += shape.V0;
  return volume;
}

} // namespace

TEST(StructuredMesh, CubeOf16IsTheFebioReferenceMesh)
{
  const FebioMesh febio = read_febio_mesh(LIGSIM_SOURCE_DIR "/data/febio-cube/mesh.txt");
  const ligsim::TetMesh ours = structured_cube_mesh(16, 1.0);
  ASSERT_EQ(ours.V.rows(), febio.mesh.V.rows());
  EXPECT_LT((ours.V - febio.mesh.V).cwiseAbs().maxCoeff(), 1e-12);
  EXPECT_EQ(sorted_tets(ours.T), sorted_tets(febio.mesh.T));
  EXPECT_EQ(nodes_on_plane(ours.V, 2, 0.0, 1e-9), febio.bottom_nodes);
  EXPECT_EQ(nodes_on_plane(ours.V, 2, 1.0, 1e-9), febio.top_nodes);
}

TEST(StructuredMesh, GeneratedMeshesArePositiveAndFillTheirVolume)
{
  EXPECT_NEAR(total_volume(structured_cube_mesh(3, 2.0)), 8.0, 1e-12);
  const ligsim::TetMesh bar = bent_bar_mesh({40, 6, 5}, {30.0, 6.0, 3.0}, 40.0);
  EXPECT_EQ(bar.T.rows(), 6000);
  // Bending about the mid-surface keeps the volume to second order in thickness / radius.
  EXPECT_NEAR(total_volume(bar), 30.0 * 6.0 * 3.0, 0.01 * 540.0);
}

TEST(RestShape, BadMeshesAreNamedInTheError)
{
  ligsim::TetMesh mesh = structured_cube_mesh(1, 1.0);
  std::swap(mesh.T(2, 0), mesh.T(2, 1));
  EXPECT_THROW(
      {
        try {
          compute_rest_shapes(mesh);
        } catch (const ligsim::InputError& e) {
          EXPECT_NE(std::string(e.what()).find("element 2"), std::string::npos) << e.what();
          EXPECT_NE(std::string(e.what()).find("inverted"), std::string::npos) << e.what();
          throw;
        }
      },
      ligsim::InputError);

  mesh = structured_cube_mesh(1, 1.0);
  mesh.V(3, 0) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(compute_rest_shapes(mesh), ligsim::InputError);

  mesh = structured_cube_mesh(1, 1.0);
  mesh.T(0, 3) = 99;
  EXPECT_THROW(compute_rest_shapes(mesh), ligsim::InputError);

  mesh = structured_cube_mesh(1, 1.0);
  mesh.V.row(mesh.T(0, 3)) = mesh.V.row(mesh.T(0, 2)); // two corners coincide
  EXPECT_THROW(compute_rest_shapes(mesh), ligsim::InputError);
}

TEST(NodeSelection, PlanesAndBoxes)
{
  const ligsim::TetMesh mesh = structured_cube_mesh(4, 1.0);
  EXPECT_EQ(nodes_on_plane(mesh.V, 0, 1.0, 1e-9).size(), 25u);
  EXPECT_EQ(nodes_in_box(mesh.V, Eigen::Vector3d(-1, -1, -1), Eigen::Vector3d(0.3, 2, 2)).size(),
            50u);
}
