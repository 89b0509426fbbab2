#pragma once
/// @brief The tear's path as a table: one row per tearing event, in the order they happened (the
/// step, the tip, the criterion, the segment in rest coordinates), so that two runs of a scene
/// can be compared event by event.

#include "sim/membrane/scene/tear_simulation.hpp"

#include <string>

namespace ligsim::membrane {

/// tear_path.csv's text: step,tip,initiation,criterion,from_x_mm,from_y_mm,to_x_mm,to_y_mm,
/// split_face,load_n.
std::string tear_path_csv(const TearMetrics& metrics);

} // namespace ligsim::membrane
