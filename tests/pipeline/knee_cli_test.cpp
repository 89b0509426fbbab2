/// `ligsim build` and `ligsim flexion` on a knee: a small synthetic knee of three straight
/// ligaments (two between femur and tibia, one between femur and fibula) that never touch each
/// other. Each ligament is built and cached on its own; the knee's sweep gives each ligament the
/// answer it gets alone.

#include "common/vtk_files.hpp"
#include "tests/pipeline/cli_runner.hpp"
#include "tests/pipeline/knee_fixture.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <vtkPolyData.h>

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>

using namespace ligsim;
using namespace ligsim::test;
namespace fs = std::filesystem;

namespace {

std::vector<std::string> cells(const std::string& line)
{
  std::vector<std::string> result;
  std::stringstream in(line);
  for (std::string cell; std::getline(in, cell, ',');)
    result.push_back(cell);
  if (!line.empty() && line.back() == ',')
    result.emplace_back();
  return result;
}

/// The knee's config: ligaments A (x = -6) and B (x = 6) on the tibia, C (x = 13) on the fibula;
/// `b_cell_size` sets B's own tet size.
/// The files under `folder` named as a run's temporaries (".<name>.tmp-<pid>...").
std::vector<std::string> temporaries_left(const fs::path& folder)
{
  std::vector<std::string> left;
  for (const fs::directory_entry& entry : fs::recursive_directory_iterator(folder))
    if (entry.path().filename().string().find(".tmp-") != std::string::npos)
      left.push_back(fs::relative(entry.path(), folder).string());
  return left;
}

std::string knee_config(double b_cell_size)
{
  std::ostringstream text;
  text << "[input]\nfemur = \"femur.vtp\"\ntibia = \"tibia.vtp\"\nfibula = \"fibula.vtp\"\n\n"
       << "[anatomy]\nproximal = [0, 0, 1]\nposterior = [0, 1, 0]\n\n"
       << "[voxelize]\nspacing_mm = 0.3\n\n[tetmesh]\ncell_size_mm = 1.0\n\n";
  for (const auto& [name, bone] :
       {std::pair{"A", "tibia"}, std::pair{"B", "tibia"}, std::pair{"C", "fibula"}}) {
    text << "[[ligament]]\nname = \"" << name << "\"\n"
         << "[ligament.input]\nsurface = \"" << name << ".vtp\"\n"
         << "[ligament.attachments.femur]\nrule = \"end\"\nend = \"proximal\"\n"
         << "end_length_mm = 2.0\n"
         << "[ligament.attachments." << bone << "]\nrule = \"end\"\nend = \"distal\"\n"
         << "end_length_mm = 2.0\n";
    if (std::string(name) == "B")
      text << "[ligament.tetmesh]\ncell_size_mm = " << b_cell_size << "\n";
    text << "\n";
  }
  return text.str();
}

/// The knee's surfaces and config in a folder of their own (made once per test process).
const fs::path& knee_inputs()
{
  static const fs::path dir = [] {
    const fs::path d = fresh_folder("knee_inputs_" + std::to_string(::getpid()));
    fs::create_directories(d);
    write_knee_bones(d);
    write_straight_ligament(1.5, -6.0, d / "A.vtp");
    write_straight_ligament(1.5, 6.0, d / "B.vtp");
    write_straight_ligament(1.5, 13.0, d / "C.vtp");
    std::ofstream(d / "knee.toml") << knee_config(1.0);
    return d;
  }();
  return dir;
}

/// The knee built once per test process.
const fs::path& knee_model()
{
  static const fs::path out = [] {
    const fs::path model = fresh_folder("knee_model_" + std::to_string(::getpid()));
    const CliResult built = run_ligsim("build --config " + (knee_inputs() / "knee.toml").string() +
                                       " --out " + model.string());
    EXPECT_EQ(built.exit_code, 0) << built.stderr_text;
    return model;
  }();
  return out;
}

std::map<std::string, std::string> statuses(const fs::path& dir)
{
  std::map<std::string, std::string> result;
  const nlohmann::json summary = read_json(dir / "summary.json");
  for (const auto& [name, stage] : summary["stages"].items())
    result[name] = stage["status"];
  return result;
}

/// The flexion of the knee at 0, 15 and 30 degrees about an axis along x, 5 mm behind the
/// femoral ends: every ligament turns the same way in its own plane.
CliResult flex(const fs::path& out, const std::string& more, const fs::path& model = knee_model())
{
  return run_ligsim("flexion --model " + model.string() +
                    " --axis 0,-5,16,1,-5,16 --angles 0,15,30 --out " + out.string() + " " + more);
}

} // namespace

TEST(KneeCli, BuildsEveryLigamentInItsFolderAndRebuildsOnlyTheOneChanged)
{
  const fs::path inputs = fresh_folder("knee_cache_inputs");
  fs::copy(knee_inputs(), inputs, fs::copy_options::recursive);
  const fs::path out = fresh_folder("knee_cache");
  const std::string build = "build --config " + (inputs / "knee.toml").string() + " --out ";
  const CliResult first = run_ligsim(build + out.string());
  ASSERT_EQ(first.exit_code, 0) << first.stderr_text;

  // The knee's folder: the bones once, and each ligament a model folder of its own.
  const nlohmann::json knee = read_json(out / "knee.json");
  ASSERT_EQ(knee["ligaments"].size(), 3u);
  EXPECT_EQ(knee["ligaments"][2]["name"], "C");
  EXPECT_EQ(knee["ligaments"][2]["distal_bone"], "fibula");
  EXPECT_EQ(knee["ligaments"][0]["distal_bone"], "tibia");
  for (const char* bone : {"femur", "tibia", "fibula"})
    EXPECT_GT(read_vtp(out / knee["bones"][bone].get<std::string>())->GetNumberOfPoints(), 0)
        << bone;
  for (const char* name : {"A", "B", "C"}) {
    EXPECT_TRUE(fs::exists(out / name / "model.vtu")) << name;
    EXPECT_TRUE(fs::exists(out / name / "summary.json")) << name;
  }
  for (const auto& [stage, status] : statuses(out))
    EXPECT_EQ(status, "ran") << stage;
  EXPECT_EQ(statuses(out).size(), 36u); // nine stages and three of the companion, three ligaments

  // Nothing changed: every stage of every ligament is reused.
  ASSERT_EQ(run_ligsim(build + out.string()).exit_code, 0);
  for (const auto& [stage, status] : statuses(out))
    EXPECT_EQ(status, "reused") << stage;
  // The companions' links to the reused stages were there already; nothing is left beside them.
  EXPECT_EQ(temporaries_left(out), std::vector<std::string>());

  // Only B's tet size changed: B's tet mesh and what follows it rerun, nothing else.
  std::ofstream(inputs / "knee.toml") << knee_config(1.3);
  const CliResult changed = run_ligsim(build + out.string());
  ASSERT_EQ(changed.exit_code, 0) << changed.stderr_text;
  for (const auto& [stage, status] : statuses(out)) {
    // B's companion remeshes; what follows reruns only where its coarser mesh came out new.
    if (stage == "B/companion/fibers" || stage == "B/companion/model")
      continue;
    const bool rerun = stage == "B/tetmesh" || stage == "B/fibers" || stage == "B/model" ||
                       stage == "B/companion/tetmesh";
    EXPECT_EQ(status, rerun ? "ran" : "reused") << stage;
  }

  // A stage flag sets its key in every ligament, over the shared table and over a ligament's own
  // (B's 1.3): every tet mesh reruns at the flag's size.
  const CliResult flagged = run_ligsim(build + out.string() + " --cell-size 1.1");
  ASSERT_EQ(flagged.exit_code, 0) << flagged.stderr_text;
  const std::map<std::string, std::string> after_flag = statuses(out);
  const nlohmann::json parameters = read_json(out / "summary.json")["parameters"]["ligaments"];
  for (const char* name : {"A", "B", "C"}) {
    EXPECT_EQ(after_flag.at(std::string(name) + "/tetmesh"), "ran") << name;
    EXPECT_EQ(parameters[name]["tetmesh"]["cell_size_mm"], 1.1) << name;
  }
}

TEST(KneeCli, EachLigamentAloneGivesItsAnswerInTheKnee)
{
  const fs::path together = fresh_folder("knee_flexion_all");
  const CliResult all = flex(together, "--no-images");
  ASSERT_EQ(all.exit_code, 0) << all.stderr_text;

  // flexion.csv: a row per ligament and angle; C's distal force is on the fibula.
  const std::vector<std::string> table = lines(together / "flexion.csv");
  ASSERT_EQ(table.size(), 10u);
  const std::vector<std::string> header = cells(table[0]);
  ASSERT_EQ(header.front(), "ligament");
  const auto column = [&](const std::string& name) {
    return static_cast<std::size_t>(std::find(header.begin(), header.end(), name) - header.begin());
  };
  ASSERT_LT(column("fibula_force_n"), header.size());
  for (std::size_t row = 1; row < table.size(); ++row) {
    const std::vector<std::string> values = cells(table[row]);
    ASSERT_EQ(values.size(), header.size()) << table[row];
    const bool on_fibula = values[0] == "C";
    EXPECT_EQ(values[column("tibia_force_n")].empty(), on_fibula) << table[row];
    EXPECT_EQ(values[column("fibula_force_n")].empty(), !on_fibula) << table[row];
  }
  // The pairs: apart at every angle (the ligaments stand 9 mm and 4 mm apart).
  const nlohmann::json summary = read_json(together / "summary.json");
  const nlohmann::json& pairs = summary["results"]["pairs"];
  ASSERT_EQ(pairs.size(), 9u); // three pairs at three angles
  for (const nlohmann::json& pair : pairs) {
    EXPECT_EQ(pair["nodes_inside"].get<int>(), 0) << pair.dump();
    EXPECT_GT(pair["closest_mm"].get<double>(), 2.0) << pair.dump();
  }
  EXPECT_EQ(lines(together / "pairs.csv").size(), 10u);

  // Each ligament alone: the same numbers, to round-off.
  for (const char* name : {"A", "B", "C"}) {
    const fs::path alone = fresh_folder(std::string("knee_flexion_") + name);
    const CliResult one = flex(alone, std::string("--no-images --ligaments ") + name);
    ASSERT_EQ(one.exit_code, 0) << one.stderr_text;
    const nlohmann::json own = read_json(alone / "summary.json");
    ASSERT_EQ(own["results"]["ligaments"].size(), 1u);
    const nlohmann::json& mine = own["results"]["ligaments"][name]["angles"];
    const nlohmann::json& knees = summary["results"]["ligaments"][name]["angles"];
    ASSERT_EQ(mine.size(), 3u);
    ASSERT_EQ(knees.size(), 3u);
    for (std::size_t a = 0; a < 3; ++a)
      for (const char* figure :
           {"strain_energy_mj", "max_fiber_stretch", "mean_fiber_stretch",
            "femur_force_magnitude_n", "tibia_force_magnitude_n", "length_change_mm"}) {
        const double expected = knees[a][figure].get<double>();
        EXPECT_NEAR(mine[a][figure].get<double>(), expected, 1e-12 * (1.0 + std::abs(expected)))
            << name << " " << figure << " at angle " << a;
      }
    // One ligament's folder of the knee is that ligament of the knee (its material, its bones).
    if (std::string(name) == "C") {
      const fs::path folder = fresh_folder("knee_flexion_folder_C");
      const CliResult own_folder = flex(folder, "--no-images", knee_model() / name);
      ASSERT_EQ(own_folder.exit_code, 0) << own_folder.stderr_text;
      nlohmann::json via_folder = read_json(folder / "summary.json")["results"]["ligaments"][name];
      nlohmann::json expected = mine;
      for (nlohmann::json* angles : {&via_folder["angles"], &expected})
        for (nlohmann::json& angle : *angles)
          angle.erase("wall_s");
      EXPECT_EQ(via_folder["angles"], expected);
    }
    // The ligament is loaded: the comparison is not one of zeros.
    EXPECT_GT(knees[2]["strain_energy_mj"].get<double>(), 1e-3) << name;
  }
}

TEST(KneeCli, InteractiveKneeReportsOneFrameRateForAllItsLigaments)
{
  const fs::path out = fresh_folder("knee_flexion_interactive");
  const CliResult result = flex(out, "--mode interactive --speed 90 --no-images");
  ASSERT_EQ(result.exit_code, 0) << result.stderr_text;
  const nlohmann::json summary = read_json(out / "summary.json");
  // Each ligament's frames take their turn: the knee's rate is below each ligament's own.
  const double knee = summary["results"]["frames_per_second"].get<double>();
  EXPECT_GT(knee, 0.0);
  for (const char* name : {"A", "B", "C"}) {
    const nlohmann::json& ligament = summary["results"]["ligaments"][name];
    EXPECT_EQ(ligament["angles"].size(), 3u) << name;
    EXPECT_GT(ligament["frames_per_second"].get<double>(), knee) << name;
  }
}

TEST(KneeCli, PicturesShowTheWholeKneeFromTheFrontAndTheSide)
{
  const fs::path out = fresh_folder("knee_flexion_pictures");
  const fs::path config = fresh_folder("knee_pictures.toml");
  std::ofstream(config) << "image_angles_deg = [0, 30]\n";
  const CliResult result = flex(out, "--config " + config.string());
  ASSERT_EQ(result.exit_code, 0) << result.stderr_text;
  for (const char* picture :
       {"knee_front_0.png", "knee_front_30.png", "knee_medial_0.png", "knee_medial_30.png"})
    EXPECT_GT(fs::file_size(out / picture), 10000u) << picture;
  // Each ligament's own pictures in its folder, as a one-ligament model draws them.
  for (const char* picture : {"A/ligament_0.png", "B/ligament_30.png", "C/strain_energy.png"})
    EXPECT_GT(fs::file_size(out / picture), 10000u) << picture;
  // The ligaments' states in their folders, the bones once, all in one ParaView series.
  for (const char* file : {"A/ligament_30.vtu", "C/ligament_0.vtu", "femur_30.vtp", "tibia.vtp",
                           "fibula.vtp", "flexion.pvd"})
    EXPECT_TRUE(fs::exists(out / file)) << file;
}

TEST(KneeCli, ALigamentOnTheFibulaIsExportedWithTheKneesThreeBones)
{
  const fs::path out = fresh_folder("knee_export") / "C.feb";
  const std::string export_febio =
      "export febio --axis 0,-5,16,1,-5,16 --angles 0,30 --out " + out.string() + " --model ";
  const CliResult result = run_ligsim(export_febio + (knee_model() / "C").string());
  ASSERT_EQ(result.exit_code, 0) << result.stderr_text;
  std::ifstream in(out);
  const std::string feb{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  // C's distal footprint is bound to the fibula; it slides on the tibia as in the flexion.
  for (const char* bone : {"femur", "tibia", "fibula"})
    EXPECT_NE(feb.find("<Elements type=\"tri3\" name=\"" + std::string(bone) + "\""),
              std::string::npos)
        << bone;
  EXPECT_NE(feb.find("<NodeSet name=\"fibula_attachment\">"), std::string::npos);
  EXPECT_EQ(feb.find("<NodeSet name=\"tibia_attachment\">"), std::string::npos);
  EXPECT_NE(feb.find("name=\"ligament_on_tibia\""), std::string::npos);
  EXPECT_NE(feb.find("the tibia and the fibula are fixed"), std::string::npos);

  // The ligament's contact bones in knee.json ([[ligament]] contact_bones) hold, as in the
  // flexion: C kept off the tibia.
  const fs::path knee = fresh_folder("knee_export_contact_bones");
  fs::copy(knee_model(), knee, fs::copy_options::recursive);
  nlohmann::json manifest = read_json(knee / "knee.json");
  manifest["ligaments"][2]["contact_bones"] = {"femur", "fibula"};
  std::ofstream(knee / "knee.json") << manifest.dump(2);
  const CliResult kept = run_ligsim(export_febio + (knee / "C").string());
  ASSERT_EQ(kept.exit_code, 0) << kept.stderr_text;
  std::ifstream kept_off(out);
  const std::string off{std::istreambuf_iterator<char>(kept_off), std::istreambuf_iterator<char>()};
  EXPECT_EQ(off.find("name=\"ligament_on_tibia\""), std::string::npos);
  EXPECT_NE(off.find("name=\"ligament_on_fibula\""), std::string::npos);

  // The knee's own folder holds three ligaments: the user is asked for one.
  const fs::path refused_out = fresh_folder("knee_export_refused") / "knee.feb";
  const CliResult refused = run_ligsim("export febio --axis 0,-5,16,1,-5,16 --out " +
                                       refused_out.string() + " --model " + knee_model().string());
  EXPECT_NE(refused.exit_code, 0);
  EXPECT_NE(refused.stderr_text.find("a knee of 3 ligaments (A, B, C)"), std::string::npos)
      << refused.stderr_text;
  EXPECT_FALSE(fs::exists(refused_out));
}

TEST(KneeCli, BadKneeConfigsAreRejectedWithWhereAndWhat)
{
  const auto expect_rejected = [](const std::string& text, const std::string& expected) {
    const fs::path dir = fresh_folder("knee_bad_config");
    fs::copy(knee_inputs(), dir, fs::copy_options::recursive);
    std::ofstream(dir / "knee.toml") << text;
    const fs::path out = fresh_folder("knee_bad_out");
    const CliResult result =
        run_ligsim("build --config " + (dir / "knee.toml").string() + " --out " + out.string());
    EXPECT_NE(result.exit_code, 0) << text;
    EXPECT_NE(result.stderr_text.find(expected), std::string::npos) << result.stderr_text;
    EXPECT_FALSE(fs::exists(out)) << text;
  };
  const std::string bones = "[input]\nfemur = \"femur.vtp\"\ntibia = \"tibia.vtp\"\n";
  const std::string a = "[[ligament]]\nname = \"A\"\n[ligament.input]\nsurface = \"A.vtp\"\n";
  expect_rejected(bones + a + a, "two ligaments are called A");
  expect_rejected(bones + "[[ligament]]\nname = \"A\"\n", "ligament A has no surface");
  expect_rejected(bones + "[[ligament]]\nname = \"A B\"\n", "needs a name");
  expect_rejected(bones + a + "[ligament.attachments.fibula]\nrule = \"end\"\n",
                  "attaches to the fibula, but [input] gives no fibula");
  expect_rejected(bones + a + "[ligament.tetmesh]\ncell_sise_mm = 1\n",
                  "unknown key 'cell_sise_mm' in [ligament.A.tetmesh]");
  expect_rejected(bones + a +
                      "[ligament.attachments.tibia]\nrule = \"end\"\n"
                      "[ligament.attachments.fibula]\nrule = \"end\"\n",
                  "gives both tibia and fibula");
  expect_rejected(bones + "[material]\nmu_mpa = 1\n" + a, "per ligament");
  expect_rejected("[input]\nfemur = \"femur.vtp\"\n" + a, "needs the femur and the tibia");

  // An attachment flag would give every ligament the same footprint rule: refused.
  const fs::path out = fresh_folder("knee_flag_out");
  const CliResult flagged = run_ligsim("build --config " + (knee_inputs() / "knee.toml").string() +
                                       " --femur-rule end --out " + out.string());
  EXPECT_NE(flagged.exit_code, 0);
  EXPECT_NE(flagged.stderr_text.find("each ligament has its own footprints"), std::string::npos)
      << flagged.stderr_text;
  EXPECT_FALSE(fs::exists(out));
}

TEST(KneeCli, TheFreeKneesPathReplayedAsATableGivesItsForcesAndACutLigamentChangesIt)
{
  // The synthetic knee's femur free (no articular contact: its bones stand 16 mm apart), held by
  // its three pre-stretched ligaments, which pull it down until they hold it.
  const fs::path config = knee_inputs() / "free.toml";
  std::ofstream(config) << "[motion]\npath = \"free\"\n\n[loads]\ncompression_n = 0\n\n"
                        << "[articular]\nenabled = false\n";
  const fs::path free = fresh_folder("knee_flexion_free");
  const CliResult found = flex(free, "--no-images --config " + config.string());
  ASSERT_EQ(found.exit_code, 0) << found.stderr_text;
  const std::vector<std::string> kinematics = lines(free / "kinematics.csv");
  ASSERT_EQ(kinematics.size(), 4u);
  const std::vector<std::string> header = cells(kinematics[0]);
  for (const char* name : {"angle_deg", "varus_deg", "internal_rotation_deg", "anterior_mm",
                           "medial_mm", "proximal_mm", "medial_contact_force_n",
                           "lateral_contact_force_n", "residual_force_n", "residual_moment_nmm"})
    EXPECT_NE(std::find(header.begin(), header.end(), name), header.end()) << name;
  // The found path drawn beside the passive cadaver knee's.
  std::ifstream svg(free / "kinematics.svg");
  const std::string plot{std::istreambuf_iterator<char>(svg), std::istreambuf_iterator<char>()};
  EXPECT_NE(plot.find("internal rotation, this knee"), std::string::npos);
  EXPECT_NE(plot.find("Walker 1988"), std::string::npos);
  const nlohmann::json summary = read_json(free / "summary.json");
  for (const nlohmann::json& angle : summary["results"]["free"]["angles"]) {
    EXPECT_TRUE(angle["converged"].get<bool>()) << angle.dump();
    // In equilibrium: what is left is round-off against the ligaments' pull.
    EXPECT_LT(angle["residual_force_n"].get<double>(),
              1e-4 * angle["force_scale_n"].get<double>() + 1e-9);
    // The femur came down the tibial axis, the ligaments' pre-stretch let go.
    EXPECT_GT(angle["proximal_mm"].get<double>(), 0.05) << angle.dump();
  }

  // The found path prescribed as a table gives the same forces.
  const fs::path replay_config = knee_inputs() / "replay.toml";
  std::ofstream(replay_config) << "[motion]\npath = \"table\"\ntable = \""
                               << (free / "kinematics.csv").string() << "\"\n";
  const fs::path replay = fresh_folder("knee_flexion_replay");
  const CliResult replayed = flex(replay, "--no-images --config " + replay_config.string());
  ASSERT_EQ(replayed.exit_code, 0) << replayed.stderr_text;
  const nlohmann::json again = read_json(replay / "summary.json");
  for (const char* name : {"A", "B", "C"})
    for (std::size_t a = 0; a < 3; ++a) {
      const double expected =
          summary["results"]["ligaments"][name]["angles"][a]["femur_force_magnitude_n"];
      const double got =
          again["results"]["ligaments"][name]["angles"][a]["femur_force_magnitude_n"];
      EXPECT_NEAR(got, expected, 1e-6 * std::max(1.0, std::abs(expected))) << name << " " << a;
    }

  // Cutting A: the femur finds another pose (the others carry what A held).
  const fs::path cut = fresh_folder("knee_flexion_without_A");
  const CliResult sectioned = flex(cut, "--no-images --without A --config " + config.string());
  ASSERT_EQ(sectioned.exit_code, 0) << sectioned.stderr_text;
  const nlohmann::json without = read_json(cut / "summary.json");
  EXPECT_FALSE(without["results"]["ligaments"].contains("A"));
  const double with_a = summary["results"]["free"]["angles"][2]["varus_deg"];
  const double without_a = without["results"]["free"]["angles"][2]["varus_deg"];
  EXPECT_GT(std::abs(with_a - without_a), 0.01);
  EXPECT_NE(run_ligsim("flexion --model " + knee_model().string() + " --without X --out " +
                       fresh_folder("knee_flexion_without_X").string())
                .stderr_text.find("--without names X"),
            std::string::npos);

  // A drawer: --load pulls the tibia forward of the unloaded knee's pose.
  const fs::path drawer = fresh_folder("knee_flexion_drawer");
  const CliResult pulled =
      flex(drawer, "--no-images --load anterior_n=5 --config " + config.string());
  ASSERT_EQ(pulled.exit_code, 0) << pulled.stderr_text;
  const nlohmann::json loaded = read_json(drawer / "summary.json");
  for (std::size_t a = 0; a < 3; ++a)
    EXPECT_GT(loaded["results"]["free"]["angles"][a]["anterior_mm"].get<double>(),
              summary["results"]["free"]["angles"][a]["anterior_mm"].get<double>() + 0.01)
        << a;
  for (const auto& [load, said] :
       {std::pair{"anterior=5", "unknown key 'anterior'"}, {"anterior_n", "expected KEY=VALUE"}})
    EXPECT_NE(flex(fresh_folder("knee_flexion_bad_load"),
                   std::string("--no-images --load ") + load + " --config " + config.string())
                  .stderr_text.find(said),
              std::string::npos)
        << load;
}
