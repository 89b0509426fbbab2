#include "sim/flexion/knee_motion.hpp"

#include "common/error.hpp"
#include "common/progress.hpp"
#include "common/run_summary.hpp"
#include "sim/kinematics/kinematics_csv.hpp"

#include <Eigen/Eigenvalues>
#include <fmt/format.h>

#include <cmath>

namespace ligsim::sim {

namespace {

constexpr double degree = M_PI / 180.0;

double angle_between_deg(const Eigen::Vector3d& a, const Eigen::Vector3d& b)
{
  return std::acos(std::clamp(a.normalized().dot(b.normalized()), -1.0, 1.0)) / degree;
}

ResolvedAxis axis_through_points(const AxisSettings& settings)
{
  const Eigen::Vector3d direction = settings.second_mm - settings.first_mm;
  if (!direction.allFinite() || direction.norm() < 1e-9)
    fail("flexion axis: the two points {} and {} coincide: the axis has zero length",
         json_vector3(settings.first_mm).dump(), json_vector3(settings.second_mm).dump());
  ResolvedAxis resolved;
  resolved.axis = {settings.first_mm, direction.normalized()};
  resolved.method = "given as two points";
  resolved.figures = AxisPoints{settings.first_mm, settings.second_mm};
  return resolved;
}

ResolvedAxis axis_of_condyles(const KneeModel& model, const AxisSettings& settings,
                              const KneeAnatomy& anatomy)
{
  Eigen::Vector3d posterior = settings.posterior;
  if (!(posterior.allFinite() && posterior.norm() > 1e-12) && anatomy.posterior)
    posterior = *anatomy.posterior;
  if (!posterior.allFinite() || posterior.norm() < 1e-12)
    fail("flexion axis: fitting it to the femoral condyles needs the posterior direction of the "
         "data (--posterior x,y,z, [axis] posterior or [anatomy] posterior, or a model built from "
         "a label map), which makes positive angles flex the knee; or give the axis as two "
         "points (--axis x1,y1,z1,x2,y2,z2) or through the epicondyles");
  const TriangleSurface& femur = *model.femur;
  const Eigen::Vector3d proximal = anatomy.proximal ? *anatomy.proximal : proximal_direction(model);
  const CondyleAxisFit fit = fit_condyle_axis(femur, proximal, posterior.normalized());
  ResolvedAxis resolved;
  resolved.axis = fit.axis;
  resolved.method = "cylinder fitted to the posterior femoral condyles";
  resolved.figures = CondyleFitFigures{fit.radius_mm,         fit.rms_residual_mm,   fit.span_mm,
                                       fit.points_used,       fit.points_considered, proximal,
                                       posterior.normalized()};
  return resolved;
}

/// The epicondyle `name`: the settings' point, else the anatomy's landmark.
Eigen::Vector3d epicondyle(const Eigen::Vector3d& given, const KneeAnatomy& anatomy,
                           const std::string& name)
{
  if (given.allFinite())
    return given;
  const auto found = anatomy.landmarks.find(name);
  if (found == anatomy.landmarks.end())
    fail("flexion axis: the transepicondylar axis needs the {} (give [axis] {}_mm, or build the "
         "model with [anatomy] {}_mm or {}_surface)",
         name, name, name, name);
  return found->second.point_mm;
}

ResolvedAxis axis_through_epicondyles(const AxisSettings& settings, const KneeAnatomy& anatomy)
{
  const Eigen::Vector3d medial =
      epicondyle(settings.medial_epicondyle_mm, anatomy, "medial_epicondyle");
  const Eigen::Vector3d lateral =
      epicondyle(settings.lateral_epicondyle_mm, anatomy, "lateral_epicondyle");
  Eigen::Vector3d direction = lateral - medial;
  if (!direction.allFinite() || direction.norm() < 10.0)
    fail("flexion axis: the epicondyles are {:.3g} mm apart; a knee's are 70-100 mm apart",
         direction.norm());
  // Positive rotation must flex: the axis points to the subject's right (anterior x proximal),
  // which is lateral in a right knee and medial in a left one.
  std::string orientation;
  if (anatomy.proximal && anatomy.posterior) {
    const Eigen::Vector3d right = (-*anatomy.posterior).cross(*anatomy.proximal);
    if (direction.dot(right) < 0.0)
      direction = -direction;
    orientation = "toward the subject's right (anterior x proximal)";
  } else if (anatomy.side_sign() != 0) {
    if (anatomy.side_sign() < 0)
      direction = -direction;
    orientation = anatomy.side_sign() > 0 ? "lateral (right knee)" : "medial (left knee)";
  } else {
    fail("flexion axis: the transepicondylar axis needs the knee's side ([anatomy] side = "
         "\"left\" or \"right\") or its posterior and proximal directions to know which way "
         "flexes");
  }
  ResolvedAxis resolved;
  resolved.axis = {0.5 * (medial + lateral), direction.normalized()};
  resolved.method = "transepicondylar: through the medial and lateral epicondyles";
  resolved.figures = EpicondylarFigures{medial, lateral, (lateral - medial).norm(), orientation};
  return resolved;
}

/// The tibia's long axis: its principal axis when the surface is long (a whole or most of a
/// tibia), else the proximal direction.
Eigen::Vector3d tibial_axis(const KneeModel& model, const Eigen::Vector3d& proximal,
                            TibialAxisFigures& figures)
{
  const TriangleSurface& tibia = *model.tibia;
  const Eigen::RowVector3d mean = tibia.V.colwise().mean();
  const Eigen::MatrixX3d centred = tibia.V.rowwise() - mean;
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> principal(centred.transpose() * centred);
  const Eigen::Vector3d values = principal.eigenvalues();
  // Length at least twice the width (variance ratio 4): the shaft shows.
  if (values(2) > 4.0 * values(1)) {
    Eigen::Vector3d axis = principal.eigenvectors().col(2);
    if (axis.dot(proximal) < 0.0)
      axis = -axis;
    figures = {"principal axis of the tibia", axis, angle_between_deg(axis, proximal)};
    return axis;
  }
  figures = {"the proximal direction (the tibia surface is too short for its own axis)", proximal,
             std::nullopt};
  return proximal;
}

/// How far the knee was flexed where it was built: the angle about the flexion axis from the
/// tibia's long axis to the femoral shaft's (Grood & Suntay's flexion, 0 in full extension). The
/// shaft is the line through the centroids of the femur's 10 mm slices from 60 to 200 mm above
/// its distal end (the distal shaft, above the condyles and the metaphysis' flare), so a femur
/// shorter than 120 mm is not measured. The angles a sweep names stay counted from the built pose.
BuiltPose built_flexion(const KneeModel& model, const Eigen::Vector3d& proximal,
                        const JointCoordinateSystem& jcs)
{
  constexpr double from_mm = 60.0, to_mm = 200.0, slice_mm = 10.0;
  constexpr int least_slices = 6;
  if (!model.femur)
    return {std::nullopt, Eigen::Vector3d::Zero(), "", "the knee has no femur"};
  const TriangleSurface& femur = *model.femur;
  const Eigen::VectorXd height = femur.V * proximal;
  const double distal = height.minCoeff();
  std::vector<Eigen::Vector3d> centroids;
  for (double low = distal + from_mm; low < distal + to_mm; low += slice_mm) {
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    int count = 0;
    for (Eigen::Index v = 0; v < femur.V.rows(); ++v)
      if (height(v) >= low && height(v) < low + slice_mm) {
        sum += femur.V.row(v).transpose();
        ++count;
      }
    if (count >= 8)
      centroids.push_back(sum / count);
  }
  if (static_cast<int>(centroids.size()) < least_slices)
    return {std::nullopt, Eigen::Vector3d::Zero(), "",
            fmt::format("the femur reaches {:.0f} mm above its distal end: its shaft shows from "
                        "{:g} mm, and {:g} mm of it are needed",
                        height.maxCoeff() - distal, from_mm, least_slices * slice_mm)};
  Eigen::MatrixX3d points(static_cast<Eigen::Index>(centroids.size()), 3);
  for (std::size_t i = 0; i < centroids.size(); ++i)
    points.row(static_cast<Eigen::Index>(i)) = centroids[i].transpose();
  const Eigen::RowVector3d mean = points.colwise().mean();
  const Eigen::MatrixX3d centred = points.rowwise() - mean;
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> principal(centred.transpose() * centred);
  Eigen::Vector3d shaft = principal.eigenvectors().col(2);
  if (shaft.dot(proximal) < 0.0)
    shaft = -shaft;
  // Both axes seen along the flexion axis; turning the femur positively about it flexes.
  const Eigen::Vector3d e1 = jcs.flexion_axis.normalized();
  const Eigen::Vector3d tibia = (jcs.tibial_axis - jcs.tibial_axis.dot(e1) * e1).normalized();
  const Eigen::Vector3d femoral = (shaft - shaft.dot(e1) * e1).normalized();
  const double angle = std::atan2(e1.dot(tibia.cross(femoral)), tibia.dot(femoral)) / degree;
  return {angle, shaft,
          fmt::format("the tibia's long axis against the femoral shaft (the centroids of {} slices "
                      "of 10 mm, {:g} to {:g} mm above the femur's distal end), about the flexion "
                      "axis",
                      centroids.size(), from_mm, from_mm + slice_mm * centroids.size()),
          ""};
}

KneePath knee_path(const FlexionSettings& settings, const KneeAnatomy& anatomy,
                   MotionFigures& figures)
{
  const MotionSettings& motion = settings.motion;
  const bool sided = anatomy.side_sign() != 0;
  const auto need_side = [&](const char* what) {
    if (!sided)
      fail("flexion: {} needs the knee's side: give [anatomy] side = \"left\" or \"right\" (in the "
           "flexion or the build config), or the epicondyles and the posterior direction",
           what);
  };
  switch (motion.path) {
  case MotionSettings::Path::pure:
    return KneePath::pure_flexion();
  case MotionSettings::Path::passive:
    need_side("the passive path ([motion] path = \"passive\")");
    return KneePath::passive(motion.coupled_translations);
  case MotionSettings::Path::table:
    need_side("a table of Grood & Suntay coordinates");
    return read_kinematics_csv(motion.table);
  case MotionSettings::Path::free:
    // The knee's own path is found by the free solve (free_flexion.hpp), which replaces this.
    return KneePath::pure_flexion();
  case MotionSettings::Path::automatic:
    break;
  }
  if (sided)
    return KneePath::passive(motion.coupled_translations);
  figures.note = "the knee's side is not known: pure flexion instead of the passive knee's "
                 "coupled motion (give [anatomy] side to couple them)";
  log_info("flexion: " + figures.note);
  return KneePath::pure_flexion();
}

} // namespace

KneeAnatomy effective_anatomy(const KneeModel& model, const FlexionSettings& settings)
{
  KneeAnatomy anatomy = model.anatomy;
  const AnatomySettings& given = settings.anatomy;
  if (!given.side.empty())
    anatomy.side = given.side;
  if (given.proximal.allFinite() && given.proximal.norm() > 0.0)
    anatomy.proximal = given.proximal.normalized();
  if (given.posterior.allFinite() && given.posterior.norm() > 0.0)
    anatomy.posterior = given.posterior.normalized();
  else if (settings.axis.posterior.allFinite() && settings.axis.posterior.norm() > 0.0)
    anatomy.posterior = settings.axis.posterior.normalized();
  if (!anatomy.proximal && model.femur && model.tibia)
    anatomy.proximal = proximal_direction(model);
  return anatomy;
}

ResolvedAxis resolve_flexion_axis(const KneeModel& model, const AxisSettings& settings,
                                  const KneeAnatomy& anatomy)
{
  switch (settings.source) {
  case AxisSettings::Source::points:
    return axis_through_points(settings);
  case AxisSettings::Source::condyles:
    return axis_of_condyles(model, settings, anatomy);
  case AxisSettings::Source::transepicondylar:
    return axis_through_epicondyles(settings, anatomy);
  }
  fail("flexion axis: unknown method");
}

ResolvedAxis resolve_flexion_axis(const KneeModel& model, const AxisSettings& settings)
{
  FlexionSettings defaults;
  defaults.axis = settings;
  return resolve_flexion_axis(model, settings, effective_anatomy(model, defaults));
}

KneeMotion resolve_knee_motion(const KneeModel& model, const FlexionSettings& settings)
{
  const KneeAnatomy anatomy = effective_anatomy(model, settings);
  KneeMotion motion;
  motion.axis = resolve_flexion_axis(model, settings.axis, anatomy);

  // The other anatomical axis, for the angle between the two.
  if (settings.axis.source != AxisSettings::Source::points) {
    AxisSettings other = settings.axis;
    other.source = settings.axis.source == AxisSettings::Source::condyles
                       ? AxisSettings::Source::transepicondylar
                       : AxisSettings::Source::condyles;
    OtherAxis& entry = motion.figures.other_axis.emplace();
    entry.method = to_string(other.source);
    try {
      entry.found = resolve_flexion_axis(model, other, anatomy);
      entry.angle_deg = angle_between_deg(entry.found->axis.direction, motion.axis.axis.direction);
    } catch (const InputError& e) {
      entry.not_available = e.what();
    }
  }

  const Eigen::Vector3d proximal =
      anatomy.proximal ? *anatomy.proximal
                       : Eigen::Vector3d(motion.axis.axis.direction.unitOrthogonal());
  motion.jcs.origin_mm = motion.axis.axis.point_mm;
  motion.jcs.flexion_axis = motion.axis.axis.direction;
  motion.jcs.tibial_axis = tibial_axis(model, proximal, motion.figures.tibial_axis);
  motion.jcs.side = anatomy.side_sign() < 0 ? -1 : 1;
  motion.figures.built_pose = built_flexion(model, proximal, motion.jcs);
  if (motion.figures.built_pose.flexion_deg)
    log_info(fmt::format("flexion: the knee was built at {:.1f} degrees of flexion (its femoral "
                         "shaft against its tibia); the angles are counted from there",
                         *motion.figures.built_pose.flexion_deg));
  motion.figures.side = anatomy.side.empty() ? "not known" : anatomy.side;
  motion.figures.frame_source = anatomy.frame_source;

  KneePath path = knee_path(settings, anatomy, motion.figures);
  motion.figures.path = path.description();
  if (path.parameter() == KneePath::Parameter::time_s) {
    if (settings.mode == FlexionMode::interactive)
      fail("flexion: a motion in time ({}) runs quasi-statically: set mode = \"static\"",
           settings.motion.table.string());
    const std::vector<double>& times = path.knots();
    const double first = times.front(), last = times.back();
    for (double time : times) {
      motion.times_s.push_back(time);
      motion.angles_deg.push_back(path.at(time).flexion_deg);
      motion.load_factors.push_back(last > first ? (time - first) / (last - first) : 0.0);
    }
    motion.femur_path = std::make_shared<FemurPath>(motion.jcs, std::move(path), first, last);
  } else {
    if (settings.angles_deg.empty())
      fail("flexion: no angles to sweep (give angles_deg, or a table with a time_s column)");
    const double last = settings.angles_deg.back();
    motion.angles_deg = settings.angles_deg;
    for (double angle : settings.angles_deg)
      motion.load_factors.push_back(last > 0.0 ? angle / last : 0.0);
    motion.load_factors.back() = last > 0.0 ? 1.0 : 0.0;
    motion.femur_path = std::make_shared<FemurPath>(motion.jcs, std::move(path), 0.0, last);
  }
  return motion;
}

RigidMotion femur_rigid_motion(const KneeMotion& motion)
{
  RigidMotion rigid;
  rigid.axis = motion.jcs.flexion_axis;
  rigid.point_mm = motion.jcs.origin_mm;
  rigid.path = motion.femur_path;
  return rigid;
}

} // namespace ligsim::sim
