#include "LimitsCommand.hpp"

#include <cstdio>

#include "core/limits/Limits.hpp"

namespace archipelago::cli {

void addLimitsCommand(CLI::App& app, int& status) {
  CLI::App* cmd = app.add_subcommand(
      "limits", "the largest thread count, raster, q and orbit length anything accepts (core's one table, Markdown)");
  cmd->callback([&status] {
    std::fputs(limitsMarkdown().c_str(), stdout);
    status = 0;
  });
}

}  // namespace archipelago::cli
