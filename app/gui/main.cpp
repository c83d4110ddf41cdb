// archipelago: the desktop application (Qt Widgets + Qwt).  A thin main(); the window lives in ui/, the command line is
// read whole, before any application object exists, by GuiOptions.
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
#include <QComboBox>
#include <QCommandLineParser>
#include <QLineEdit>
#include <QLocale>
#include <QSpinBox>
#include <QTabWidget>
#include <QTimer>
#include <qwt_global.h>

#include <algorithm>
#include <clocale>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <optional>
#include <string>
#include <utility>
#include <variant>

#include "GuiOptions.hpp"
#include "LatencyProbe.hpp"
#include "core/measures/OrbitMeasures.hpp"
#include "core/session/OrbitFamily.hpp"
#include "core/trapping/LongestSegments.hpp"
#include "core/view/Viewport.hpp"
#include "ui/portrait/OrbitListPanel.hpp"
#include "ui/portrait/PortraitController.hpp"
#include "ui/portrait/PortraitPanel.hpp"
#include "ui/portrait/RotationProfilePanel.hpp"
#include "ui/segments/LongSegmentsPanel.hpp"
#include "ui/window/MainWindow.hpp"
#include "ui/window/ParameterPanel.hpp"
#include "ui/window/Resources.hpp"

namespace {

using archipelago::app::GuiOptions;
using archipelago::app::Refusal;
using archipelago::ui::MainWindow;
using archipelago::ui::PortraitPanel;

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

/// argv as text: what QCoreApplication::arguments() gives once the application is made.
QStringList argumentsOf(int argc, char** argv) {
  QStringList arguments;
  for (int i = 0; i < argc; ++i) arguments.append(QString::fromLocal8Bit(argv[i]));
  return arguments;
}

/// A refusal whose line is Qt text (a preset's or a tab's name), in the locale's encoding as qPrintable gives it.
Refusal refusal(const QString& line, int status) { return {line.toLocal8Bit().toStdString(), status}; }

/// Prints the refusal's line on stderr; its status.
int report(const Refusal& refused) {
  std::fprintf(stderr, "%s\n", refused.line.c_str());
  return refused.status;
}

/// The application's names (its settings' folder, the parser's messages), given before it is made.
void nameApplication() {
  QCoreApplication::setApplicationName(QStringLiteral("Archipelago"));
  QCoreApplication::setOrganizationName(QStringLiteral("Archipelago"));
  QCoreApplication::setApplicationVersion(QStringLiteral(ARCHIPELAGO_VERSION));
}

/// --help, --help-all or --version, answered with a QCoreApplication: no display is needed, so that they work on a
/// server, in a package build (help2man) or over ssh.  --version names the Qt (at run time, and at build time when
/// they differ) and the Qwt in use.
int answerInformation(int& argc, char** argv, GuiOptions::Information asked) {
  QCoreApplication app(argc, argv);
  if (asked == GuiOptions::Information::Version) {
    const QString built = QStringLiteral(QT_VERSION_STR);
    const QString qt = QString::fromLatin1(qVersion());
    std::printf("Archipelago %s (Qt %s%s, Qwt %s)\n", ARCHIPELAGO_VERSION, qPrintable(qt),
                qt == built ? "" : qPrintable(QStringLiteral(", built with ") + built), QWT_VERSION_STR);
    return 0;
  }
  QCommandLineParser parser;
  archipelago::app::addGuiOptions(parser);
  // Qt writes --help-all's text (with Qt's own options) only from process(), which prints the help and exits with 0.
  const bool all = asked == GuiOptions::Information::HelpAll;
  parser.process(QStringList{QCoreApplication::arguments().constFirst(),
                             all ? QStringLiteral("--help-all") : QStringLiteral("--help")});
  return 0;
}

/// --preset NAME; an unknown name is refused with the presets' names (status 1).
std::optional<Refusal> applyPreset(MainWindow& window, const QString& name) {
  archipelago::ui::ParameterPanel* panel = window.parameterPanel();
  if (panel->applyPreset(name)) return std::nullopt;
  return refusal(QStringLiteral("ERROR: no preset named \"") + name + QStringLiteral("\"; presets: ") +
                     panel->presetNames().join(QStringLiteral(", ")),
                 1);
}

/// --tab NAME: the first tab whose title starts with NAME (in any case); none is refused (status 1).
std::optional<Refusal> showTab(MainWindow& window, const QString& name) {
  QTabWidget* tabs = window.tabs();
  for (int i = 0; i < tabs->count(); ++i)
    if (tabs->tabText(i).startsWith(name, Qt::CaseInsensitive)) {
      tabs->setCurrentIndex(i);
      return std::nullopt;
    }
  return refusal(QStringLiteral("ERROR: no tab named \"") + name + QStringLiteral("\""), 1);
}

/// --segment N [--island]: the segment is selected once the opened run file is analysed; a rank beyond the segments
/// the run keeps is an error known only then (one ERROR line, status 2).
void selectSegment(MainWindow& window, int rank, bool island) {
  window.showLongSegment(rank, island);
  QObject::connect(&window, &MainWindow::runStatusChanged, &window, [&window, rank](auto status) {
    if (archipelago::ui::isLive(status) || !window.latestSnapshot()) return;
    window.refreshNow();
    const auto kept = static_cast<std::uint64_t>(window.longSegments()->model()->rowCount());
    const auto error = archipelago::longestRankError("--segment", static_cast<std::uint64_t>(rank), kept);
    if (!error) return;
    std::fprintf(stderr, "ERROR: %s\n", error->c_str());
    std::fflush(stderr);
    QTimer::singleShot(0, [] { QApplication::exit(2); });
  });
}

/// The window as asked: no confirmations when a script drives it, the preset, the chains identified, the threads,
/// then (shown) the tab, the file and its segment.  A screenshot of a segment shows the opened run: it starts none.
std::optional<Refusal> applyWindowOptions(MainWindow& window, const GuiOptions& options) {
  window.setConfirmations(!options.scripted());
  if (options.preset) {
    if (auto refused = applyPreset(window, *options.preset)) return refused;
  }
  if (options.chainRows) window.longSegments()->setAutoIdentifiedRows(*options.chainRows);
  if (options.threads) window.setThreads(*options.threads);
  window.show();
  if (options.tab) {
    if (auto refused = showTab(window, *options.tab)) return refused;
  }
  if (options.file) window.openInteractively(*options.file);
  if (options.segment) selectSegment(window, *options.segment, options.island);
  return std::nullopt;
}

/// --view: the portrait's rectangle; one outside the box of the loaded parameters is refused (status 2).
std::optional<Refusal> applyView(PortraitPanel& portrait, const archipelago::PhysicalRect& r) {
  const archipelago::MapParameters& map = portrait.controller()->map();
  if (const auto e = archipelago::Viewport::validationError(map, r)) return Refusal{"ERROR: --view: " + *e, 2};
  portrait.controller()->setViewport(archipelago::Viewport::fromPhysical(map, r));
  return std::nullopt;
}

/// --orbit: the orbit launched and selected (its chain's centres drawn); a start outside the box is refused (status 2).
std::optional<Refusal> launchOrbit(PortraitPanel& portrait, const archipelago::PhysicalPoint& start) {
  if (const auto e = archipelago::boxPointError("--orbit", portrait.controller()->map(), start))
    return Refusal{"ERROR: " + *e, 2};
  portrait.controller()->highlightOrbit(portrait.controller()->launchOrbit(start.x, start.y));
  portrait.sidePages()->setCurrentWidget(portrait.orbitList());
  return std::nullopt;
}

/// --orbits: typed into the Orbits page's fields, then Line/Grid, as a user does.
void launchOrbits(PortraitPanel& portrait, const archipelago::OrbitFamily& f) {
  archipelago::ui::OrbitListPanel* list = portrait.orbitList();
  const auto text = [](long double v) { return QString::number(static_cast<double>(v), 'g', QLocale::FloatingPointShortest); };
  list->startXField()->setText(text(f.from.x));
  list->startYField()->setText(text(f.from.y));
  list->endXField()->setText(text(f.to.x));
  list->endYField()->setText(text(f.to.y));
  list->columnsBox()->setValue(static_cast<int>(f.columns));
  list->rowsBox()->setValue(static_cast<int>(f.rows));
  list->launchFamily();
  portrait.sidePages()->setCurrentWidget(list);
}

/// --profile: the rotation profile of the line; with --periodic, about the orbit found there, once it is found
/// (About: the periodic orbit drawn).
void showProfile(PortraitPanel& portrait, std::pair<archipelago::PhysicalPoint, archipelago::PhysicalPoint> line,
                 bool aboutPeriodic) {
  archipelago::ui::RotationProfilePanel* profilePanel = portrait.profilePanel();
  portrait.sidePages()->setCurrentWidget(profilePanel);
  const auto [from, to] = line;
  if (!aboutPeriodic) {
    profilePanel->profile(from, to, 400);
    return;
  }
  auto* once = new QObject(profilePanel);
  QObject::connect(portrait.controller(), &archipelago::ui::PortraitController::periodicOrbitFound, once,
                   [profilePanel, once, from = from, to = to] {
                     profilePanel->aboutBox()->setCurrentIndex(1);
                     profilePanel->profile(from, to, 400);
                     once->deleteLater();
                   });
}

/// The portrait as asked (README screenshots, docs/images): its mode, budget, view, manifolds, orbits, periodic orbit
/// and rotation profile.
std::optional<Refusal> applyPortraitOptions(PortraitPanel& portrait, const GuiOptions& options) {
  if (options.mode) portrait.setDisplay(*options.mode);
  if (options.budget) portrait.controller()->setPointBudget(*options.budget);
  if (options.view) {
    if (auto refused = applyView(portrait, *options.view)) return refused;
  }
  if (options.manifolds) portrait.manifoldsAction()->setChecked(true);
  if (options.orbit) {
    if (auto refused = launchOrbit(portrait, *options.orbit)) return refused;
  }
  if (options.orbits) launchOrbits(portrait, *options.orbits);
  if (options.periodic) portrait.controller()->findPeriodicOrbitAt(options.periodic->x, options.periodic->y);
  if (options.profile) showProfile(portrait, *options.profile, options.periodic.has_value());
  return std::nullopt;
}

/// --screenshot PATH: after `seconds`, the window saved as PATH ("wrote PATH" or "could not write PATH"), then quit.
void scheduleScreenshot(MainWindow& window, const QString& path, double seconds) {
  QTimer::singleShot(static_cast<int>(1000 * seconds), &window, [&window, path] {
    const bool ok = window.grab().save(path);
    std::printf("%s %s\n", ok ? "wrote" : "could not write", qPrintable(path));
    window.stopRun();
    QTimer::singleShot(0, [] { QApplication::exit(0); });
  });
}

/// --measure SECONDS: event latency and refresh rate measured during the run, printed as JSON, then quit.
void scheduleMeasure(MainWindow& window, double seconds) {
  auto* probe = new archipelago::app::LatencyProbe(window, seconds, &window);
  QObject::connect(probe, &archipelago::app::LatencyProbe::done, &window, [&window](const QString& json) {
    std::printf("%s\n", qPrintable(json));
    std::fflush(stdout);
    window.stopRun();
    QTimer::singleShot(0, [] { QApplication::exit(0); });
  });
  probe->start();
}

}  // namespace

int main(int argc, char** argv) {
  archipelago::ui::configureProcessMemory();
  std::setlocale(LC_ALL, "");  // as QCoreApplication does when it is made: argv's text in the user's encoding
  std::setlocale(LC_NUMERIC, "C");
  nameApplication();
  // Every option is read and checked before any application object: a bad one is one line, without a display.
  const auto read = archipelago::app::readGuiOptions(argumentsOf(argc, argv));
  if (const auto* refused = std::get_if<Refusal>(&read)) return report(*refused);
  const GuiOptions& options = std::get<GuiOptions>(read);
  if (options.information != GuiOptions::Information::None) return answerInformation(argc, argv, options.information);
  if (displayMissing(argc, argv)) return report({"ERROR: no display: set DISPLAY, or run with -platform offscreen", 2});

  QApplication app(argc, argv);
  // Qt sets the user's locale for the C library; files and ids are never localised (issue #23: a decimal
  // comma once made sessions unreadable in another locale).  The widgets' text uses QLocale, untouched here.
  std::setlocale(LC_NUMERIC, "C");
  MainWindow window;
  if (const auto refused = applyWindowOptions(window, options)) return report(*refused);
  if (const auto refused = applyPortraitOptions(*window.portraitPanel(), options)) return report(*refused);
  // A screenshot shows a run only when asked (--run); the latency measure always runs one.
  if (options.run || options.measureSeconds) QTimer::singleShot(0, &window, [&window] { window.startRun(); });
  if (options.screenshot) scheduleScreenshot(window, *options.screenshot, options.afterSeconds);
  if (options.measureSeconds) scheduleMeasure(window, *options.measureSeconds);
  return QApplication::exec();
}
