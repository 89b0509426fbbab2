#pragma once
/// @brief What `ligsim build` shows of the anatomy it found, beside anatomy.json: the landmarks as
/// VTK points (landmarks.vtp, a "name" array to label them in ParaView) and a picture of the
/// bones with the landmarks on them (anatomy.png).

#include <filesystem>

namespace ligsim::cli {

/// Writes `dir`/landmarks.vtp and, with `picture`, `dir`/anatomy.png from `dir`/anatomy.json and
/// the bone and ligament surfaces of the model folder `dir` (a knee's or one ligament's). A
/// picture that cannot be drawn (no X display, no Xvfb) is said on stderr, not an error.
void write_anatomy_outputs(const std::filesystem::path& dir, bool picture);

} // namespace ligsim::cli
