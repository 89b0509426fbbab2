#pragma once
/// @brief Is a flexion answer one a knee could give? The footprints the ligament is bound by
/// (their areas beside published ones, their distance from the flexion axis), and per angle the
/// share of the ligament strained past its failure strain and forces past its failure load,
/// with the likely causes said out loud.

#include "sim/flexion/axis/condyle_axis.hpp"
#include "sim/flexion/flexion_settings.hpp"
#include "sim/flexion/initial_overlap.hpp"
#include "sim/flexion/knee_model.hpp"

#include <optional>
#include <string>
#include <vector>

namespace ligsim::sim {

struct AngleResult;

/// One bone's footprint as the model binds it.
struct Footprint {
  std::string bone;
  int nodes = 0;
  double area_mm2 = 0.0; ///< boundary triangles whose three nodes are bound to the bone
  double mean_axis_distance_mm = 0.0; ///< of the bound nodes from the flexion axis
  double max_axis_distance_mm = 0.0;
};

/// A published footprint area, mm^2 (mean, sd) and its source; none for an unknown ligament.
struct PublishedArea {
  double mean_mm2 = 0.0;
  double sd_mm2 = 0.0;
  std::string source;
};
std::optional<PublishedArea> published_footprint_area(const std::string& ligament,
                                                      const std::string& bone);

/// The femoral and tibial footprints of `model` about `axis`.
std::vector<Footprint> footprints(const KneeModel& model, const FlexionAxis& axis);

/// A published mid-substance cross-section (mm^2) and its source; none for a ligament without
/// one here.
struct PublishedCrossSection {
  double mm2 = 0.0;
  std::string source;
};
std::optional<PublishedCrossSection> published_cross_section(const std::string& ligament);

/// How thick the ligament was built: its volume over its centerline's length.
struct LigamentThickness {
  double volume_mm3 = 0.0;
  double centerline_mm = 0.0;
  double mean_cross_section_mm2 = 0.0;
};
/// None for a centerline of fewer than two points.
std::optional<LigamentThickness> ligament_thickness(const TetMesh& mesh, const Points& centerline);

/// A built ligament of a third of its published cross-section or less is too thin for its
/// stiffness and forces to be a real one's: one line that says so, or none.
std::optional<std::string> thin_ligament_finding(const std::string& ligament,
                                                 const LigamentThickness& thickness);

/// What the sweep knows that may explain an implausible angle.
struct PlausibilityContext {
  LigamentSettings ligament;
  std::vector<Footprint> footprints;
  double in_situ_strain = 0.0;
  std::optional<std::string> thin; ///< thin_ligament_finding's line
};

/// The warnings of one angle (empty: plausible by these checks), each one line.
std::vector<std::string> plausibility_warnings(const AngleResult& angle,
                                               const PlausibilityContext& context);

} // namespace ligsim::sim
