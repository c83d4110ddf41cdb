// archipelago-reproduce: Karney (1983) reproduced by one command.  Thin: the options, then Report.cpp's runReport
// (core/report's runs and statements of the paper's table, the GUI's plot code for the figures).
#include <CLI/CLI.hpp>
#include <QApplication>

#include <stdlib.h>  // mkdtemp

#include <clocale>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <string>
#include <system_error>

#include "Report.hpp"
#include "core/paper/PaperTable.hpp"
#include "core/runspec/InputRules.hpp"

using namespace archipelago;

namespace {

/// Qt's platform start looks up its runtime folder (QStandardPaths::RuntimeLocation: a flatpak's marker) and warns
/// on stderr when XDG_RUNTIME_DIR is not set, as for a user without a login session (`nobody`, cron, a batch job;
/// issue 54, finding 7).  Then this gives Qt a folder of the program's own for the run — private (mkdtemp: 0700, the
/// user's), in the temporary folder — and removes it at the end.  A set XDG_RUNTIME_DIR is left as it is.
class RuntimeFolder {
 public:
  RuntimeFolder() {
    if (!qEnvironmentVariableIsEmpty("XDG_RUNTIME_DIR")) return;
    std::error_code e;
    std::string folder = (std::filesystem::temp_directory_path(e) / "archipelago-runtime-XXXXXX").string();
    if (e || ::mkdtemp(folder.data()) == nullptr) return;  // Qt then says itself what it lacks
    folder_ = folder;
    qputenv("XDG_RUNTIME_DIR", QByteArray::fromStdString(folder_));
  }
  ~RuntimeFolder() {
    std::error_code ignored;
    if (!folder_.empty()) std::filesystem::remove_all(folder_, ignored);
  }
  RuntimeFolder(const RuntimeFolder&) = delete;
  RuntimeFolder& operator=(const RuntimeFolder&) = delete;

 private:
  std::string folder_;
};

}  // namespace

int main(int argc, char** argv) {
  if (qEnvironmentVariableIsEmpty("QT_QPA_PLATFORM")) qputenv("QT_QPA_PLATFORM", "offscreen");
  CLI::App app{"Karney (1983) reproduced: every figure and number into OUTDIR/index.html and OUTDIR/report.pdf"};
  app.set_version_flag("--version", std::string("archipelago-reproduce ") + ARCHIPELAGO_VERSION);
  app::ReportOptions options;
  std::string outdir;
  bool quick = false, full = false, table = false;
  auto* outOption =
      app.add_option("OUTDIR", outdir, "the report folder (created; runs are kept in OUTDIR/runs and reused)");
  auto* q = app.add_flag("--quick", quick, "CI size: a few minutes on two cores (the default)");
  app.add_flag("--full", full, "the paper's sizes (resumable: reuses finished runs, resumes a stopped one)")->excludes(q);
  app.add_option("--only", options.only, "compute and print this one statement (its id in items.csv), no figures")
      ->check(CLI::Validator([](std::string& id) { return id.empty() ? std::string("an empty id") : std::string(); },
                             "ID"));
  app.add_option_function<std::string>(
         "--threads", [&options](const std::string& text) { options.threads = readThreads(text); },
         "OpenMP threads (0: one per core; core's rule, at most " + std::to_string(kMaxThreads) + ")")
      ->type_name("INT");
  app.add_flag("--table", table, "print the table of the paper's statements (Markdown) and stop")
      ->excludes(outOption);
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {  // one ERROR line and status 2, as archipelago-cli (issue #23)
    std::fprintf(stderr, "ERROR: %s\n", e.what());
    return 2;
  } catch (const std::exception& e) {  // an option's own reader (--threads)
    std::fprintf(stderr, "ERROR: %s\n", e.what());
    return 2;
  }
  if (table) {
    std::fputs(paper::markdownTable().c_str(), stdout);
    return 0;
  }
  if (outdir.empty()) {
    std::fprintf(stderr, "ERROR: OUTDIR is required (or --table)\n");
    return 2;
  }
  // An unknown statement is refused before any work (issue #23: a typo once computed every run first).
  if (!options.only.empty() && paper::findStatement(options.only) == nullptr) {
    std::fprintf(stderr, "ERROR: --only '%s': no such statement (archipelago-reproduce --table lists them)\n",
                 options.only.c_str());
    return 2;
  }
  options.out = outdir;
  options.size = full ? report::ReportSize::full : report::ReportSize::quick;
  const RuntimeFolder runtime;  // before Qt starts, removed after it has ended
  QApplication qapp(argc, argv);
  // Qt sets the user's locale for the C library; printf-style text of this program is never localised (a
  // decimal comma once split items.csv's columns and changed statement ids, issue #23).  Qt's own text uses
  // QLocale, which this does not touch.
  std::setlocale(LC_NUMERIC, "C");
  app::installReportInterruptHandlers();
  try {
    return app::runReport(options);
  } catch (const app::Interrupted&) {
    std::fprintf(stderr, "interrupted: the same command resumes\n");
    return 130;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "ERROR: %s\n", e.what());
    return 1;
  }
}
