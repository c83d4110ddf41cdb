#pragma once
// The desktop application's command line, read whole by one parse before any application object exists: a bad number
// is one `ERROR:` line and status 2 without a display (Qt's xcb plugin aborts the process when it finds none), and
// --help, --help-all and --version are answered without one (a QCoreApplication).  Every number is read by core's
// readers; the rules that need the window (a --view or --orbit inside the box of the loaded parameters, a --segment
// beyond the segments the run file keeps, a --preset or --tab that exists) are checked once it is made.

#include <QCommandLineParser>
#include <QString>
#include <QStringList>

#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <variant>

#include "core/session/OrbitFamily.hpp"
#include "core/view/Viewport.hpp"
#include "ui/portrait/PortraitPanel.hpp"

namespace archipelago::app {

/// Every option of the command line, read and checked (absent: not given).
struct GuiOptions {
  /// --help, --help-all, --version: answered without a display; nothing else is read.
  enum class Information { None, Help, HelpAll, Version };
  Information information = Information::None;
  std::optional<QString> file;  ///< a run file (.json) or a session (.archipelago) to open
  std::optional<QString> preset;
  bool run = false;
  std::optional<int> threads;  ///< core's readThreads (0: all)
  std::optional<QString> screenshot;
  double afterSeconds = 20;  ///< before the screenshot
  std::optional<double> measureSeconds;
  std::optional<QString> tab;
  std::optional<int> segment;  ///< the rank of the long segment to select (needs a file)
  bool island = false;         ///< zoom to its island (needs segment)
  std::optional<ui::PortraitDisplay> mode;
  std::optional<PhysicalRect> view;
  std::optional<std::uint64_t> budget;
  bool manifolds = false;
  std::optional<int> chainRows;
  std::optional<PhysicalPoint> orbit;
  std::optional<OrbitFamily> orbits;
  std::optional<PhysicalPoint> periodic;
  std::optional<std::pair<PhysicalPoint, PhysicalPoint>> profile;

  /// Whether a script drives the window (a screenshot or a measure): no confirmation dialogs.
  [[nodiscard]] bool scripted() const { return screenshot || measureSeconds; }
};

/// A command line refused: the line to print on stderr and the exit status.
struct Refusal {
  std::string line;
  int status = 2;
};

/// Adds the application's options and its positional argument to `parser`: the one definition, used by the parse
/// and by --help's text.
void addGuiOptions(QCommandLineParser& parser);

/// `arguments` (argv as text, the program first) without Qt's own options, which QApplication takes out of argv when
/// it is made, after this parse.
[[nodiscard]] QStringList withoutQtOptions(const QStringList& arguments);

/// The options of `arguments` (argv as text, the program first; Qt's own options among them are skipped), or why
/// they are refused: the parser's error (status 1, in Qt's words: "Archipelago: Unknown option 'x'.") or a bad value
/// or combination (one ERROR line, status 2).
[[nodiscard]] std::variant<GuiOptions, Refusal> readGuiOptions(const QStringList& arguments);

}  // namespace archipelago::app
