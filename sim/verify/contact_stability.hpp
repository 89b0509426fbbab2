#pragma once
/// @brief The contact rows of `verify stability`: a band (the ligament) held at both ends, a
/// rigid sphere (the bone, an OpenVDB level set of a triangulated sphere) moved 2 mm into it in
/// one load step with d_hat from 0.01 to 1 mm, and nodes that start inside the bone (pushed out
/// when the grid knows the way out, a diagnostic when they lie beyond its band).

#include "sim/verify/stability.hpp"

#include <optional>
#include <string>
#include <vector>

namespace ligsim::sim {

std::vector<StabilityCase> contact_stability_cases();

/// The result of the contact case `name`; nullopt when `name` is not one of them.
std::optional<StabilityResult> run_contact_stability_case(const std::string& name);

} // namespace ligsim::sim
