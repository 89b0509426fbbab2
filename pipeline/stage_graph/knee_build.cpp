#include "pipeline/stage_graph/knee_build.hpp"

#include "common/atomic_file.hpp"
#include "common/error.hpp"
#include "common/knee_manifest.hpp"
#include "common/progress.hpp"
#include "common/run_summary.hpp"
#include "common/vtk_files.hpp"
#include "pipeline/stage_graph/companion_build.hpp"
#include "pipeline/stage_graph/stage_files.hpp"
#include "pipeline/stage_graph/stage_graph.hpp"
#include "stages/io/vtk_convert.hpp"

#include <fmt/format.h>
#include <vtkPolyData.h>

namespace ligsim::pipeline {

namespace fs = std::filesystem;

namespace {

/// The knee's bones in its folder, repaired as a ligament's model stage repairs them.
std::map<std::string, std::string> write_bones(const KneeConfig& knee, const fs::path& dir)
{
  std::map<std::string, std::string> bones;
  for (const auto& [name, file] : {std::pair{"femur", knee.femur}, std::pair{"tibia", knee.tibia},
                                   std::pair{"fibula", knee.fibula}}) {
    const std::string target = std::string(name) + ".vtp";
    if (file.empty()) {
      std::error_code ignored;
      fs::remove(dir / target, ignored);
      continue;
    }
    write_vtk(io::to_polydata(*load_bone(file)), dir / target);
    bones[name] = target;
  }
  return bones;
}

} // namespace

nlohmann::json to_json(const KneeConfig& knee)
{
  nlohmann::json ligaments = nlohmann::json::object();
  for (const LigamentConfig& ligament : knee.ligaments) {
    nlohmann::json entry = to_json(ligament.build);
    entry["distal_bone"] = ligament.distal_bone;
    entry["failure_strain"] = ligament.failure_strain;
    entry["failure_load_n"] = ligament.failure_load_n;
    entry["material"] = material_json(ligament.build.material);
    entry["defaults_source"] = ligament.defaults_source;
    entry["contact_bones"] = ligament.contact_bones;
    ligaments[ligament.name] = entry;
  }
  return {{"femur", knee.femur.string()},
          {"tibia", knee.tibia.string()},
          {"fibula", knee.fibula.string()},
          {"ligaments", ligaments}};
}

void build_knee_ligament(const KneeConfig& knee, const LigamentConfig& ligament,
                         const fs::path& dir, const std::string& target, bool force,
                         RunSummary& summary)
{
  log_info(fmt::format("ligament {}", ligament.name));
  RunSummary own(target == "model" ? "build" : target);
  own.inputs() = {{"config", knee.file.string()},
                  {"ligament", ligament.name},
                  {"surface", ligament.build.surface.string()},
                  {"femur", ligament.build.femur.string()},
                  {ligament.distal_bone, ligament.build.tibia.string()}};
  own.parameters() = to_json(ligament.build);
  // A stage's error names its ligament: the knee builds several, one after another.
  try {
    run_target(ligament.build, dir / ligament.name, target, force, own);
    if (target == "model")
      build_companion(ligament.build, dir / ligament.name, force, own);
  } catch (const InputError& e) {
    fail("ligament {}: {}", ligament.name, e.what());
  } catch (const SolverError& e) {
    fail<SolverError>("ligament {}: {}", ligament.name, e.what());
  }
  own.write(dir / ligament.name);
  for (const auto& [stage, entry] : own.json()["stages"].items())
    summary.stage(ligament.name + "/" + stage) = entry;
}

KneeConfig with_knee_anatomy(const KneeConfig& knee)
{
  KneeConfig found = knee;
  found.shared.anatomy.known = knee_anatomy(knee.shared);
  for (LigamentConfig& ligament : found.ligaments)
    ligament.build.anatomy.known = found.shared.anatomy.known;
  return found;
}

void write_knee_files(const KneeConfig& knee, const fs::path& dir)
{
  KneeManifest manifest;
  for (const LigamentConfig& ligament : knee.ligaments) {
    KneeLigament entry;
    entry.name = ligament.name;
    entry.folder = ligament.name;
    entry.distal_bone = ligament.distal_bone;
    entry.in_situ_strain = ligament.build.model.in_situ_strain;
    entry.failure_strain = ligament.failure_strain;
    entry.failure_load_n = ligament.failure_load_n;
    entry.material = material_json(ligament.build.material);
    entry.defaults_source = ligament.defaults_source;
    entry.contact_bones = ligament.contact_bones;
    manifest.ligaments.push_back(entry);
  }
  manifest.bones = write_bones(knee, dir);
  write_text_atomically(dir / knee_anatomy_file, to_json(knee_anatomy(knee.shared)).dump(2) + "\n");
  write_text_atomically(dir / knee_manifest_file, to_json(manifest).dump(2) + "\n");
}

void build_knee(const KneeConfig& knee, const fs::path& dir, const std::string& target, bool force,
                RunSummary& summary)
{
  ensure_directory(dir);
  const KneeConfig found = with_knee_anatomy(knee);
  for (const LigamentConfig& ligament : found.ligaments)
    build_knee_ligament(found, ligament, dir, target, force, summary);
  if (target == "model")
    write_knee_files(found, dir);
}

} // namespace ligsim::pipeline
