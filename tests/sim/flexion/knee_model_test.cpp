/// Reading a built model folder, and a clear error for each thing that can be missing.

#include "common/error.hpp"
#include "common/vtk_files.hpp"
#include "sim/flexion/knee_model.hpp"
#include "sim/mesh/structured_mesh.hpp"

#include <gtest/gtest.h>
#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkDoubleArray.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkUnstructuredGrid.h>

#include <filesystem>

using namespace ligsim;
using namespace ligsim::sim;
namespace fs = std::filesystem;

namespace {

vtkSmartPointer<vtkDoubleArray> array(const char* name, int components, vtkIdType tuples)
{
  auto values = vtkSmartPointer<vtkDoubleArray>::New();
  values->SetName(name);
  values->SetNumberOfComponents(components);
  values->SetNumberOfTuples(tuples);
  values->Fill(0.0);
  return values;
}

/// A triangle (enough for a "bone" file) at height z.
vtkSmartPointer<vtkPolyData> triangle(double z)
{
  auto points = vtkSmartPointer<vtkPoints>::New();
  points->InsertNextPoint(0, 0, z);
  points->InsertNextPoint(1, 0, z);
  points->InsertNextPoint(0, 1, z);
  auto polys = vtkSmartPointer<vtkCellArray>::New();
  const vtkIdType ids[3] = {0, 1, 2};
  polys->InsertNextCell(3, ids);
  auto surface = vtkSmartPointer<vtkPolyData>::New();
  surface->SetPoints(points);
  surface->SetPolys(polys);
  return surface;
}

/// What to leave out of the model folder.
struct Omit {
  bool femur_flags = false;
  bool tibia_nodes = false;
  bool tibia_surface = false;
  bool fiber = false;
};

Omit omitting(bool Omit::*piece)
{
  Omit omit;
  omit.*piece = true;
  return omit;
}

fs::path write_model(const std::string& name, const Omit& omit)
{
  const fs::path dir = fs::temp_directory_path() / ("ligsim_knee_model_" + name);
  fs::remove_all(dir);
  fs::create_directories(dir);
  const ligsim::TetMesh mesh = structured_box_mesh({1, 1, 2}, {1.0, 1.0, 2.0});
  auto grid = vtkSmartPointer<vtkUnstructuredGrid>::New();
  auto points = vtkSmartPointer<vtkPoints>::New();
  for (Eigen::Index n = 0; n < mesh.V.rows(); ++n)
    points->InsertNextPoint(mesh.V(n, 0), mesh.V(n, 1), mesh.V(n, 2));
  grid->SetPoints(points);
  for (Eigen::Index e = 0; e < mesh.T.rows(); ++e) {
    const vtkIdType ids[4] = {mesh.T(e, 0), mesh.T(e, 1), mesh.T(e, 2), mesh.T(e, 3)};
    grid->InsertNextCell(VTK_TETRA, 4, ids);
  }
  auto fiber = array("fiber", 3, mesh.T.rows());
  for (Eigen::Index e = 0; e < mesh.T.rows(); ++e)
    fiber->SetComponent(e, 2, 1.029);
  auto femur = array("femur_attached", 1, mesh.V.rows());
  auto tibia = array("tibia_attached", 1, mesh.V.rows());
  for (Eigen::Index n = 0; n < mesh.V.rows(); ++n) {
    femur->SetValue(n, mesh.V(n, 2) > 1.999 ? 1.0 : 0.0);
    tibia->SetValue(n, mesh.V(n, 2) < 0.001 && !omit.tibia_nodes ? 1.0 : 0.0);
  }
  if (!omit.fiber)
    grid->GetCellData()->AddArray(fiber);
  if (!omit.femur_flags)
    grid->GetPointData()->AddArray(femur);
  grid->GetPointData()->AddArray(tibia);
  ligsim::write_vtk(grid, dir / "model.vtu");
  ligsim::write_vtk(triangle(3.0), dir / "femur.vtp");
  if (!omit.tibia_surface)
    ligsim::write_vtk(triangle(-1.0), dir / "tibia.vtp");
  return dir;
}

/// The InputError's message when loading `dir`, or "" when it loads.
std::string load_error(const fs::path& dir)
{
  try {
    load_knee_model(dir);
  } catch (const ligsim::InputError& e) {
    return e.what();
  }
  return "";
}

} // namespace

TEST(KneeModel, ReadsTetsFibersSetsAndBones)
{
  const KneeModel model = load_knee_model(write_model("complete", {}));
  EXPECT_EQ(model.mesh.T.rows(), 10);
  EXPECT_EQ(model.femur_nodes.size(), 4u);
  EXPECT_EQ(model.tibia_nodes.size(), 4u);
  // Directions come back unit length: the sweep applies its own in-situ strain.
  EXPECT_NEAR(model.fiber_directions.row(3).norm(), 1.0, 1e-12);
  EXPECT_EQ(model.femur->F.rows(), 1);
}

TEST(KneeModel, EachMissingPieceIsNamed)
{
  EXPECT_NE(load_error("/nonexistent/ligsim/model").find("does not exist"), std::string::npos);
  EXPECT_NE(
      load_error(write_model("no_femur_set", omitting(&Omit::femur_flags))).find("femur_attached"),
      std::string::npos);
  EXPECT_NE(load_error(write_model("empty_tibia_set", omitting(&Omit::tibia_nodes))).find("empty"),
            std::string::npos);
  EXPECT_NE(load_error(write_model("no_tibia", omitting(&Omit::tibia_surface))).find("tibia.vtp"),
            std::string::npos);
  EXPECT_NE(load_error(write_model("no_fiber", omitting(&Omit::fiber))).find("'fiber'"),
            std::string::npos);
  const fs::path empty = fs::temp_directory_path() / "ligsim_knee_model_empty";
  fs::create_directories(empty);
  EXPECT_NE(load_error(empty).find("model.vtu"), std::string::npos);
}

TEST(KneeModel, WithQuadraticTetsBindsTheMidEdgeNodesOfBoundEdges)
{
  KneeModel model;
  model.mesh = structured_box_mesh({1, 1, 3}, {2.0, 2.0, 6.0});
  model.fiber_directions = Eigen::MatrixX3d::Zero(model.mesh.T.rows(), 3);
  model.fiber_directions.col(2).setOnes();
  for (Eigen::Index n = 0; n < model.mesh.V.rows(); ++n) {
    if (model.mesh.V(n, 2) < 1e-9)
      model.tibia_nodes.push_back(static_cast<int>(n));
    if (model.mesh.V(n, 2) > 6.0 - 1e-9)
      model.femur_nodes.push_back(static_cast<int>(n));
  }
  const KneeModel quadratic = with_quadratic_tets(model);
  ASSERT_EQ(quadratic.tet10.rows(), model.mesh.T.rows());
  EXPECT_EQ(quadratic.mesh.T, model.mesh.T);
  EXPECT_EQ(quadratic.mesh.V.topRows(model.mesh.V.rows()), model.mesh.V);
  // The bound faces' mid-edge nodes join their footprints: on a face of one hex split into
  // tets, its 4 edges and the diagonal, 5 nodes beside the 4 corners.
  EXPECT_EQ(quadratic.tibia_nodes.size(), model.tibia_nodes.size() + 5);
  EXPECT_EQ(quadratic.femur_nodes.size(), model.femur_nodes.size() + 5);
  for (int n : quadratic.tibia_nodes)
    EXPECT_NEAR(quadratic.mesh.V(n, 2), 0.0, 1e-12) << "node " << n;
  for (int n : quadratic.femur_nodes)
    EXPECT_NEAR(quadratic.mesh.V(n, 2), 6.0, 1e-12) << "node " << n;

  const HyperelasticBody body = ligament_body(quadratic, mcl_material(), 0.029);
  EXPECT_TRUE(body.quadratic());
  EXPECT_NEAR(body.rest_volume(), 24.0, 1e-12);
  EXPECT_NEAR(body.fiber(3).norm(), 1.029, 1e-15);
  EXPECT_FALSE(ligament_body(model, mcl_material(), 0.0).quadratic());
  EXPECT_EQ(with_quadratic_tets(quadratic).mesh.V.rows(), quadratic.mesh.V.rows());

  // Back to linear tets on the corners (the implicit Euler frames): the model it came from.
  KneeModel with_point_fibers = quadratic;
  with_point_fibers.fiber_directions_at_points =
      Eigen::MatrixX3d::Ones(4 * quadratic.tet10.rows(), 3);
  const KneeModel linear = with_linear_tets(with_point_fibers);
  EXPECT_EQ(linear.tet10.rows(), 0);
  EXPECT_EQ(linear.fiber_directions_at_points.rows(), 0);
  EXPECT_EQ(linear.mesh.V, model.mesh.V);
  EXPECT_EQ(linear.mesh.T, model.mesh.T);
  EXPECT_EQ(linear.fiber_directions, model.fiber_directions);
  EXPECT_EQ(linear.femur_nodes, model.femur_nodes);
  EXPECT_EQ(linear.tibia_nodes, model.tibia_nodes);
}

TEST(KneeModel, WithLinearTetsRenumbersCornersThatAreNotFirst)
{
  // A 10-node tet whose corners come after its mid-edge nodes in the file.
  KneeModel model;
  model.mesh.V.resize(10, 3);
  const Eigen::Matrix<double, 4, 3> corners =
      (Eigen::Matrix<double, 4, 3>() << 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1).finished();
  for (int c = 0; c < 4; ++c)
    model.mesh.V.row(6 + c) = corners.row(c);
  for (int k = 0; k < 6; ++k)
    model.mesh.V.row(k) = 0.5 * (corners.row(kQuadraticTetEdges[static_cast<std::size_t>(k)][0]) +
                                 corners.row(kQuadraticTetEdges[static_cast<std::size_t>(k)][1]));
  model.tet10.resize(1, 10);
  model.tet10 << 6, 7, 8, 9, 0, 1, 2, 3, 4, 5;
  model.mesh.T = model.tet10.leftCols<4>();
  model.fiber_directions = Eigen::RowVector3d::UnitX();
  model.femur_nodes = {9, 3, 4, 5};
  model.tibia_nodes = {6, 7, 0};
  const KneeModel linear = with_linear_tets(model);
  EXPECT_EQ(linear.mesh.V, corners);
  EXPECT_EQ(linear.mesh.T, (Tetrahedra(1, 4) << 0, 1, 2, 3).finished());
  EXPECT_EQ(linear.femur_nodes, std::vector<int>{3});
  EXPECT_EQ(linear.tibia_nodes, (std::vector<int>{0, 1}));
}
