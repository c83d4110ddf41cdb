// archipelago: the desktop application (Qt Widgets + Qwt).  A thin main(); the window lives in ui/.
//
// Options for scripts (README screenshots, scripts/gui-latency.py):
//   --preset NAME        load a preset instead of the last parameters
//   --run                start the run at once
//   --screenshot PATH    after --after seconds of running, save the window as PATH and quit
//   --measure SECONDS    run, measure event latency and plot refresh rate, print them as JSON and quit
//   --segment N          select the long segment of rank N (0: the longest) of the opened run file
//   --island             and zoom to one island of its chain once it is identified
//   FILE.json            open a run file
//   FILE.archipelago     open a session (the window as it was saved)
#include <QApplication>

#include <clocale>
#include <QTabWidget>
#include <QCommandLineParser>
#include <QTimer>
#include <qwt_global.h>

#include <cstdio>
#include <cstring>
#include <memory>

#include "LatencyProbe.hpp"
#include "core/spec/InputRules.hpp"
#include "ui/window/MainWindow.hpp"
#include "ui/window/ParameterPanel.hpp"
#include "ui/window/Resources.hpp"

namespace {

/// Whether the command line asks only for --help or --version: those are answered without a display (a
/// QCoreApplication), so that they work on a server, in a package build (help2man) or over ssh.
/// The scan skips the value of an option that takes one (`--preset -v` names a preset), as the parser does.
bool onlyInformation(int argc, char** argv) {
  for (int i = 1; i < argc; ++i) {
    for (const char* option : {"-h", "--help", "--help-all", "-?", "-v", "--version"})
      if (std::strcmp(argv[i], option) == 0) return true;
    for (const char* withValue :
         {"--preset", "--threads", "--screenshot", "--after", "--measure", "--tab", "--segment"})
      if (std::strcmp(argv[i], withValue) == 0) ++i;
  }
  return false;
}

}  // namespace

int main(int argc, char** argv) {
  archipelago::ui::configureProcessMemory();
  const std::unique_ptr<QCoreApplication> application =
      onlyInformation(argc, argv) ? std::make_unique<QCoreApplication>(argc, argv)
                                  : std::make_unique<QApplication>(argc, argv);
  QCoreApplication& app = *application;
  // Qt sets the user's locale for the C library; files and ids are never localised (issue #23: a decimal
  // comma once made sessions unreadable in another locale).  The widgets' text uses QLocale, untouched here.
  std::setlocale(LC_NUMERIC, "C");
  QApplication::setApplicationName(QStringLiteral("Archipelago"));
  QApplication::setOrganizationName(QStringLiteral("Archipelago"));
  QApplication::setApplicationVersion(QStringLiteral(ARCHIPELAGO_VERSION));

  QCommandLineParser parser;
  parser.setApplicationDescription(QStringLiteral("Long-time correlations in the stochastic regime (Karney 1983)"));
  parser.addHelpOption();
  // --version names the Qt (at run time, and at build time when they differ) and the Qwt in use.
  const QCommandLineOption version({QStringLiteral("v"), QStringLiteral("version")},
                                   QStringLiteral("Displays version information (with Qt and Qwt)."));
  const QCommandLineOption preset(QStringLiteral("preset"), QStringLiteral("Load the preset NAME: its name or id (archipelago-cli presets lists them)."), QStringLiteral("NAME"));
  const QCommandLineOption run(QStringLiteral("run"), QStringLiteral("Start the run at once."));
  const QCommandLineOption threads(QStringLiteral("threads"), QStringLiteral("Worker threads (0 = all)."), QStringLiteral("N"));
  const QCommandLineOption screenshot(QStringLiteral("screenshot"), QStringLiteral("Save the window as PATH and quit."),
                                      QStringLiteral("PATH"));
  const QCommandLineOption after(QStringLiteral("after"), QStringLiteral("Seconds before the screenshot (default 20)."),
                                 QStringLiteral("SECONDS"), QStringLiteral("20"));
  const QCommandLineOption measure(QStringLiteral("measure"),
                                   QStringLiteral("Measure event latency and refresh rate for SECONDS, print JSON."),
                                   QStringLiteral("SECONDS"));
  const QCommandLineOption tab(QStringLiteral("tab"), QStringLiteral("Show the tab whose title starts with NAME."),
                               QStringLiteral("NAME"));
  const QCommandLineOption segment(QStringLiteral("segment"),
                                   QStringLiteral("Select the long segment of rank N of the run file (0: the longest)."),
                                   QStringLiteral("N"));
  const QCommandLineOption island(QStringLiteral("island"), QStringLiteral("Zoom to one island of its chain."));
  parser.addOptions({version, preset, run, threads, screenshot, after, measure, tab, segment, island});
  parser.addPositionalArgument(QStringLiteral("file"), QStringLiteral("A run file (.json) or a session (.archipelago) to open."),
                               QStringLiteral("[file.json|file.archipelago]"));
  parser.process(app);
  if (parser.isSet(version)) {
    const QString built = QStringLiteral(QT_VERSION_STR);
    const QString qt = QString::fromLatin1(qVersion());
    std::printf("Archipelago %s (Qt %s%s, Qwt %s)\n", ARCHIPELAGO_VERSION, qPrintable(qt),
                qt == built ? "" : qPrintable(QStringLiteral(", built with ") + built), QWT_VERSION_STR);
    return 0;
  }

  archipelago::ui::MainWindow window;
  const bool scripted = parser.isSet(screenshot) || parser.isSet(measure);
  window.setConfirmations(!scripted);
  auto* panel = window.parameterPanel();
  if (parser.isSet(preset) && !panel->applyPreset(parser.value(preset))) {
    std::fprintf(stderr, "ERROR: no preset named \"%s\"; presets: %s\n", qPrintable(parser.value(preset)),
                 qPrintable(panel->presetNames().join(QStringLiteral(", "))));
    return 1;
  }
  if (parser.isSet(threads)) {
    try {
      window.setThreads(archipelago::readThreads(parser.value(threads).toStdString()));  // core's one rule
    } catch (const std::exception& e) {
      std::fprintf(stderr, "ERROR: --%s\n", e.what());
      return 2;
    }
  }
  window.show();
  if (parser.isSet(tab)) {
    bool found = false;
    for (int i = 0; i < window.tabs()->count() && !found; ++i)
      if (window.tabs()->tabText(i).startsWith(parser.value(tab), Qt::CaseInsensitive)) {
        window.tabs()->setCurrentIndex(i);
        found = true;
      }
    if (!found) {
      std::fprintf(stderr, "ERROR: no tab named \"%s\"\n", qPrintable(parser.value(tab)));
      return 1;
    }
  }
  if (!parser.positionalArguments().isEmpty()) window.openInteractively(parser.positionalArguments().front());
  if (parser.isSet(segment)) window.showLongSegment(parser.value(segment).toInt(), parser.isSet(island));
  // A screenshot of a segment shows the opened run, so it does not start a new one.
  if (parser.isSet(run) || (scripted && !parser.isSet(segment))) QTimer::singleShot(0, &window, [&window] { window.startRun(); });

  if (parser.isSet(screenshot)) {
    const int ms = static_cast<int>(1000 * parser.value(after).toDouble());
    QTimer::singleShot(ms, &window, [&window, path = parser.value(screenshot)] {
      const bool ok = window.grab().save(path);
      std::printf("%s %s\n", ok ? "wrote" : "could not write", qPrintable(path));
      window.stopRun();
      QTimer::singleShot(0, [] { QApplication::exit(0); });
    });
  }
  if (parser.isSet(measure)) {
    auto* probe = new archipelago::app::LatencyProbe(window, parser.value(measure).toDouble(), &window);
    QObject::connect(probe, &archipelago::app::LatencyProbe::done, &window, [&window](const QString& json) {
      std::printf("%s\n", qPrintable(json));
      std::fflush(stdout);
      window.stopRun();
      QTimer::singleShot(0, [] { QApplication::exit(0); });
    });
    probe->start();
  }
  return QApplication::exec();
}
