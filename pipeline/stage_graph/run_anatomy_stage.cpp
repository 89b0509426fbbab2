/// The first stage: what the config and the data say of the knee's anatomy (anatomy.json).

#include "pipeline/stage_graph/stage_files.hpp"

#include "common/atomic_file.hpp"
#include "common/error.hpp"
#include "common/knee_anatomy.hpp"
#include "common/run_summary.hpp"
#include "stages/io/surface_reader.hpp"

#include <Eigen/Geometry>

namespace ligsim::pipeline {

namespace fs = std::filesystem;

namespace {

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
    fail("anatomy: the landmark surface {} has no area", what);
  return sum / area;
}

Eigen::Vector3d mean_vertex(const TriangleSurface& surface)
{
  return surface.V.colwise().mean().transpose();
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

} // namespace

KneeAnatomy knee_anatomy(const BuildConfig& config)
{
  const AnatomyInputs& given = config.anatomy;
  KneeAnatomy anatomy;
  anatomy.side = given.side;
  add_landmark(anatomy, "medial_epicondyle", given.medial_epicondyle_mm,
               given.medial_epicondyle_surface);
  add_landmark(anatomy, "lateral_epicondyle", given.lateral_epicondyle_mm,
               given.lateral_epicondyle_surface);

  // Directions: the config's, else a label map's frame (ITK reads it as LPS: +y posterior, +z
  // superior), else the bones (up: from the tibia's mean vertex to the femur's).
  std::vector<std::string> sources;
  if (given.proximal.norm() > 0.0) {
    anatomy.proximal = given.proximal.normalized();
    sources.push_back("proximal given");
  }
  if (given.posterior.norm() > 0.0) {
    anatomy.posterior = given.posterior.normalized();
    sources.push_back("posterior given");
  }
  if (!config.labels.empty()) {
    if (!anatomy.proximal) {
      anatomy.proximal = Eigen::Vector3d::UnitZ();
      sources.push_back("proximal = +S of the label map's LPS frame");
    }
    if (!anatomy.posterior) {
      anatomy.posterior = Eigen::Vector3d::UnitY();
      sources.push_back("posterior = +P of the label map's LPS frame");
    }
  }
  if (!anatomy.proximal && !config.femur.empty() && !config.tibia.empty()) {
    const Eigen::Vector3d up =
        mean_vertex(*load_bone(config.femur)) - mean_vertex(*load_bone(config.tibia));
    if (up.norm() > 0.0) {
      anatomy.proximal = up.normalized();
      sources.push_back("proximal from the tibia's mean vertex to the femur's");
    }
  }
  if (anatomy.proximal && anatomy.posterior &&
      anatomy.proximal->cross(*anatomy.posterior).norm() < 0.5)
    fail("anatomy: the proximal and posterior directions are less than 30 degrees apart");

  // The epicondyles say which way is lateral: with the directions that gives the side, or with
  // the side the posterior direction. The subject's right is anterior x proximal.
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
        sources.push_back("side from the epicondyles");
      anatomy.side = side;
    } else if (!anatomy.side.empty()) {
      const Eigen::Vector3d right = anatomy.side == "right" ? outward : Eigen::Vector3d(-outward);
      const Eigen::Vector3d across = right - right.dot(*anatomy.proximal) * *anatomy.proximal;
      anatomy.posterior = -anatomy.proximal->cross(across).normalized();
      sources.push_back("posterior from the side and the epicondyles");
    }
  }
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
