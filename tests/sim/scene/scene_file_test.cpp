#include "common/error.hpp"
#include "common/vtk_files.hpp"
#include "pipeline/scenes/scene_runner.hpp"
#include "sim/mesh/structured_mesh.hpp"
#include "sim/scene/scene.hpp"

#include <gtest/gtest.h>
#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkDoubleArray.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkUnsignedCharArray.h>
#include <vtkUnstructuredGrid.h>

#include <filesystem>
#include <fstream>
#include <string>

using namespace ligsim::sim;
namespace fs = std::filesystem;

namespace {

const std::string cube_scene = R"(
[mesh]
generator = "cube"
cells = 2

[fibers]
direction = [0, 0, 2]

[node_sets]
bottom = { plane = { axis = "z", at_mm = 0.0 } }
top = { box = { min_mm = [-1, -1, 0.99], max_mm = [2, 2, 2] } }
corner = { nodes = [0] }

[[fix]]
set = "bottom"

[[displace]]
set = "corner"
displacement_mm = { x = 0.0 }

[[force]]
set = "top"
total_n = [0, 0, 0.9]

[solver]
load_steps = 3
)";

/// The message of the InputError that parsing `text` throws ("" if none).
std::string parse_error(const std::string& text, const fs::path& base = fs::temp_directory_path())
{
  try {
    parse_scene(text, base, "test.toml");
  } catch (const ligsim::InputError& e) {
    return e.what();
  }
  return "";
}

std::string replaced(std::string text, const std::string& from, const std::string& to)
{
  text.replace(text.find(from), from.size(), to);
  return text;
}

/// A pipeline-style model: a 2 x 1 x 1 box with fiber cell data (|a| = 1.029) and femur / tibia
/// point data marking its two ends.
fs::path write_model(const fs::path& directory, bool with_pyramid = false)
{
  const ligsim::TetMesh mesh = structured_box_mesh({4, 2, 2}, {2.0, 1.0, 1.0});
  auto grid = vtkSmartPointer<vtkUnstructuredGrid>::New();
  auto points = vtkSmartPointer<vtkPoints>::New();
  auto femur = vtkSmartPointer<vtkUnsignedCharArray>::New();
  auto tibia = vtkSmartPointer<vtkUnsignedCharArray>::New();
  femur->SetName("femur_attached");
  tibia->SetName("tibia_attached");
  for (Eigen::Index n = 0; n < mesh.V.rows(); ++n) {
    points->InsertNextPoint(mesh.V(n, 0), mesh.V(n, 1), mesh.V(n, 2));
    femur->InsertNextValue(mesh.V(n, 0) > 1.99 ? 1 : 0);
    tibia->InsertNextValue(mesh.V(n, 0) < 0.01 ? 1 : 0);
  }
  grid->SetPoints(points);
  grid->GetPointData()->AddArray(femur);
  grid->GetPointData()->AddArray(tibia);
  auto fiber = vtkSmartPointer<vtkDoubleArray>::New();
  fiber->SetName("fiber");
  fiber->SetNumberOfComponents(3);
  for (Eigen::Index e = 0; e < mesh.T.rows(); ++e) {
    const vtkIdType ids[4] = {mesh.T(e, 0), mesh.T(e, 1), mesh.T(e, 2), mesh.T(e, 3)};
    grid->InsertNextCell(VTK_TETRA, 4, ids);
    fiber->InsertNextTuple3(1.029, 0.0, 0.0);
  }
  if (with_pyramid) {
    const vtkIdType ids[5] = {0, 1, 2, 3, 4};
    grid->InsertNextCell(VTK_PYRAMID, 5, ids);
    fiber->InsertNextTuple3(1.029, 0.0, 0.0);
  }
  grid->GetCellData()->AddArray(fiber);
  const fs::path file = directory / (with_pyramid ? "pyramid.vtu" : "model.vtu");
  ligsim::write_vtk(grid, file);
  return file;
}

const std::string model_scene = R"(
[mesh]
file = "model.vtu"

[fibers]
cell_data = "fiber"

[node_sets]
femur = { point_data = "femur_attached" }
tibia = { point_data = "tibia_attached" }

[[fix]]
set = "tibia"

[[rigid]]
set = "femur"
axis = [0, 0, 1]
point_mm = [0, 0.5, 0.5]
angle_deg = 0.0

[solver]
load_steps = 2
residual_tolerance = 1e-10
)";

} // namespace

TEST(SceneFile, ReadsAGeneratedCubeScene)
{
  const Scene scene = parse_scene(cube_scene, fs::temp_directory_path(), "cube.toml");
  EXPECT_EQ(scene.mesh.T.rows(), 40);
  EXPECT_EQ(scene.node_sets.at("bottom").size(), 9u);
  EXPECT_EQ(scene.node_sets.at("top").size(), 9u);
  ASSERT_EQ(scene.conditions.constraints.size(), 2u);
  EXPECT_FALSE(scene.conditions.constraints[1].components[1]);
  EXPECT_TRUE(scene.conditions.constraints[1].components[0]);
  EXPECT_NEAR(scene.conditions.loads[0].force_per_node_n.z(), 0.1, 1e-15);
  ASSERT_EQ(scene.fibers.rows(), 1);
  EXPECT_NEAR(scene.fibers.row(0).norm(), 1.0, 1e-15); // a direction is normalised
  EXPECT_EQ(scene.newton.load_steps, 3);
  EXPECT_EQ(scene.kind, SceneKind::quasi_static);
}

TEST(SceneFile, ErrorsNameTheTableAndKey)
{
  EXPECT_NE(parse_error(replaced(cube_scene, "load_steps = 3", "load_step = 3"))
                .find("unknown key 'load_step'"),
            std::string::npos);
  EXPECT_NE(parse_error(replaced(cube_scene, "set = \"bottom\"", "set = \"floor\""))
                .find("no node set named 'floor'"),
            std::string::npos);
  EXPECT_NE(parse_error(replaced(cube_scene, "generator = \"cube\"", "generator = \"sphere\""))
                .find("generator"),
            std::string::npos);
  EXPECT_NE(parse_error(replaced(cube_scene, "cells = 2", "cells = \"two\"")).find("cells"),
            std::string::npos);
  EXPECT_NE(parse_error(replaced(cube_scene, "at_mm = 0.0", "at_mm = 7.0")).find("no node"),
            std::string::npos);
  EXPECT_NE(parse_error(replaced(cube_scene, "[fibers]", "[fibers]\ncell_data = \"fiber\""))
                .find("exactly one"),
            std::string::npos);
  EXPECT_NE(
      parse_error(replaced(cube_scene, "[solver]", "[solver]\nkind = \"implicit\"")).find("kind"),
      std::string::npos);
  EXPECT_NE(parse_error("[mesh\n").find("line"), std::string::npos);
  EXPECT_NE(parse_error("[mesh]\nfile = \"missing.vtu\"\n").find("missing.vtu"), std::string::npos);
  const std::string unconstrained =
      replaced(replaced(cube_scene, "[[fix]]\nset = \"bottom\"\n", ""),
               "[[displace]]\nset = \"corner\"\ndisplacement_mm = { x = 0.0 }\n", "");
  EXPECT_NE(parse_error(unconstrained).find("freely"), std::string::npos);
  EXPECT_NE(parse_error(replaced(cube_scene, "nodes = [0]", "nodes = [1000]")).find("1000"),
            std::string::npos);
}

TEST(SceneFile, PipelineModelWithInSituStrainIsInEquilibriumBetweenItsAttachments)
{
  const fs::path directory = fs::temp_directory_path() / "ligsim_scene_model";
  fs::create_directories(directory);
  write_model(directory);
  {
    std::ofstream out(directory / "scene.toml");
    out << model_scene;
  }
  const Scene scene = load_scene(directory / "scene.toml");
  ASSERT_EQ(scene.fibers.rows(), 80);
  EXPECT_NEAR(scene.fibers.row(0).norm(), 1.029, 1e-12); // used as is
  EXPECT_EQ(scene.node_sets.at("femur").size(), 9u);

  const fs::path out = directory / "out";
  ligsim::RunSummary summary("simulate");
  const ligsim::scenes::SceneRunReport report = ligsim::scenes::run_scene(scene, out, summary);
  ASSERT_TRUE(report.success) << report.failure;
  EXPECT_TRUE(fs::exists(out / "series.pvd"));
  EXPECT_TRUE(fs::exists(out / "step_0002.vtu"));
  EXPECT_TRUE(fs::exists(out / "reactions.csv"));
  // The pre-stretched fibers pull the attachments together with equal and opposite forces.
  const auto& reactions = summary.results()["steps"].back()["reactions"];
  const double femur_x = reactions["femur"]["force_n"][0];
  const double tibia_x = reactions["tibia"]["force_n"][0];
  EXPECT_GT(std::abs(femur_x), 0.01);
  EXPECT_NEAR(femur_x, -tibia_x, 1e-8 * std::abs(femur_x));
  EXPECT_GT(summary.results()["steps"].back()["strain_energy_mj"].get<double>(), 0.0);
}

TEST(SceneFile, VtuWithOtherCellsIsRejected)
{
  const fs::path directory = fs::temp_directory_path() / "ligsim_scene_pyramid";
  fs::create_directories(directory);
  write_model(directory, true);
  const std::string message =
      parse_error(replaced(model_scene, "model.vtu", "pyramid.vtu"), directory);
  EXPECT_NE(message.find("not a linear tetrahedron"), std::string::npos) << message;
}
