// archipelago: the desktop application (Qt Widgets + Qwt).  A thin main(); the window lives in ui/.
//
// Options for scripts (README screenshots, scripts/gui-latency.py):
//   --preset NAME        load a preset instead of the last parameters
//   --run                start the run at once
//   --screenshot PATH    after --after seconds, save the window as PATH and quit (a run only with --run)
//   --measure SECONDS    run, measure event latency and plot refresh rate, print them as JSON and quit
//   --mode NAME          the portrait's mode (orbits, density, stickiness) or indicator (dig, rotation, …)
//   --view X0,X1,Y0,Y1   the portrait's rectangle;  --budget POINTS  its points budget
//   --manifolds          the manifolds of the hyperbolic fixed point with the turnstile and the flux
//   --segment N          select the long segment of rank N (0: the longest) of the opened run file (a rank
//                        beyond the segments it keeps is an error: one ERROR line, status 2)
//   --island             and zoom to one island of its chain once it is identified
//   --chains ROWS        the top ROWS segments get their island chain identified as they appear (default 10;
//                        0: none; scripts/gui-portrait-yield.py --chains compares the run's rate with and without)
//   FILE.json            open a run file
//   FILE.archipelago     open a session (the window as it was saved)
#include <QAction>
#include <QApplication>

#include <clocale>
#include <QTabWidget>
#include <QCommandLineParser>
#include <QComboBox>
#include <QLineEdit>
#include <QLocale>
#include <QSpinBox>
#include <QTimer>
#include <qwt_global.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>

#include "LatencyProbe.hpp"
#include "core/io/NumberText.hpp"
#include "core/limits/Limits.hpp"
#include "core/runspec/InputRules.hpp"
#include "core/trapping/LongestSegments.hpp"
#include "ui/window/MainWindow.hpp"
#include "core/measures/OrbitMeasures.hpp"
#include "core/view/Viewport.hpp"
#include "core/session/OrbitFamily.hpp"
#include "ui/portrait/OrbitListPanel.hpp"
#include "ui/portrait/RotationProfilePanel.hpp"
#include "ui/portrait/PortraitController.hpp"
#include "ui/portrait/PortraitPanel.hpp"
#include "ui/segments/LongSegmentsPanel.hpp"
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
         {"--preset", "--threads", "--screenshot", "--after", "--measure", "--tab", "--segment", "--mode", "--view",
          "--budget", "--chains", "--orbit", "--orbits", "--periodic", "--profile"})
      if (std::strcmp(argv[i], withValue) == 0) ++i;
  }
  return false;
}

/// Throws std::invalid_argument with core's message, if there is one.
void refuse(const std::optional<std::string>& error) {
  if (error) throw std::invalid_argument(*error);
}

/// A number of seconds given to `option` (`text`), read by core's one reader, in [lo, the table's script seconds]
/// (issue #23, finding 9: --after nan|-5|1e12 never quit).  Throws std::invalid_argument with the message.
double readSeconds(const char* option, const QString& text, double lo) {
  const std::string name = std::string("--") + option;
  const double v = archipelago::io::parseNumber<double>(name, text.toStdString());
  refuse(archipelago::realRangeError(name, v, lo, archipelago::limits::kScriptSeconds, "seconds"));
  return v;
}

/// The rank given to --segment: a whole number (core's reader: "abc", "1.5", "-1" are errors) below the most longest
/// segments a run keeps.
int readRank(const QString& text) {
  const auto v = archipelago::io::parseNumber<std::uint32_t>("--segment", text.toStdString());
  refuse(archipelago::longestRankError("--segment", v));
  return static_cast<int>(v);
}

/// --chains ROWS: the rows of the segment table whose chain is identified automatically.
int readChainRows(const QString& text) {
  const auto v = archipelago::io::parseNumber<std::uint32_t>("--chains", text.toStdString());
  refuse(archipelago::rangeError("--chains", v, 0, archipelago::limits::kChainRows, "rows"));
  return static_cast<int>(v);
}

/// --view X0,X1,Y0,Y1: a rectangle of the portrait, physical coordinates (checked against the box later).
archipelago::PhysicalRect readView(const QString& text) {
  return archipelago::parsePhysicalRect(text.toStdString(), "--view");  // core's one parser of a typed view
}

/// --orbit X,Y: the start of an orbit to launch and select (physical coordinates).
archipelago::PhysicalPoint readOrbit(const QString& text) {
  const auto v = archipelago::io::parseNumbers<long double>("--orbit", text.toStdString(), ',', 2,
                                                           "two finite numbers x,y (physical coordinates)");
  return {v[0], v[1]};
}

/// --orbits X0,Y0,X1,Y1,N,M: a line (M = 1) or a grid of orbits (issue 37, finding 15); the counts' rule is core's
/// (orbitFamilyStarts), applied when they are launched.
archipelago::OrbitFamily readOrbits(const QString& text) {
  const auto v = archipelago::io::parseNumbers<long double>("--orbits", text.toStdString(), ',', 6,
                                                           "x0,y0,x1,y1,n,m: two points and the counts");
  const auto whole = [](long double c) {
    const auto n = static_cast<std::uint64_t>(c < 0 ? 0 : c);
    if (static_cast<long double>(n) != c) throw std::invalid_argument("--orbits: the counts n,m must be whole numbers");
    return n;
  };
  archipelago::OrbitFamily f{{v[0], v[1]}, {v[2], v[3]}, whole(v[4]), whole(v[5])};
  (void)archipelago::orbitFamilyStarts(f);  // core's rule of the counts, before any window
  return f;
}

/// --profile X0,Y0,X1,Y1: the rotation profile of the line between two points (physical coordinates).
std::pair<archipelago::PhysicalPoint, archipelago::PhysicalPoint> readProfile(const QString& text) {
  const auto v = archipelago::io::parseNumbers<long double>("--profile", text.toStdString(), ',', 4,
                                                           "x0,y0,x1,y1: the line's two ends");
  return {{v[0], v[1]}, {v[2], v[3]}};
}

/// --budget N: the portrait's points budget (the table's portrait budget).
std::uint64_t readBudget(const QString& text) {
  const auto v = archipelago::io::parseNumber<std::uint64_t>("--budget", text.toStdString());
  refuse(archipelago::rangeError("--budget", v, archipelago::limits::kPortraitBudgetMin,
                                 archipelago::limits::kPortraitBudget, "points"));
  return v;
}

/// --mode NAME: a portrait mode (orbits, density, stickiness) or an indicator (dig, rotation, fli, megno, lyapunov).
archipelago::ui::PortraitDisplay readMode(const QString& text) {
  const std::string name = text.toStdString();
  if (const auto mode = archipelago::parsePortraitMode(name)) return {*mode, std::nullopt};
  if (const auto kind = archipelago::parseIndicatorKind(name)) return {archipelago::PortraitMode::Orbits, *kind};
  throw std::invalid_argument("--mode = " + archipelago::io::shortText(name) +
                              " must be orbits, density, stickiness, or an indicator: " + archipelago::indicatorKindNames());
}

/// The numbers of the command line checked before any window or display: the first error's message, if any.
/// (The parser reads them again below, through the same functions.)
std::optional<std::string> numberError(int argc, char** argv) {
  try {
    for (int i = 1; i < argc; ++i) {
      const QString arg = QString::fromLocal8Bit(argv[i]);
      for (const char* name : {"after", "measure", "segment", "threads", "view", "budget", "mode", "chains", "orbit",
                               "orbits", "periodic", "profile"}) {
        const QString option = QStringLiteral("--") + QLatin1String(name);
        QString value;
        if (arg == option && i + 1 < argc) value = QString::fromLocal8Bit(argv[i + 1]);
        else if (arg.startsWith(option + QLatin1Char('='))) value = arg.mid(option.size() + 1);
        else continue;
        if (std::strcmp(name, "after") == 0) (void)readSeconds("after", value, 0);
        else if (std::strcmp(name, "measure") == 0) (void)readSeconds("measure", value, 1);
        else if (std::strcmp(name, "segment") == 0) (void)readRank(value);
        else if (std::strcmp(name, "view") == 0) (void)readView(value);
        else if (std::strcmp(name, "budget") == 0) (void)readBudget(value);
        else if (std::strcmp(name, "mode") == 0) (void)readMode(value);
        else if (std::strcmp(name, "chains") == 0) (void)readChainRows(value);
        else if (std::strcmp(name, "orbit") == 0) (void)readOrbit(value);
        else if (std::strcmp(name, "orbits") == 0) (void)readOrbits(value);
        else if (std::strcmp(name, "periodic") == 0) (void)readOrbit(value);
        else if (std::strcmp(name, "profile") == 0) (void)readProfile(value);
        else (void)archipelago::readThreads(value.toStdString());
      }
    }
  } catch (const std::exception& e) {
    return std::string(e.what());
  }
  return std::nullopt;
}

/// Whether the window system Qt will load needs a display that the environment does not name: the platform given by
/// -platform or QT_QPA_PLATFORM (a list "a;b" is tried in order) is xcb or wayland, or none is given (the default is
/// one of them), and neither DISPLAY nor WAYLAND_DISPLAY is set.  Qt's xcb plugin aborts the process (SIGABRT) when
/// it finds no display (issue 36); offscreen, minimal, vnc, eglfs, linuxfb … need none.
bool displayMissing(int argc, char** argv) {
  const auto set = [](const char* name) {
    const char* v = std::getenv(name);
    return v != nullptr && *v != '\0';
  };
  if (set("DISPLAY") || set("WAYLAND_DISPLAY")) return false;
  std::string platform = set("QT_QPA_PLATFORM") ? std::getenv("QT_QPA_PLATFORM") : "";
  for (int i = 1; i + 1 < argc; ++i)
    if (std::strcmp(argv[i], "-platform") == 0 || std::strcmp(argv[i], "--platform") == 0) platform = argv[i + 1];
  if (platform.empty()) return true;
  for (std::size_t from = 0; from <= platform.size();) {
    const std::size_t end = std::min(platform.find(';', from), platform.size());
    const std::string name = platform.substr(from, std::min(platform.find(':', from), end) - from);  // "xcb:arg"
    if (name != "xcb" && name.rfind("wayland", 0) != 0) return false;  // one that needs no display
    from = end + 1;
  }
  return true;
}

}  // namespace

int main(int argc, char** argv) {
  archipelago::ui::configureProcessMemory();
  std::setlocale(LC_NUMERIC, "C");
  if (!onlyInformation(argc, argv)) {
    if (const auto e = numberError(argc, argv)) {
      std::fprintf(stderr, "ERROR: %s\n", e->c_str());
      return 2;
    }
    if (displayMissing(argc, argv)) {
      std::fprintf(stderr, "ERROR: no display: set DISPLAY, or run with -platform offscreen\n");
      return 2;
    }
  }
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
  const QCommandLineOption mode(QStringLiteral("mode"),
                                QStringLiteral("Portrait mode: orbits, density, stickiness, dig, rotation, fli, megno or lyapunov."),
                                QStringLiteral("NAME"));
  const QCommandLineOption view(QStringLiteral("view"), QStringLiteral("Show the portrait's rectangle x0,x1,y0,y1."),
                                QStringLiteral("X0,X1,Y0,Y1"));
  const QCommandLineOption budget(QStringLiteral("budget"), QStringLiteral("The portrait's points budget."),
                                  QStringLiteral("POINTS"));
  const QCommandLineOption manifolds(QStringLiteral("manifolds"),
                                     QStringLiteral("Draw the manifolds of the hyperbolic fixed point and the flux."));
  const QCommandLineOption orbit(QStringLiteral("orbit"),
                                 QStringLiteral("Launch an orbit from (X, Y) and select it (its chain's centres drawn)."),
                                 QStringLiteral("X,Y"));
  const QCommandLineOption chains(QStringLiteral("chains"),
                                  QStringLiteral("Identify the island chains of the top ROWS segments (default 10)."),
                                  QStringLiteral("ROWS"));
  const QCommandLineOption orbits(QStringLiteral("orbits"),
                                  QStringLiteral("Launch a line (M = 1) or an N x M grid of orbits between two points."),
                                  QStringLiteral("X0,Y0,X1,Y1,N,M"));
  const QCommandLineOption periodic(QStringLiteral("periodic"),
                                    QStringLiteral("Find the periodic orbit at (X, Y), as a Shift+click does."),
                                    QStringLiteral("X,Y"));
  const QCommandLineOption profile(QStringLiteral("profile"),
                                   QStringLiteral("The rotation profile of the line from (X0, Y0) to (X1, Y1) (with --periodic: about that orbit)."),
                                   QStringLiteral("X0,Y0,X1,Y1"));
  parser.addOptions({version, preset, run, threads, screenshot, after, measure, tab, segment, island, mode, view, budget,
                     manifolds, chains, orbit, orbits, periodic, profile});
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

  // Every number of the command line is read and checked before the window opens: one ERROR line and status 2.
  double afterSeconds = 20, measureSeconds = 0;
  int segmentRank = -1;
  try {
    if (parser.isSet(after)) afterSeconds = readSeconds("after", parser.value(after), 0);
    if (parser.isSet(measure)) measureSeconds = readSeconds("measure", parser.value(measure), 1);
    if (parser.isSet(segment)) {
      segmentRank = readRank(parser.value(segment));
      if (parser.positionalArguments().isEmpty())
        throw std::invalid_argument("--segment needs a run file or a session to take the segment from");
    }
    if (parser.isSet(island) && !parser.isSet(segment)) throw std::invalid_argument("--island needs --segment N");
    if (parser.isSet(threads)) (void)archipelago::readThreads(parser.value(threads).toStdString());  // core's rule
  } catch (const std::exception& e) {
    std::fprintf(stderr, "ERROR: %s\n", e.what());
    return 2;
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
  if (parser.isSet(chains)) window.longSegments()->setAutoIdentifiedRows(readChainRows(parser.value(chains)));
  if (parser.isSet(threads)) window.setThreads(archipelago::readThreads(parser.value(threads).toStdString()));
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
  if (segmentRank >= 0) {
    window.showLongSegment(segmentRank, parser.isSet(island));
    // A rank beyond the segments the run keeps is an error, known once the run file is analysed.
    QObject::connect(&window, &archipelago::ui::MainWindow::runStatusChanged, &window, [&window, segmentRank](auto status) {
      if (archipelago::ui::isLive(status) || !window.latestSnapshot()) return;
      window.refreshNow();
      const auto kept = static_cast<std::uint64_t>(window.longSegments()->model()->rowCount());
      const auto error = archipelago::longestRankError("--segment", static_cast<std::uint64_t>(segmentRank), kept);
      if (!error) return;
      std::fprintf(stderr, "ERROR: %s\n", error->c_str());
      std::fflush(stderr);
      QTimer::singleShot(0, [] { QApplication::exit(2); });
    });
  }
  // A screenshot of a segment shows the opened run, so it does not start a new one.
  // The portrait as asked (README screenshots, docs/images).
  archipelago::ui::PortraitPanel* portrait = window.portraitPanel();
  if (parser.isSet(mode)) portrait->setDisplay(readMode(parser.value(mode)));
  if (parser.isSet(budget)) portrait->controller()->setPointBudget(readBudget(parser.value(budget)));
  if (parser.isSet(view)) {
    const archipelago::PhysicalRect r = readView(parser.value(view));
    const archipelago::MapParameters& map = portrait->controller()->map();
    if (const auto e = archipelago::Viewport::validationError(map, r)) {
      std::fprintf(stderr, "ERROR: --view: %s\n", e->c_str());
      return 2;
    }
    portrait->controller()->setViewport(archipelago::Viewport::fromPhysical(map, r));
  }
  if (parser.isSet(manifolds)) portrait->manifoldsAction()->setChecked(true);
  if (parser.isSet(orbit)) {
    const archipelago::PhysicalPoint start = readOrbit(parser.value(orbit));
    if (const auto e = archipelago::boxPointError("--orbit", portrait->controller()->map(), start)) {
      std::fprintf(stderr, "ERROR: %s\n", e->c_str());
      return 2;
    }
    portrait->controller()->highlightOrbit(portrait->controller()->launchOrbit(start.x, start.y));
    portrait->sidePages()->setCurrentWidget(portrait->orbitList());
  }
  if (parser.isSet(orbits)) {  // typed into the Orbits page's fields, then Line/Grid, as a user does
    const archipelago::OrbitFamily f = readOrbits(parser.value(orbits));
    archipelago::ui::OrbitListPanel* list = portrait->orbitList();
    const auto text = [](long double v) { return QString::number(static_cast<double>(v), 'g', QLocale::FloatingPointShortest); };
    list->startXField()->setText(text(f.from.x));
    list->startYField()->setText(text(f.from.y));
    list->endXField()->setText(text(f.to.x));
    list->endYField()->setText(text(f.to.y));
    list->columnsBox()->setValue(static_cast<int>(f.columns));
    list->rowsBox()->setValue(static_cast<int>(f.rows));
    list->launchFamily();
    portrait->sidePages()->setCurrentWidget(list);
  }
  if (parser.isSet(periodic)) {
    const archipelago::PhysicalPoint at = readOrbit(parser.value(periodic));
    portrait->controller()->findPeriodicOrbitAt(at.x, at.y);
  }
  if (parser.isSet(profile)) {
    const auto [from, to] = readProfile(parser.value(profile));
    portrait->sidePages()->setCurrentWidget(portrait->profilePanel());
    archipelago::ui::RotationProfilePanel* profilePanel = portrait->profilePanel();
    if (!parser.isSet(periodic)) {
      profilePanel->profile(from, to, 400);
    } else {  // with --periodic: about the orbit found there, once it is found (About: the periodic orbit drawn)
      auto* once = new QObject(profilePanel);
      QObject::connect(portrait->controller(), &archipelago::ui::PortraitController::periodicOrbitFound, once,
                       [profilePanel, once, from = from, to = to] {
                         profilePanel->aboutBox()->setCurrentIndex(1);
                         profilePanel->profile(from, to, 400);
                         once->deleteLater();
                       });
    }
  }
  // A screenshot shows a run only when asked (--run); the latency measure always runs one.
  if (parser.isSet(run) || parser.isSet(measure)) QTimer::singleShot(0, &window, [&window] { window.startRun(); });

  if (parser.isSet(screenshot)) {
    const int ms = static_cast<int>(1000 * afterSeconds);
    QTimer::singleShot(ms, &window, [&window, path = parser.value(screenshot)] {
      const bool ok = window.grab().save(path);
      std::printf("%s %s\n", ok ? "wrote" : "could not write", qPrintable(path));
      window.stopRun();
      QTimer::singleShot(0, [] { QApplication::exit(0); });
    });
  }
  if (parser.isSet(measure)) {
    auto* probe = new archipelago::app::LatencyProbe(window, measureSeconds, &window);
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
