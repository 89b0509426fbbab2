#pragma once
/// Runs the built `ligsim` binary as a user would, capturing its exit code and stderr, and reads
/// what it wrote.

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <sys/wait.h>
#include <unistd.h>
#include <vector>

namespace ligsim::test {

struct CliResult {
  int exit_code;
  std::string stderr_text;
};

inline CliResult run_ligsim(const std::string& arguments)
{
  // ctest runs test processes in parallel: the log's name carries the process id.
  static int calls = 0;
  const std::filesystem::path log =
      std::filesystem::temp_directory_path() /
      ("ligsim_cli_" + std::to_string(::getpid()) + "_" + std::to_string(++calls) + ".log");
  const std::string command =
      std::string(LIGSIM_BINARY) + " " + arguments + " 2> " + log.string() + " > /dev/null";
  const int status = std::system(command.c_str());
  std::ifstream in(log);
  std::string text{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  std::filesystem::remove(log);
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, text};
}

/// run_ligsim with DISPLAY unset: what a user on a machine without a screen sees.
inline CliResult run_ligsim_without_display(const std::string& arguments)
{
  const char* display = std::getenv("DISPLAY");
  const std::string saved = display ? display : "";
  ::unsetenv("DISPLAY");
  CliResult result = run_ligsim(arguments);
  if (display)
    ::setenv("DISPLAY", saved.c_str(), 1);
  return result;
}

/// This test process's scratch root, removed with everything in it when the process ends (a suite
/// run leaves about 500 MB of model folders otherwise); LIGSIM_KEEP_TEST_FILES=1 keeps it to look
/// at. The process id keeps suites of several checkouts run at once apart.
inline const std::filesystem::path& scratch_root()
{
  struct Root {
    std::filesystem::path path =
        std::filesystem::temp_directory_path() / ("ligsim_pipeline_" + std::to_string(::getpid()));
    ~Root()
    {
      if (!std::getenv("LIGSIM_KEEP_TEST_FILES")) {
        std::error_code ignored;
        std::filesystem::remove_all(path, ignored);
      }
    }
  };
  static const Root root;
  return root.path;
}

/// An empty folder of its own under this process's scratch root.
inline std::filesystem::path fresh_folder(const std::string& name)
{
  const auto dir = scratch_root() / name;
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(scratch_root());
  return dir;
}

inline std::filesystem::path source_path(const std::string& relative)
{
  return std::filesystem::path(LIGSIM_SOURCE_DIR) / relative;
}

inline nlohmann::json read_json(const std::filesystem::path& file)
{
  std::ifstream in(file);
  return nlohmann::json::parse(in);
}

/// "--axis" through the point and along the direction the model stage of the model folder
/// `model` chose (its summary.json), to 17 digits.
inline std::string flexion_axis_argument(const std::filesystem::path& model)
{
  const nlohmann::json axis =
      read_json(model / "summary.json")["stages"]["model"]["figures"]["flexion_axis"];
  std::ostringstream text;
  text.precision(17);
  text << "--axis ";
  for (int i = 0; i < 3; ++i)
    text << axis["point_mm"][i].get<double>() << ",";
  for (int i = 0; i < 3; ++i)
    text << axis["point_mm"][i].get<double>() + axis["direction"][i].get<double>()
         << (i < 2 ? "," : "");
  return text.str();
}

/// A one-ligament model's results in a job's summary.json results (`results.ligaments`'s only
/// entry).
inline nlohmann::json only_ligament(const nlohmann::json& results)
{
  const nlohmann::json& ligaments = results.at("ligaments");
  EXPECT_EQ(ligaments.size(), 1u) << ligaments.dump().substr(0, 200);
  return ligaments.begin().value();
}

/// The lines of a text file (a CSV table, a log).
inline std::vector<std::string> lines(const std::filesystem::path& file)
{
  std::ifstream in(file);
  std::vector<std::string> result;
  for (std::string line; std::getline(in, line);)
    result.push_back(line);
  return result;
}

/// Builds the synthetic band of `shape` (a `ligsim synth band` folder) into a fresh folder
/// `name`, with 0.4 mm voxels, the further config text `keys` and the further build `flags`.
inline std::filesystem::path build_band_model(const std::filesystem::path& shape,
                                              const std::string& name, const std::string& keys,
                                              const std::string& flags = "")
{
  const std::filesystem::path out = fresh_folder(name);
  const std::filesystem::path config = scratch_root() / (name + ".toml");
  std::ofstream(config) << "[voxelize]\nspacing_mm = 0.4\n\n" << keys;
  const CliResult built =
      run_ligsim("build --config " + config.string() + " --surface " +
                 (shape / "surface.stl").string() + " --femur " + (shape / "femur.stl").string() +
                 " --tibia " + (shape / "tibia.stl").string() + " --out " + out.string() + flags);
  EXPECT_EQ(built.exit_code, 0) << built.stderr_text;
  return out;
}

} // namespace ligsim::test
