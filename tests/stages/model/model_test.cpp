#include "common/error.hpp"
#include "common/tet_faces.hpp"
#include "stages/model/model.hpp"
#include "stages/synthetic/shapes.hpp"

#include <gtest/gtest.h>

namespace ligsim::model {
namespace {

/// A bar of nx x side x side nodes, 1 mm apart from the origin, each cube cut into the six tets
/// of its main diagonal: with side 3 its only interior nodes are (i, 1, 1).
TetMesh bar(int nx, int side = 3)
{
  const auto node = [side](int i, int j, int k) { return (i * side + j) * side + k; };
  TetMesh mesh;
  mesh.V.resize(nx * side * side, 3);
  for (int i = 0; i < nx; ++i)
    for (int j = 0; j < side; ++j)
      for (int k = 0; k < side; ++k)
        mesh.V.row(node(i, j, k)) << i, j, k;
  const int paths[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
  std::vector<Eigen::RowVector4i> tets;
  for (int i = 0; i + 1 < nx; ++i)
    for (int j = 0; j + 1 < side; ++j)
      for (int k = 0; k + 1 < side; ++k)
        for (const auto& path : paths) {
          int c[3] = {i, j, k};
          Eigen::RowVector4i tet;
          tet[0] = node(c[0], c[1], c[2]);
          for (int s = 0; s < 3; ++s) {
            ++c[path[s]];
            tet[s + 1] = node(c[0], c[1], c[2]);
          }
          tets.push_back(tet);
        }
  mesh.T.resize(static_cast<Eigen::Index>(tets.size()), 4);
  for (std::size_t t = 0; t < tets.size(); ++t)
    mesh.T.row(static_cast<Eigen::Index>(t)) = tets[t];
  return mesh;
}

/// The bar as a model whose tibial footprint is its boundary nodes with x <= `end_mm` and whose
/// femoral footprint is its boundary nodes at the far end.
Model bar_model(int nx, double end_mm, int side = 3)
{
  Model model;
  model.mesh = bar(nx, side);
  const std::vector<bool> boundary = boundary_nodes(model.mesh);
  for (Eigen::Index v = 0; v < model.mesh.V.rows(); ++v) {
    const double x = model.mesh.V(v, 0);
    model.tibia_nodes.push_back(boundary[v] && x <= end_mm);
    model.femur_nodes.push_back(boundary[v] && x >= nx - 1);
  }
  return model;
}

int node_at(int i)
{
  return (i * 3 + 1) * 3 + 1;
}

TEST(FootprintClosing, InteriorNodesInsideTheBoneAmongTheFootprintJoinIt)
{
  Model model = bar_model(9, 2.0);
  ASSERT_FALSE(model.tibia_nodes[node_at(1)]);
  ASSERT_FALSE(model.tibia_nodes[node_at(2)]);
  // The tibia holds the bar up to x = 2.5: the interior nodes at x = 1 and 2 lie in it, the
  // first with 13 of its 14 neighbours bound, the second with 10 once the first has joined.
  const TriangleSurface tibia = synthetic::box({-5, -5, -5}, {2.5, 10, 10});
  const FootprintClosing closed = close_footprints_in_bones(model, nullptr, &tibia);
  EXPECT_EQ(closed.tibia_nodes, 2);
  EXPECT_EQ(closed.femur_nodes, 0);
  EXPECT_TRUE(model.tibia_nodes[node_at(1)]);
  EXPECT_TRUE(model.tibia_nodes[node_at(2)]);
  EXPECT_FALSE(model.tibia_nodes[node_at(3)]);
}

TEST(FootprintClosing, ANodeOutsideTheBoneStaysFreeHoweverItIsSurrounded)
{
  Model model = bar_model(9, 2.0);
  // The bone ends at x = 1.5: the node at x = 2 is surrounded by the footprint but not in bone.
  const TriangleSurface tibia = synthetic::box({-5, -5, -5}, {1.5, 10, 10});
  EXPECT_EQ(close_footprints_in_bones(model, nullptr, &tibia).tibia_nodes, 1);
  EXPECT_TRUE(model.tibia_nodes[node_at(1)]);
  EXPECT_FALSE(model.tibia_nodes[node_at(2)]);
}

TEST(FootprintClosing, ALigamentLyingInTheBoneAwayFromItsFootprintStaysFree)
{
  Model model = bar_model(9, 0.0);
  // The whole bar lies in the bone, but only its x = 0 face is bound: every interior node has
  // more free neighbours than bound ones. Only the interior node next to the face joins (the
  // one ring of interior nodes in the bone that contact cannot push out), no further one.
  const TriangleSurface tibia = synthetic::box({-5, -5, -5}, {20, 10, 10});
  std::vector<bool> expected = model.tibia_nodes;
  expected[static_cast<std::size_t>(node_at(1))] = true;
  EXPECT_EQ(close_footprints_in_bones(model, nullptr, &tibia).tibia_nodes, 1);
  EXPECT_EQ(model.tibia_nodes, expected);
}

TEST(FootprintClosing, TheInteriorRingJoinsOnlyInsideTheBone)
{
  Model model = bar_model(9, 0.0);
  // The bone ends at x = 0.5: the interior node at x = 1 shares tets with the footprint but lies
  // outside the bone, so contact can hold it out like the surface: it stays free.
  const TriangleSurface tibia = synthetic::box({-5, -5, -5}, {0.5, 10, 10});
  EXPECT_EQ(close_footprints_in_bones(model, nullptr, &tibia).tibia_nodes, 0);
  EXPECT_FALSE(model.tibia_nodes[node_at(1)]);
}

TEST(FootprintClosing, DeeperRingsJoinOnlyAwayFromTheFreeSurface)
{
  // A 5 x 5 bar bound at its x = 0 face, in a bone up to x = 2.5: the first ring (the nine
  // interior nodes at x = 1) joins; of the interior nodes at x = 2 only the middle one, whose
  // neighbours are all interior, joins; the others touch the free surface at x = 2.
  Model model = bar_model(9, 0.0, 5);
  const auto node = [](int i, int j, int k) { return (i * 5 + j) * 5 + k; };
  const TriangleSurface tibia = synthetic::box({-5, -5, -5}, {2.5, 10, 10});
  EXPECT_EQ(close_footprints_in_bones(model, nullptr, &tibia).tibia_nodes, 10);
  for (int j = 1; j <= 3; ++j)
    for (int k = 1; k <= 3; ++k)
      EXPECT_TRUE(model.tibia_nodes[node(1, j, k)]) << j << " " << k;
  EXPECT_TRUE(model.tibia_nodes[node(2, 2, 2)]);
  EXPECT_FALSE(model.tibia_nodes[node(2, 1, 1)]);
  EXPECT_FALSE(model.tibia_nodes[node(2, 1, 2)]);
  EXPECT_FALSE(model.tibia_nodes[node(3, 2, 2)]); // outside the bone
}

TEST(FootprintClosing, NodesOfTheOtherBonesFootprintAreNeverTaken)
{
  Model model = bar_model(9, 2.0);
  // A femur box over the whole bar: the tibia's footprint nodes and their interior nodes are
  // inside it, but they belong to the tibia (the interior ones have tibial, not femoral,
  // neighbours); only the femur's own end closes, by its interior ring (the node at x = 7).
  const TriangleSurface femur = synthetic::box({-5, -5, -5}, {20, 10, 10});
  const FootprintClosing closed = close_footprints_in_bones(model, &femur, nullptr);
  EXPECT_EQ(closed.femur_nodes, 1);
  EXPECT_TRUE(model.femur_nodes[node_at(7)]);
  for (Eigen::Index v = 0; v < model.mesh.V.rows(); ++v)
    EXPECT_FALSE(model.femur_nodes[v] && model.tibia_nodes[v]) << v;
}

TEST(FootprintArea, ANodeBoundAloneOrInALineIsFreedAndTheAreaKept)
{
  Model model = bar_model(9, 2.0);
  const auto node = [](int i, int j, int k) { return (i * 3 + j) * 3 + k; };
  const std::vector<bool> area = model.tibia_nodes;
  // A lone surface node at x = 6 and a line of three across the side at x = 4: neither is a
  // corner of a boundary face whose three corners are bound.
  model.tibia_nodes[node(6, 2, 1)] = true;
  for (int k = 0; k < 3; ++k)
    model.tibia_nodes[node(4, 0, k)] = true;
  EXPECT_EQ(free_unsupported_nodes(tet_boundary_faces(model.mesh.T), model.tibia_nodes), 4);
  EXPECT_EQ(model.tibia_nodes, area);
}

TEST(FootprintArea, OneSquareOfTheSurfaceIsAnAreaAndStays)
{
  Model model = bar_model(9, 2.0);
  const auto node = [](int i, int j, int k) { return (i * 3 + j) * 3 + k; };
  // The four corners of one square of the y = 0 side: both its triangles are bound faces,
  // whichever diagonal cuts it.
  for (int i = 4; i <= 5; ++i)
    for (int k = 0; k <= 1; ++k)
      model.tibia_nodes[node(i, 0, k)] = true;
  const std::vector<bool> patch = model.tibia_nodes;
  EXPECT_EQ(free_unsupported_nodes(tet_boundary_faces(model.mesh.T), model.tibia_nodes), 0);
  EXPECT_EQ(model.tibia_nodes, patch);
}

/// The bar's boundary as a surface (its interior nodes unused), `scale` mm between nodes.
TriangleSurface bar_surface(int nx, double scale)
{
  const TetMesh mesh = bar(nx);
  TriangleSurface surface{scale * mesh.V, {}};
  const std::vector<std::array<int, 3>> faces = tet_boundary_faces(mesh.T);
  surface.F.resize(static_cast<Eigen::Index>(faces.size()), 3);
  for (std::size_t f = 0; f < faces.size(); ++f)
    surface.F.row(static_cast<Eigen::Index>(f)) << faces[f][0], faces[f][1], faces[f][2];
  return surface;
}

/// The surface's vertices with x <= `x_mm` (as the attachments stage gives an area), or >=.
std::vector<int> vertices_with_x(const TriangleSurface& surface, double x_mm, bool below)
{
  std::vector<int> area;
  for (Eigen::Index v = 0; v < surface.V.rows(); ++v)
    if (below ? surface.V(v, 0) <= x_mm : surface.V(v, 0) >= x_mm)
      area.push_back(static_cast<int>(v));
  return area;
}

/// Every tet's fiber along the bar.
Eigen::MatrixX3d along_x(const TetMesh& mesh)
{
  return Eigen::RowVector3d::UnitX().replicate(mesh.T.rows(), 1);
}

TEST(FootprintArea, AFinerMeshBindsTheFacesInsideTheRimAndTheSameArea)
{
  // The ligament's surface: a 2 x 2 x 8 mm bar, nodes 1 mm apart. Its tibial area, the vertices
  // with x <= 2, has its rim (the indicator's 0.5 level) at x = 2.5 on every side.
  const TriangleSurface ligament = bar_surface(9, 1.0);
  const std::vector<int> tibial = vertices_with_x(ligament, 2.0, true);
  const std::vector<int> femoral = vertices_with_x(ligament, 8.0, false);
  // Meshed with nodes 0.5 mm apart, the rim is a chain of mesh edges: the faces up to x = 2.5
  // bind, the end (4 mm^2) and 2.5 mm of each of the four 2 mm sides (20 mm^2).
  TetMesh fine = bar(17, 5);
  fine.V *= 0.5;
  const Model on_fine =
      assemble(fine, along_x(fine), ligament, femoral, tibial, {}, FootprintRule::faces_inside_rim);
  EXPECT_NEAR(on_fine.tibia_area_mm2, 24.0, 1e-9);
  const std::vector<bool> boundary = boundary_nodes(fine);
  for (Eigen::Index v = 0; v < fine.V.rows(); ++v)
    EXPECT_EQ(on_fine.tibia_nodes[v], boundary[v] && fine.V(v, 0) <= 2.5) << v;
  // The surface's own mesh cuts the rim: half the faces between x = 2 and 3, those with two
  // corners in the area, bind, and the area is the same 24 mm^2.
  const TetMesh coarse = bar(9);
  const Model on_coarse = assemble(coarse, along_x(coarse), ligament, femoral, tibial, {},
                                   FootprintRule::faces_inside_rim);
  EXPECT_NEAR(on_coarse.tibia_area_mm2, 24.0, 1e-9);
  // The femoral area is the far end's face alone: its rim lies half an element inside the sides.
  EXPECT_NEAR(on_fine.femur_area_mm2, 4.0 + 4 * 2 * 0.5, 1e-9);
}

TEST(FootprintArea, AnAreaThatNoFaceReachesIsAClearError)
{
  const TriangleSurface ligament = bar_surface(9, 1.0);
  const TetMesh mesh = bar(9);
  // One vertex: its rim encloses less than half of any face around it.
  const std::vector<int> lone = {static_cast<int>(vertices_with_x(ligament, 8.0, false)[0])};
  try {
    assemble(mesh, along_x(mesh), ligament, lone, vertices_with_x(ligament, 2.0, true), {},
             FootprintRule::faces_inside_rim);
    FAIL() << "no error";
  } catch (const InputError& error) {
    EXPECT_NE(std::string(error.what()).find("femoral attachment"), std::string::npos)
        << error.what();
  }
}

} // namespace
} // namespace ligsim::model
