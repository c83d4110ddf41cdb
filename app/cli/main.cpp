// archipelago-cli: headless front end of the Archipelago engine (core only, no Qt).
// Each subcommand parses its options, calls core and formats; every error is one line "ERROR: ..." on
// stderr with a non-zero exit status.

#include <CLI/CLI.hpp>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <exception>
#include <iostream>
#include <string>

#include "CliCommon.hpp"
#include "OrbitCommand.hpp"
#include "RunCommand.hpp"
#include "ScanCommand.hpp"
#include "StatsCommand.hpp"
#include "PeriodicCommand.hpp"
#include "PortraitCommand.hpp"
#include "ReplayCommand.hpp"
#include "StochasticAreaCommand.hpp"
#include "MarkovCommand.hpp"
#include "MergeCommand.hpp"
#include "PresetsCommand.hpp"
#include "LimitsCommand.hpp"
#include "RotationCommand.hpp"
#include "IndicatorCommand.hpp"
#include "ManifoldCommand.hpp"
#include "AtlasCommand.hpp"
#include "MarkovTreeCommand.hpp"
#include "FluxCommand.hpp"
#include "CantorusCommand.hpp"
#include "TailCommand.hpp"
#include "TailScanCommand.hpp"

namespace {
/// Issue 36, class 2: what a command printed must have reached stdout, as a file's content must reach the disk (a
/// full disk, a closed pipe's reader, /dev/full): else one ERROR and a non-zero exit, never a silent 0.
int checkedStandardOutput(int status) {
  errno = 0;
  std::cout.flush();
  const bool failed = std::fflush(stdout) != 0 || std::ferror(stdout) != 0 || !std::cout;
  if (!failed) return status;
  const int error = errno;
  std::fprintf(stderr, "ERROR: writing standard output: %s\n", error != 0 ? std::strerror(error) : "a write failed");
  return status != 0 ? status : 1;
}
}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"archipelago-cli " ARCHIPELAGO_VERSION
               " -- exact trapping statistics of the quadratic map Q* (Karney, Physica D 8, 1983)"};
  app.require_subcommand(1);
  app.set_version_flag("--version", std::string("archipelago-cli ") + ARCHIPELAGO_VERSION);
  int status = 0;  // the chosen command's exit status: it returns here, never calls std::exit
  archipelago::cli::addOrbitCommand(app, status);
  archipelago::cli::addRunCommand(app, status);
  archipelago::cli::addScanCommand(app, status);
  archipelago::cli::addStatsCommand(app, status);
  archipelago::cli::addMergeCommand(app, status);
  archipelago::cli::addReplayCommand(app, status);
  archipelago::cli::addPeriodicCommand(app, status);
  archipelago::cli::addPortraitCommand(app, status);
  archipelago::cli::addStochasticAreaCommand(app, status);
  archipelago::cli::addMarkovCommand(app, status);
  archipelago::cli::addPresetsCommand(app, status);
  archipelago::cli::addLimitsCommand(app, status);
  archipelago::cli::addRotationCommand(app, status);
  archipelago::cli::addIndicatorCommand(app, status);
  archipelago::cli::addManifoldCommand(app, status);
  archipelago::cli::addFluxCommand(app, status);
  archipelago::cli::addCantorusCommand(app, status);
  archipelago::cli::addAtlasCommand(app, status);
  archipelago::cli::addMarkovTreeCommand(app, status);
  archipelago::cli::addTailCommand(app, status);
  archipelago::cli::addTailScanCommand(app, status);
  if (argc > 1 && argv[1][0] != '-') {  // name an unknown command instead of CLI11's generic message
    std::string names;
    bool known = false;
    for (const CLI::App* sub : app.get_subcommands([](CLI::App*) { return true; })) {
      known = known || sub->get_name() == argv[1];
      names += (names.empty() ? "" : ", ") + sub->get_name();
    }
    if (!known) {
      std::fprintf(stderr, "ERROR: unknown command '%s' (commands: %s)\n", argv[1], names.c_str());
      return 2;
    }
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return checkedStandardOutput(app.exit(e));
  } catch (const CLI::CallForAllHelp& e) {
    return checkedStandardOutput(app.exit(e));
  } catch (const CLI::CallForVersion& e) {
    return checkedStandardOutput(app.exit(e));
  } catch (const CLI::ParseError& e) {
    return archipelago::cli::parseErrorStatus(app, e);
  } catch (const std::exception& e) {
    // One line whatever a message quotes: a folder named with a newline gave two (issue 54, item 5); nothing is cut.
    std::fprintf(stderr, "ERROR: %s\n", archipelago::io::shortText(e.what(), std::size_t{1} << 20).c_str());
    return 1;
  }
  return checkedStandardOutput(status);
}
