/// `ligsim build` and `ligsim flexion` killed with SIGKILL at seeded random moments spread over a
/// run: every file left is the previous run's or the new parameters' complete version, and the
/// next run completes, reuses exactly the stages the killed run finished, and writes the same
/// bytes as an uninterrupted run (the band model: seconds per run).

#include "tests/pipeline/cli_runner.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <random>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

extern char** environ;

using namespace ligsim::test;
namespace fs = std::filesystem;

namespace {

/// Kill points per job; the seed is fixed so that a failure can be replayed.
constexpr int kKills = 10;
constexpr unsigned kSeed = 20261123;

using Files = std::map<std::string, std::string>; ///< relative path -> bytes

std::string read_bytes(const fs::path& file)
{
  std::ifstream in(file, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

/// What AtomicFile leaves behind when its writer is killed: ".<stem>.tmp-<pid><ext>"; and the
/// folder a companion model is built in (".companion.tmp-<pid>"), with what is in it.
bool is_temporary(const fs::path& file)
{
  for (const fs::path& part : file) {
    const std::string name = part.string();
    if (name.rfind('.', 0) == 0 && name.find(".tmp-") != std::string::npos)
      return true;
  }
  return false;
}

/// Every file under `dir` but the temporaries.
Files snapshot(const fs::path& dir)
{
  Files files;
  for (const fs::directory_entry& entry : fs::recursive_directory_iterator(dir))
    if (entry.is_regular_file() && !is_temporary(entry.path()))
      files[fs::relative(entry.path(), dir).string()] = read_bytes(entry.path());
  return files;
}

int count_temporaries(const fs::path& dir)
{
  int count = 0;
  for (const fs::directory_entry& entry : fs::recursive_directory_iterator(dir))
    count += is_temporary(entry.path()) ? 1 : 0;
  return count;
}

/// Files whose bytes carry the run's timings (summary.json, the stage records, the wall_s
/// column of flexion.csv): checked for being complete, not byte for byte.
bool has_timings(const std::string& relative)
{
  const fs::path path(relative);
  return path.filename() == "summary.json" || path.extension() == ".csv" ||
         relative.find(".ligsim-cache/") != std::string::npos; // the companion's too
}

nlohmann::json parse_json(const std::string& bytes)
{
  return nlohmann::json::parse(bytes, nullptr, /*allow_exceptions=*/false);
}

long line_count(const std::string& bytes)
{
  return std::count(bytes.begin(), bytes.end(), '\n');
}

/// A file with timings is complete: JSON that parses, or a table with as many lines as one of
/// the uninterrupted runs' and its last line ended.
bool complete(const std::string& name, const std::string& bytes, const Files& runs1,
              const Files& runs2)
{
  if (fs::path(name).extension() == ".json")
    return !parse_json(bytes).is_discarded();
  for (const Files* run : {&runs1, &runs2})
    if (run->count(name) && line_count(run->at(name)) == line_count(bytes) && !bytes.empty() &&
        bytes.back() == '\n')
      return true;
  return false;
}

/// `ligsim` started with `arguments`, stderr into `log`.
class Job {
public:
  Job(const std::vector<std::string>& arguments, const fs::path& log)
  {
    std::vector<std::string> words{LIGSIM_BINARY};
    words.insert(words.end(), arguments.begin(), arguments.end());
    std::vector<char*> argv;
    for (std::string& word : words)
      argv.push_back(word.data());
    argv.push_back(nullptr);
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_addopen(&actions, 1, "/dev/null", O_WRONLY, 0);
    posix_spawn_file_actions_addopen(&actions, 2, log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    const int error = posix_spawn(&m_pid, LIGSIM_BINARY, &actions, nullptr, argv.data(), environ);
    posix_spawn_file_actions_destroy(&actions);
    if (error != 0)
      m_pid = -1;
  }

  bool started() const { return m_pid > 0; }

  /// Exit status once it ends by itself.
  int wait()
  {
    int status = 0;
    ::waitpid(m_pid, &status, 0);
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  }

  /// SIGKILL; false if it had already ended.
  bool kill()
  {
    int status = 0;
    if (::waitpid(m_pid, &status, WNOHANG) == m_pid)
      return false;
    ::kill(m_pid, SIGKILL);
    ::waitpid(m_pid, &status, 0);
    return WIFSIGNALED(status) && WTERMSIG(status) == SIGKILL;
  }

private:
  pid_t m_pid = -1;
};

struct Completed {
  double seconds;
  std::string stderr_text;
};

Completed run_to_end(const std::vector<std::string>& arguments, const fs::path& log)
{
  const auto start = std::chrono::steady_clock::now();
  Job job(arguments, log);
  EXPECT_TRUE(job.started());
  const int exit_code = job.wait();
  const std::chrono::duration<double> took = std::chrono::steady_clock::now() - start;
  const std::string text = read_bytes(log);
  EXPECT_EQ(exit_code, 0) << text;
  return {took.count(), text};
}

/// Starts the job, kills it after `delay_s`; false if it ended first.
bool run_and_kill(const std::vector<std::string>& arguments, const fs::path& log, double delay_s)
{
  Job job(arguments, log);
  EXPECT_TRUE(job.started());
  std::this_thread::sleep_for(std::chrono::duration<double>(delay_s));
  return job.kill();
}

/// Kill moments as fractions of a run: one uniform draw in each tenth.
std::vector<double> kill_fractions(std::mt19937& random)
{
  std::uniform_real_distribution<double> within(0.0, 1.0);
  std::vector<double> fractions;
  for (int k = 0; k < kKills; ++k)
    fractions.push_back((k + within(random)) / kKills);
  return fractions;
}

/// What a killed run may leave: every previous output the new run keeps still there, and every
/// file either the previous run's or the new run's complete version (files with timings:
/// complete JSON).
void expect_previous_or_new(const fs::path& dir, const Files& previous, const Files& next,
                            const std::string& where)
{
  const Files now = snapshot(dir);
  for (const auto& [name, bytes] : previous) {
    // An output the new run removes (a companion it cannot mesh) may be gone.
    if (has_timings(name) || !next.count(name))
      continue;
    EXPECT_TRUE(now.count(name)) << where << ": previous output " << name << " is gone";
  }
  for (const auto& [name, bytes] : now) {
    if (has_timings(name)) {
      EXPECT_TRUE(complete(name, bytes, previous, next)) << where << ": " << name << " is cut";
      continue;
    }
    // The companion's inputs are links to the model's own files, the previous or the new.
    const std::string linked = name.rfind("companion/", 0) == 0 ? name.substr(10) : name;
    const bool is_previous = (previous.count(name) && previous.at(name) == bytes) ||
                             (previous.count(linked) && previous.at(linked) == bytes);
    const bool is_next = (next.count(name) && next.at(name) == bytes) ||
                         (next.count(linked) && next.at(linked) == bytes);
    EXPECT_TRUE(is_previous || is_next)
        << where << ": " << name << " (" << bytes.size() << " bytes) is neither the previous ("
        << (previous.count(name) ? previous.at(name).size() : 0) << " bytes) nor the new ("
        << (next.count(name) ? next.at(name).size() : 0) << " bytes) complete file";
  }
}

/// After the run that follows a kill: the same files and bytes as an uninterrupted run, and no
/// temporary left over.
void expect_same_as_uninterrupted(const fs::path& dir, const Files& expected,
                                  const std::string& where)
{
  const Files now = snapshot(dir);
  for (const auto& [name, bytes] : expected) {
    ASSERT_TRUE(now.count(name)) << where << ": " << name << " missing";
    if (has_timings(name))
      EXPECT_TRUE(complete(name, now.at(name), expected, expected)) << where << ": " << name;
    else
      EXPECT_TRUE(now.at(name) == bytes) << where << ": " << name << " differs";
  }
  EXPECT_EQ(count_temporaries(dir), 0) << where << ": temporaries left after a complete run";
}

std::string cache_key(const fs::path& dir, const std::string& stage)
{
  const nlohmann::json record = parse_json(read_bytes(dir / ".ligsim-cache" / (stage + ".json")));
  return record.is_object() ? record.value("key", "") : "";
}

/// Two sets of build parameters for the band: the previous run's and the changed input's. Both
/// coarse (about 700 and 500 tets) so that a run takes about 2 CPU seconds; they differ in the
/// voxel and the tet sizes, so every stage but the attachments reruns.
struct BuildParameters {
  const char* voxel_mm;
  const char* cell_size_mm;
  const char* facet_distance_mm;
};
constexpr BuildParameters kPreviousBuild{"0.9", "3", "0.6"};
constexpr BuildParameters kChangedBuild{"1", "4", "1"};

std::vector<std::string> build_arguments(const fs::path& shape, const BuildParameters& parameters,
                                         const fs::path& out)
{
  return {"build",
          "--surface",
          (shape / "surface.stl").string(),
          "--femur",
          (shape / "femur.stl").string(),
          "--tibia",
          (shape / "tibia.stl").string(),
          "--voxel",
          parameters.voxel_mm,
          "--cell-size",
          parameters.cell_size_mm,
          "--facet-size",
          parameters.cell_size_mm,
          "--facet-distance",
          parameters.facet_distance_mm,
          "--out",
          out.string()};
}

fs::path band_shape()
{
  const fs::path shape = fresh_folder("kill_band_shape");
  const CliResult made = run_ligsim("synth band --out " + shape.string());
  EXPECT_EQ(made.exit_code, 0) << made.stderr_text;
  return shape;
}

/// A fresh copy of `from` (the previous run's folder) at `to`.
void copy_folder(const fs::path& from, const fs::path& to)
{
  fs::remove_all(to);
  fs::copy(from, to, fs::copy_options::recursive);
}

/// The band model's flexion axis, as the model stage found it.
std::vector<std::string> band_axis(const fs::path& model)
{
  const nlohmann::json axis =
      parse_json(read_bytes(model / "summary.json"))["stages"]["model"]["figures"]["flexion_axis"];
  std::ostringstream text;
  for (int i = 0; i < 3; ++i)
    text << axis["point_mm"][i].get<double>() << ",";
  for (int i = 0; i < 3; ++i)
    text << axis["point_mm"][i].get<double>() + axis["direction"][i].get<double>()
         << (i < 2 ? "," : "");
  return {"--axis", text.str()};
}

} // namespace

TEST(KillBuild, EveryKillLeavesCompleteFilesAndTheNextRunReusesWhatWasFinished)
{
  const fs::path shape = band_shape();
  const fs::path log = fresh_folder("kill_build.log");
  // The previous run, and what the changed input gives uninterrupted over it.
  const fs::path previous_dir = fresh_folder("kill_build_previous");
  const fs::path next_dir = fresh_folder("kill_build_next");
  run_to_end(build_arguments(shape, kPreviousBuild, previous_dir), log);
  copy_folder(previous_dir, next_dir);
  const double first_s = run_to_end(build_arguments(shape, kChangedBuild, next_dir), log).seconds;
  // Twice, to check that an uninterrupted run writes the same bytes every time (what the checks
  // below rely on), and to time the run by the shorter one: a load spike on a shared machine
  // would otherwise push the late kill moments past the end.
  const fs::path again_dir = fresh_folder("kill_build_again");
  copy_folder(previous_dir, again_dir);
  const double again_s = run_to_end(build_arguments(shape, kChangedBuild, again_dir), log).seconds;
  const double duration_s = std::min(first_s, again_s);
  const Files previous = snapshot(previous_dir);
  const Files next = snapshot(next_dir);
  expect_same_as_uninterrupted(again_dir, next, "a second uninterrupted run");
  fs::remove_all(again_dir);
  ASSERT_TRUE(next.count("model.vtu"));
  ASSERT_NE(previous.at("model.vtu"), next.at("model.vtu"));

  std::mt19937 random(kSeed);
  const std::vector<double> fractions = kill_fractions(random);
  int killed = 0;
  for (int k = 0; k < kKills; ++k) {
    const double delay_s = fractions[k] * duration_s;
    const std::string where =
        "build kill " + std::to_string(k) + " at " + std::to_string(delay_s) + " s";
    const fs::path dir = fresh_folder("kill_build_" + std::to_string(k));
    copy_folder(previous_dir, dir);
    const bool landed = run_and_kill(build_arguments(shape, kChangedBuild, dir), log, delay_s);
    killed += landed ? 1 : 0;
    expect_previous_or_new(dir, previous, next, where);

    // The next run goes on with the new input, or (every other time) back to the previous one:
    // a stage is reused exactly when the killed run left its finished record for that input.
    const bool go_back = k % 2 == 1;
    const fs::path& reference = go_back ? previous_dir : next_dir;
    std::map<std::string, bool> reusable;
    for (const auto& [name, bytes] : next)
      if (name.rfind(".ligsim-cache/", 0) == 0) {
        const std::string stage = fs::path(name).stem().string();
        reusable[stage] = cache_key(dir, stage) == cache_key(reference, stage);
      }
    run_to_end(build_arguments(shape, go_back ? kPreviousBuild : kChangedBuild, dir), log);
    const nlohmann::json stages = parse_json(read_bytes(dir / "summary.json"))["stages"];
    std::string reused_stages;
    for (const auto& [stage, reuse] : reusable) {
      EXPECT_EQ(stages[stage].value("status", ""), reuse ? "reused" : "ran")
          << where << ", then the " << (go_back ? "previous" : "changed") << " input: stage "
          << stage;
      reused_stages += reuse ? " " + stage : "";
    }
    std::cout << where << (landed ? ": killed" : ": ended first") << "; the "
              << (go_back ? "previous" : "changed") << " input reused:" << reused_stages << "\n";
    expect_same_as_uninterrupted(dir, go_back ? previous : next, where);
    fs::remove_all(dir);
  }
  // The delays cover the run: nearly all of them land before its end.
  EXPECT_GE(killed, kKills / 2);
  std::cout << "build: " << killed << " of " << kKills << " runs killed (run " << duration_s
            << " s, seed " << kSeed << ")\n";
  fs::remove_all(previous_dir);
  fs::remove_all(next_dir);
  fs::remove_all(shape);
  fs::remove(log);
}

TEST(KillFlexion, EveryKillLeavesCompleteFilesAndTheNextRunReusesTheContactCache)
{
  const fs::path shape = band_shape();
  const fs::path log = fresh_folder("kill_flexion.log");
  const fs::path model = fresh_folder("kill_flexion_model");
  run_to_end(build_arguments(shape, kChangedBuild, model), log);
  const auto flexion = [&](const fs::path& model_dir, double in_situ_strain, const fs::path& out) {
    std::vector<std::string> arguments{
        "flexion", "--model",     model_dir.string(), "--angles",
        "0,30,60", "--no-images", "--in-situ-strain", std::to_string(in_situ_strain),
        "--out",   out.string()};
    const std::vector<std::string> axis = band_axis(model);
    arguments.insert(arguments.end(), axis.begin(), axis.end());
    return arguments;
  };
  // The previous sweep (in-situ strain 0.03), the changed input's (0.02) uninterrupted; the
  // first also writes the bones' contact level sets into the model's contact/ cache.
  const fs::path previous_dir = fresh_folder("kill_flexion_previous");
  const fs::path next_dir = fresh_folder("kill_flexion_next");
  const double without_cache_s = run_to_end(flexion(model, 0.03, previous_dir), log).seconds;
  const double with_cache_s = run_to_end(flexion(model, 0.02, next_dir), log).seconds;
  const Files previous = snapshot(previous_dir);
  const Files next = snapshot(next_dir);
  ASSERT_TRUE(next.count("ligament_60.vtu"));
  ASSERT_NE(previous.at("ligament_60.vtu"), next.at("ligament_60.vtu"));
  const Files model_files = snapshot(model);
  Files model_without_cache = model_files;
  for (const auto& [name, bytes] : model_files)
    if (name.rfind("contact/", 0) == 0)
      model_without_cache.erase(name);

  std::mt19937 random(kSeed + 1);
  const std::vector<double> fractions = kill_fractions(random);
  int killed = 0;
  for (int k = 0; k < kKills; ++k) {
    // Every other time the model comes without its contact cache, so kills also land while the
    // level sets are built and written.
    const bool without_cache = k % 2 == 0;
    const double delay_s = fractions[k] * (without_cache ? without_cache_s : with_cache_s);
    const std::string where =
        "flexion kill " + std::to_string(k) + " at " + std::to_string(delay_s) + " s";
    const fs::path dir = fresh_folder("kill_flexion_" + std::to_string(k));
    copy_folder(previous_dir, dir);
    const fs::path model_copy = fresh_folder("kill_flexion_model_" + std::to_string(k));
    copy_folder(model, model_copy);
    if (without_cache)
      fs::remove_all(model_copy / "contact");
    const bool landed = run_and_kill(flexion(model_copy, 0.02, dir), log, delay_s);
    killed += landed ? 1 : 0;
    expect_previous_or_new(dir, previous, next, where);
    expect_previous_or_new(model_copy, without_cache ? model_without_cache : model_files,
                           model_files, where + " (model)");

    // A level set the killed run finished writing is complete, and is reused.
    std::map<std::string, bool> level_set_left;
    for (const char* bone : {"femur", "tibia"})
      level_set_left[bone] = fs::exists(model_copy / "contact" / (std::string(bone) + ".vdb"));
    const bool go_back = k % 4 == 1;
    run_to_end(flexion(model_copy, go_back ? 0.03 : 0.02, dir), log);
    const nlohmann::json contact =
        only_ligament(parse_json(read_bytes(dir / "summary.json"))["results"])["setup"]["contact"];
    std::string reused_level_sets;
    for (const auto& [bone, left] : level_set_left) {
      EXPECT_EQ(contact[bone].value("reused", !left), left)
          << where << ": " << bone << " level set";
      reused_level_sets += left ? " " + bone : "";
    }
    std::cout << where << (without_cache ? " (no contact cache)" : "")
              << (landed ? ": killed" : ": ended first")
              << "; level sets reused:" << reused_level_sets << "\n";
    expect_same_as_uninterrupted(dir, go_back ? previous : next, where);
    expect_same_as_uninterrupted(model_copy, model_files, where + " (model)");
    fs::remove_all(dir);
    fs::remove_all(model_copy);
  }
  EXPECT_GE(killed, kKills / 2);
  std::cout << "flexion: " << killed << " of " << kKills << " runs killed (run " << with_cache_s
            << " s, " << without_cache_s << " s building the contact cache, seed " << kSeed + 1
            << ")\n";
  for (const fs::path& dir : {previous_dir, next_dir, model, shape})
    fs::remove_all(dir);
  fs::remove(log);
}
