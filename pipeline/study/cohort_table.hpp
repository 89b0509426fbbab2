#pragma once
/// @brief `ligsim study cohort`: one table and one plot from the flexion sweeps of several
/// subjects or variants (the last step of the Snakemake workflow in workflow/).

#include <nlohmann/json.hpp>

#include <filesystem>
#include <string>
#include <vector>

namespace ligsim::study {

struct CohortMember {
  std::string name;
  std::filesystem::path flexion_dir; ///< an output folder of `ligsim flexion`
};

/// Reads each member's summary.json and writes cohort.csv (member x angle), cohort.md (femur
/// force and strain energy per angle, one row per member) and cohort.png / .svg (femur force
/// against angle, one curve per member). Throws InputError naming the member and file when a
/// summary is missing or is not a flexion's, or when two members share a name.
nlohmann::json write_cohort_table(const std::vector<CohortMember>& members,
                                  const std::filesystem::path& out, bool png);

} // namespace ligsim::study
