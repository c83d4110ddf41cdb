#include "GuiOptions.hpp"

#include <QCoreApplication>

#include <cstdint>
#include <exception>
#include <stdexcept>

#include "core/io/NumberText.hpp"
#include "core/limits/Limits.hpp"
#include "core/measures/IndicatorKind.hpp"
#include "core/runspec/InputRules.hpp"
#include "core/trapping/LongestSegments.hpp"

namespace archipelago::app {
namespace {

/// Throws std::invalid_argument with core's message, if there is one.
void refuse(const std::optional<std::string>& error) {
  if (error) throw std::invalid_argument(*error);
}

/// A number of seconds given to `option` (`text`), read by core's one reader, in [lo, the table's script seconds]
/// (issue #23, finding 9: --after nan|-5|1e12 never quit).  Throws std::invalid_argument with the message.
double readSeconds(const char* option, const QString& text, double lo) {
  const std::string name = std::string("--") + option;
  const double v = io::parseNumber<double>(name, text.toStdString());
  refuse(realRangeError(name, v, lo, limits::kScriptSeconds, "seconds"));
  return v;
}

/// The rank given to --segment: a whole number (core's reader: "abc", "1.5", "-1" are errors) below the most longest
/// segments a run keeps.
int readRank(const QString& text) {
  const auto v = io::parseNumber<std::uint32_t>("--segment", text.toStdString());
  refuse(longestRankError("--segment", v));
  return static_cast<int>(v);
}

/// --chains ROWS: the rows of the segment table whose chain is identified automatically.
int readChainRows(const QString& text) {
  const auto v = io::parseNumber<std::uint32_t>("--chains", text.toStdString());
  refuse(rangeError("--chains", v, 0, limits::kChainRows, "rows"));
  return static_cast<int>(v);
}

/// --view X0,X1,Y0,Y1: a rectangle of the portrait, physical coordinates (checked against the box later).
PhysicalRect readView(const QString& text) {
  return parsePhysicalRect(text.toStdString(), "--view");  // core's one parser of a typed view
}

/// --orbit X,Y (and --periodic X,Y): a point, physical coordinates.
PhysicalPoint readOrbit(const QString& text, const char* option = "--orbit") {
  const auto v = io::parseNumbers<long double>(option, text.toStdString(), ',', 2,
                                               "two finite numbers x,y (physical coordinates)");
  return {v[0], v[1]};
}

/// --orbits X0,Y0,X1,Y1,N,M: a line (M = 1) or a grid of orbits (issue 37, finding 15); the counts' rule is core's
/// (orbitFamilyStarts), applied when they are launched.
OrbitFamily readOrbits(const QString& text) {
  const auto v = io::parseNumbers<long double>("--orbits", text.toStdString(), ',', 6,
                                               "x0,y0,x1,y1,n,m: two points and the counts");
  const auto whole = [](long double c) {
    const auto n = static_cast<std::uint64_t>(c < 0 ? 0 : c);
    if (static_cast<long double>(n) != c) throw std::invalid_argument("--orbits: the counts n,m must be whole numbers");
    return n;
  };
  OrbitFamily f{{v[0], v[1]}, {v[2], v[3]}, whole(v[4]), whole(v[5])};
  (void)orbitFamilyStarts(f);  // core's rule of the counts, before any window
  return f;
}

/// --profile X0,Y0,X1,Y1: the rotation profile of the line between two points (physical coordinates).
std::pair<PhysicalPoint, PhysicalPoint> readProfile(const QString& text) {
  const auto v = io::parseNumbers<long double>("--profile", text.toStdString(), ',', 4,
                                               "x0,y0,x1,y1: the line's two ends");
  return {{v[0], v[1]}, {v[2], v[3]}};
}

/// --budget N: the portrait's points budget (the table's portrait budget).
std::uint64_t readBudget(const QString& text) {
  const auto v = io::parseNumber<std::uint64_t>("--budget", text.toStdString());
  refuse(rangeError("--budget", v, limits::kPortraitBudgetMin, limits::kPortraitBudget, "points"));
  return v;
}

/// --mode NAME: a portrait mode (orbits, density, stickiness) or an indicator (dig, rotation, fli, megno, lyapunov).
ui::PortraitDisplay readMode(const QString& text) {
  const std::string name = text.toStdString();
  if (const auto mode = parsePortraitMode(name)) return {*mode, std::nullopt};
  if (const auto kind = parseIndicatorKind(name)) return {PortraitMode::Orbits, *kind};
  throw std::invalid_argument("--mode = " + io::shortText(name) +
                              " must be orbits, density, stickiness, or an indicator: " + indicatorKindNames());
}

/// --threads N: core's rule of the worker threads (0: all).
int readThreadCount(const QString& text) { return readThreads(text.toStdString()); }

/// The text given to an option as it is.
QString asText(const QString& text) { return text; }

/// The value of option `name` read by `reader`, if it is given.
template <class Reader>
auto readGiven(const QCommandLineParser& parser, const char* name, Reader reader)
    -> std::optional<decltype(reader(QString()))> {
  const QString option = QString::fromLatin1(name);
  if (!parser.isSet(option)) return std::nullopt;
  return reader(parser.value(option));
}

/// --help, --help-all or --version, in the order Qt's parser answered them (help first).
GuiOptions::Information informationAsked(const QCommandLineParser& parser) {
  if (parser.isSet(QStringLiteral("help"))) return GuiOptions::Information::Help;
  if (parser.isSet(QStringLiteral("help-all"))) return GuiOptions::Information::HelpAll;
  if (parser.isSet(QStringLiteral("version"))) return GuiOptions::Information::Version;
  return GuiOptions::Information::None;
}

/// Every option's value read by core's readers, and the rules between options.  Throws std::invalid_argument with
/// the first error's message.
GuiOptions readValues(const QCommandLineParser& parser) {
  GuiOptions o;
  if (!parser.positionalArguments().isEmpty()) o.file = parser.positionalArguments().front();
  o.preset = readGiven(parser, "preset", asText);
  o.run = parser.isSet(QStringLiteral("run"));
  o.afterSeconds = readSeconds("after", parser.value(QStringLiteral("after")), 0);  // the option's default if not given
  o.measureSeconds = readGiven(parser, "measure", [](const QString& t) { return readSeconds("measure", t, 1); });
  o.segment = readGiven(parser, "segment", readRank);
  if (o.segment && !o.file) throw std::invalid_argument("--segment needs a run file or a session to take the segment from");
  o.island = parser.isSet(QStringLiteral("island"));
  if (o.island && !o.segment) throw std::invalid_argument("--island needs --segment N");
  o.threads = readGiven(parser, "threads", readThreadCount);
  o.view = readGiven(parser, "view", readView);
  o.budget = readGiven(parser, "budget", readBudget);
  o.mode = readGiven(parser, "mode", readMode);
  o.chainRows = readGiven(parser, "chains", readChainRows);
  o.orbit = readGiven(parser, "orbit", [](const QString& t) { return readOrbit(t); });
  o.orbits = readGiven(parser, "orbits", readOrbits);
  o.periodic = readGiven(parser, "periodic", [](const QString& t) { return readOrbit(t, "--periodic"); });
  o.profile = readGiven(parser, "profile", readProfile);
  o.screenshot = readGiven(parser, "screenshot", asText);
  o.tab = readGiven(parser, "tab", asText);
  o.manifolds = parser.isSet(QStringLiteral("manifolds"));
  return o;
}

}  // namespace

void addGuiOptions(QCommandLineParser& parser) {
  parser.setApplicationDescription(QStringLiteral("Long-time correlations in the stochastic regime (Karney 1983)"));
  parser.addHelpOption();
  const auto option = [&parser](QStringList names, const char* description, const char* value = nullptr,
                                const char* byDefault = nullptr) {
    QCommandLineOption o(names, QString::fromUtf8(description));
    if (value) o.setValueName(QString::fromLatin1(value));
    if (byDefault) o.setDefaultValue(QString::fromLatin1(byDefault));
    parser.addOption(o);
  };
  // --version names the Qt (at run time, and at build time when they differ) and the Qwt in use.
  option({QStringLiteral("v"), QStringLiteral("version")}, "Displays version information (with Qt and Qwt).");
  option({QStringLiteral("preset")}, "Load the preset NAME: its name or id (archipelago-cli presets lists them).", "NAME");
  option({QStringLiteral("run")}, "Start the run at once.");
  option({QStringLiteral("threads")}, "Worker threads (0 = all).", "N");
  option({QStringLiteral("screenshot")}, "Save the window as PATH and quit.", "PATH");
  option({QStringLiteral("after")}, "Seconds before the screenshot (default 20).", "SECONDS", "20");
  option({QStringLiteral("measure")}, "Measure event latency and refresh rate for SECONDS, print JSON.", "SECONDS");
  option({QStringLiteral("tab")}, "Show the tab whose title starts with NAME.", "NAME");
  option({QStringLiteral("segment")}, "Select the long segment of rank N of the run file (0: the longest).", "N");
  option({QStringLiteral("island")}, "Zoom to one island of its chain.");
  option({QStringLiteral("mode")}, "Portrait mode: orbits, density, stickiness, dig, rotation, fli, megno or lyapunov.",
         "NAME");
  option({QStringLiteral("view")}, "Show the portrait's rectangle x0,x1,y0,y1.", "X0,X1,Y0,Y1");
  option({QStringLiteral("budget")}, "The portrait's points budget.", "POINTS");
  option({QStringLiteral("manifolds")}, "Draw the manifolds of the hyperbolic fixed point and the flux.");
  option({QStringLiteral("chains")}, "Identify the island chains of the top ROWS segments (default 10).", "ROWS");
  option({QStringLiteral("orbit")}, "Launch an orbit from (X, Y) and select it (its chain's centres drawn).", "X,Y");
  option({QStringLiteral("orbits")}, "Launch a line (M = 1) or an N x M grid of orbits between two points.",
         "X0,Y0,X1,Y1,N,M");
  option({QStringLiteral("periodic")}, "Find the periodic orbit at (X, Y), as a Shift+click does.", "X,Y");
  option({QStringLiteral("profile")},
         "The rotation profile of the line from (X0, Y0) to (X1, Y1) (with --periodic: about that orbit).",
         "X0,Y0,X1,Y1");
  parser.addPositionalArgument(QStringLiteral("file"), QStringLiteral("A run file (.json) or a session (.archipelago) to open."),
                               QStringLiteral("[file.json|file.archipelago]"));
}

// QGuiApplication's and QApplication's documented options (QGuiApplication and QApplication, "Supported command-line
// options"), which both take with one dash or two; -style=X and -stylesheet=X are QApplication's too.
QStringList withoutQtOptions(const QStringList& arguments) {
  static const QStringList withValue{
      QStringLiteral("-platform"),       QStringLiteral("-platformpluginpath"), QStringLiteral("-platformtheme"),
      QStringLiteral("-plugin"),         QStringLiteral("-qwindowgeometry"),    QStringLiteral("-qwindowicon"),
      QStringLiteral("-qwindowtitle"),   QStringLiteral("-session"),            QStringLiteral("-display"),
      QStringLiteral("-geometry"),       QStringLiteral("-style"),              QStringLiteral("-stylesheet"),
      QStringLiteral("-title"),          QStringLiteral("-name")};
  static const QStringList alone{QStringLiteral("-reverse"), QStringLiteral("-widgetcount"), QStringLiteral("-nograb"),
                                 QStringLiteral("-dograb"), QStringLiteral("-sync")};
  QStringList kept = arguments.mid(0, 1);  // the program
  for (int i = 1; i < arguments.size(); ++i) {
    const QString& argument = arguments[i];
    const QString name = argument.startsWith(QStringLiteral("--")) ? argument.mid(1) : argument;
    if (withValue.contains(name)) ++i;  // and its value (Qt takes the option even when the value is missing)
    else if (!alone.contains(name) && !name.startsWith(QStringLiteral("-style=")) &&
             !name.startsWith(QStringLiteral("-stylesheet=")))
      kept.append(argument);
  }
  return kept;
}

std::variant<GuiOptions, Refusal> readGuiOptions(const QStringList& arguments) {
  QCommandLineParser parser;
  addGuiOptions(parser);
  if (!parser.parse(withoutQtOptions(arguments)))  // Qt's words, as QCommandLineParser::process() printed them
    return Refusal{(QCoreApplication::applicationName() + QStringLiteral(": ") + parser.errorText()).toLocal8Bit().toStdString(), 1};
  if (const auto asked = informationAsked(parser); asked != GuiOptions::Information::None) {
    GuiOptions o;
    o.information = asked;
    return o;
  }
  try {
    return readValues(parser);
  } catch (const std::exception& e) {
    return Refusal{std::string("ERROR: ") + e.what(), 2};
  }
}

}  // namespace archipelago::app
