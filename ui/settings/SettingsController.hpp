#pragma once
/// \file SettingsController.hpp
/// \brief Everything the window remembers between starts (QSettings), in one place: geometry, dock layout,
/// the last parameters (a run spec through core's codec), recent files and the last folder of each dialog.
///
/// A restored geometry is clamped to the screen the window opens on: a size saved on a large monitor never
/// leaves the window bigger than a 1280×800 laptop screen, nor its title bar off-screen.

#include <QByteArray>
#include <QRect>
#include <QString>
#include <QStringList>

#include <optional>

#include "core/runspec/RunSpec.hpp"

class QMainWindow;

namespace archipelago::ui {

class SettingsController {
 public:
  static constexpr int kMaxRecentFiles = 8;

  /// Restores size, position and dock layout, clamped to the available area of the window's screen; on a first
  /// start (nothing saved), firstGeometry() of that area.
  static void restoreWindow(QMainWindow& window);
  /// The window on a first start (issue 53, finding 20: 1200 × 760 in the middle of a 1920 × 1080 screen): nine
  /// tenths of the available area each way, at least 1200 × 760 where the area holds it, centred.
  [[nodiscard]] static QRect firstGeometry(const QRect& available);
  static void saveWindow(const QMainWindow& window);
  /// `wanted` moved and shrunk to fit inside `available` (both in global screen coordinates).
  [[nodiscard]] static QRect clampToScreen(const QRect& wanted, const QRect& available);

  /// The parameters of the last session; nothing on a first start.  `error` says why a stored spec was unreadable.
  [[nodiscard]] static std::optional<RunSpec> lastSpec(QString* error = nullptr);
  static void setLastSpec(const RunSpec& spec);

  [[nodiscard]] static QStringList recentFiles();
  static void addRecentFile(const QString& path);

  /// The folder the last file dialog used (every dialog: runs, sessions, exports, portraits); home at first or
  /// when it no longer exists.
  [[nodiscard]] static QString lastFolder();
  /// Remembers the folder of `path` (a file, or a folder itself when it is one) for lastFolder().
  static void rememberFolder(const QString& path);
};

}  // namespace archipelago::ui
