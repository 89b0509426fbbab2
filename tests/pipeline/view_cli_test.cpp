/// `ligsim view` end to end under a virtual X server: a scripted drag of the slider on the VHF
/// and the HRA MCL, every frame drawn and recorded, the last one at the quasi-static sweep's
/// state; the square sheet torn live along the batch tear's path; and the clear error without a
/// display.

#include "tests/pipeline/cli_runner.hpp"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

using namespace ligsim::test;
namespace fs = std::filesystem;

namespace {

/// Runs ligsim under `xvfb-run` (a screen of its own), as the docs tell a user without one.
CliResult run_on_virtual_screen(const std::string& arguments)
{
  const fs::path log = fresh_folder("view_log") += ".txt";
  const std::string command = "xvfb-run -a -s '-screen 0 1280x1024x24' " +
                              std::string(LIGSIM_BINARY) + " " + arguments + " 2> " + log.string() +
                              " > /dev/null";
  const int status = std::system(command.c_str());
  std::ifstream in(log);
  std::string text{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, text};
}

std::vector<std::string> csv_cells(const std::string& line)
{
  std::vector<std::string> cells;
  std::string cell;
  bool quoted = false;
  for (char c : line) {
    if (c == '"')
      quoted = !quoted;
    else if (c == ',' && !quoted) {
      cells.push_back(cell);
      cell.clear();
    } else
      cell += c;
  }
  cells.push_back(cell);
  return cells;
}

} // namespace

TEST(ViewCli, WithoutADisplayItSaysSoAndGivesTheXvfbLine)
{
  const CliResult result = run_ligsim_without_display("view --model nowhere");
  EXPECT_NE(result.exit_code, 0);
  EXPECT_NE(result.stderr_text.find("DISPLAY is not set"), std::string::npos) << result.stderr_text;
  EXPECT_NE(result.stderr_text.find("xvfb-run -a"), std::string::npos) << result.stderr_text;
}

namespace {

/// Plays the slider dragged from 0 to 90 degrees in 2 s (the femur's own speed limit,
/// 45 deg/s), then held for 1 s while the tissue settles: 300 frames of 10 ms, recorded in
/// `record`.
CliResult drag_to_90_degrees(const std::string& name, const std::string& config,
                             const fs::path& model, const fs::path& record)
{
  const fs::path script = fresh_folder("view_script_" + name) += ".csv";
  std::ofstream(script) << "time_s,angle_deg\n0,0\n2,90\n3,90\n";
  return run_on_virtual_screen("view --config " + config + " --model " + model.string() +
                               " --script " + script.string() + " --record " + record.string() +
                               " --size 320");
}

/// Builds an MCL (`build`: the build command's config and flags), sweeps it quasi-statically to
/// 90 degrees with the flexion config `flexion`, and drags the live window's slider there: every
/// frame drawn and recorded, the overlay's figures and frames.pvd those of the frames, the last
/// frame's femur force and regional peak within 5 % of the sweep's at 90 degrees.
void expect_drag_to_90_degrees_ends_at_the_quasi_static_state(const std::string& name,
                                                              const std::string& build,
                                                              const std::string& flexion)
{
  const fs::path model = fresh_folder("view_model_" + name);
  const std::string config = source_path(flexion).string();
  const CliResult built = run_ligsim("build " + build + " --no-images --out " + model.string());
  ASSERT_EQ(built.exit_code, 0) << built.stderr_text;
  const fs::path sweep = fresh_folder("view_sweep_" + name);
  const CliResult swept = run_ligsim("flexion --config " + config + " --model " + model.string() +
                                     " --angles 0,90 --no-images --out " + sweep.string());
  ASSERT_EQ(swept.exit_code, 0) << swept.stderr_text;
  const nlohmann::json at_90 =
      only_ligament(read_json(sweep / "summary.json")["results"])["angles"][1];
  const double quasi_static = at_90["femur_force_magnitude_n"];
  const double regional_pct = 100.0 * at_90["max_regional_fiber_strain"].get<double>();

  const fs::path record = fresh_folder("view_record_" + name);
  const CliResult viewed = drag_to_90_degrees(name, config, model, record);
  ASSERT_EQ(viewed.exit_code, 0) << viewed.stderr_text;

  const std::vector<std::string> rows = lines(record / "frames.csv");
  ASSERT_EQ(rows.size(), 301u);
  const std::vector<std::string> header = csv_cells(rows[0]);
  ASSERT_EQ(header[4], "MCL_femur_force_n");
  ASSERT_EQ(header[5], "MCL_regional_peak_pct");
  ASSERT_EQ(header.back(), "overlay");
  for (std::size_t f = 1; f < rows.size(); ++f) {
    const std::vector<std::string> cells = csv_cells(rows[f]);
    ASSERT_EQ(cells.size(), header.size()) << rows[f];
    // Every frame drawn, and the overlay shows the frame's own figures.
    EXPECT_TRUE(fs::exists(record / fmt::format("frame_{:05d}.png", f))) << f;
    EXPECT_NE(cells.back().find(fmt::format("MCL {} N, {} % over 2 mm", cells[4], cells[5])),
              std::string::npos)
        << rows[f];
  }
  // frames.pvd: per frame the ligament and the femur, at the frame's time, the tibia once.
  std::vector<std::string> ligament_entries;
  for (const std::string& line : lines(record / "frames.pvd"))
    if (line.find("part=\"0\"") != std::string::npos)
      ligament_entries.push_back(line);
  ASSERT_EQ(ligament_entries.size(), 300u);
  for (std::size_t f = 1; f < rows.size(); f += 50) {
    const std::string file = fmt::format("series/MCL_{:05d}.vtp", f);
    EXPECT_NE(ligament_entries[f - 1].find(
                  fmt::format("timestep=\"{:g}\"", std::stod(csv_cells(rows[f])[1]))),
              std::string::npos)
        << ligament_entries[f - 1];
    EXPECT_NE(ligament_entries[f - 1].find(file), std::string::npos) << ligament_entries[f - 1];
    EXPECT_TRUE(fs::exists(record / file)) << file;
    EXPECT_TRUE(fs::exists(record / fmt::format("series/femur_{:05d}.vtp", f))) << f;
  }
  EXPECT_TRUE(fs::exists(record / "series/tibia.vtp"));

  const std::vector<std::string> last = csv_cells(rows.back());
  EXPECT_DOUBLE_EQ(std::stod(last[2]), 90.0);
  EXPECT_NEAR(std::stod(last[4]), quasi_static, 0.05 * quasi_static) << rows.back();
  EXPECT_NEAR(std::stod(last[5]), regional_pct, 0.05 * regional_pct) << rows.back();
}

bool has_xvfb()
{
  return std::system("command -v xvfb-run > /dev/null 2>&1") == 0;
}

} // namespace

TEST(ViewCli, AScriptedDragTo90DegreesDrawsEveryFrameAndEndsAtTheQuasiStaticForce)
{
  if (!has_xvfb())
    GTEST_SKIP() << "xvfb-run is not installed (Debian package xvfb)";
  expect_drag_to_90_degrees_ends_at_the_quasi_static_state(
      "vhf_mcl", "--config " + source_path("data/vhf-right-knee/mcl.toml").string(),
      "data/vhf-right-knee/flexion.toml");
}

/// The HRA female MCL as linear tets of 1.5 mm (9,906) on the passive knee's path. Linear, as the
/// view would run the shipped 10-node model's corners as linear tets where the quasi-static sweep
/// it is held against runs the 10-node tets.
TEST(ViewCli, TheHraMclDraggedTo90DegreesEndsAtTheQuasiStaticState)
{
  if (!has_xvfb())
    GTEST_SKIP() << "xvfb-run is not installed (Debian package xvfb)";
  expect_drag_to_90_degrees_ends_at_the_quasi_static_state(
      "hra_mcl",
      "--config " + source_path("data/hra-knee/mcl-female.toml").string() +
          " --cell-size 1.5 --facet-size 1.5 --order 1",
      "data/hra-knee/flexion.toml");
}

TEST(ViewCli, TheSquareSheetTearsLiveAlongTheSamePathAsTheBatchTear)
{
  if (!has_xvfb())
    GTEST_SKIP() << "xvfb-run is not installed (Debian package xvfb)";
  const std::string scene = source_path("data/scenes/square-sheet-45.toml").string();
  const fs::path batch = fresh_folder("view_tear_batch");
  const CliResult torn = run_ligsim("tear " + scene + " --no-png --out " + batch.string());
  ASSERT_EQ(torn.exit_code, 0) << torn.stderr_text;
  const fs::path live = fresh_folder("view_tear_live");
  const CliResult viewed =
      run_on_virtual_screen("view " + scene + " --record " + live.string() + " --size 320");
  ASSERT_EQ(viewed.exit_code, 0) << viewed.stderr_text;

  // The same elements split in the same order: every event's step, tip and segment alike.
  const std::vector<std::string> path = lines(batch / "tear_path.csv");
  ASSERT_GT(path.size(), 10u);
  EXPECT_EQ(lines(live / "tear_path.csv"), path);
  // A frame every `frame_every` (10) steps and the last: all drawn and recorded.
  const int steps = read_json(batch / "summary.json")["results"]["steps"];
  const int frames = (steps + 9) / 10;
  EXPECT_TRUE(fs::exists(live / fmt::format("frame_{:05d}.png", frames)));
  EXPECT_FALSE(fs::exists(live / fmt::format("frame_{:05d}.png", frames + 1)));
}

TEST(ViewCli, AScriptedHandPullsTheSheetHeldAtItsOtherSideAndItTears)
{
  if (!has_xvfb())
    GTEST_SKIP() << "xvfb-run is not installed (Debian package xvfb)";
  // The 45-degree square sheet held at its left side, its right side's middle pulled 4 mm
  // outward by the script.
  const std::string scene = source_path("data/scenes/square-sheet-held.toml").string();
  const fs::path dir = fresh_folder("view_hand");
  const CliResult viewed =
      run_on_virtual_screen("view " + scene + " --script " +
                            source_path("data/scenes/square-sheet-held-hand.csv").string() +
                            " --record " + (dir / "record").string() + " --size 320");
  ASSERT_EQ(viewed.exit_code, 0) << viewed.stderr_text;
  const std::vector<std::string> path = lines(dir / "record" / "tear_path.csv");
  ASSERT_GT(path.size(), 10u) << "the sheet did not tear";
  EXPECT_TRUE(fs::exists(dir / "record" / "frame_00001.png"));

  // A hand that takes the sheet where it is not: a clear error.
  fs::create_directories(dir);
  std::ofstream(dir / "off.csv") << "time_s,x_mm,y_mm\n0,20,0\n0.2,25,0\n";
  const CliResult off =
      run_on_virtual_screen("view " + scene + " --script " + (dir / "off.csv").string() +
                            " --record " + (dir / "off").string());
  EXPECT_NE(off.exit_code, 0);
  EXPECT_NE(off.stderr_text.find("is not on the sheet"), std::string::npos) << off.stderr_text;
}

/// The four-ligament HRA knee on its live mesh (docs/view.md): dragged to 90 degrees, each
/// ligament's last frame at the quasi-static sweep's femur force and regional peak.
TEST(ViewCli, TheFourLigamentKneeLiveEndsAtItsQuasiStaticState)
{
  if (!has_xvfb())
    GTEST_SKIP() << "xvfb-run is not installed (Debian package xvfb)";
  const fs::path model = fresh_folder("view_knee_model");
  const CliResult built = run_ligsim(
      "build --config " + source_path("data/hra-knee/knee.toml").string() +
      " --cell-size 2.5 --facet-size 2.5 --facet-distance 0.3 --no-images --out " + model.string());
  ASSERT_EQ(built.exit_code, 0) << built.stderr_text;
  const std::string config = source_path("data/hra-knee/flexion.toml").string();
  const fs::path sweep = fresh_folder("view_knee_sweep");
  const CliResult swept = run_ligsim("flexion --config " + config + " --model " + model.string() +
                                     " --angles 0,90 --no-images --out " + sweep.string());
  ASSERT_EQ(swept.exit_code, 0) << swept.stderr_text;
  const fs::path record = fresh_folder("view_record_knee");
  const CliResult viewed = drag_to_90_degrees("knee", config, model, record);
  ASSERT_EQ(viewed.exit_code, 0) << viewed.stderr_text;

  const std::vector<std::string> rows = lines(record / "frames.csv");
  ASSERT_EQ(rows.size(), 301u);
  const std::vector<std::string> header = csv_cells(rows[0]);
  const std::vector<std::string> last = csv_cells(rows.back());
  const nlohmann::json ligaments = read_json(sweep / "summary.json")["results"]["ligaments"];
  ASSERT_EQ(ligaments.size(), 4u);
  for (const auto& [name, ligament] : ligaments.items()) {
    const nlohmann::json& at_90 = ligament["angles"][1];
    ASSERT_DOUBLE_EQ(at_90["angle_deg"].get<double>(), 90.0);
    const auto column = [&](const std::string& title) {
      const auto found = std::find(header.begin(), header.end(), title);
      EXPECT_NE(found, header.end()) << title;
      return found == header.end() ? NAN : std::stod(last[found - header.begin()]);
    };
    const double force = at_90["femur_force_magnitude_n"];
    const double regional = 100.0 * at_90["max_regional_fiber_strain"].get<double>();
    EXPECT_NEAR(column(name + "_femur_force_n"), force, 0.05 * force) << name;
    EXPECT_NEAR(column(name + "_regional_peak_pct"), regional, 0.05 * regional) << name;
  }
}
