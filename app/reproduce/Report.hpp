#pragma once
// The reproduction report's execution: the runs of core/report/ReportRuns.hpp (run, resumed or reused in OUTDIR/runs),
// the statements of the paper's table (core/report), the figures (ui/report, the GUI's plot code), and the files
// (core/report/ReportWriters.hpp, the PDF through ui/report).  main.cpp parses the options and calls it.
#include <filesystem>
#include <optional>
#include <string>

#include "core/report/ReportRuns.hpp"

namespace archipelago::app {

struct ReportOptions {
  std::filesystem::path out;
  report::ReportSize size = report::ReportSize::quick;
  int threads = 0;
  std::string only;  ///< one statement's id: compute what it needs, print it, no figures
};

/// Thrown when SIGINT/SIGTERM stopped the report, after the work in progress is saved.
struct Interrupted {};

/// Installs the SIGINT/SIGTERM handlers the runs poll.
void installReportInterruptHandlers();

/// Runs the report; returns the process's status: 0, or 2 when a statement differs unexplained.  Throws
/// Interrupted, or std::exception with the one line main() prints after "ERROR: ".
int runReport(const ReportOptions& options);

}  // namespace archipelago::app
