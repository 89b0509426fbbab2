#include "stages/anatomy/knee_landmarks.hpp"

#include "common/error.hpp"
#include "stages/anatomy/facets.hpp"
#include "stages/geometry/surface_query.hpp"

#include <Eigen/Geometry>

#include <fmt/format.h>

#include <cmath>

namespace ligsim::anatomy {

namespace {

constexpr double kSideCueMm = 5.0;        // a part nearer the plateau's centre tells no side
constexpr double kCondyleReach = 1.75;    // condyle region: within this many radii of the axis
constexpr double kProminenceMm = 3.0;     // within this of the most prominent point
constexpr double kLigamentEndMm = 6.0;    // a collateral's femoral end: its proximal 6 mm
constexpr double kLigamentReachMm = 20.0; // farther from the face: not this epicondyle's
constexpr double kPlateauDepthMm = 12.0;  // the tibial plateau
constexpr double kUpwardCos = 0.7071;     // its facets face within 45 degrees of proximal
constexpr double kFibularHeadMm = 10.0;

/// The centroid of the ligament's vertices within kLigamentEndMm of its most proximal one.
Eigen::Vector3d proximal_end(const TriangleSurface& ligament, const Eigen::Vector3d& proximal)
{
  const Eigen::VectorXd h = ligament.V * proximal;
  const double top = h.maxCoeff();
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  int count = 0;
  for (Eigen::Index v = 0; v < h.size(); ++v)
    if (h(v) >= top - kLigamentEndMm) {
      sum += ligament.V.row(v).transpose();
      ++count;
    }
  return sum / count;
}

/// The epicondyle at the end of the axis `outward` points to (axis.medial or its opposite).
std::optional<Landmark> epicondyle(const TriangleSurface& femur, const Facets& f,
                                   const CondyleCylinder& axis, const Eigen::Vector3d& outward,
                                   const Eigen::Vector3d& proximal, const TriangleSurface* ligament,
                                   const char* ligament_name)
{
  // The condyle's outward-facing facets within reach of the axis, and the outermost of them.
  std::vector<Eigen::Index> near;
  double extreme = -std::numeric_limits<double>::infinity();
  for (Eigen::Index i = 0; i < f.area.size(); ++i) {
    const Eigen::Vector3d d = f.centroid.row(i).transpose() - axis.point_mm;
    const double along = d.dot(outward);
    if ((d - along * outward).norm() > kCondyleReach * axis.radius_mm ||
        f.normal.row(i).dot(outward.transpose()) <= 0.0)
      continue;
    near.push_back(i);
    extreme = std::max(extreme, along);
  }
  TriangleSurface face{femur.V, Triangles(0, 3)};
  std::vector<Eigen::Index> rows;
  for (Eigen::Index i : near)
    if ((f.centroid.row(i).transpose() - axis.point_mm).dot(outward) >= extreme - kProminenceMm)
      rows.push_back(i);
  if (rows.empty())
    return std::nullopt;
  face.F.resize(static_cast<Eigen::Index>(rows.size()), 3);
  for (std::size_t r = 0; r < rows.size(); ++r)
    face.F.row(static_cast<Eigen::Index>(r)) = femur.F.row(rows[r]);
  const auto whole = region(facets_of(face), [](Eigen::Index) { return true; });
  if (!whole)
    return std::nullopt;
  const SurfaceQuery query(face);
  const std::string prominence = fmt::format(
      "the condyle's most prominent face along the flexion axis (the femur within {:.0f} mm of "
      "its outermost point, {:.0f} mm^2)",
      kProminenceMm, whole->area_mm2);
  Landmark landmark;
  if (ligament != nullptr) {
    const Eigen::Vector3d end = proximal_end(*ligament, proximal);
    const SurfaceQuery::Closest nearest = query.closest(end);
    if (nearest.distance <= kLigamentReachMm) {
      landmark.point_mm = nearest.point;
      landmark.how = fmt::format("the point of {} nearest the {}'s femoral end ({:.1f} mm away)",
                                 prominence, ligament_name, nearest.distance);
      return landmark;
    }
    landmark.how = fmt::format("; the {}'s femoral end lies {:.1f} mm from it: not used",
                               ligament_name, nearest.distance);
  }
  landmark.point_mm = query.closest(whole->centroid).point;
  landmark.how = "the centroid of " + prominence + landmark.how;
  return landmark;
}

} // namespace

SideFinding side_from_parts(const std::vector<SidePart>& parts,
                            const Eigen::Vector3d& plateau_centre_mm,
                            const Eigen::Vector3d& proximal, const Eigen::Vector3d& posterior)
{
  SideFinding found;
  const Eigen::Vector3d right = (-posterior).cross(proximal).normalized();
  int right_votes = 0, left_votes = 0;
  for (const SidePart& part : parts) {
    const double toward_right = (part.centroid_mm - plateau_centre_mm).dot(right);
    if (std::abs(toward_right) < kSideCueMm) {
      found.evidence.push_back(fmt::format("the {} lies {:.1f} mm from the plateau's centre "
                                           "across the knee: too near to tell",
                                           part.name, std::abs(toward_right)));
      continue;
    }
    // A lateral part on the subject's right, or a medial one on their left: a right knee.
    const bool right_knee = (toward_right > 0.0) != part.medial;
    (right_knee ? right_votes : left_votes) += 1;
    found.evidence.push_back(
        fmt::format("the {} ({}) lies {:.1f} mm to the subject's {} of the "
                    "tibial plateau's centre: a {} knee",
                    part.name, part.medial ? "medial" : "lateral", std::abs(toward_right),
                    toward_right > 0.0 ? "right" : "left", right_knee ? "right" : "left"));
  }
  found.contradicted = right_votes > 0 && left_votes > 0;
  if (!found.contradicted && right_votes + left_votes > 0)
    found.side = right_votes > 0 ? "right" : "left";
  return found;
}

std::map<std::string, Landmark> femur_landmarks(const TriangleSurface& femur,
                                                const CondyleCylinder& axis,
                                                const Eigen::Vector3d& proximal,
                                                const TriangleSurface* mcl,
                                                const TriangleSurface* lcl)
{
  const Facets f = facets_of(femur);
  std::map<std::string, Landmark> found;
  const auto medial = epicondyle(femur, f, axis, axis.medial, proximal, mcl, "MCL");
  const auto lateral = epicondyle(femur, f, axis, -axis.medial, proximal, lcl, "LCL");
  if (medial)
    found["medial_epicondyle"] = *medial;
  if (lateral)
    found["lateral_epicondyle"] = *lateral;
  if (medial && lateral) {
    // The notch lies between the condyles, where the flexion axis leaves the bone.
    const Eigen::Vector3d middle =
        axis.point_mm +
        0.5 * (medial->point_mm + lateral->point_mm - 2.0 * axis.point_mm).dot(axis.medial) *
            axis.medial;
    found["intercondylar_notch"] = {
        SurfaceQuery(femur).closest(middle).point,
        "the femur's surface nearest the flexion axis midway between the epicondyles"};
  }
  return found;
}

std::map<std::string, Landmark> tibia_landmarks(const TriangleSurface& tibia,
                                                const Eigen::Vector3d& proximal,
                                                const Eigen::Vector3d& medial)
{
  const Facets f = facets_of(tibia);
  const double top = highest(f, proximal);
  const auto upward = [&](Eigen::Index i) {
    return top - f.centroid.row(i).dot(proximal.transpose()) <= kPlateauDepthMm &&
           f.normal.row(i).dot(proximal.transpose()) >= kUpwardCos;
  };
  std::map<std::string, Landmark> found;
  const auto plateau = region(f, upward);
  if (!plateau)
    return found;
  const std::string what =
      fmt::format("the tibia's upward-facing surface within {:.0f} mm of its most proximal point",
                  kPlateauDepthMm);
  found["tibial_plateau_centre"] = {
      plateau->centroid, fmt::format("centroid of {} ({:.0f} mm^2)", what, plateau->area_mm2)};
  for (const auto& [name, sign] :
       {std::pair{"medial_tibial_plateau", 1.0}, std::pair{"lateral_tibial_plateau", -1.0}}) {
    const auto half = region(f, [&](Eigen::Index i) {
      return upward(i) &&
             sign * (f.centroid.row(i).transpose() - plateau->centroid).dot(medial) > 0.0;
    });
    if (half)
      found[name] = {half->centroid,
                     fmt::format("centroid of the {} half of {} ({:.0f} mm^2)",
                                 sign > 0 ? "medial" : "lateral", what, half->area_mm2)};
  }
  return found;
}

std::optional<Landmark> fibular_head(const TriangleSurface& fibula, const Eigen::Vector3d& proximal)
{
  const Facets f = facets_of(fibula);
  const double top = highest(f, proximal);
  const auto head = region(f, [&](Eigen::Index i) {
    return top - f.centroid.row(i).dot(proximal.transpose()) <= kFibularHeadMm;
  });
  if (!head)
    return std::nullopt;
  return Landmark{head->centroid,
                  fmt::format("centroid of the fibula's surface within {:.0f} mm of its most "
                              "proximal point",
                              kFibularHeadMm)};
}

} // namespace ligsim::anatomy
