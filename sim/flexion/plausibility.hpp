#pragma once
/// @brief Is a flexion answer one a knee could give? The footprints the ligament is bound by
/// (their areas beside published ones, their distance from the flexion axis), and per angle the
/// share of the ligament strained past its failure strain and forces past its failure load,
/// with the likely causes said out loud.

#include "sim/flexion/axis/condyle_axis.hpp"
#include "sim/flexion/flexion_settings.hpp"
#include "sim/flexion/initial_overlap.hpp"
#include "sim/flexion/knee_model.hpp"

#include <nlohmann/json.hpp>

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

nlohmann::json footprints_json(const std::vector<Footprint>& prints, const std::string& ligament);

/// What the sweep knows that may explain an implausible angle.
struct PlausibilityContext {
  LigamentSettings ligament;
  std::vector<Footprint> footprints;
  double in_situ_strain = 0.0;
};

/// The warnings of one angle (empty: plausible by these checks), each one line.
std::vector<std::string> plausibility_warnings(const AngleResult& angle,
                                               const PlausibilityContext& context);

} // namespace ligsim::sim
