#include "sim/flexion/flexion_settings.hpp"

#include "common/error.hpp"

#include <cmath>

namespace ligsim::sim {

void validate(const FlexionSettings& settings)
{
  const std::vector<double>& angles = settings.angles_deg;
  if (angles.empty())
    fail("flexion: the list of angles is empty: give at least one angle (degrees)");
  for (std::size_t i = 0; i < angles.size(); ++i) {
    if (!std::isfinite(angles[i]) || angles[i] < 0.0 || angles[i] > 180.0)
      fail("flexion: angle {} is {} degrees; angles lie in [0, 180] (0: the pose the model was "
           "built in)",
           i + 1, angles[i]);
    if (i > 0 && !(angles[i] > angles[i - 1]))
      fail("flexion: the angles must increase; angle {} ({} deg) follows {} deg", i + 1, angles[i],
           angles[i - 1]);
  }
  if (settings.axis.source == AxisSettings::Source::points &&
      (!(settings.axis.second_mm - settings.axis.first_mm).allFinite() ||
       (settings.axis.second_mm - settings.axis.first_mm).norm() < 1e-9))
    fail("flexion: the two axis points coincide: the flexion axis has zero length");
  if (!(settings.in_situ_strain > -1.0) || !std::isfinite(settings.in_situ_strain))
    fail("flexion: in_situ_strain must be above -1, got {}", settings.in_situ_strain);
  const InteractiveSettings& interactive = settings.interactive;
  if (!(interactive.angular_speed_deg_s > 0.0) || !std::isfinite(interactive.angular_speed_deg_s))
    fail("flexion: the angular speed must be positive, got {} deg/s",
         interactive.angular_speed_deg_s);
  if (!(interactive.time_step_s > 0.0) || !std::isfinite(interactive.time_step_s))
    fail("flexion: the time step must be positive, got {} s", interactive.time_step_s);
  if (!(interactive.density_kg_m3 > 0.0) || !(interactive.mass_damping_per_s >= 0.0))
    fail("flexion: the density must be positive and the damping not negative");
  if (interactive.max_iterations < 1 || !(interactive.iteration_tolerance > 0.0))
    fail("flexion: [interactive] max_iterations must be at least 1 and iteration_tolerance "
         "positive, got {} and {}",
         interactive.max_iterations, interactive.iteration_tolerance);
  if (!settings.anatomy.side.empty() && settings.anatomy.side != "left" &&
      settings.anatomy.side != "right")
    fail("flexion: [anatomy] side must be \"left\" or \"right\", got \"{}\"",
         settings.anatomy.side);
  if (settings.motion.path == MotionSettings::Path::table && settings.motion.table.empty())
    fail("flexion: [motion] path = \"table\" needs `table`, the CSV file of the knee's "
         "coordinates");
  if (!(settings.ligament.failure_strain > 0.0) || !(settings.ligament.failure_load_n > 0.0))
    fail("flexion: [ligament] failure_strain and failure_load_n must be positive");
  if (!settings.material.fiber)
    fail("flexion: the ligament material needs its fiber law");
  sim::validate(settings.material);
  sim::validate(settings.contact);
}

std::string to_string(FlexionMode mode)
{
  return mode == FlexionMode::quasi_static ? "static" : "interactive";
}

std::string to_string(AxisSettings::Source source)
{
  switch (source) {
  case AxisSettings::Source::condyles:
    return "condyles";
  case AxisSettings::Source::points:
    return "points";
  case AxisSettings::Source::transepicondylar:
    return "transepicondylar";
  }
  return "?";
}

std::string to_string(MotionSettings::Path path)
{
  switch (path) {
  case MotionSettings::Path::automatic:
    return "auto";
  case MotionSettings::Path::pure:
    return "pure";
  case MotionSettings::Path::passive:
    return "passive";
  case MotionSettings::Path::table:
    return "table";
  case MotionSettings::Path::free:
    return "free";
  }
  return "?";
}

} // namespace ligsim::sim
