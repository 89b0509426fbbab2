#include "pipeline/study/study_model.hpp"

#include "common/error.hpp"
#include "pipeline/stage_graph/build_config.hpp"

#include <algorithm>

namespace ligsim::study {

namespace fs = std::filesystem;

StudyModel load_study_model(const fs::path& file, const std::vector<std::string>& chosen,
                            const std::string& job)
{
  StudyModel model;
  if (!pipeline::is_knee_config(file)) {
    if (!chosen.empty())
      fail("{}: --ligaments chooses among a knee config's ligaments; {} describes one ligament",
           job, file.string());
    model.config.file = file;
    model.config.ligaments.push_back({});
    model.config.ligaments.front().build = pipeline::load_build_config(file);
    return model;
  }
  model.knee = true;
  model.config = pipeline::load_knee_config(file);
  if (!model.config.labels.empty())
    fail("{}: {} takes the knee's surfaces from a label map, which the studies do not read yet: "
         "give the surfaces `ligsim build` took from it (labels_*.vtp in its output) as files",
         job, file.string());
  if (chosen.empty())
    return model;
  std::string names;
  for (const pipeline::LigamentConfig& ligament : model.config.ligaments)
    names += (names.empty() ? "" : ", ") + ligament.name;
  for (const std::string& name : chosen) {
    if (std::count(chosen.begin(), chosen.end(), name) > 1)
      fail("{}: --ligaments names {} twice", job, name);
    if (std::none_of(model.config.ligaments.begin(), model.config.ligaments.end(),
                     [&](const pipeline::LigamentConfig& l) { return l.name == name; }))
      fail("{}: the knee of {} has no ligament called {} (it has {})", job, file.string(), name,
           names);
  }
  std::vector<pipeline::LigamentConfig> kept;
  for (const pipeline::LigamentConfig& ligament : model.config.ligaments)
    if (std::find(chosen.begin(), chosen.end(), ligament.name) != chosen.end())
      kept.push_back(ligament);
  model.config.ligaments = kept;
  return model;
}

std::vector<std::string> ligament_names(const StudyModel& model, const std::string& single_name)
{
  if (!model.knee)
    return {single_name};
  std::vector<std::string> names;
  for (const pipeline::LigamentConfig& ligament : model.config.ligaments)
    names.push_back(ligament.name);
  return names;
}

fs::path ligament_folder(const StudyModel& model, std::size_t ligament, const fs::path& dir)
{
  return model.knee ? dir / model.config.ligaments.at(ligament).name : dir;
}

} // namespace ligsim::study
