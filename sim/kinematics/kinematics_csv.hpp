#pragma once
/// @brief Knee kinematics from a CSV file: Grood & Suntay coordinates of the tibia relative to
/// the femur per flexion angle or per time, as robot and motion-capture labs export them.
///
/// The first line that is not a comment (#) names the columns, separated by commas:
/// `flexion_deg` (required), `time_s` (optional: then the rows are a motion in time),
/// `varus_deg`, `internal_rotation_deg`, `lateral_mm`, `anterior_mm`, `proximal_mm` (optional,
/// 0 when absent). Each further line is one row of numbers. A free run's kinematics.csv reads as
/// it is: its `angle_deg` is the flexion, its `medial_mm` minus `lateral_mm`, and its contact and
/// residual columns are skipped.

#include "sim/kinematics/knee_path.hpp"

#include <filesystem>

namespace ligsim::sim {

/// Reads the file. Throws InputError naming the file and line on a missing or unknown column, a
/// row with the wrong number of fields, a field that is not a finite number, no rows, or a
/// parameter (time, else flexion) that does not increase.
KneePath read_kinematics_csv(const std::filesystem::path& file);

} // namespace ligsim::sim
