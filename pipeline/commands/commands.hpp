#pragma once
/// @brief The ligsim subcommands. Each add_* function registers one job (or one family of
/// jobs) on the top-level CLI; its callback runs the job and throws ligsim::Error on failure.

namespace CLI {
class App;
}

namespace ligsim::cli {

/// `build` and one subcommand per model-building stage (voxelize ... model).
void add_build_commands(CLI::App& app);
/// `bench`: benchmark jobs (long runs, outside the test suite).
void add_bench_command(CLI::App& app);
/// `synth`: synthetic shapes with known axes.
void add_synth_command(CLI::App& app);

/// `ligsim labelmap`: surfaces voxelized into a segmentation label map.
void add_labelmap_command(CLI::App& app);
/// `simulate`: run a hyperelastic scene file.
void add_simulate_command(CLI::App& app);
/// `verify`: cube against FEBio, error against run time, stability report.
void add_verify_command(CLI::App& app);
/// `tear`: membrane tearing scenes.
void add_tear_command(CLI::App& app);
/// `export`: a built knee model as another program's input (`export febio`).
void add_export_command(CLI::App& app);
/// `flexion`: the knee flexion sweep on a built model.
void add_flexion_command(CLI::App& app);
/// `view`: a built knee moved by hand in a live window.
void add_view_command(CLI::App& app);
/// `study`: convergence ladders, segmentation sensitivity, cohort tables.
void add_study_command(CLI::App& app);

/// After the commands above: `ligsim <job> --help` ends with the user guide's page for the job
/// ("Guide: docs/flexion.md").
void add_guide_footers(CLI::App& app);
/// The documentation test's dry run (LIGSIM_CHECK_ONLY=1): every job only checks its command
/// line and loads the config and scene files it names, with the job's own readers, and runs
/// nothing.
void make_jobs_check_only(CLI::App& app);

} // namespace ligsim::cli
