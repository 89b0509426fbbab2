#pragma once
/// @brief Runs FEBio's solver on a .feb file, as a separate process, and says how it ended.

#include "sim/febio/febio_log.hpp"

#include <filesystem>

namespace ligsim::sim {

struct FebioRun {
  std::filesystem::path log;     ///< <stem>.log beside the input
  std::filesystem::path console; ///< <stem>.console.txt: what FEBio printed
  double wall_s = 0.0;           ///< the whole FEBio process, wall clock
  FebioLog parsed;
};

/// Runs `executable -i feb -o <stem>.log -p <stem>.xplt` in the input's folder, its console
/// output into <stem>.console.txt. Throws InputError when `executable` is not an executable
/// file, and SolverError (naming FEBio's own message) when the run does not end with FEBio's
/// normal termination.
FebioRun run_febio(const std::filesystem::path& executable, const std::filesystem::path& feb);

} // namespace ligsim::sim
