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

/// Reads each member's summary.json (one ligament, or a knee's several) and writes cohort.csv
/// (member x ligament x angle), cohort.md (femur force per angle and strain energy at the last,
/// one row per member and ligament) and cohort.png / .svg (femur force against angle, one curve
/// per member and ligament). `ligaments` keeps those ligaments of every member (all when
/// empty). Throws InputError naming the member and file when a summary is missing or is not a
/// flexion's, when two members share a name, or naming a chosen ligament a member lacks (and the
/// ones it has).
nlohmann::json write_cohort_table(const std::vector<CohortMember>& members,
                                  const std::filesystem::path& out, bool png,
                                  const std::vector<std::string>& ligaments = {});

} // namespace ligsim::study
