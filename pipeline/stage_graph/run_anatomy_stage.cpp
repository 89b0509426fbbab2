/// The first stage: what the config says of the knee's anatomy, completed from its parts
/// (anatomy.json): directions, side and landmarks, each with how it was found.

#include "pipeline/stage_graph/stage_files.hpp"

#include "common/atomic_file.hpp"
#include "common/error.hpp"
#include "common/knee_anatomy.hpp"
#include "common/run_summary.hpp"
#include "sim/flexion/axis/condyle_axis.hpp"
#include "stages/anatomy/bone_directions.hpp"
#include "stages/anatomy/knee_landmarks.hpp"
#include "stages/io/surface_reader.hpp"

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>

#include <cmath>

namespace ligsim::pipeline {

namespace fs = std::filesystem;

namespace {

constexpr double kFrameAgreementDeg = 45.0; // a label map's frame against the bones

/// The area-weighted centroid of a surface's triangles, mm.
Eigen::Vector3d centroid_of(const TriangleSurface& surface, const std::string& what)
{
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  double area = 0.0;
  for (Eigen::Index f = 0; f < surface.F.rows(); ++f) {
    const Eigen::Vector3d a = surface.V.row(surface.F(f, 0));
    const Eigen::Vector3d b = surface.V.row(surface.F(f, 1));
    const Eigen::Vector3d c = surface.V.row(surface.F(f, 2));
    const double piece = 0.5 * (b - a).cross(c - a).norm();
    sum += piece * (a + b + c) / 3.0;
    area += piece;
  }
  if (!(area > 0.0))
    fail("anatomy: the surface {} has no area", what);
  return sum / area;
}

/// A landmark from its point or its surface (the surface wins when both are given).
void add_landmark(KneeAnatomy& anatomy, const std::string& name, const Eigen::Vector3d& point,
                  const std::string& surface)
{
  if (!surface.empty())
    anatomy.landmarks[name] = {centroid_of(io::read_surface(surface), surface),
                               "centroid of " + surface};
  else if (point.allFinite())
    anatomy.landmarks[name] = {point, "given"};
}

double angle_deg(const Eigen::Vector3d& a, const Eigen::Vector3d& b)
{
  return std::acos(std::clamp(a.normalized().dot(b.normalized()), -1.0, 1.0)) * 180.0 / M_PI;
}

/// The surfaces the anatomy is read off: the bones and the named parts.
struct Parts {
  std::optional<TriangleSurface> femur, tibia, fibula, patella;
  std::map<std::string, TriangleSurface> ligaments;

  const TriangleSurface* ligament(const std::string& name) const
  {
    const auto found = ligaments.find(name);
    return found == ligaments.end() ? nullptr : &found->second;
  }
};

Parts read_parts(const BuildConfig& config)
{
  Parts parts;
  parts.femur = load_bone(config.femur);
  parts.tibia = load_bone(config.tibia); // a knee's ligament on the fibula: the knee's tibia below
  if (!config.surface.empty() && !config.anatomy.parts.count("MCL") &&
      !config.anatomy.parts.count("LCL") && !config.anatomy.parts.count("ACL") &&
      !config.anatomy.parts.count("PCL"))
    parts.ligaments["ligament"] = io::read_surface(config.surface);
  for (const auto& [name, file] : config.anatomy.parts) {
    if (name == "tibia")
      parts.tibia = load_bone(file);
    else if (name == "fibula")
      parts.fibula = load_bone(file);
    else if (name == "patella")
      parts.patella = load_bone(file);
    else
      parts.ligaments[name] = io::read_surface(file);
  }
  return parts;
}

/// Without a femur: proximal along a ligament, from its end at the tibia to its far end (a
/// ligament joins the tibia to a bone above it).
void proximal_along_a_ligament(const Parts& parts, KneeAnatomy& anatomy,
                               std::vector<std::string>& sources)
{
  if (anatomy.proximal || !parts.tibia || parts.ligaments.empty())
    return;
  const auto& [name, ligament] = *parts.ligaments.begin();
  const Eigen::Vector3d tibia = centroid_of(*parts.tibia, "tibia");
  const Eigen::RowVector3d mean = ligament.V.colwise().mean();
  const Eigen::Matrix3d scatter =
      (ligament.V.rowwise() - mean).transpose() * (ligament.V.rowwise() - mean);
  Eigen::Vector3d axis =
      Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(scatter).eigenvectors().col(2);
  const Eigen::VectorXd along = ligament.V * axis;
  const Eigen::Vector3d low =
      ligament.V
          .row(static_cast<Eigen::Index>(
              std::min_element(along.data(), along.data() + along.size()) - along.data()))
          .transpose();
  const Eigen::Vector3d high =
      ligament.V
          .row(static_cast<Eigen::Index>(
              std::max_element(along.data(), along.data() + along.size()) - along.data()))
          .transpose();
  if ((high - tibia).norm() < (low - tibia).norm())
    axis = -axis;
  anatomy.proximal = axis;
  sources.push_back(fmt::format("proximal along the {}, from its end nearer the tibia's centroid "
                                "to its far end (no femur)",
                                name));
}

/// Proximal and posterior: the config's, else the label map's LPS frame (checked against the
/// bones), else the bones'.
void find_directions(const BuildConfig& config, const Parts& parts, KneeAnatomy& anatomy,
                     std::vector<std::string>& sources)
{
  const AnatomyInputs& given = config.anatomy;
  if (given.proximal.norm() > 0.0) {
    anatomy.proximal = given.proximal.normalized();
    sources.push_back("proximal given");
  }
  if (given.posterior.norm() > 0.0) {
    anatomy.posterior = given.posterior.normalized();
    sources.push_back("posterior given");
  }
  if (anatomy.proximal && anatomy.posterior)
    return;
  std::optional<anatomy::BoneDirections> bones;
  if (parts.femur && parts.tibia) {
    try {
      bones = anatomy::directions_from_bones({&*parts.femur, &*parts.tibia,
                                              parts.fibula ? &*parts.fibula : nullptr,
                                              parts.patella ? &*parts.patella : nullptr});
    } catch (const InputError& e) {
      anatomy.not_found.push_back(fmt::format("directions from the bones: {}", e.what()));
    }
  }
  if (config.label_frame_anatomical) {
    // ITK reads the map as LPS: +y posterior, +z superior. Checked against the bones, which
    // win: a map whose header lies about its frame is not unheard of.
    const Eigen::Vector3d superior = Eigen::Vector3d::UnitZ(), back = Eigen::Vector3d::UnitY();
    const bool disagrees = bones && (angle_deg(superior, bones->proximal) > kFrameAgreementDeg ||
                                     angle_deg(back, bones->posterior) > kFrameAgreementDeg);
    if (!disagrees) {
      if (!anatomy.proximal) {
        anatomy.proximal = superior;
        sources.push_back("proximal = +S of the label map's LPS frame");
      }
      if (!anatomy.posterior) {
        anatomy.posterior = back;
        sources.push_back("posterior = +P of the label map's LPS frame");
      }
      if (bones)
        sources.push_back(fmt::format("the bones agree (proximal {:.0f}, posterior {:.0f} "
                                      "degrees from the frame's)",
                                      angle_deg(superior, bones->proximal),
                                      angle_deg(back, bones->posterior)));
      return;
    }
    sources.push_back(fmt::format(
        "the label map's LPS frame disagrees with the bones (its superior axis {:.0f} degrees "
        "from their proximal direction, its posterior axis {:.0f} degrees from theirs): the "
        "bones' directions are used",
        angle_deg(superior, bones->proximal), angle_deg(back, bones->posterior)));
  }
  if (!bones) {
    proximal_along_a_ligament(parts, anatomy, sources);
    return;
  }
  if (!anatomy.proximal)
    anatomy.proximal = bones->proximal;
  if (!anatomy.posterior) {
    const Eigen::Vector3d& up = *anatomy.proximal;
    anatomy.posterior = (bones->posterior - bones->posterior.dot(up) * up).normalized();
  }
  for (const std::string& line : bones->evidence)
    sources.push_back(line);
}

/// The side: the config's, checked against what the parts say; else theirs.
void find_side(const BuildConfig& config, const Parts& parts, const Eigen::Vector3d& plateau,
               KneeAnatomy& anatomy)
{
  std::vector<anatomy::SidePart> cues;
  if (parts.fibula)
    cues.push_back({"fibula", centroid_of(*parts.fibula, "fibula"), false});
  for (const auto& [name, medial] : {std::pair{"MCL", true}, std::pair{"LCL", false}})
    if (const TriangleSurface* ligament = parts.ligament(name))
      cues.push_back({name, centroid_of(*ligament, name), medial});
  const anatomy::SideFinding found =
      anatomy::side_from_parts(cues, plateau, *anatomy.proximal, *anatomy.posterior);
  std::string evidence;
  for (const std::string& line : found.evidence)
    evidence += (evidence.empty() ? "" : "; ") + line;
  if (found.contradicted)
    fail("anatomy: the knee's parts disagree on its side: {}", evidence);
  const std::string& given = config.anatomy.side;
  if (!given.empty() && !found.side.empty() && given != found.side)
    fail("anatomy: the config says a {} knee, but its anatomy is a {} knee's: {} (check [anatomy] "
         "side and posterior)",
         given, found.side, evidence);
  if (!given.empty()) {
    anatomy.side_source = "given" + (evidence.empty() ? "" : "; the anatomy agrees: " + evidence);
  } else if (!found.side.empty()) {
    anatomy.side = found.side;
    anatomy.side_source = evidence;
  } else {
    anatomy.not_found.push_back(
        "side: no fibula, MCL or LCL lies clearly to one side of the tibial plateau" +
        (evidence.empty() ? std::string() : " (" + evidence + ")"));
  }
}

/// The landmarks found on the bones, `fit` the condyles' axis (the given ones are kept).
void find_landmarks(const Parts& parts, const std::optional<sim::CondyleAxisFit>& fit,
                    KneeAnatomy& anatomy)
{
  const Eigen::Vector3d& proximal = *anatomy.proximal;
  const auto keep = [&](const std::map<std::string, anatomy::Landmark>& found) {
    for (const auto& [name, landmark] : found)
      anatomy.landmarks.emplace(name, KneeLandmark{landmark.point_mm, landmark.how});
  };
  if (!parts.femur)
    anatomy.not_found.push_back("femoral landmarks: no femur");
  else if (anatomy.side.empty())
    anatomy.not_found.push_back("femoral landmarks: the side is not known, so neither condyle is "
                                "known to be the medial one");
  else if (fit) {
    // The fit's direction points medially in a left knee, laterally in a right one.
    const Eigen::Vector3d medial =
        anatomy.side == "left" ? fit->axis.direction : Eigen::Vector3d(-fit->axis.direction);
    keep(anatomy::femur_landmarks(*parts.femur, {fit->axis.point_mm, medial, fit->radius_mm},
                                  proximal, parts.ligament("MCL"), parts.ligament("LCL")));
  }
  if (parts.tibia && !anatomy.side.empty()) {
    const Eigen::Vector3d right = (-*anatomy.posterior).cross(proximal).normalized();
    keep(anatomy::tibia_landmarks(*parts.tibia, proximal,
                                  anatomy.side == "left" ? right : Eigen::Vector3d(-right)));
  }
  if (parts.fibula)
    if (const auto head = anatomy::fibular_head(*parts.fibula, proximal))
      anatomy.landmarks.emplace("fibular_head", KneeLandmark{head->point_mm, head->how});
}

/// The plateau's centre for the side cues (the centroid of the tibia's proximal end).
std::optional<Eigen::Vector3d> plateau_centre(const Parts& parts, const Eigen::Vector3d& proximal)
{
  if (!parts.tibia)
    return std::nullopt;
  const auto found = anatomy::tibia_landmarks(*parts.tibia, proximal, proximal.unitOrthogonal());
  const auto centre = found.find("tibial_plateau_centre");
  if (centre == found.end())
    return std::nullopt;
  return centre->second.point_mm;
}

/// The cylinder of the posterior condyles (Churchill et al. 1998's flexion axis), and the
/// posterior direction turned to lie across it when the config did not give it: the knee's own
/// frame rather than the scanner's or the plateau's.
std::optional<sim::CondyleAxisFit> fit_condyles(const BuildConfig& config, const Parts& parts,
                                                KneeAnatomy& anatomy,
                                                std::vector<std::string>& sources)
{
  if (!parts.femur)
    return std::nullopt;
  try {
    const sim::CondyleAxisFit fit =
        sim::fit_condyle_axis(*parts.femur, *anatomy.proximal, *anatomy.posterior);
    if (config.anatomy.posterior.norm() == 0.0) {
      const Eigen::Vector3d across = fit.axis.direction.cross(*anatomy.proximal).normalized();
      sources.push_back(fmt::format("posterior turned {:.1f} degrees to lie across the posterior "
                                    "condyles' axis",
                                    angle_deg(across, *anatomy.posterior)));
      anatomy.posterior = across;
    }
    return fit;
  } catch (const InputError& e) {
    anatomy.not_found.push_back(fmt::format("the condyles' axis: {}", e.what()));
    return std::nullopt;
  }
}

} // namespace

KneeAnatomy knee_anatomy(const BuildConfig& config)
{
  const AnatomyInputs& given = config.anatomy;
  if (given.known)
    return *given.known;
  const Parts parts = read_parts(config);
  KneeAnatomy anatomy;
  anatomy.side = given.side;
  add_landmark(anatomy, "medial_epicondyle", given.medial_epicondyle_mm,
               given.medial_epicondyle_surface);
  add_landmark(anatomy, "lateral_epicondyle", given.lateral_epicondyle_mm,
               given.lateral_epicondyle_surface);

  std::vector<std::string> sources;
  find_directions(config, parts, anatomy, sources);
  if (anatomy.proximal && anatomy.posterior &&
      anatomy.proximal->cross(*anatomy.posterior).norm() < 0.5)
    fail("anatomy: the proximal and posterior directions are less than 30 degrees apart");
  std::optional<sim::CondyleAxisFit> fit;
  if (anatomy.proximal && anatomy.posterior)
    fit = fit_condyles(config, parts, anatomy, sources);

  // Given epicondyles say which way is lateral: with the directions that gives the side, or
  // with the side the posterior direction. The subject's right is anterior x proximal.
  const auto medial = anatomy.landmarks.find("medial_epicondyle");
  const auto lateral = anatomy.landmarks.find("lateral_epicondyle");
  if (medial != anatomy.landmarks.end() && lateral != anatomy.landmarks.end() && anatomy.proximal) {
    const Eigen::Vector3d outward = lateral->second.point_mm - medial->second.point_mm;
    if (anatomy.posterior) {
      const Eigen::Vector3d right = (-*anatomy.posterior).cross(*anatomy.proximal);
      const std::string side = outward.dot(right) > 0.0 ? "right" : "left";
      if (!anatomy.side.empty() && anatomy.side != side)
        fail("anatomy: the config says a {} knee, but its lateral epicondyle lies on the "
             "subject's {} of the medial one (check side, posterior and the epicondyles)",
             anatomy.side, side);
      if (anatomy.side.empty())
        anatomy.side_source = "the given epicondyles";
      anatomy.side = side;
    } else if (!anatomy.side.empty()) {
      const Eigen::Vector3d right = anatomy.side == "right" ? outward : Eigen::Vector3d(-outward);
      const Eigen::Vector3d across = right - right.dot(*anatomy.proximal) * *anatomy.proximal;
      anatomy.posterior = -anatomy.proximal->cross(across).normalized();
      sources.push_back("posterior from the side and the epicondyles");
    }
  }
  if (anatomy.proximal && anatomy.posterior) {
    if (const auto plateau = plateau_centre(parts, *anatomy.proximal))
      find_side(config, parts, *plateau, anatomy);
    find_landmarks(parts, fit, anatomy);
  } else {
    anatomy.not_found.push_back(fmt::format(
        "{}: no [anatomy] {}, no label map in a scanner's frame, and no femur and tibia to read "
        "{} off; the side and the landmarks need both directions",
        anatomy.proximal ? "posterior" : "directions",
        anatomy.proximal ? "posterior" : "proximal and posterior",
        anatomy.proximal ? "it" : "them"));
  }
  if (!given.side.empty() && anatomy.side_source.empty())
    anatomy.side_source = "given";
  for (const std::string& source : sources)
    anatomy.frame_source += (anatomy.frame_source.empty() ? "" : "; ") + source;
  return anatomy;
}

nlohmann::json run_anatomy(const BuildConfig& config, const fs::path& dir)
{
  const KneeAnatomy anatomy = knee_anatomy(config);
  const nlohmann::json json = to_json(anatomy);
  write_text_atomically(dir / files::anatomy, json.dump(2) + "\n");
  return json;
}

} // namespace ligsim::pipeline
