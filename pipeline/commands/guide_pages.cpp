#include "pipeline/commands/commands.hpp"

#include "pipeline/stage_graph/stage_graph.hpp"

#include <CLI/CLI.hpp>

#include <map>
#include <string>

namespace ligsim::cli {

namespace {

/// The user guide's page of each job, by its command path ("verify febio"); a subcommand
/// without an entry takes its parent's page.
std::map<std::string, std::string> guide_pages()
{
  std::map<std::string, std::string> pages = {
      {"", "docs/README.md"},          {"build", "docs/build.md"},
      {"synth", "docs/build.md"},      {"labelmap", "docs/labelmap.md"},
      {"bench", "docs/validation.md"}, {"simulate", "docs/simulate.md"},
      {"verify", "docs/simulate.md"},  {"verify febio", "docs/export.md"},
      {"tear", "docs/tear.md"},        {"flexion", "docs/flexion.md"},
      {"export", "docs/export.md"},    {"study", "docs/studies.md"},
      {"view", "docs/view.md"},
  };
  for (const pipeline::Stage& stage : pipeline::build_stages())
    pages[stage.name] = "docs/build.md";
  return pages;
}

void add_footers(CLI::App& command, const std::string& path, const std::string& inherited,
                 const std::map<std::string, std::string>& pages)
{
  const auto found = pages.find(path);
  const std::string page = found != pages.end() ? found->second : inherited;
  if (!page.empty())
    command.footer("Guide: " + page);
  for (CLI::App* sub : command.get_subcommands({}))
    add_footers(*sub, path.empty() ? sub->get_name() : path + " " + sub->get_name(), page, pages);
}

} // namespace

void add_guide_footers(CLI::App& app)
{
  add_footers(app, "", "", guide_pages());
}

} // namespace ligsim::cli
