/// `ligsim build --labels seg --out K` with nothing else, as a user with a named segmentation has
/// it: the HRA female left knee voxelized at 0.3 x 0.3 x 1 mm with Slicer-style names (bones,
/// four ligaments, a meniscus, a ligament ligsim does not build), its colour table under another
/// stem, in NIfTI (whose header cannot say it was made from surfaces: its frame is the atlas',
/// and the bones must overrule it). Then the shipped VHF map, which has no femur, and inputs that
/// cannot make a knee.

#include "stages/geometry/surface_query.hpp"
#include "stages/io/surface_reader.hpp"
#include "stages/io/vtk_convert.hpp"
#include "stages/synthetic/shapes.hpp"
#include "tests/pipeline/cli_runner.hpp"
#include "tests/pipeline/knee_fixture.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <Eigen/Geometry>

#include <fstream>
#include <sstream>

using namespace ligsim;
using namespace ligsim::test;
namespace fs = std::filesystem;

namespace {

const std::string kKnee = source_path("data/hra-knee/VH_F_Knee_L.glb").string();
const std::string kLigaments = source_path("data/hra-knee/VH_F_Ligaments_Knee_L.glb").string();

/// The atlas femur closed by its cartilage sheet and patches (it is open where they sit).
const char* kFemur =
    "VH_F_femur_L+VH_F_intercondylar_fossa_L+VH_F_anterior_cruciate_enthesis_L+"
    "VH_F_posterior_cruciate_enthesis_L+VH_F_lateral_perichondular_surface_L+"
    "VH_F_lateral_epicondylar_enthesis_L+VH_F_medial_epicondylar_enthesis_L+"
    "VH_F_trochlear_groove_L+VH_F_medial_perichondular_surface_L+"
    "VH_F_articular_cartilage_of_knee_L+VH_F_medial_condyle_of_left_femur_inf+"
    "VH_F_lateral_condyle_of_femur_inf_L+VH_F_lateral_condyle_of_femur_frontal_L+"
    "VH_F_distal_most_point_of_medial_condyle_L+VH_F_lateral_condyle_of_femur_sup_L+"
    "VH_F_medial_condyle_of_left_femur_sup";

/// The atlas has no tibial cartilage: its plateaus covered by 2 mm of it. The tibia's
/// upward-facing triangles (normal within 45 degrees of +y) of its proximal 12 mm, less the middle
/// fifth of their width (the intercondylar eminence, where the cruciates attach), extruded 2 mm
/// along +y into a closed shell.
TriangleSurface tibial_cartilage()
{
  const TriangleSurface tibia = io::read_surface(kKnee + "#VH_F_tibia_L");
  const double top = tibia.V.col(1).maxCoeff();
  std::vector<Eigen::Vector3i> plateau;
  for (Eigen::Index f = 0; f < tibia.F.rows(); ++f) {
    const Eigen::Vector3d a = tibia.V.row(tibia.F(f, 0)), b = tibia.V.row(tibia.F(f, 1)),
                          c = tibia.V.row(tibia.F(f, 2));
    if ((b - a).cross(c - a).normalized().y() > 0.7 && (a + b + c).y() / 3.0 > top - 12.0)
      plateau.push_back(tibia.F.row(f).transpose());
  }
  double lo = 1e9, hi = -1e9;
  for (const Eigen::Vector3i& f : plateau)
    for (int k = 0; k < 3; ++k) {
      lo = std::min(lo, tibia.V(f(k), 0));
      hi = std::max(hi, tibia.V(f(k), 0));
    }
  std::map<int, int> index; // tibia vertex -> cartilage's lower vertex
  std::vector<Eigen::Vector3i> lower;
  for (const Eigen::Vector3i& f : plateau) {
    const double x = (tibia.V(f(0), 0) + tibia.V(f(1), 0) + tibia.V(f(2), 0)) / 3.0;
    if (std::abs(x - 0.5 * (lo + hi)) < 0.1 * (hi - lo))
      continue;
    Eigen::Vector3i g;
    for (int k = 0; k < 3; ++k)
      g(k) = index.emplace(f(k), static_cast<int>(index.size())).first->second;
    lower.push_back(g);
  }
  const int n = static_cast<int>(index.size());
  TriangleSurface shell;
  shell.V.resize(2 * n, 3);
  for (const auto& [from, to] : index) {
    shell.V.row(to) = tibia.V.row(from);
    shell.V.row(to + n) = tibia.V.row(from) + Eigen::RowVector3d(0.0, 2.0, 0.0);
  }
  std::map<std::pair<int, int>, int> edges;
  for (const Eigen::Vector3i& f : lower)
    for (int k = 0; k < 3; ++k)
      ++edges[{f(k), f((k + 1) % 3)}];
  std::vector<Eigen::Vector3i> faces;
  for (const Eigen::Vector3i& f : lower) {
    faces.emplace_back(f(0), f(2), f(1));             // the underside, facing down
    faces.emplace_back(f(0) + n, f(1) + n, f(2) + n); // the top
  }
  for (const auto& [edge, count] : edges)
    if (!edges.count({edge.second, edge.first})) { // a rim edge: a wall
      faces.emplace_back(edge.first, edge.second, edge.second + n);
      faces.emplace_back(edge.first, edge.second + n, edge.first + n);
    }
  shell.F.resize(static_cast<Eigen::Index>(faces.size()), 3);
  for (std::size_t f = 0; f < faces.size(); ++f)
    shell.F.row(static_cast<Eigen::Index>(f)) = faces[f].transpose();
  return shell;
}

/// seg.nii.gz and knee.ctbl in a folder of their own: 497 x 550 x 113 voxels around the four
/// ligaments with 25 mm to spare. Later parts keep the voxels they share with earlier ones, as a
/// segmentation labels each voxel once: the tibial cartilage comes first (the femur keeps what
/// both would take) and the ligaments last.
fs::path hra_label_map()
{
  const fs::path dir = fresh_folder("hra_named_map");
  fs::create_directories(dir);
  write_vtk(io::to_polydata(synthetic::box({44, -482, -145}, {193, -317, -32})), dir / "box.vtp");
  write_vtk(io::to_polydata(tibial_cartilage()), dir / "tibial_cartilage.vtp");
  std::string parts =
      " --part \"" + (dir / "tibial_cartilage.vtp").string() + ":11:tibial_cartilage\"";
  for (const auto& [file, mesh, label, name] :
       {std::tuple{kKnee, std::string(kFemur), 1, "femur"},
        std::tuple{kKnee, std::string("VH_F_tibia_L"), 2, "tibia"},
        std::tuple{kKnee, std::string("VH_F_fibula_L"), 3, "fibula"},
        std::tuple{kKnee, std::string("VH_F_patella_L"), 4, "patella"},
        std::tuple{kKnee, std::string("VH_F_meniscus_L"), 5, "lateral_meniscus"},
        std::tuple{kLigaments, std::string("VH_F_left_tibial_collateral_ligament"), 6,
                   "tibial_collateral_ligament"},
        std::tuple{kLigaments, std::string("VH_F_fibular_collateral_ligament_L"), 7,
                   "fibular_collateral_ligament"},
        std::tuple{kLigaments, std::string("VH_F_anterior_cruciate_ligament_of_knee_L"), 8,
                   "anterior_cruciate_ligament"},
        std::tuple{kLigaments, std::string("VH_F_posterior_cruciate_ligament_of_knee_L"), 9,
                   "posterior_cruciate_ligament"},
        std::tuple{kLigaments, std::string("VH_F_anterolateral_ligament_of_knee_L"), 10,
                   "anterolateral_ligament"}})
    parts += " --part \"" + file + "#" + mesh + ":" + std::to_string(label) + ":" + name + "\"";
  const CliResult made =
      run_ligsim("labelmap" + parts + " --around " + (dir / "box.vtp").string() +
                 " --margin 0 --spacing 0.3,0.3,1 --out " + (dir / "seg.nii.gz").string());
  if (made.exit_code != 0)
    throw std::runtime_error("ligsim labelmap failed: " + made.stderr_text);
  fs::rename(dir / "seg.ctbl", dir / "knee.ctbl"); // as a Slicer bundle names its table
  return dir;
}

Eigen::Vector3d enthesis_centroid(const std::string& mesh)
{
  const TriangleSurface s = io::read_surface(kKnee + "#" + mesh);
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  double area = 0.0;
  for (Eigen::Index f = 0; f < s.F.rows(); ++f) {
    const Eigen::Vector3d a = s.V.row(s.F(f, 0)), b = s.V.row(s.F(f, 1)), c = s.V.row(s.F(f, 2));
    const double piece = 0.5 * (b - a).cross(c - a).norm();
    sum += piece * (a + b + c) / 3.0;
    area += piece;
  }
  return sum / area;
}

Eigen::Vector3d vector_of(const nlohmann::json& json)
{
  return {json[0].get<double>(), json[1].get<double>(), json[2].get<double>()};
}

/// data/hra-knee/knee.toml's anatomy and footprints, with the map's labels for the surfaces.
std::string hand_written_knee(const std::string& side)
{
  std::ostringstream text;
  text << "[input]\nlabels = \"seg.nii.gz\"\nfemur_label = \"femur\"\ntibia_label = \"tibia\"\n"
       << "fibula_label = \"fibula\"\n[anatomy]\nside = \"" << side << "\"\n"
       << "proximal = [0, 1, 0]\nposterior = [0, 0, -1]\nmedial_epicondyle_surface = \"" << kKnee
       << "#VH_F_medial_epicondylar_enthesis_L\"\nlateral_epicondyle_surface = \"" << kKnee
       << "#VH_F_lateral_epicondylar_enthesis_L\"\n[tetmesh]\ncell_size_mm = 1.2\n"
       << "[[ligament]]\nname = \"MCL\"\n[ligament.input]\nlabel = 6\n"
       << "[ligament.attachments.femur]\nrule = \"landmark\"\nlandmark = \"medial_epicondyle\"\n"
       << "proximal_mm = 3.2\nposterior_mm = 4.8\nradius_mm = 6.0\n"
       << "[ligament.attachments.tibia]\nrule = \"end\"\nend = \"distal\"\nend_length_mm = 15.0\n"
       << "bone_distance_mm = 2.0\n"
       << "[[ligament]]\nname = \"LCL\"\n[ligament.input]\nlabel = 7\n"
       << "[ligament.attachments.femur]\nrule = \"landmark\"\nlandmark = \"lateral_epicondyle\"\n"
       << "proximal_mm = 1.4\nposterior_mm = 3.1\nradius_mm = 6.0\n"
       << "[ligament.attachments.fibula]\nrule = \"proximity\"\ndistance_mm = 2.6\n";
  for (const auto& [name, label, distance] : {std::tuple{"ACL", 8, "3.2"}, {"PCL", 9, "4.0"}})
    text << "[[ligament]]\nname = \"" << name << "\"\n[ligament.input]\nlabel = " << label
         << "\n[ligament.attachments.femur]\nrule = \"end\"\nend = \"proximal\"\n"
         << "end_length_mm = 6.0\n[ligament.attachments.tibia]\nrule = \"proximity\"\n"
         << "distance_mm = " << distance << "\n";
  return text.str();
}

std::string read_text(const fs::path& file)
{
  std::ifstream in(file);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

} // namespace

TEST(KneeFromLabels, TheHraKneeIsBuiltFromItsNamesAloneAndFlexes)
{
  const fs::path map = hra_label_map();
  const fs::path knee = fresh_folder("hra_named_knee");
  const CliResult built = run_ligsim("build --labels " + (map / "seg.nii.gz").string() + " --out " +
                                     knee.string() + " --cell-size 1.2");
  ASSERT_EQ(built.exit_code, 0) << built.stderr_text;

  // What each label was taken for, in the summary and in the config written for the user.
  const nlohmann::json found = read_json(knee / "summary.json")["results"]["found_by_name"];
  std::map<int, std::string> taken;
  for (const nlohmann::json& label : found["labels"])
    taken[label["label"].get<int>()] = label["taken_for"].get<std::string>();
  EXPECT_EQ(taken[1], "femur");
  EXPECT_EQ(taken[6], "MCL");
  EXPECT_EQ(taken[7], "LCL");
  EXPECT_EQ(taken[9], "PCL");
  EXPECT_NE(taken[5].find("not used"), std::string::npos);
  EXPECT_EQ(taken[10], "not recognised");
  EXPECT_EQ(taken[11], "tibial_cartilage: joined to the tibia as its articular layer");
  const std::string config = read_text(knee / "knee.toml");
  EXPECT_NE(config.find("tibia_label = \"2+11\""), std::string::npos) << config;
  EXPECT_NE(config.find("10 'anterolateral_ligament': not recognised"), std::string::npos);
  EXPECT_NE(config.find("landmark = \"medial_epicondyle\""), std::string::npos);

  // The side from the fibula and the collaterals; the atlas frame (not a scanner's) overruled
  // by the bones; the epicondyles within 5 mm of the atlas' enthesis patches.
  const nlohmann::json anatomy = read_json(knee / "anatomy.json");
  EXPECT_EQ(anatomy["side"], "left");
  EXPECT_NE(anatomy["side_source"].get<std::string>().find("fibula"), std::string::npos);
  EXPECT_NE(anatomy["frame_source"].get<std::string>().find("disagrees with the bones"),
            std::string::npos)
      << anatomy["frame_source"];
  // Proximal from the tibia's centroid to the femur's: on bones cut 100 mm from the joint, their
  // centroids stand apart across the knee too. Measured: 9.6 degrees from the atlas' +y (2.2 with
  // whole bones; the femoral shaft itself stands 7 degrees from it).
  EXPECT_GT(anatomy["proximal"][1].get<double>(), std::cos(12.0 * M_PI / 180.0));
  for (const auto& [landmark, enthesis] :
       {std::pair{"medial_epicondyle", "VH_F_medial_epicondylar_enthesis_L"},
        std::pair{"lateral_epicondyle", "VH_F_lateral_epicondylar_enthesis_L"}}) {
    const Eigen::Vector3d point = vector_of(anatomy["landmarks"][landmark]["point_mm"]);
    EXPECT_LT((point - enthesis_centroid(enthesis)).norm(), 5.0) << landmark;
  }
  for (const char* landmark : {"intercondylar_notch", "tibial_plateau_centre", "fibular_head"})
    EXPECT_TRUE(anatomy["landmarks"].contains(landmark)) << landmark;
  EXPECT_TRUE(fs::exists(knee / "landmarks.vtp"));
  EXPECT_TRUE(fs::exists(knee / "anatomy.png"));

  // Each footprint within 4 mm and half its area of the one data/hra-knee/knee.toml's rules give
  // on the same map (its epicondyles the atlas' enthesis centroids).
  std::ofstream(map / "hand.toml") << hand_written_knee("left");
  const fs::path hand = fresh_folder("hra_hand_knee");
  const CliResult placed = run_ligsim("attachments --config " + (map / "hand.toml").string() +
                                      " --out " + hand.string());
  ASSERT_EQ(placed.exit_code, 0) << placed.stderr_text;
  for (const char* ligament : {"MCL", "LCL", "ACL", "PCL"})
    for (const char* bone : {"femur", "tibia"}) {
      const auto area_of = [&](const fs::path& dir) {
        return read_json(dir / ligament / "summary.json")["stages"]["attachments"]["figures"][bone];
      };
      const nlohmann::json ours = area_of(knee), theirs = area_of(hand);
      EXPECT_LT((vector_of(ours["mean_mm"]) - vector_of(theirs["mean_mm"])).norm(), 4.0)
          << ligament << " " << bone;
      EXPECT_NEAR(ours["area_mm2"].get<double>(), theirs["area_mm2"].get<double>(),
                  0.5 * theirs["area_mm2"].get<double>())
          << ligament << " " << bone;
    }

  // A config's side against the anatomy is an error that says both.
  std::ofstream(map / "wrong_side.toml") << hand_written_knee("right");
  const CliResult wrong = run_ligsim("anatomy --config " + (map / "wrong_side.toml").string() +
                                     " --out " + fresh_folder("hra_wrong_side").string());
  EXPECT_NE(wrong.exit_code, 0);
  EXPECT_NE(wrong.stderr_text.find("the config says a right knee, but"), std::string::npos)
      << wrong.stderr_text;

  // Flexed with no config (the femur free: the knee has both collaterals and both cruciates):
  // every ligament converges at every angle and stays out of the bones, but where a footprint
  // bound to one bone meets the other: measured 0.19 mm (the ACL's free nodes beside its femoral
  // footprint at 0 degrees) and 0.44 mm (the PCL's tibial footprint, every node within 4 mm of the
  // tibia, which the femur's notch reaches at 120 degrees as it rolls back and comes down).
  const fs::path flexion = fresh_folder("hra_named_flexion");
  const CliResult flexed = run_ligsim("flexion --model " + knee.string() + " --out " +
                                      flexion.string() + " --angles 0,60,120 --no-images");
  ASSERT_EQ(flexed.exit_code, 0) << flexed.stderr_text;
  EXPECT_TRUE(fs::exists(flexion / "kinematics.csv"));
  // The femur meets the tibial cartilage: the lateral compartment seats 2.20 mm apart as built,
  // where the same map without the cartilage label seats it 2.86 mm apart (on the tibia's bone).
  const nlohmann::json seat =
      read_json(flexion / "summary.json")["results"]["free"]["articular_seat"];
  EXPECT_LT(seat["lateral_built_separation_mm"].get<double>(), 2.5) << seat.dump();
  const std::vector<std::string> rows = lines(flexion / "flexion.csv");
  ASSERT_EQ(rows.size(), 1u + 4u * 3u);
  const auto column = [&](const std::string& name) {
    std::stringstream header(rows[0]);
    std::string cell;
    for (int c = 0; std::getline(header, cell, ','); ++c)
      if (cell == name)
        return c;
    return -1;
  };
  const int converged = column("converged"), penetration = column("max_penetration_mm");
  ASSERT_GE(converged, 0);
  ASSERT_GE(penetration, 0);
  for (std::size_t r = 1; r < rows.size(); ++r) {
    std::vector<std::string> cells;
    std::stringstream row(rows[r]);
    for (std::string cell; std::getline(row, cell, ',');)
      cells.push_back(cell);
    EXPECT_EQ(cells[converged], "1") << rows[r];
    EXPECT_LE(std::stod(cells[penetration]), 0.5) << rows[r];
  }
}

TEST(KneeFromLabels, ALigamentsLabelNameGivesItsDefaultsInAOneLigamentBuild)
{
  const fs::path map = hra_label_map();
  const fs::path out = fresh_folder("hra_named_mcl");
  const CliResult built = run_ligsim("build --labels " + (map / "seg.nii.gz").string() +
                                     " --ligament-label tibial_collateral_ligament --femur-label "
                                     "femur --tibia-label tibia --out " +
                                     out.string() + " --cell-size 1.5 --no-images");
  ASSERT_EQ(built.exit_code, 0) << built.stderr_text;
  const nlohmann::json defaults = read_json(out / "summary.json")["results"]["defaults_by_name"];
  EXPECT_EQ(defaults["ligament"], "MCL");
  EXPECT_NE(defaults["used"].get<std::string>().find("Gardiner & Weiss"), std::string::npos);
  // The human MCL's material (mu = 2 C1 = 2.88 MPa), not the ligament paper's 27.7 MPa, and its
  // femoral footprint at the epicondyle the anatomy found.
  EXPECT_NE(read_text(out / "scene.toml").find("2.88"), std::string::npos);
  const nlohmann::json femur =
      read_json(out / "summary.json")["stages"]["attachments"]["figures"]["femur"];
  EXPECT_NE(femur["rule"].get<std::string>().find("medial_epicondyle"), std::string::npos);
}

TEST(KneeFromLabels, TheVhfMapBuildsAndSaysWhatItCannotFind)
{
  // Its labels: MCL, femoral_cartilage, tibia. No femur, and a frame made from surfaces.
  const fs::path out = fresh_folder("vhf_named_knee");
  const CliResult built =
      run_ligsim("build --labels " + source_path("data/vhf-right-knee/knee_labels.nrrd").string() +
                 " --out " + out.string() + " --no-images");
  ASSERT_EQ(built.exit_code, 0) << built.stderr_text;
  EXPECT_NE(built.stderr_text.find("no label names the femur"), std::string::npos);
  const nlohmann::json anatomy = read_json(out / "anatomy.json");
  EXPECT_EQ(anatomy["side"], ""); // nothing guessed
  std::string not_found;
  for (const nlohmann::json& line : anatomy["not_found"])
    not_found += line.get<std::string>() + "\n";
  EXPECT_NE(not_found.find("no femur"), std::string::npos) << not_found;
  EXPECT_NE(not_found.find("posterior"), std::string::npos) << not_found;
  EXPECT_EQ(read_text(out / "knee.toml").find("femur_label"), std::string::npos);
  EXPECT_TRUE(fs::exists(out / "MCL" / "model.vtu"));
  // Its flexion cannot turn a femur it does not have, and says so.
  const CliResult flexed = run_ligsim("flexion --model " + out.string() + " --out " +
                                      fresh_folder("vhf_named_flexion").string() + " --no-images");
  EXPECT_NE(flexed.exit_code, 0);
  EXPECT_NE(flexed.stderr_text.find("has no femur"), std::string::npos) << flexed.stderr_text;
}

TEST(KneeFromLabels, CartilageLabelsJoinTheBonesTheyCover)
{
  // The synthetic knee's boxes with a 2 mm cartilage slab under the femur and two on the tibia
  // (medial and lateral, as Slicer atlases split them), and a meniscus.
  const fs::path dir = fresh_folder("named_cartilage_map");
  fs::create_directories(dir);
  write_knee_bones(dir);
  write_straight_ligament(1.5, -6.0, dir / "MCL.vtp");
  write_vtk(io::to_polydata(synthetic::box({-15, -10, 14.2}, {20, 10, 16.2})), dir / "fc.vtp");
  write_vtk(io::to_polydata(synthetic::box({-15, -10, -0.2}, {-8, 10, 1.8})), dir / "mtc.vtp");
  write_vtk(io::to_polydata(synthetic::box({1, -10, -0.2}, {9, 10, 1.8})), dir / "ltc.vtp");
  write_vtk(io::to_polydata(synthetic::box({-7, 8, -0.2}, {0, 10, 1.8})), dir / "men.vtp");
  write_vtk(io::to_polydata(synthetic::box({-16, -11, -15}, {21, 11, 31})), dir / "around.vtp");
  std::string parts;
  for (const auto& [file, label, name] :
       {std::tuple{"femur.vtp", 1, "femur"}, std::tuple{"tibia.vtp", 2, "tibia"},
        std::tuple{"fc.vtp", 3, "femoral_cartilage"},
        std::tuple{"mtc.vtp", 4, "medial_tibial_cartilage"},
        std::tuple{"ltc.vtp", 5, "lateral_tibial_cartilage"},
        std::tuple{"men.vtp", 6, "medial_meniscus"}, std::tuple{"MCL.vtp", 7, "MCL"}})
    parts += " --part " + (dir / file).string() + ":" + std::to_string(label) + ":" + name;
  const fs::path map = dir / "seg.nrrd";
  const CliResult made =
      run_ligsim("labelmap --spacing 0.5 0.5 0.5 --margin 0 --around " +
                 (dir / "around.vtp").string() + parts + " --out " + map.string());
  ASSERT_EQ(made.exit_code, 0) << made.stderr_text;

  const fs::path knee = fresh_folder("named_cartilage_knee");
  const CliResult built = run_ligsim("build --labels " + map.string() + " --out " + knee.string() +
                                     " --cell-size 1.0 --no-images");
  ASSERT_EQ(built.exit_code, 0) << built.stderr_text;
  const std::string config = read_text(knee / "knee.toml");
  EXPECT_NE(config.find("femur_label = \"1+3\""), std::string::npos) << config;
  EXPECT_NE(config.find("tibia_label = \"2+4+5\""), std::string::npos) << config;
  const nlohmann::json summary = read_json(knee / "summary.json")["results"];
  std::map<int, std::string> taken;
  for (const nlohmann::json& label : summary["found_by_name"]["labels"])
    taken[label["label"].get<int>()] = label["taken_for"].get<std::string>();
  EXPECT_EQ(taken[3], "femoral_cartilage: joined to the femur as its articular layer");
  EXPECT_EQ(taken[4], "tibial_cartilage: joined to the tibia as its articular layer");
  EXPECT_NE(taken[6].find("not used: meniscus"), std::string::npos) << taken[6];

  // The bones' surfaces enclose their cartilage: the femur reaches down to the slab's underside
  // (z = 14.2 mm, where the box alone ends at 16.2), the tibia up to 1.8 mm on both plateaus.
  const nlohmann::json& map_report = summary["label_map"];
  EXPECT_EQ(map_report["femur"]["joined_labels"], nlohmann::json::array({3}));
  EXPECT_EQ(map_report["tibia"]["joined_labels"], nlohmann::json::array({4, 5}));
  const TriangleSurface femur = io::read_surface(knee / "femur.vtp");
  const TriangleSurface tibia = io::read_surface(knee / "tibia.vtp");
  EXPECT_NEAR(femur.V.col(2).minCoeff(), 14.2, 0.5);
  EXPECT_NEAR(tibia.V.col(2).maxCoeff(), 1.8, 0.5);
  for (const double x : {-12.0, 5.0}) {
    const auto top = [&](const TriangleSurface& s) {
      double z = -1e9;
      for (Eigen::Index v = 0; v < s.V.rows(); ++v)
        if (std::abs(s.V(v, 0) - x) < 1.0 && std::abs(s.V(v, 1)) < 5.0)
          z = std::max(z, s.V(v, 2));
      return z;
    };
    EXPECT_NEAR(top(tibia), 1.8, 0.5) << "the plateau at x = " << x;
  }
}

TEST(KneeFromLabels, MapsThatCannotMakeAKneeAreClearErrors)
{
  // The synthetic knee's boxes and straight ligaments, named by the labels of each case.
  const fs::path dir = fresh_folder("named_bad_maps");
  fs::create_directories(dir);
  write_knee_bones(dir);
  write_straight_ligament(1.5, -6.0, dir / "A.vtp");
  write_straight_ligament(1.5, -6.0, dir / "far.vtp");
  {
    TriangleSurface far = io::read_surface(dir / "far.vtp");
    far.V.col(1).array() += 30.0; // 20 mm beyond the bones' side
    write_vtk(io::to_polydata(far), dir / "far.vtp");
  }
  write_vtk(io::to_polydata(synthetic::box({-16, -11, -15}, {21, 42, 31})), dir / "around.vtp");
  const auto map = [&](const std::string& parts, const std::string& name) {
    const fs::path file = dir / (name + ".nrrd");
    const CliResult made =
        run_ligsim("labelmap --spacing 0.5 0.5 0.5 --margin 0 --around " +
                   (dir / "around.vtp").string() + parts + " --out " + file.string());
    EXPECT_EQ(made.exit_code, 0) << made.stderr_text;
    return file;
  };
  const auto part = [&](const char* file, int label, const char* name) {
    return " --part " + (dir / file).string() + ":" + std::to_string(label) + ":" + name;
  };
  const auto expect_refused = [&](const fs::path& labels, const std::string& expected) {
    const fs::path out = fresh_folder("named_bad_out");
    const CliResult result =
        run_ligsim("build --labels " + labels.string() + " --out " + out.string());
    EXPECT_NE(result.exit_code, 0) << labels;
    EXPECT_NE(result.stderr_text.find(expected), std::string::npos) << result.stderr_text;
  };
  expect_refused(map(part("femur.vtp", 1, "blob") + part("A.vtp", 2, "MCL"), "no_bone"),
                 "no label names a bone");
  expect_refused(map(part("femur.vtp", 1, "femur") + part("tibia.vtp", 2, "Femur_bone") +
                         part("fibula.vtp", 3, "tibia") + part("A.vtp", 4, "MCL"),
                     "two_femurs"),
                 "two labels name the femur");
  expect_refused(
      map(part("femur.vtp", 1, "femur") + part("tibia.vtp", 2, "tibia") + part("far.vtp", 3, "MCL"),
          "far"),
      "ligament MCL touches no bone");
  expect_refused(map(part("femur.vtp", 1, "femur") + part("tibia.vtp", 2, "tibia") +
                         part("A.vtp", 3, "stripe"),
                     "no_ligament"),
                 "no label names a ligament ligsim builds");
}

TEST(KneeFromLabels, AThinObliqueLigamentInOneMillimetreSlicesContoursAndBuilds)
{
  // A band 1.5 mm thick and 6 mm wide crossing the 1 mm slices at 30 degrees, between two boxes:
  // its contour must be a closed surface that does not cross itself (the build refuses one that
  // does).
  const fs::path dir = fresh_folder("thin_band_map");
  fs::create_directories(dir);
  TriangleSurface band = synthetic::box({-20, -3, -0.75}, {20, 3, 0.75});
  const Eigen::Matrix3d tilt = Eigen::AngleAxisd(-M_PI / 6.0, Eigen::Vector3d::UnitY()).matrix();
  band.V = band.V * tilt.transpose();
  write_vtk(io::to_polydata(band), dir / "band.vtp");
  const Eigen::Vector3d top = tilt * Eigen::Vector3d(20, 0, 0), bottom = -top;
  write_vtk(io::to_polydata(synthetic::box(top + Eigen::Vector3d(-3, -8, -1),
                                           top + Eigen::Vector3d(12, 8, 12))),
            dir / "femur.vtp");
  write_vtk(io::to_polydata(synthetic::box(bottom + Eigen::Vector3d(-12, -8, -12),
                                           bottom + Eigen::Vector3d(3, 8, 1))),
            dir / "tibia.vtp");
  write_vtk(io::to_polydata(synthetic::box(bottom - Eigen::Vector3d(14, 10, 14),
                                           top + Eigen::Vector3d(14, 10, 14))),
            dir / "around.vtp");
  const CliResult made =
      run_ligsim("labelmap --spacing 0.3,0.3,1 --margin 0 --around " +
                 (dir / "around.vtp").string() + " --part " + (dir / "femur.vtp").string() +
                 ":1:femur --part " + (dir / "tibia.vtp").string() + ":2:tibia --part " +
                 (dir / "band.vtp").string() + ":3:MCL --out " + (dir / "seg.nrrd").string());
  ASSERT_EQ(made.exit_code, 0) << made.stderr_text;
  const fs::path out = fresh_folder("thin_band_model");
  const CliResult built = run_ligsim("build --labels " + (dir / "seg.nrrd").string() +
                                     " --ligament-label MCL --femur-label femur --tibia-label "
                                     "tibia --out " +
                                     out.string() + " --no-images");
  ASSERT_EQ(built.exit_code, 0) << built.stderr_text;
  const TriangleSurface contour = io::read_surface(out / "labels_ligament.vtp");
  EXPECT_TRUE(self_intersections(contour, 1).empty());
  EXPECT_TRUE(fs::exists(out / "model.vtu"));
}
