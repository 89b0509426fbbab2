/// The .feb file itself, without FEBio: well-formed XML, the model's counts, nodes and tets that
/// read back exactly, the femur's pose as FEBio's rigid degrees of freedom, the material and
/// contact the settings ask for, and the problems it refuses.

#include "common/error.hpp"
#include "common/progress.hpp"
#include "sim/febio/feb_writer.hpp"
#include "sim/febio/knee_feb.hpp"
#include "sim/flexion/femur_poses.hpp"
#include "sim/flexion/knee_flexion.hpp"
#include "sim/mesh/quadratic_tet.hpp"
#include "tests/sim/febio/bar_knee.hpp"

#include <gtest/gtest.h>
#include <vtkSmartPointer.h>
#include <vtkXMLDataElement.h>
#include <vtkXMLUtilities.h>

#include <cmath>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

using namespace ligsim;
using namespace ligsim::sim;
using namespace ligsim::test;

namespace {

FebProblem bar_problem(const FlexionSettings& settings,
                       std::vector<std::string>* warnings = nullptr,
                       const FebContactSettings& contact = {})
{
  const KneeModel model = bar_knee();
  std::vector<std::string> ignored;
  return knee_feb_problem(model, settings, knee_conditions(model, bar_axis(), 60.0),
                          angle_steps(settings.angles_deg), bar_axis().point_mm,
                          warnings ? *warnings : ignored, contact);
}

/// The parsed document (the test fails on malformed XML).
vtkSmartPointer<vtkXMLDataElement> parsed(const std::string& text)
{
  vtkSmartPointer<vtkXMLDataElement> root;
  root.TakeReference(vtkXMLUtilities::ReadElementFromString(text.c_str()));
  return root;
}

/// The child of `parent` called `name` whose attribute `key` is `value` (any, when key is empty).
vtkXMLDataElement* child(vtkXMLDataElement* parent, const std::string& name,
                         const std::string& key = "", const std::string& value = "")
{
  for (int i = 0; parent && i < parent->GetNumberOfNestedElements(); ++i) {
    vtkXMLDataElement* element = parent->GetNestedElement(i);
    if (name != element->GetName())
      continue;
    if (key.empty())
      return element;
    const char* attribute = element->GetAttribute(key.c_str());
    if (attribute && value == attribute)
      return element;
  }
  return nullptr;
}

int count(vtkXMLDataElement* parent, const std::string& name)
{
  int n = 0;
  for (int i = 0; parent && i < parent->GetNumberOfNestedElements(); ++i)
    n += name == parent->GetNestedElement(i)->GetName() ? 1 : 0;
  return n;
}

std::vector<double> numbers(const char* text)
{
  std::vector<double> values;
  std::stringstream in(text ? text : "");
  std::string item;
  while (std::getline(in, item, ','))
    values.push_back(std::stod(item));
  return values;
}

std::string text_of(vtkXMLDataElement* element)
{
  return element && element->GetCharacterData() ? element->GetCharacterData() : "";
}

} // namespace

TEST(FebWriter, WritesWellFormedXmlWithTheModelsCounts)
{
  const FebProblem problem = bar_problem(bar_settings(0.029));
  const auto root = parsed(feb_text(problem));
  ASSERT_NE(root, nullptr);
  EXPECT_STREQ(root->GetName(), "febio_spec");
  EXPECT_STREQ(root->GetAttribute("version"), "4.0");
  vtkXMLDataElement* mesh = child(root, "Mesh");
  const KneeModel model = bar_knee();
  EXPECT_EQ(count(child(mesh, "Nodes", "name", "ligament"), "node"), model.mesh.V.rows());
  EXPECT_EQ(count(child(mesh, "Nodes", "name", "femur"), "node"), model.femur->V.rows());
  EXPECT_EQ(count(child(mesh, "Elements", "name", "ligament"), "elem"), model.mesh.T.rows());
  EXPECT_EQ(count(child(mesh, "Elements", "name", "tibia"), "elem"), model.tibia->F.rows());
  EXPECT_EQ(count(child(child(root, "MeshData"), "ElementData", "name", "fiber"), "e"),
            model.mesh.T.rows());
  const std::string femur_set = text_of(child(mesh, "NodeSet", "name", "femur_attachment"));
  EXPECT_EQ(numbers(femur_set.c_str()).size(), model.femur_nodes.size());
  EXPECT_EQ(text_of(child(child(root, "Control"), "time_steps")), "3");
  // The must points, the in-situ stretch's ramp and the femur's six degrees of freedom; the
  // tibia is fixed.
  EXPECT_EQ(count(child(root, "LoadData"), "load_controller"), 8);
  EXPECT_EQ(count(child(root, "Rigid"), "rigid_bc"), 7);
  EXPECT_NE(child(child(root, "Rigid"), "rigid_bc", "type", "rigid_fixed"), nullptr);
  EXPECT_EQ(child(root, "Contact"), nullptr);
  EXPECT_EQ(text_of(child(child(child(root, "Control"), "solver"), "dtol")), "1e-06");
}

TEST(FebWriter, NodesTetsAndFibersReadBackExactly)
{
  const FebProblem problem = bar_problem(bar_settings(0.029));
  const auto root = parsed(feb_text(problem));
  ASSERT_NE(root, nullptr);
  vtkXMLDataElement* mesh = child(root, "Mesh");
  vtkXMLDataElement* nodes = child(mesh, "Nodes", "name", "ligament");
  ASSERT_EQ(nodes->GetNumberOfNestedElements(), problem.ligament.V.rows());
  for (int n = 0; n < nodes->GetNumberOfNestedElements(); ++n) {
    vtkXMLDataElement* node = nodes->GetNestedElement(n);
    EXPECT_EQ(std::stoi(node->GetAttribute("id")), n + 1);
    const std::vector<double> xyz = numbers(node->GetCharacterData());
    ASSERT_EQ(xyz.size(), 3u);
    for (int c = 0; c < 3; ++c)
      EXPECT_EQ(xyz[static_cast<std::size_t>(c)], problem.ligament.V(n, c)) << "node " << n;
  }
  vtkXMLDataElement* tets = child(mesh, "Elements", "name", "ligament");
  for (int t = 0; t < tets->GetNumberOfNestedElements(); ++t) {
    const std::vector<double> ids = numbers(tets->GetNestedElement(t)->GetCharacterData());
    ASSERT_EQ(ids.size(), 4u);
    for (int c = 0; c < 4; ++c)
      EXPECT_EQ(ids[static_cast<std::size_t>(c)], problem.ligament.T(t, c) + 1);
  }
  vtkXMLDataElement* fibers = child(child(root, "MeshData"), "ElementData", "name", "fiber");
  for (int e = 0; e < fibers->GetNumberOfNestedElements(); ++e) {
    const std::vector<double> a = numbers(fibers->GetNestedElement(e)->GetCharacterData());
    EXPECT_EQ(Eigen::Vector3d(a[0], a[1], a[2]), problem.fiber_directions.row(e).transpose());
  }
}

TEST(FebWriter, RigidDegreesOfFreedomPlaceTheBodyAtThePose)
{
  // A turn about an axis through the center is a rotation vector and no displacement.
  const Eigen::Vector3d center(2.0, -1.0, 5.0);
  const Eigen::Vector3d axis = Eigen::Vector3d(1.0, 2.0, -0.5).normalized();
  Eigen::Isometry3d turn = Eigen::Isometry3d::Identity();
  turn.translate(center).rotate(Eigen::AngleAxisd(1.2, axis)).translate(-center);
  const auto dofs = feb_rigid_dofs(turn, center);
  EXPECT_LT(dofs.head<3>().norm(), 1e-12);
  EXPECT_LT((dofs.tail<3>() - 1.2 * axis).norm(), 1e-12);
  // Any pose: FEBio's placement x = c + d + R (X - c) is the pose.
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.rotate(Eigen::AngleAxisd(2.5, Eigen::Vector3d(0.3, -1.0, 0.4).normalized()));
  pose.pretranslate(Eigen::Vector3d(4.0, 7.0, -3.0));
  const auto general = feb_rigid_dofs(pose, center);
  const Eigen::Vector3d rotation_vector = general.tail<3>();
  const Eigen::AngleAxisd rotation(rotation_vector.norm(), rotation_vector.normalized());
  for (const Eigen::Vector3d& X : {Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(10, -3, 8)})
    EXPECT_LT((center + general.head<3>() + rotation * (X - center) - pose * X).norm(), 1e-12);
}

TEST(FebWriter, FemurPosesTurnAboutTheFlexionAxis)
{
  const KneeModel model = bar_knee();
  const std::vector<Eigen::Isometry3d> poses =
      femur_poses(knee_conditions(model, bar_axis(), 60.0), angle_steps({0.0, 30.0, 60.0}));
  ASSERT_EQ(poses.size(), 3u);
  EXPECT_TRUE(poses[0].isApprox(Eigen::Isometry3d::Identity()));
  const Eigen::AngleAxisd turn(poses[2].linear());
  EXPECT_NEAR(turn.angle(), M_PI / 3.0, 1e-12);
  EXPECT_LT((turn.axis() - Eigen::Vector3d::UnitX()).norm(), 1e-12);
  EXPECT_LT((poses[1] * bar_axis().point_mm - bar_axis().point_mm).norm(), 1e-12);
}

TEST(FebWriter, APathThatStartsOffTheBuiltPoseSettlesThereFirst)
{
  // Angles 30 and 60: the first pose is turned, so time 1 is the built pose (the prestrain
  // settles alone, as ligsim's sweep does), and the angles end at times 2 and 3.
  FlexionSettings settings = bar_settings(0.029);
  settings.angles_deg = {30.0, 60.0};
  const FebProblem problem = bar_problem(settings);
  EXPECT_EQ(problem.settle_steps, 1);
  const auto root = parsed(feb_text(problem));
  ASSERT_NE(root, nullptr);
  EXPECT_EQ(text_of(child(child(root, "Control"), "time_steps")), "3");
  // The femur's turn about x (its rotation vector's x component, Ru): 0 at times 0 and 1, then
  // the two angles.
  vtkXMLDataElement* turn =
      child(child(child(root, "Rigid"), "rigid_bc", "name", "femur_Ru"), "value");
  ASSERT_NE(turn, nullptr);
  ASSERT_NE(turn->GetAttribute("lc"), nullptr);
  vtkXMLDataElement* curve = child(
      child(child(root, "LoadData"), "load_controller", "id", turn->GetAttribute("lc")), "points");
  ASSERT_NE(curve, nullptr);
  ASSERT_EQ(count(curve, "pt"), 4);
  const std::vector<double> at_one = numbers(text_of(curve->GetNestedElement(1)).c_str());
  const std::vector<double> at_two = numbers(text_of(curve->GetNestedElement(2)).c_str());
  const std::vector<double> at_three = numbers(text_of(curve->GetNestedElement(3)).c_str());
  EXPECT_EQ(at_one, (std::vector<double>{1.0, 0.0}));
  EXPECT_NEAR(std::abs(at_two[1]), M_PI / 6.0, 1e-12);
  EXPECT_NEAR(std::abs(at_three[1]), M_PI / 3.0, 1e-12);
  // A path from the built pose needs no such step.
  EXPECT_EQ(bar_problem(bar_settings(0.029)).settle_steps, 0);
}

TEST(FebWriter, MaterialFollowsTheSettings)
{
  FlexionSettings settings = bar_settings(0.0);
  settings.material.volumetric = VolumetricLaw::lnj;
  auto root = parsed(feb_text(bar_problem(settings)));
  vtkXMLDataElement* ligament = child(child(root, "Material"), "material", "name", "ligament");
  EXPECT_STREQ(ligament->GetAttribute("type"), "trans iso Mooney-Rivlin");
  EXPECT_EQ(text_of(child(ligament, "pressure_model")), "default");
  EXPECT_EQ(std::stod(text_of(child(ligament, "c1"))), 0.5 * settings.material.mu_mpa);
  EXPECT_EQ(std::stod(text_of(child(ligament, "lam_max"))), settings.material.fiber->lambda_star);

  settings = bar_settings(0.04);
  root = parsed(feb_text(bar_problem(settings)));
  ligament = child(child(root, "Material"), "material", "name", "ligament");
  EXPECT_STREQ(ligament->GetAttribute("type"), "uncoupled solid mixture");
  EXPECT_EQ(text_of(child(ligament, "pressure_model")), "Abaqus");
  vtkXMLDataElement* prestrained = child(ligament, "solid", "type", "uncoupled prestrain elastic");
  ASSERT_NE(prestrained, nullptr);
  vtkXMLDataElement* stretch = child(prestrained, "prestrain", "type", "in-situ stretch");
  EXPECT_EQ(std::stod(text_of(child(stretch, "stretch"))), 1.04);
  EXPECT_EQ(text_of(child(stretch, "isochoric")), "1");
  // The stretch is ramped over the first step by its load curve: 1.04 x (1 / 1.04) = 1 at time
  // 0, the full 1.04 at the end of each step.
  const char* ramp_id = child(stretch, "stretch")->GetAttribute("lc");
  ASSERT_NE(ramp_id, nullptr);
  vtkXMLDataElement* ramp =
      child(child(child(root, "LoadData"), "load_controller", "id", ramp_id), "points");
  ASSERT_NE(ramp, nullptr);
  ASSERT_EQ(count(ramp, "pt"), 4);
  const std::vector<double> at_zero = numbers(text_of(ramp->GetNestedElement(0)).c_str());
  EXPECT_EQ(at_zero[0], 0.0);
  EXPECT_NEAR(1.04 * at_zero[1], 1.0, 1e-15);
  for (int k = 1; k <= 3; ++k)
    EXPECT_EQ(numbers(text_of(ramp->GetNestedElement(k)).c_str()),
              (std::vector<double>{static_cast<double>(k), 1.0}));
  EXPECT_NE(child(prestrained, "elastic", "type", "uncoupled fiber-exp-linear"), nullptr);
  // The ground substance is not pre-stretched.
  EXPECT_NE(child(ligament, "solid", "type", "Mooney-Rivlin"), nullptr);
}

TEST(FebWriter, ContactKeepsTheMatrixSymmetricForSkyline)
{
  FlexionSettings settings = bar_settings(0.029);
  settings.contact.enabled = true;
  settings.contact.bones = {"femur"};
  const FebProblem problem = bar_problem(settings);
  const auto root = parsed(feb_text(problem));
  vtkXMLDataElement* contact = child(root, "Contact");
  ASSERT_NE(contact, nullptr);
  EXPECT_EQ(count(contact, "contact"), 1); // the femur only
  vtkXMLDataElement* femur = child(contact, "contact", "name", "ligament_on_femur");
  EXPECT_STREQ(femur->GetAttribute("type"), "sliding-elastic");
  EXPECT_EQ(text_of(child(femur, "symmetric_stiffness")), "1");
  EXPECT_EQ(text_of(child(child(child(root, "Control"), "solver"), "symmetric_stiffness")),
            "symmetric");
  // The free surface: boundary faces with a node not bound to a bone.
  vtkXMLDataElement* surface =
      child(child(root, "Mesh"), "Surface", "name", "ligament_free_surface");
  ASSERT_NE(surface, nullptr);
  const KneeModel model = bar_knee();
  std::vector<bool> bound(static_cast<std::size_t>(model.mesh.V.rows()), false);
  for (int n : model.femur_nodes)
    bound[static_cast<std::size_t>(n)] = true;
  for (int n : model.tibia_nodes)
    bound[static_cast<std::size_t>(n)] = true;
  // A 2 x 2 x 8 box: 4 x 8 x 2 quads per side, two triangles each; the end faces are all bound.
  EXPECT_EQ(count(surface, "tri3"), 4 * 8 * 2 * 2);
  for (int f = 0; f < surface->GetNumberOfNestedElements(); ++f) {
    const std::vector<double> ids = numbers(surface->GetNestedElement(f)->GetCharacterData());
    bool free = false;
    for (double id : ids)
      free = free || !bound[static_cast<std::size_t>(id) - 1];
    EXPECT_TRUE(free) << "face " << f;
  }
}

TEST(FebWriter, ContactWithoutOverlapHasThePenaltyAndNoOffset)
{
  FlexionSettings settings = bar_settings(0.029);
  settings.contact.enabled = true;
  FebContactSettings penalty;
  penalty.penalty = 3.5;
  const FebProblem problem = bar_problem(settings, nullptr, penalty);
  EXPECT_EQ(problem.bones[feb_femur].contact_start_offset_mm, 0.0);
  EXPECT_EQ(problem.bones[feb_tibia].contact_start_offset_mm, 0.0);
  const auto root = parsed(feb_text(problem));
  vtkXMLDataElement* contact = child(root, "Contact");
  ASSERT_EQ(count(contact, "contact"), 2);
  for (int c = 0; c < 2; ++c) {
    vtkXMLDataElement* pair = contact->GetNestedElement(c);
    EXPECT_EQ(text_of(child(pair, "laugon")), "PENALTY");
    EXPECT_EQ(std::stod(text_of(child(pair, "penalty"))), 3.5);
    EXPECT_EQ(text_of(child(pair, "auto_penalty")), "1");
    EXPECT_EQ(child(pair, "offset"), nullptr);
  }
  // The must points, the in-situ stretch's ramp and the femur's six degrees of freedom, no
  // contact ramp.
  EXPECT_EQ(count(child(root, "LoadData"), "load_controller"), 8);
  EXPECT_NE(feb_text(problem).find("automatic penalty scaled by 3.5"), std::string::npos);
  EXPECT_NE(feb_text(problem).find("does not overlap the bones"), std::string::npos);
  // Newton on the symmetrized contact stiffness converges linearly: no displacement criterion.
  EXPECT_EQ(text_of(child(child(child(root, "Control"), "solver"), "dtol")), "0");
  EXPECT_EQ(text_of(child(child(child(root, "Control"), "solver"), "rtol")), "1e-08");
}

TEST(FebWriter, OverlappedBoneStartsShrunkAndGrowsOverTheFirstStep)
{
  const double overlap_mm = 0.3;
  FlexionSettings settings = bar_settings(0.029);
  settings.contact.enabled = true;
  settings.contact.barrier.d_hat_mm = 0.1;
  settings.contact.reshape_overlap = false; // the push as a deformation, in both programs
  const KneeModel model = overlapping_bar_knee(overlap_mm);
  std::vector<std::string> warnings;
  const FebProblem problem =
      knee_feb_problem(model, settings, knee_conditions(model, bar_axis(), 60.0),
                       angle_steps(settings.angles_deg), bar_axis().point_mm, warnings);
  // The bar's side lies 0.3 mm inside the box: shrunk by that plus half of d_hat, as ligsim's
  // pre-push starts; the femur is not overlapped.
  EXPECT_NEAR(problem.bones[feb_tibia].contact_start_offset_mm, overlap_mm + 0.05, 1e-6);
  EXPECT_EQ(problem.bones[feb_femur].contact_start_offset_mm, 0.0);

  const auto root = parsed(feb_text(problem));
  ASSERT_NE(root, nullptr);
  vtkXMLDataElement* tibia = child(child(root, "Contact"), "contact", "name", "ligament_on_tibia");
  vtkXMLDataElement* offset = child(tibia, "offset");
  ASSERT_NE(offset, nullptr);
  EXPECT_EQ(std::stod(text_of(offset)), -problem.bones[feb_tibia].contact_start_offset_mm);
  EXPECT_EQ(child(child(child(root, "Contact"), "contact", "name", "ligament_on_femur"), "offset"),
            nullptr);
  // Its load curve: 1 at time 0, 0 from the end of step 1 on.
  vtkXMLDataElement* curve =
      child(child(root, "LoadData"), "load_controller", "id", offset->GetAttribute("lc"));
  ASSERT_NE(curve, nullptr);
  EXPECT_EQ(text_of(child(curve, "interpolate")), "LINEAR");
  vtkXMLDataElement* points = child(curve, "points");
  ASSERT_EQ(count(points, "pt"), 4);
  EXPECT_EQ(numbers(points->GetNestedElement(0)->GetCharacterData()),
            (std::vector<double>{0.0, 1.0}));
  for (int k = 1; k <= 3; ++k)
    EXPECT_EQ(numbers(points->GetNestedElement(k)->GetCharacterData()),
              (std::vector<double>{static_cast<double>(k), 0.0}));
  // The notes say so.
  EXPECT_NE(feb_text(problem).find("overlaps the tibia by up to 0.3 mm"), std::string::npos);

  FebProblem bad = problem;
  bad.bones[feb_tibia].contact_start_offset_mm = -1.0;
  EXPECT_THROW(feb_text(bad), InputError);
}

TEST(FebWriter, AReshapedOverlapIsWrittenAsTheRestShapeTheSweepUses)
{
  ligsim::Progress::set_quiet(true);
  FlexionSettings settings = bar_settings(0.029);
  settings.angles_deg = {0.0};
  settings.contact.enabled = true;
  settings.contact.barrier.d_hat_mm = 0.1;
  settings.contact.reshape_overlap = true;
  const KneeModel model = overlapping_bar_knee(0.3);
  const BoundaryConditions conditions = knee_conditions(model, bar_axis(), 60.0);
  const std::filesystem::path cache =
      std::filesystem::temp_directory_path() / "ligsim_feb_reshape_cache";
  std::filesystem::remove_all(cache);
  const KneeContact contact(model, conditions, settings.contact, cache);

  OverlapReport report;
  const KneeModel reshaped = with_overlap_reshaped(model, settings, conditions, contact, &report);
  ASSERT_TRUE(report.reshaped);
  EXPECT_GT(report.max_node_move_mm, 0.3); // out of the box, past the barrier's gap
  EXPECT_FALSE(reshaped.mesh.V.isApprox(model.mesh.V));

  // The sweep's own rest shape, reshaped by the same push.
  Eigen::VectorXd swept_rest;
  const HyperelasticBody body = ligament_body(model, settings.material, settings.in_situ_strain);
  const SweepResult sweep = run_flexion_sweep(
      body, conditions, settings,
      [&](const AngleResult&, const HyperelasticBody& swept, const Eigen::VectorXd&) {
        swept_rest = swept.rest_positions();
      },
      &contact);
  ASSERT_TRUE(sweep.success) << sweep.failure;
  ASSERT_EQ(swept_rest.size(), 3 * reshaped.mesh.V.rows());
  for (Eigen::Index n = 0; n < reshaped.mesh.V.rows(); ++n)
    EXPECT_LT((swept_rest.segment<3>(3 * n) - reshaped.mesh.V.row(n).transpose()).norm(), 1e-9)
        << "node " << n;

  // What the export and the cross-check write: that shape (with the config's contact cache).
  FlexionSettings in_folder = settings;
  in_folder.model_dir = cache;
  EXPECT_EQ(feb_start_model(model, in_folder, conditions).mesh.V, reshaped.mesh.V);
  in_folder.contact.reshape_overlap = false;
  EXPECT_EQ(feb_start_model(model, in_folder, conditions).mesh.V, model.mesh.V);

  // Written from that shape, FEBio starts outside the bones: no shrunk bone, no warning.
  std::vector<std::string> warnings;
  const FebProblem problem =
      knee_feb_problem(reshaped, settings, conditions, angle_steps(settings.angles_deg),
                       bar_axis().point_mm, warnings);
  EXPECT_EQ(problem.ligament.V, reshaped.mesh.V);
  EXPECT_EQ(problem.bones[feb_tibia].contact_start_offset_mm, 0.0);
  EXPECT_TRUE(warnings.empty());
  EXPECT_NE(feb_text(problem).find("rest shape ligsim pushed out of the bones"), std::string::npos);

  // Given the segmented shape with reshape asked for, it says how deep FEBio has to push.
  const FebProblem unreshaped = knee_feb_problem(
      model, settings, conditions, angle_steps(settings.angles_deg), bar_axis().point_mm, warnings);
  EXPECT_GT(unreshaped.bones[feb_tibia].contact_start_offset_mm, 0.3);
  ASSERT_EQ(warnings.size(), 1U);
  EXPECT_NE(warnings.front().find("up to 0.3 mm inside a bone"), std::string::npos)
      << warnings.front();
}

TEST(FebWriter, PaperConventionIsWrittenWithAWarning)
{
  FlexionSettings settings = bar_settings(0.029);
  settings.material.fiber->convention = FiberConvention::paper;
  std::vector<std::string> warnings;
  const FebProblem problem = bar_problem(settings, &warnings);
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_NE(warnings[0].find("weiss"), std::string::npos);
  EXPECT_NE(feb_text(problem).find("<!-- WARNING: the model's fiber convention is 'paper'"),
            std::string::npos);
}

TEST(FebWriter, AnLclIsBoundToTheFibulaAndSlidesOnTheTibiaToo)
{
  // The bar as an LCL: its distal footprint on the fibula (the sphere below), the tibia a
  // sphere beside the bar.
  KneeModel model = bar_knee();
  model.fibula = model.tibia;
  model.tibia = bone(sphere_surface({12.0, 2.0, 4.0}, 3.0, 1));
  model.distal_bone = "fibula";
  FlexionSettings settings = bar_settings(0.029);
  settings.contact.enabled = true;
  std::vector<std::string> warnings;
  const FebProblem problem =
      knee_feb_problem(model, settings, knee_conditions(model, bar_axis(), 60.0),
                       angle_steps(settings.angles_deg), bar_axis().point_mm, warnings);
  ASSERT_EQ(problem.bones.size(), 3u);
  EXPECT_EQ(problem.bones[feb_tibia].name, "tibia");
  EXPECT_EQ(problem.bones[feb_tibia].surface.V, model.tibia->V);
  EXPECT_TRUE(problem.bones[feb_tibia].attached_nodes.empty());
  EXPECT_EQ(problem.bones[feb_fibula].name, "fibula");
  EXPECT_EQ(problem.bones[feb_fibula].attached_nodes, model.tibia_nodes);
  const auto root = parsed(feb_text(problem));
  vtkXMLDataElement* mesh = child(root, "Mesh");
  EXPECT_EQ(count(child(mesh, "Elements", "name", "fibula"), "elem"), model.fibula->F.rows());
  EXPECT_EQ(count(child(mesh, "Elements", "name", "tibia"), "elem"), model.tibia->F.rows());
  EXPECT_NE(child(mesh, "NodeSet", "name", "fibula_attachment"), nullptr);
  EXPECT_EQ(child(mesh, "NodeSet", "name", "tibia_attachment"), nullptr);
  EXPECT_EQ(count(child(root, "Contact"), "contact"), 3);
  EXPECT_NE(child(child(root, "Contact"), "contact", "name", "ligament_on_tibia"), nullptr);
  // A footprint bound to a bone the model lacks is refused.
  model.fibula = nullptr;
  EXPECT_THROW(knee_feb_problem(model, settings, knee_conditions(model, bar_axis(), 60.0),
                                angle_steps(settings.angles_deg), bar_axis().point_mm, warnings),
               InputError);
}

TEST(FebWriter, RefusesProblemsItCannotWrite)
{
  const FebProblem good = bar_problem(bar_settings(0.029));
  FebProblem problem = good;
  problem.fiber_directions.conservativeResize(3, 3);
  EXPECT_THROW(feb_text(problem), InputError);
  problem = good;
  problem.bones[feb_tibia].attached_nodes.push_back(problem.bones[feb_femur].attached_nodes[0]);
  EXPECT_THROW(feb_text(problem), InputError);
  problem = good;
  problem.bones[feb_femur].poses.pop_back();
  EXPECT_THROW(feb_text(problem), InputError);
  problem = good;
  problem.step_labels.clear();
  EXPECT_THROW(feb_text(problem), InputError);
  problem = good;
  problem.material.fiber.reset();
  EXPECT_THROW(feb_text(problem), InputError);
}

TEST(FebWriter, QuadraticTetsAreWrittenAsTet10G4WithTheirTenNodes)
{
  FebProblem problem = bar_problem(bar_settings(0.029));
  const QuadraticTetMesh quadratic = promote_to_quadratic(problem.ligament);
  problem.ligament.V = quadratic.V;
  problem.ligament_tet10 = quadratic.T;
  const auto root = parsed(feb_text(problem));
  vtkXMLDataElement* elements = child(child(root, "Mesh"), "Elements", "name", "ligament");
  ASSERT_NE(elements, nullptr);
  EXPECT_STREQ(elements->GetAttribute("type"), "TET10G4");
  ASSERT_EQ(count(elements, "elem"), static_cast<int>(quadratic.T.rows()));
  const std::vector<double> last = numbers(
      elements->GetNestedElement(static_cast<int>(quadratic.T.rows()) - 1)->GetCharacterData());
  ASSERT_EQ(last.size(), 10u);
  for (int i = 0; i < 10; ++i) // 1-based in the file
    EXPECT_EQ(last[static_cast<std::size_t>(i)], quadratic.T(quadratic.T.rows() - 1, i) + 1);

  FebProblem refused = problem;
  refused.ligament_tet10(0, 4) = refused.ligament_tet10(0, 5) = -1;
  EXPECT_THROW(feb_text(refused), InputError);
}

TEST(FebWriter, ContactOnTenNodeTetsSlidesOnTheirSixNodeFaces)
{
  FlexionSettings settings = bar_settings(0.029);
  settings.contact.enabled = true;
  FebProblem problem = bar_problem(settings);
  const QuadraticTetMesh quadratic = promote_to_quadratic(problem.ligament);
  problem.ligament.V = quadratic.V;
  problem.ligament_tet10 = quadratic.T;
  const auto root = parsed(feb_text(problem));
  vtkXMLDataElement* surface =
      child(child(root, "Mesh"), "Surface", "name", "ligament_free_surface");
  ASSERT_NE(surface, nullptr);
  ASSERT_GT(surface->GetNumberOfNestedElements(), 0);
  for (int f = 0; f < surface->GetNumberOfNestedElements(); ++f) {
    vtkXMLDataElement* facet = surface->GetNestedElement(f);
    ASSERT_STREQ(facet->GetName(), "tri6");
    const std::vector<double> ids = numbers(facet->GetCharacterData());
    ASSERT_EQ(ids.size(), 6u);
    std::vector<int> nodes;
    for (double id : ids)
      nodes.push_back(static_cast<int>(id) - 1);
    // Nodes 4-6 are the middles of edges 1-2, 2-3, 3-1 (the promoted tets are straight).
    for (int c = 0; c < 3; ++c) {
      const Eigen::Vector3d middle =
          0.5 * (quadratic.V.row(nodes[c]) + quadratic.V.row(nodes[(c + 1) % 3])).transpose();
      EXPECT_LT((quadratic.V.row(nodes[3 + c]).transpose() - middle).norm(), 1e-12)
          << "facet " << f + 1 << ", node " << 4 + c;
    }
  }
}
