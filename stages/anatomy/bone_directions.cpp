#include "stages/anatomy/bone_directions.hpp"

#include "common/error.hpp"
#include "stages/anatomy/facets.hpp"

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>

#include <cmath>

namespace ligsim::anatomy {

namespace {

constexpr double kPlateauDepthMm = 15.0; // the tibia's proximal slab: its plateau
constexpr double kCondyleDepthMm = 25.0; // the femur's distal slab: its condyles
constexpr double kShaftFromMm = 35.0;    // the femur's shaft slab, above the condyles
constexpr double kShaftToMm = 70.0;
constexpr double kFibularHeadMm = 20.0; // the fibula's proximal slab
constexpr double kMinCueMm = 2.0;       // a smaller offset tells nothing
constexpr double kMinAspect = 1.15;     // plateau: long over short axis

Eigen::Vector3d centroid(const TriangleSurface& surface)
{
  const Facets f = facets_of(surface);
  const auto all = region(f, [](Eigen::Index) { return true; });
  if (!all)
    fail("anatomy: a bone surface has no area");
  return all->centroid;
}

/// The facets of `surface` whose height along `up` lies in [top - to, top - from] (from the
/// surface's highest point `top`); or, with `from_bottom`, in [bottom + from, bottom + to].
std::optional<Region> slab(const TriangleSurface& surface, const Eigen::Vector3d& up, double from,
                           double to, bool from_bottom = false)
{
  const Facets f = facets_of(surface);
  const double top = highest(f, up), bottom = -highest(f, -up);
  return region(f, [&](Eigen::Index i) {
    const double h = f.centroid.row(i).dot(up.transpose());
    const double depth = from_bottom ? h - bottom : top - h;
    return depth >= from && depth <= to;
  });
}

/// The plateau's long axis across `up`, and how much longer it is than the short one.
Eigen::Vector3d plateau_long_axis(const TriangleSurface& tibia, const Eigen::Vector3d& up,
                                  double& aspect)
{
  const Facets f = facets_of(tibia);
  const double top = highest(f, up);
  Eigen::Matrix3d scatter = Eigen::Matrix3d::Zero();
  const auto plateau = region(f, [&](Eigen::Index i) {
    return top - f.centroid.row(i).dot(up.transpose()) <= kPlateauDepthMm;
  });
  if (!plateau)
    fail("anatomy: the tibia has no proximal end");
  const Eigen::Matrix3d across = Eigen::Matrix3d::Identity() - up * up.transpose();
  for (Eigen::Index i = 0; i < f.area.size(); ++i) {
    if (top - f.centroid.row(i).dot(up.transpose()) > kPlateauDepthMm)
      continue;
    const Eigen::Vector3d d = across * (f.centroid.row(i).transpose() - plateau->centroid);
    scatter += f.area(i) * d * d.transpose();
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(scatter);
  aspect = std::sqrt(eigen.eigenvalues()(2) / std::max(eigen.eigenvalues()(1), 1e-12));
  return eigen.eigenvectors().col(2).normalized();
}

} // namespace

BoneDirections directions_from_bones(const KneeBones& bones)
{
  if (bones.femur == nullptr || bones.tibia == nullptr)
    fail("anatomy: the directions need the femur and the tibia");
  BoneDirections d;
  const Eigen::Vector3d femur_centre = centroid(*bones.femur);
  const Eigen::Vector3d tibia_centre = centroid(*bones.tibia);
  const Eigen::Vector3d up = femur_centre - tibia_centre;
  if (!(up.norm() > 1.0))
    fail("anatomy: the femur's and the tibia's centroids coincide: no proximal direction");
  d.proximal = up.normalized();
  d.evidence.push_back(fmt::format(
      "proximal: from the tibia's centroid to the femur's ({:.0f} mm apart)", up.norm()));

  double aspect = 1.0;
  d.mediolateral = plateau_long_axis(*bones.tibia, d.proximal, aspect);
  if (aspect < kMinAspect)
    fail("anatomy: the tibial plateau is as long as it is wide ({:.2f}): no mediolateral "
         "direction from it",
         aspect);
  d.evidence.push_back(fmt::format(
      "mediolateral: the tibial plateau's long axis ({:.2f} times its short one)", aspect));
  const Eigen::Vector3d across = d.proximal.cross(d.mediolateral).normalized();

  // Each cue: an offset along `across` whose sign says where posterior is (positive: +across).
  struct Cue {
    std::string what;
    double posterior_mm;
  };
  std::vector<Cue> cues;
  const auto condyles = slab(*bones.femur, d.proximal, 0.0, kCondyleDepthMm, true);
  if (bones.patella != nullptr && condyles)
    cues.push_back({"the patella lies in front of the femoral condyles",
                    -(centroid(*bones.patella) - condyles->centroid).dot(across)});
  const auto shaft = slab(*bones.femur, d.proximal, kShaftFromMm, kShaftToMm, true);
  if (condyles && shaft)
    cues.push_back({"the femoral condyles lie behind the femoral shaft",
                    (condyles->centroid - shaft->centroid).dot(across)});
  const auto plateau = slab(*bones.tibia, d.proximal, 0.0, kPlateauDepthMm);
  if (bones.fibula != nullptr && plateau) {
    if (const auto head = slab(*bones.fibula, d.proximal, 0.0, kFibularHeadMm))
      cues.push_back({"the fibular head lies behind the tibial plateau's centre",
                      (head->centroid - plateau->centroid).dot(across)});
  }
  int votes = 0;
  std::string said;
  for (const Cue& cue : cues) {
    if (std::abs(cue.posterior_mm) < kMinCueMm)
      continue;
    votes += cue.posterior_mm > 0.0 ? 1 : -1;
    said += fmt::format("{}{} ({:.1f} mm)", said.empty() ? "" : "; ", cue.what,
                        std::abs(cue.posterior_mm));
  }
  const bool agree = std::all_of(cues.begin(), cues.end(), [&](const Cue& cue) {
    return std::abs(cue.posterior_mm) < kMinCueMm || (cue.posterior_mm > 0.0) == (votes > 0);
  });
  if (votes == 0 || !agree) {
    std::string all;
    for (const Cue& cue : cues)
      all += fmt::format("{}{}: {:+.1f} mm", all.empty() ? "" : "; ", cue.what, cue.posterior_mm);
    fail("anatomy: the bones do not tell anterior from posterior ({}); give [anatomy] posterior",
         all.empty() ? "no patella, no fibula, no femoral shaft" : all);
  }
  d.posterior = votes > 0 ? across : Eigen::Vector3d(-across);
  d.evidence.push_back("posterior: " + said);
  return d;
}

} // namespace ligsim::anatomy
