#pragma once
/// @brief Measurements of a tear: its direction, its distance from a centre, whether the
/// membrane fell apart.

#include "sim/membrane/crack/tearing.hpp"
#include "sim/membrane/mesh/membrane_mesh.hpp"

#include <vector>

namespace ligsim::membrane {

/// Mean direction of the tear path, degrees from +x in [0, 180): the axial mean of the
/// segments' directions (doubled angles), weighted by their lengths. NaN without segments.
double mean_tear_direction_deg(const std::vector<TearEvent>& events);

struct RadiusStatistics {
  double mean_mm = 0.0;
  double standard_deviation_mm = 0.0;
  double coefficient_of_variation = 0.0; ///< standard deviation over mean
  int points = 0;
};

/// Distance from `centre` of the tear path's points (the end of every event), mm.
RadiusStatistics tear_radius(const std::vector<TearEvent>& events, const Vec2& centre);

/// Number of pieces: triangles connected through shared nodes.
int component_count(const MembraneMesh& mesh);

} // namespace ligsim::membrane
