#pragma once
/// \file FileController.hpp
/// \brief The File menu's flows: run files (open, save, Save As), atlases (File ▸ Open Atlas), sessions, exports,
/// recent files and drops — each asks its file dialog (ui/settings/FileDialogs), calls the owner of the file (the
/// RunController, the SessionController, the Atlas page, ExportActions) and says how it went: in the status bar
/// (statusMessage), and in a dialog for an error the status bar would cut off.

#include <QObject>
#include <QString>

#include <functional>

#include "ui/run/RunController.hpp"

class QMenu;
class QTabWidget;
class QWidget;

namespace archipelago::ui {

class ParameterPanel;
class PortraitPanel;
class SessionController;
class StatisticsPlot;
class StatisticsView;

/// The window's parts the flows use (none may be null).
struct FileParts {
  QWidget* window = nullptr;  ///< the dialogs' parent
  RunController* run = nullptr;
  SessionController* sessions = nullptr;
  PortraitPanel* portrait = nullptr;
  StatisticsView* statistics = nullptr;
  ParameterPanel* parameters = nullptr;
  QTabWidget* tabs = nullptr;
  /// Shows the run's newest snapshot now and returns the snapshot shown (what an export writes).
  std::function<RunSnapshotPtr()> refreshNow;
  /// The threads and companion a run opened with.
  std::function<RunSettings()> runSettings;
};

class FileController : public QObject {
  Q_OBJECT
 public:
  FileController(FileParts parts, QObject* parent);

  /// A run file or a session, by its suffix: what may be dropped on the window.
  [[nodiscard]] static bool opens(const QString& path);

  // Each returns false with the reason in `error` (and the status bar, or a dialog) when it cannot.
  bool openRunFile(const QString& path, QString* error = nullptr);
  bool saveRunFile(const QString& path, QString* error = nullptr);
  /// Shows an atlas file on the portrait's Atlas page (AtlasPanel::openAtlasFile), the page in sight.
  bool openAtlasFile(const QString& path, QString* error = nullptr);
  bool saveSession(const QString& path, QString* error = nullptr);
  bool openSession(const QString& path, QString* error = nullptr);
  /// Writes every plot (PNG, SVG, PDF) and every CSV file of the run on screen (as `stats --csv` does) into `folder`.
  bool exportAllTo(const QString& folder, QString* error = nullptr);
  /// Opens a file the user chose (a run file, or a session by its .archipelago suffix); a failure is a dialog with
  /// the whole reason.  (Open dialogs, recent files, drops, and `archipelago FILE`.)
  void openInteractively(const QString& path);
  /// The reason a file cannot be opened: whole in a dialog (window-modal, not blocking), cut in the status bar.
  void showOpenError(const QString& title, const QString& path, const QString& reason);

  // The dialogs of the File menu.
  void openRunDialog();
  /// Save Run File As…: true when the run was written.
  bool saveRunDialog();
  /// Save Run File: to its file, or as Save As… when it has none (or is the checkpoint).
  void save();
  void openAtlasDialog();
  void openSessionDialog();
  bool saveSessionDialog();
  void exportAllDialog();
  void exportPlotDialog(StatisticsPlot* plot);
  /// File ▸ Open Recent's entries.
  void fillRecentMenu(QMenu* menu);

 Q_SIGNALS:
  void statusMessage(const QString& text, int timeoutMs);

 private:
  FileParts parts_;
};

}  // namespace archipelago::ui
