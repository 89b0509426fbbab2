#pragma once
/// @brief A FebProblem as a FEBio 4 input file (febio_spec 4.0): one time step per entry of
/// step_labels, ending at times 1, 2, ... (must points), the bones' poses prescribed exactly at
/// those times, the ligament's node positions, the rigid bodies' positions and reactions and
/// the elements' strain energy density logged at each of them (docs/export.md).

#include "sim/febio/feb_problem.hpp"

#include <filesystem>
#include <string>

namespace ligsim::sim {

/// FEBio's rigid-body degrees of freedom of a pose turning about `center_mm`: the displacement
/// of the center (x, y, z, mm) and the rotation vector (Ru, Rv, Rw: axis times angle, rad).
/// FEBio places a rigid body at x = center + d + R (X - center), R the rotation of that vector.
Eigen::Matrix<double, 6, 1> feb_rigid_dofs(const Eigen::Isometry3d& pose,
                                           const Eigen::Vector3d& center_mm);

/// The .feb text. Throws InputError for a problem that cannot be written: no tets or steps,
/// fibers not one per tet or not unit, a node index out of range or bound to two bones, a
/// bone's poses not one per step, a material without fibers.
std::string feb_text(const FebProblem& problem);

/// Writes feb_text(problem) to `file` atomically.
void write_feb(const std::filesystem::path& file, const FebProblem& problem);

} // namespace ligsim::sim
