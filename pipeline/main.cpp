/// ligsim: from a segmented ligament surface to a simulation model, and its simulation.

#include "common/error.hpp"
#include "common/progress.hpp"
#include "common/vtk_files.hpp"
#include "pipeline/commands/commands.hpp"

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>

int main(int argc, char** argv)
{
  ligsim::silence_vtk_output();
  CLI::App app{"ligsim: subject-specific ligament models, hyperelastic simulation and "
               "membrane tearing"};
  app.require_subcommand(1);
  app.fallthrough(); // --quiet also after the subcommand
  bool quiet = false;
  app.add_flag("-q,--quiet", quiet, "no progress on stderr");
  app.parse_complete_callback([&] { ligsim::Progress::set_quiet(quiet); });

  ligsim::cli::add_build_commands(app);
  ligsim::cli::add_synth_command(app);
  ligsim::cli::add_labelmap_command(app);
  ligsim::cli::add_bench_command(app);
  ligsim::cli::add_simulate_command(app);
  ligsim::cli::add_verify_command(app);
  ligsim::cli::add_tear_command(app);
  ligsim::cli::add_flexion_command(app);
  ligsim::cli::add_view_command(app);
  ligsim::cli::add_export_command(app);
  ligsim::cli::add_study_command(app);
  ligsim::cli::add_guide_footers(app);
  if (const char* check_only = std::getenv("LIGSIM_CHECK_ONLY");
      check_only != nullptr && std::string(check_only) == "1")
    ligsim::cli::make_jobs_check_only(app);

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  } catch (const ligsim::Error& e) {
    fmt::print(stderr, "ligsim: error: {}\n", e.what());
    return 1;
  } catch (const std::bad_alloc&) {
    fmt::print(stderr, "ligsim: error: out of memory\n");
    return 1;
  } catch (const std::exception& e) {
    fmt::print(stderr, "ligsim: error: internal: {}\n", e.what());
    return 3;
  }
  return 0;
}
