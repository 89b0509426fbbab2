/// The knee's motion from its anatomy: which way the transepicondylar axis points, which path
/// the femur follows and what each needs; the ligament's length through its tets; the push of
/// an overlapping ligament out of a bone; the plausibility warnings.

#include "common/error.hpp"
#include "common/progress.hpp"
#include "sim/flexion/initial_overlap.hpp"
#include "sim/flexion/knee_flexion.hpp"
#include "sim/flexion/knee_motion.hpp"
#include "sim/flexion/ligament_length.hpp"
#include "sim/flexion/plausibility.hpp"
#include "sim/kinematics/joint_coordinates.hpp"
#include "sim/mesh/structured_mesh.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <tuple>

using namespace ligsim;
using namespace ligsim::sim;
namespace fs = std::filesystem;

namespace {

/// A closed box surface, outward triangles, mm.
BoneSurface box(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi)
{
  TriangleSurface surface;
  surface.V.resize(8, 3);
  for (int i = 0; i < 8; ++i)
    surface.V.row(i) << ((i & 1) ? hi.x() : lo.x()), ((i & 2) ? hi.y() : lo.y()),
        ((i & 4) ? hi.z() : lo.z());
  surface.F.resize(12, 3);
  surface.F << 0, 2, 1, 1, 2, 3, 4, 5, 6, 5, 7, 6, 0, 1, 4, 1, 5, 4, 2, 6, 3, 3, 6, 7, 0, 4, 2, 2,
      4, 6, 1, 3, 5, 3, 7, 5;
  return std::make_shared<const TriangleSurface>(std::move(surface));
}

/// A 4 x 4 x 20 mm bar along z (the ligament), fibers along it: tibia attached at z = 0, femur
/// at z = 20; a long tibia below and a femur above; +y anterior, +z proximal.
KneeModel bar_knee()
{
  KneeModel model;
  model.mesh = structured_box_mesh({2, 2, 8}, {4.0, 4.0, 20.0});
  model.fiber_directions = Eigen::MatrixX3d::Zero(model.mesh.T.rows(), 3);
  model.fiber_directions.col(2).setOnes();
  for (Eigen::Index n = 0; n < model.mesh.V.rows(); ++n) {
    if (model.mesh.V(n, 2) < 1e-9)
      model.tibia_nodes.push_back(static_cast<int>(n));
    if (model.mesh.V(n, 2) > 20.0 - 1e-9)
      model.femur_nodes.push_back(static_cast<int>(n));
  }
  model.tibia = box({-20.0, -20.0, -200.0}, {24.0, 24.0, -1.0});
  model.femur = box({-20.0, -20.0, 21.0}, {24.0, 24.0, 200.0});
  model.anatomy.proximal = Eigen::Vector3d::UnitZ();
  model.centerline.resize(2, 3);
  model.centerline << 2.0, 2.0, 0.0, 2.0, 2.0, 20.0;
  return model;
}

FlexionSettings epicondylar(const Eigen::Vector3d& medial, const Eigen::Vector3d& lateral)
{
  FlexionSettings settings;
  settings.axis.source = AxisSettings::Source::transepicondylar;
  settings.axis.medial_epicondyle_mm = medial;
  settings.axis.lateral_epicondyle_mm = lateral;
  settings.images = false;
  return settings;
}

/// The plausibility context of bar_knee() turning about an axis through its femoral footprint.
PlausibilityContext bar_context(const FlexionSettings& settings)
{
  return {settings.ligament, footprints(bar_knee(), {{2.0, 2.0, 20.0}, Eigen::Vector3d::UnitX()}),
          settings.in_situ_strain, std::nullopt};
}

/// The ligament of `model` pushed out of its tibia at rest (no in-situ strain), as the sweep does
/// before its first angle.
struct PushedOut {
  HyperelasticBody body;
  OverlapReport report;
  Eigen::VectorXd x; ///< the pushed positions
};

PushedOut pushed_out_of_tibia(const KneeModel& model, const std::string& cache_name)
{
  ligsim::Progress::set_quiet(true);
  FlexionSettings settings;
  settings.in_situ_strain = 0.0;
  PushedOut pushed{ligament_body(model, settings.material, settings.in_situ_strain), {}, {}};
  const BoundaryConditions conditions =
      knee_conditions(model, FlexionAxis{{2.0, 2.0, 20.0}, Eigen::Vector3d::UnitX()}, 0.0);
  ContactConfig config;
  config.bones = {"tibia"};
  const fs::path cache = fs::temp_directory_path() / cache_name;
  fs::remove_all(cache);
  const KneeContact contact(model, conditions, config, cache);
  pushed.x = pushed.body.rest_positions();
  pushed.report =
      resolve_initial_overlap(pushed.body, conditions, contact, settings.newton, pushed.x);
  return pushed;
}

} // namespace

TEST(KneeMotion, TransepicondylarAxisPointsTheWayThatFlexes)
{
  // Subject's right = anterior x proximal = +x. A right knee's lateral epicondyle lies at +x, a
  // left knee's at -x; both axes must point to +x (lateral in the right knee, medial in the
  // left), so that a positive angle swings the femoral shaft back.
  KneeModel model = bar_knee();
  for (const std::string side : {"right", "left"}) {
    SCOPED_TRACE(side);
    const double out = side == "right" ? 1.0 : -1.0;
    FlexionSettings settings =
        epicondylar({2.0 - out * 40.0, 2.0, 22.0}, {2.0 + out * 38.0, 2.0, 22.0});
    settings.anatomy.side = side; // the side alone orients it ...
    const KneeMotion by_side = resolve_knee_motion(model, settings);
    EXPECT_GT(by_side.axis.axis.direction.x(), 0.999);
    EXPECT_NEAR(by_side.axis.axis.point_mm.x(), 2.0 - out, 1e-12); // the epicondyles' midpoint
    settings.anatomy.side.clear(); // ... and so do the directions alone
    settings.anatomy.posterior = -Eigen::Vector3d::UnitY();
    const KneeMotion by_frame = resolve_knee_motion(model, settings);
    EXPECT_GT(by_frame.axis.axis.direction.x(), 0.999);
    // The femur's shaft goes posterior under positive flexion.
    const Eigen::Vector3d shaft = by_frame.axis.axis.point_mm + Eigen::Vector3d(0, 0, 50);
    EXPECT_LT(by_frame.femur_path->pose(1.0).translation().y() +
                  (by_frame.femur_path->pose(1.0).linear() * shaft).y(),
              by_frame.axis.axis.point_mm.y());
  }
  FlexionSettings unknown = epicondylar({-38.0, 2.0, 22.0}, {42.0, 2.0, 22.0});
  EXPECT_THROW(resolve_knee_motion(model, unknown), InputError); // no side, no posterior
  FlexionSettings missing;
  missing.axis.source = AxisSettings::Source::transepicondylar;
  missing.anatomy.side = "right";
  EXPECT_THROW(resolve_knee_motion(model, missing), InputError); // no epicondyles anywhere
  // The model's own landmarks serve when the settings give none.
  model.anatomy.landmarks["medial_epicondyle"] = {Eigen::Vector3d(-38.0, 2.0, 22.0), "given"};
  model.anatomy.landmarks["lateral_epicondyle"] = {Eigen::Vector3d(42.0, 2.0, 22.0), "given"};
  EXPECT_GT(resolve_knee_motion(model, missing).axis.axis.direction.x(), 0.999);
}

TEST(KneeMotion, PathsAndWhatTheyNeed)
{
  const KneeModel model = bar_knee();
  FlexionSettings settings = epicondylar({-38.0, 2.0, 22.0}, {42.0, 2.0, 22.0});
  settings.anatomy.posterior = -Eigen::Vector3d::UnitY(); // orients the axis, not the side
  settings.angles_deg = {0.0, 45.0, 90.0};
  settings.motion.path = MotionSettings::Path::passive;
  EXPECT_THROW(resolve_knee_motion(model, settings), InputError); // the coupling needs the side
  settings.motion.path = MotionSettings::Path::automatic;
  const KneeMotion pure = resolve_knee_motion(model, settings);
  EXPECT_NE(pure.figures.note.find("side is not known"), std::string::npos);
  EXPECT_NEAR(joint_pose(pure.jcs, pure.femur_path->pose(1.0)).internal_rotation_deg, 0.0, 1e-9);

  settings.anatomy.side = "right";
  const KneeMotion passive = resolve_knee_motion(model, settings);
  const JointPose at90 = joint_pose(passive.jcs, passive.femur_path->pose(1.0));
  EXPECT_NEAR(at90.flexion_deg, 90.0, 1e-9);
  EXPECT_NEAR(at90.internal_rotation_deg, 14.88, 0.01); // Walker et al. 1988
  EXPECT_EQ(passive.load_factors, (std::vector<double>{0.0, 0.5, 1.0}));
  EXPECT_EQ(passive.figures.tibial_axis.source, "principal axis of the tibia");

  // A motion in time: its rows are the steps.
  const fs::path csv = fs::temp_directory_path() / "ligsim_knee_motion_time.csv";
  std::ofstream(csv) << "time_s,flexion_deg,internal_rotation_deg\n0,0,0\n1,30,5\n2,10,2\n";
  settings.motion.path = MotionSettings::Path::table;
  settings.motion.table = csv;
  const KneeMotion timed = resolve_knee_motion(model, settings);
  EXPECT_EQ(timed.times_s, (std::vector<double>{0.0, 1.0, 2.0}));
  EXPECT_EQ(timed.angles_deg, (std::vector<double>{0.0, 30.0, 10.0}));
  EXPECT_EQ(timed.load_factors, (std::vector<double>{0.0, 0.5, 1.0}));
  settings.mode = FlexionMode::interactive;
  EXPECT_THROW(resolve_knee_motion(model, settings), InputError);
}

TEST(LigamentLength, FollowsTheTetsItIsEmbeddedIn)
{
  const KneeModel model = bar_knee();
  const EmbeddedPolyline line(model.mesh, model.centerline);
  Eigen::VectorXd x(3 * model.mesh.V.rows());
  for (Eigen::Index n = 0; n < model.mesh.V.rows(); ++n)
    x.segment<3>(3 * n) = model.mesh.V.row(n).transpose();
  EXPECT_NEAR(line.length(x), 20.0, 1e-12);
  for (Eigen::Index n = 0; n < model.mesh.V.rows(); ++n)
    x(3 * n + 2) *= 1.1; // stretched 10 % along the bar
  EXPECT_NEAR(line.length(x), 22.0, 1e-12);
  EXPECT_EQ(line.largest_miss_mm(), 0.0);
}

TEST(InitialOverlap, NodesInsideABoneArePushedOutBeforeTheSweep)
{
  KneeModel model = bar_knee();
  // A bone bulging 0.4 mm into the bar's -x side over its middle (x < 0.4, z 6..14).
  model.tibia = box({-20.0, -20.0, 6.0}, {0.4, 24.0, 14.0});
  const auto [body, report, x] = pushed_out_of_tibia(model, "ligsim_initial_overlap_cache");
  ASSERT_TRUE(report.pushed);
  ASSERT_EQ(report.before.size(), 1u);
  EXPECT_GT(report.before[0].inside, 0);
  EXPECT_LT(report.before[0].min_gap_mm, -0.3);
  EXPECT_EQ(report.after[0].inside, 0);
  EXPECT_GT(report.after[0].min_gap_mm, 0.0);
  EXPECT_GT(report.max_node_move_mm, 0.4);
  EXPECT_LT(report.max_node_move_mm, 1.0);
  // No element was turned inside out on the way.
  for (Eigen::Index e = 0; e < body.element_count(); ++e)
    EXPECT_GT(body.measures(x, e).J, 0.5);
  // A ligament clear of the bones is left alone.
  model.tibia = box({-20.0, -20.0, 6.0}, {-1.0, 24.0, 14.0});
  const PushedOut apart = pushed_out_of_tibia(model, "ligsim_initial_overlap_cache");
  EXPECT_FALSE(apart.report.pushed);
  EXPECT_EQ(apart.x, apart.body.rest_positions());
}

TEST(PenetrationCheck, LeavesOutTheMiddlesOfEdgesFromAFootprintInTheBoneButNoFreeCorner)
{
  // The tibial footprint (z = 0) 1.5 mm deep in the tibia: the middles of the edges from it to
  // the next layer of corners (z = 1.25) lie in the bone with it; a layer of free corners
  // (z = 2.5) in the bone is a penetration.
  const KneeModel model = with_quadratic_tets(bar_knee());
  const BoundaryConditions conditions =
      knee_conditions(model, FlexionAxis{{2.0, 2.0, 20.0}, Eigen::Vector3d::UnitX()}, 0.0);
  ContactConfig config;
  config.bones = {"tibia"};
  const fs::path cache = fs::temp_directory_path() / "ligsim_penetration_check_cache";
  Eigen::VectorXd x(3 * model.mesh.V.rows());
  for (Eigen::Index n = 0; n < model.mesh.V.rows(); ++n)
    x.segment<3>(3 * n) = model.mesh.V.row(n).transpose();
  const auto deepest = [&](double bone_top_z) {
    KneeModel in_bone = model;
    in_bone.tibia = box({-4.0, -4.0, -10.0}, {8.0, 8.0, bone_top_z});
    fs::remove_all(cache);
    const KneeContact contact(in_bone, conditions, config, cache);
    Eigen::VectorXd gap, pressure;
    return contact.measure(x, 0.0, false, gap, pressure).at(0).penetration_mm;
  };
  EXPECT_EQ(deepest(1.5), 0.0);
  EXPECT_NEAR(deepest(3.0), 0.5, 1e-6);
}

TEST(InitialOverlap, AQuadraticBarsMidEdgeNodesArePushedOutToo)
{
  // A ridge of bone 0.3 mm into the bar's -x side between two layers of its corner nodes
  // (z = 7.5 and 10): only mid-edge nodes (z = 8.75) are inside, and contact must see them.
  const KneeModel linear = bar_knee();
  KneeModel model = with_quadratic_tets(linear);
  model.tibia = box({-20.0, -20.0, 8.0}, {0.3, 24.0, 9.5});
  const auto [body, report, x] = pushed_out_of_tibia(model, "ligsim_quadratic_overlap_cache");
  ASSERT_TRUE(body.quadratic());
  ASSERT_TRUE(report.pushed);
  EXPECT_GT(report.before[0].inside, 0);
  EXPECT_EQ(report.after[0].inside, 0);
  int pressed = 0;
  for (Eigen::Index n = linear.mesh.V.rows(); n < model.mesh.V.rows(); ++n) {
    const Eigen::RowVector3d rest = model.mesh.V.row(n);
    if (rest.x() > 1e-9 || rest.z() < 8.0 || rest.z() > 9.5)
      continue;
    ++pressed;
    EXPECT_GT(x(3 * n), 0.3) << "mid-edge node " << n << " left in the bone";
  }
  EXPECT_GE(pressed, 3);
}

TEST(InitialOverlap, AReshapingPushLeavesNoStrainBehind)
{
  ligsim::Progress::set_quiet(true);
  KneeModel model = bar_knee();
  model.tibia = box({-20.0, -20.0, 6.0}, {0.4, 24.0, 14.0}); // 0.4 mm into the bar
  const FlexionAxis axis{{2.0, 2.0, 20.0}, Eigen::Vector3d::UnitX()};
  const BoundaryConditions conditions = knee_conditions(model, axis, 0.0);
  const fs::path cache = fs::temp_directory_path() / "ligsim_reshaping_push_cache";
  fs::remove_all(cache);
  const auto at_rest = [&](bool reshape) {
    FlexionSettings settings;
    settings.angles_deg = {0.0};
    settings.in_situ_strain = 0.0;
    settings.contact.bones = {"tibia"};
    settings.contact.reshape_overlap = reshape;
    const HyperelasticBody body = ligament_body(model, settings.material, settings.in_situ_strain);
    const KneeContact contact(model, conditions, settings.contact, cache);
    Eigen::VectorXd rest_of_swept;
    const SweepResult sweep = run_flexion_sweep(
        body, conditions, settings,
        [&](const AngleResult&, const HyperelasticBody& swept, const Eigen::VectorXd&) {
          rest_of_swept = swept.rest_positions();
        },
        &contact);
    EXPECT_TRUE(sweep.success) << sweep.failure;
    EXPECT_TRUE(sweep.overlap.pushed);
    EXPECT_EQ(sweep.overlap.reshaped, reshape);
    EXPECT_EQ(rest_of_swept.isApprox(body.rest_positions()), !reshape);
    return sweep.angles.front();
  };
  // Deformed by the push, the bar is strained where it was pushed.
  const AngleResult deformed = at_rest(false);
  EXPECT_GT(deformed.strain_energy_mj, 1e-2);
  EXPECT_GT(deformed.max_fiber_stretch, 1.001);
  // Reshaped, the pushed bar is its own rest shape: without in-situ strain, what is left is the
  // barrier's push on the nodes still within its activation distance of the bone (deformed:
  // 18.7 mJ and 2.1 %; reshaped: 0.05 mJ and 0.13 %).
  const AngleResult reshaped = at_rest(true);
  EXPECT_LT(reshaped.strain_energy_mj, 0.01 * deformed.strain_energy_mj);
  EXPECT_LT(reshaped.max_fiber_stretch - 1.0, 0.1 * (deformed.max_fiber_stretch - 1.0));
}

TEST(KneeFlexion, TheFemursNetForceAddsItsContactToItsFootprint)
{
  // The femur reaches 0.4 mm into the bar's side below its footprint: pushed out, the bar
  // presses on the femur there, and the footprint's reaction carries that push too. With the
  // tibia's, the forces on the bar balance: femur net + tibia footprint + tibia contact = 0.
  ligsim::Progress::set_quiet(true);
  KneeModel model = bar_knee();
  model.femur = box({-20.0, -20.0, 14.0}, {0.4, 24.0, 200.0});
  const FlexionAxis axis{{2.0, 2.0, 20.0}, Eigen::Vector3d::UnitX()};
  const BoundaryConditions conditions = knee_conditions(model, axis, 0.0);
  const fs::path cache = fs::temp_directory_path() / "ligsim_net_force_cache";
  fs::remove_all(cache);
  FlexionSettings settings;
  settings.angles_deg = {0.0, 10.0};
  settings.in_situ_strain = 0.03;
  settings.contact.bones = {"femur", "tibia"};
  const HyperelasticBody body = ligament_body(model, settings.material, settings.in_situ_strain);
  const KneeContact contact(model, conditions, settings.contact, cache);
  const SweepResult sweep = run_flexion_sweep(
      body, conditions, settings,
      [](const AngleResult&, const HyperelasticBody&, const Eigen::VectorXd&) {}, &contact);
  ASSERT_TRUE(sweep.success) << sweep.failure;
  for (const AngleResult& a : sweep.angles) {
    Eigen::Vector3d femur_contact = Eigen::Vector3d::Zero(), others = a.tibia_force_n;
    for (const BoneContact& bone : a.contact)
      (bone.bone == "femur" ? femur_contact : others) += bone.force_n;
    EXPECT_GT(femur_contact.norm(), 0.05 * a.femur_force_n.norm()) << a.angle_deg;
    EXPECT_TRUE(femur_net_force(a).isApprox(a.femur_force_n + femur_contact, 1e-12));
    EXPECT_LT((femur_net_force(a) + others).norm(), 1e-4 * a.femur_force_n.norm()) << a.angle_deg;
  }
}

TEST(Plausibility, ABadAxisIsSaidOutLoud)
{
  ligsim::Progress::set_quiet(true);
  const KneeModel model = bar_knee();
  FlexionSettings settings;
  settings.angles_deg = {0.0, 30.0};
  settings.images = false;
  const HyperelasticBody body = ligament_body(model, settings.material, settings.in_situ_strain);
  const EmbeddedPolyline centerline(model.mesh, model.centerline);
  const auto warnings_of = [&](const FlexionAxis& axis) {
    PlausibilityContext context{settings.ligament, footprints(model, axis), settings.in_situ_strain,
                                std::nullopt};
    std::vector<std::string> warnings;
    const SweepResult sweep = run_flexion_sweep(
        body, knee_conditions(model, axis, 30.0), settings,
        [&](const AngleResult& angle, const HyperelasticBody&, const Eigen::VectorXd&) {
          for (const std::string& w : plausibility_warnings(angle, context))
            warnings.push_back(w);
        },
        nullptr, nullptr, &centerline);
    EXPECT_TRUE(sweep.success) << sweep.failure;
    return std::make_pair(warnings, sweep);
  };
  // Through the femoral footprint: the bar bends, no fiber near failure.
  const auto [good, good_sweep] = warnings_of({{2.0, 2.0, 20.0}, Eigen::Vector3d::UnitX()});
  EXPECT_TRUE(good.empty()) << good.front();
  EXPECT_LT(std::abs(good_sweep.angles.back().length_change_pct), 5.0);
  // 40 mm behind it: turning 30 degrees drags the footprint 21 mm away from the tibia.
  const auto [bad, bad_sweep] = warnings_of({{2.0, -38.0, 20.0}, Eigen::Vector3d::UnitX()});
  ASSERT_FALSE(bad.empty());
  EXPECT_NE(bad.front().find("beyond its failure strain of 17.1 %"), std::string::npos);
  EXPECT_NE(bad.front().find("the femoral footprint reaches"), std::string::npos);
  EXPECT_GT(bad_sweep.angles.back().failed_volume_fraction, 0.5);
  EXPECT_GT(bad_sweep.angles.back().length_change_pct, 50.0);
}

TEST(Plausibility, APeakThatNoRegionSharesIsCalledLocal)
{
  // A few elements past the failure strain: called a local peak only where the strain averaged
  // over the measuring regions stays under it; the bar's axis is on its footprint, so nothing
  // else is blamed.
  const FlexionSettings settings;
  const PlausibilityContext context = bar_context(settings);
  AngleResult angle;
  angle.failed_volume_fraction = 2e-4;
  angle.max_fiber_stretch = 1.30;
  angle.max_regional_fiber_stretch = 1.05;
  const std::vector<std::string> local = plausibility_warnings(angle, context);
  ASSERT_EQ(local.size(), 1U);
  EXPECT_NE(local.front().find("likely causes: a local peak: averaged within 2 mm"),
            std::string::npos)
      << local.front();
  angle.max_regional_fiber_stretch = 1.20; // past 17.1 % over 2 mm as well
  const std::vector<std::string> broad = plausibility_warnings(angle, context);
  ASSERT_EQ(broad.size(), 1U);
  EXPECT_EQ(broad.front().find("local peak"), std::string::npos) << broad.front();
}

namespace {

/// A Grood & Suntay table with one row per pose, every coordinate at full precision; with
/// `timed`, a time_s column (0, 1, 2, ... s) makes each row a step.
fs::path pose_table(const std::string& name, const std::vector<JointPose>& poses,
                    bool timed = false)
{
  const fs::path csv = fs::temp_directory_path() / name;
  std::ofstream out(csv);
  out << (timed ? "time_s," : "")
      << "flexion_deg,varus_deg,internal_rotation_deg,lateral_mm,anterior_mm,proximal_mm\n";
  out.precision(17);
  for (std::size_t k = 0; k < poses.size(); ++k) {
    const JointPose& p = poses[k];
    if (timed)
      out << k << ',';
    out << p.flexion_deg << ',' << p.varus_deg << ',' << p.internal_rotation_deg << ','
        << p.lateral_mm << ',' << p.anterior_mm << ',' << p.proximal_mm << '\n';
  }
  return csv;
}

} // namespace

TEST(Plausibility, AFootprintsReactionThatContactCancelsIsNoLoad)
{
  // The femur's footprint pulls with 900 N (past the MCL's 799 N) while the femur pushes back
  // on the ligament beside it with 850 N: the ligament carries 50 N, and no warning is given.
  const FlexionSettings settings;
  const PlausibilityContext context = bar_context(settings);
  AngleResult angle;
  angle.femur_force_n = Eigen::Vector3d(900.0, 0.0, 0.0);
  BoneContact femur;
  femur.bone = "femur";
  femur.force_n = Eigen::Vector3d(-850.0, 0.0, 0.0);
  angle.contact = {femur};
  EXPECT_TRUE(plausibility_warnings(angle, context).empty());
  angle.contact.front().force_n.setZero();
  const std::vector<std::string> loaded = plausibility_warnings(angle, context);
  ASSERT_EQ(loaded.size(), 1U);
  EXPECT_NE(loaded.front().find("the femur pulls on the MCL with 900 N"), std::string::npos)
      << loaded.front();
}

TEST(Plausibility, ALigamentBuiltAThirdAsThickAsPublishedIsSaidToBeTooThin)
{
  // The bar: 4 x 4 x 20 mm on a 20 mm centerline, 16 mm^2 in mean cross-section.
  const KneeModel knee = bar_knee();
  const std::optional<LigamentThickness> bar = ligament_thickness(knee.mesh, knee.centerline);
  ASSERT_TRUE(bar);
  EXPECT_NEAR(bar->volume_mm3, 320.0, 1e-9);
  EXPECT_NEAR(bar->centerline_mm, 20.0, 1e-12);
  EXPECT_NEAR(bar->mean_cross_section_mm2, 16.0, 1e-9);
  // As an ACL (38.7 mm^2 published) it is 2.4 times too thin: under the bar of three.
  EXPECT_FALSE(thin_ligament_finding("ACL", *bar));
  LigamentThickness thread = *bar;
  thread.mean_cross_section_mm2 = 2.4;
  const std::optional<std::string> thin = thin_ligament_finding("ACL", thread);
  ASSERT_TRUE(thin);
  EXPECT_NE(thin->find("16.1 times under the published 38.7 mm^2"), std::string::npos) << *thin;
  EXPECT_FALSE(thin_ligament_finding("MCL", thread)) << "no published figure, no finding";

  // The finding is given as a cause of a strain past failure.
  PlausibilityContext context = bar_context(FlexionSettings{});
  context.thin = thin;
  AngleResult angle;
  angle.failed_volume_fraction = 0.5;
  angle.max_fiber_stretch = angle.max_regional_fiber_stretch = 1.5;
  const std::vector<std::string> warnings = plausibility_warnings(angle, context);
  ASSERT_EQ(warnings.size(), 1U);
  EXPECT_NE(warnings.front().find(*thin), std::string::npos) << warnings.front();
}

TEST(KneeMotion, TheBuiltPoseIsMeasuredAsTheFemoralShaftAgainstTheTibia)
{
  // A femur 250 mm long (a tube of 12 mm radius from z = 21) over the tibia's box, standing
  // straight and then turned by 10 degrees about the flexion axis: the knee as built at 0 and 10
  // degrees of flexion. One 80 mm long has too little shaft to tell.
  KneeModel model = bar_knee();
  FlexionSettings settings = epicondylar({-38.0, 2.0, 22.0}, {42.0, 2.0, 22.0});
  settings.anatomy.posterior = -Eigen::Vector3d::UnitY();
  const auto femur_of = [](double length_mm, const Eigen::Isometry3d& pose) {
    // Rings of 48 points every 5 mm, joined by triangles (open at its ends).
    constexpr int around = 48;
    const int rings = static_cast<int>(length_mm / 5.0) + 1;
    TriangleSurface surface;
    surface.V.resize(rings * around, 3);
    for (int r = 0; r < rings; ++r)
      for (int a = 0; a < around; ++a) {
        const double phi = 2.0 * M_PI * a / around;
        surface.V.row(r * around + a) =
            (pose * Eigen::Vector3d(12.0 * std::cos(phi), 12.0 * std::sin(phi), 21.0 + 5.0 * r))
                .transpose();
      }
    surface.F.resize(2 * (rings - 1) * around, 3);
    for (int r = 0; r + 1 < rings; ++r)
      for (int a = 0; a < around; ++a) {
        const int p = r * around + a, q = r * around + (a + 1) % around;
        const int f = 2 * (r * around + a);
        surface.F.row(f) << p, q, q + around;
        surface.F.row(f + 1) << p, q + around, p + around;
      }
    return std::make_shared<const TriangleSurface>(std::move(surface));
  };
  model.femur = femur_of(250.0, Eigen::Isometry3d::Identity());
  const KneeMotion straight = resolve_knee_motion(model, settings);
  EXPECT_NEAR(straight.figures.built_pose.flexion_deg.value(), 0.0, 0.2);

  const JointCoordinateSystem& jcs = straight.jcs;
  const Eigen::Isometry3d flexed = Eigen::Translation3d(jcs.origin_mm) *
                                   Eigen::AngleAxisd(10.0 * M_PI / 180.0, jcs.flexion_axis) *
                                   Eigen::Translation3d(-jcs.origin_mm);
  model.femur = femur_of(250.0, flexed);
  const BuiltPose built = resolve_knee_motion(model, settings).figures.built_pose;
  EXPECT_NEAR(built.flexion_deg.value(), 10.0, 0.3) << built.not_measured;

  model.femur = femur_of(80.0, Eigen::Isometry3d::Identity());
  const BuiltPose short_femur = resolve_knee_motion(model, settings).figures.built_pose;
  EXPECT_FALSE(short_femur.flexion_deg.has_value());
  EXPECT_NE(short_femur.not_measured.find("reaches 80 mm"), std::string::npos)
      << short_femur.not_measured;
}

TEST(KneeMotion, APoseTableReproducesTheRigidMotionItWasMadeFrom)
{
  const KneeModel model = bar_knee();
  FlexionSettings settings = epicondylar({-38.0, 2.0, 22.0}, {42.0, 2.0, 22.0});
  settings.anatomy.posterior = -Eigen::Vector3d::UnitY();
  settings.anatomy.side = "left";
  const JointCoordinateSystem jcs = resolve_knee_motion(model, settings).jcs;

  // Known motions of the femur: turns about skew axes through points off the knee, and shifts.
  std::vector<Eigen::Isometry3d> known;
  known.push_back(Eigen::Isometry3d::Identity());
  for (const auto& [angle_deg, axis, point, shift] :
       {std::tuple{35.0, Eigen::Vector3d(1.0, 0.2, -0.1), Eigen::Vector3d(3, -4, 25),
                   Eigen::Vector3d(0.5, -2.0, 1.0)},
        std::tuple{80.0, Eigen::Vector3d(0.9, -0.3, 0.4), Eigen::Vector3d(-2, 6, 18),
                   Eigen::Vector3d(-1.5, 4.0, -0.7)}}) {
    const Eigen::AngleAxisd turn(angle_deg * M_PI / 180.0, axis.normalized());
    known.push_back(Eigen::Translation3d(point + shift) * turn * Eigen::Translation3d(-point));
  }
  std::vector<JointPose> rows;
  for (const Eigen::Isometry3d& pose : known)
    rows.push_back(joint_pose(jcs, pose));
  settings.motion.path = MotionSettings::Path::table;
  settings.motion.table = pose_table("ligsim_known_motion.csv", rows, true);
  const KneeMotion table = resolve_knee_motion(model, settings);
  ASSERT_EQ(table.load_factors.size(), known.size());
  for (std::size_t k = 0; k < known.size(); ++k)
    EXPECT_LT((table.femur_path->pose(table.load_factors[k]).matrix() - known[k].matrix())
                  .cwiseAbs()
                  .maxCoeff(),
              1e-9)
        << "pose " << k;
}

TEST(KneeMotion, APureRotationTableGivesTheAxisSweepToRoundOff)
{
  ligsim::Progress::set_quiet(true);
  const KneeModel model = bar_knee();
  FlexionSettings settings = epicondylar({-38.0, 2.0, 22.0}, {42.0, 2.0, 22.0});
  settings.anatomy.posterior = -Eigen::Vector3d::UnitY();
  settings.anatomy.side = "left";
  settings.angles_deg = {0.0, 20.0, 40.0};
  const HyperelasticBody body = ligament_body(model, settings.material, settings.in_situ_strain);
  const auto sweep_of = [&](const FlexionSettings& s) {
    const KneeMotion motion = resolve_knee_motion(model, s);
    const SweepSteps steps = motion_steps(motion);
    const SweepResult sweep =
        run_flexion_sweep(body, knee_conditions(model, femur_rigid_motion(motion)), s,
                          AngleCallback{}, nullptr, &steps);
    EXPECT_TRUE(sweep.success) << sweep.failure;
    return sweep;
  };
  settings.motion.path = MotionSettings::Path::pure;
  const SweepResult axis = sweep_of(settings);
  settings.motion.path = MotionSettings::Path::table;
  settings.motion.table = pose_table("ligsim_pure_rotation.csv", {JointPose{}, {20.0}, {40.0}});
  const SweepResult table = sweep_of(settings);
  ASSERT_EQ(axis.angles.size(), 3u);
  ASSERT_EQ(table.angles.size(), 3u);
  for (std::size_t k = 0; k < 3; ++k) {
    EXPECT_EQ(table.angles[k].angle_deg, axis.angles[k].angle_deg);
    const double force = axis.angles[k].femur_force_n.norm();
    EXPECT_GT(force, 0.0);
    EXPECT_LT((table.angles[k].femur_force_n - axis.angles[k].femur_force_n).norm(), 1e-9 * force);
    EXPECT_NEAR(table.angles[k].strain_energy_mj, axis.angles[k].strain_energy_mj,
                1e-9 * axis.angles[k].strain_energy_mj);
  }
}
