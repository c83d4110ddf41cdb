#pragma once
/// \file MainWindow.hpp
/// \brief The main window of `archipelago`: layout and wiring only.
///
/// The run on screen — its state machine, worker, files and checkpoint — belongs to the RunController; what the
/// window remembers between starts to the SettingsController; the File menu's flows to the FileController, the tail
/// estimates to the TailEstimateController, sessions to the SessionController, the Markov tree to the Atlas page's
/// MarkovTreePanel (its curve handed to the P_t plot), the checkpoint's banner, the stale run's note and the run's
/// progress to their widgets (RunNotes, RunProgressLabels).  The window lays out the parameter panel, the tabs
/// (statistics, phase portrait), the long-segments dock, menus, toolbar and status bar, and connects them:
/// the refresh timer (15 Hz) shows the controller's newest snapshot, so the event loop stays free however fast
/// chunks end.  Closing during a run asks, stops at the next chunk boundary, keeps a checkpoint and then closes;
/// the next start offers to resume it.

#include <QMainWindow>
#include <QPointer>

#include <cstdint>
#include <memory>
#include <optional>

#include "ui/run/RunController.hpp"
#include "ui/run/RunSnapshot.hpp"
#include "ui/run/RunWorker.hpp"

class QAction;
class QDockWidget;
class QFrame;
class QLabel;
class QMenu;
class QTabWidget;
class QTimer;

namespace archipelago::ui {

class CheckpointBanner;
class FileController;
class LongSegmentsPanel;
class PeriodicOrbitDialog;
class KScanDialog;
class PortraitPanel;

class ParameterPanel;
class RunGlanceView;
class RunProgressLabels;
class SessionController;
class StaleRunNote;
class TailEstimateController;
class StatisticsView;

class MainWindow : public QMainWindow {
  Q_OBJECT
 public:
  explicit MainWindow(QWidget* parent = nullptr);
  ~MainWindow() override;

  // Run control (also the slots of the Run menu).  Each returns false when it does not apply now.
  bool startRun();
  bool pauseRun();
  bool resumeRun();
  bool stopRun();
  [[nodiscard]] RunStatus runStatus() const noexcept { return run_->status(); }
  [[nodiscard]] RunController* runController() const noexcept { return run_; }

  // Files.  Errors go to the status bar and, when `error` is given, to it.
  bool openRunFile(const QString& path, QString* error = nullptr);
  /// File ▸ Open Tail Estimate: P_t of a tail file beside the run's own (issue #29).
  [[nodiscard]] TailEstimateController* tailEstimates() const noexcept { return tails_; }
  /// File ▸ Open Atlas: shows an atlas file on the portrait's Atlas page (AtlasPanel::openAtlasFile).
  bool openAtlasFile(const QString& path, QString* error = nullptr);
  bool saveRunFile(const QString& path, QString* error = nullptr);
  /// Writes every plot (PNG, SVG, PDF) and every CSV file of the run on screen (as `stats --csv` does) into `folder`.
  bool exportAllTo(const QString& folder, QString* error = nullptr);
  /// Where a run interrupted by closing the window is kept.
  [[nodiscard]] static QString checkpointPath() { return RunController::checkpointPath(); }

  /// Dialogs that ask the user (closing during a run, discarding unsaved work, overwriting) are skipped when
  /// false (tests, scripts): unsaved work is then discarded, a live run is stopped and checkpointed on close.
  void setConfirmations(bool on) noexcept { confirmations_ = on; }
  /// Worker threads for runs (0 = every core); the parameter panel's field.
  void setThreads(int threads);

  [[nodiscard]] ParameterPanel* parameterPanel() const noexcept { return panel_; }
  [[nodiscard]] StatisticsView* statisticsView() const noexcept { return statistics_; }
  [[nodiscard]] PortraitPanel* portraitPanel() const noexcept { return portrait_; }
  /// The "Long segments" dock: the run's longest trapped segments, replayed on the phase portrait.
  [[nodiscard]] LongSegmentsPanel* longSegments() const noexcept { return segments_; }
  /// Selects the segment of rank `rank` as soon as the table has it (e.g. after opening a run file) and, when
  /// `island`, zooms to one island of its chain once the chain is known.  (Scripts and screenshots.)
  void showLongSegment(int rank, bool island);
  /// Tools ▸ Find Periodic Orbit: the dialog, with K from the current parameters.
  void showPeriodicOrbitDialog();
  void showKScanDialog();
  /// Help ▸ Keyboard Shortcuts: every key of every menu (menu path, keys) and the mouse on the portrait.
  [[nodiscard]] QList<QPair<QString, QString>> keyboardShortcuts() const;
  void showKeyboardShortcuts();
  /// The "Run" page beside the portrait (f_t and C_τ live).
  [[nodiscard]] RunGlanceView* runGlance() const noexcept { return glance_; }
  [[nodiscard]] QDockWidget* parametersDock() const noexcept { return parametersDock_; }
  [[nodiscard]] QDockWidget* segmentsDock() const noexcept { return segmentsDock_; }
  [[nodiscard]] QTabWidget* tabs() const noexcept { return tabs_; }
  [[nodiscard]] RunSnapshotPtr latestSnapshot() const { return run_->latest(); }
  [[nodiscard]] QAction* runAction() const noexcept { return runAction_; }
  [[nodiscard]] QAction* pauseAction() const noexcept { return pauseAction_; }
  [[nodiscard]] QAction* resumeAction() const noexcept { return resumeAction_; }
  [[nodiscard]] QAction* stopAction() const noexcept { return stopAction_; }
  [[nodiscard]] QAction* saveAction() const noexcept { return saveAction_; }
  [[nodiscard]] const RunWorker& worker() const noexcept { return run_->worker(); }
  /// Shows the newest snapshot now (instead of at the next refresh tick).
  void refreshNow() { refreshView(); }

  // Sessions (File ▸ Save Session / Open Session, `.archipelago`).  A failure returns false with the reason.
  bool saveSession(const QString& path, QString* error = nullptr);
  bool openSession(const QString& path, QString* error = nullptr);
  /// Opens a file the user chose (a run file, or a session by its .archipelago suffix); a failure is a dialog with
  /// the whole reason.  (Open dialogs, recent files, drops, and `archipelago FILE`.)
  void openInteractively(const QString& path);
  [[nodiscard]] SessionController* sessions() const noexcept { return sessions_; }

  /// The note over the plots when they show a run whose parameters differ from the panel's (empty otherwise).
  [[nodiscard]] QString staleRunNote() const;

 Q_SIGNALS:
  void runStatusChanged(archipelago::ui::RunStatus status);

 protected:
  void closeEvent(QCloseEvent* event) override;
  void dragEnterEvent(QDragEnterEvent* event) override;
  void dropEvent(QDropEvent* event) override;

 private:
  /// The constructor's steps: the run's controller and its signals; the tabs (the portrait with the Run page, the
  /// statistics); the central widget (the checkpoint banner, the note of a stale run, the tabs); after the actions,
  /// menus and status bar, the docks (parameters, long segments); the owners of the tail estimates, sessions and
  /// files; the tail estimates' and the Atlas page's signals (its Markov tree's curve to the P_t plot); the
  /// parameters' signals.
  void createRunController();
  void createTabs();
  void createCentralWidget();
  void createDocks();
  void createControllers();
  void connectTailEstimates();
  void connectAtlasPage();
  void connectParameterPanel();
  void createActions();
  void createFileActions();
  void createRunActions();
  void createMenus();
  void createFileMenu();
  void createToolsAndHelpMenus();
  void createToolBar();
  /// View ▸ Run Page … Atlas Page (Ctrl+1 … Ctrl+5); Tools ▸ Compute Atlas, Model P_t of the Atlas….
  void addSidePageActions(QMenu* view);
  void addAtlasActions(QMenu* tools);
  void createStatusBar();
  QWidget* createParameterDock();
  void createLongSegmentsDock(QDockWidget* parametersDock);
  void restoreSettings();
  void saveSettings() const;

  void refreshView();
  void onStatusChanged(RunStatus status);
  void updateActions();
  void updateStaleNote();
  [[nodiscard]] RunSettings runSettings() const;
  RunAnswer askUser(const RunQuestion& question);
  /// Asks before the Atlas page's unsaved atlas goes for `action` (Save: Export JSON's dialog); true to go on.
  bool askAtlasDiscard(const QString& action);

  void showAbout();
  void message(const QString& text, int timeoutMs = 6000);

  RunController* run_ = nullptr;
  ParameterPanel* panel_ = nullptr;
  StatisticsView* statistics_ = nullptr;
  RunGlanceView* glance_ = nullptr;
  PortraitPanel* portrait_ = nullptr;
  QDockWidget* parametersDock_ = nullptr;
  LongSegmentsPanel* segments_ = nullptr;
  QDockWidget* segmentsDock_ = nullptr;
  PeriodicOrbitDialog* periodicDialog_ = nullptr;
  KScanDialog* kScanDialog_ = nullptr;
  SessionController* sessions_ = nullptr;
  FileController* files_ = nullptr;
  QTabWidget* tabs_ = nullptr;
  QTimer* refreshTimer_ = nullptr;
  CheckpointBanner* checkpointBanner_ = nullptr;
  StaleRunNote* staleNote_ = nullptr;

  RunProgressLabels* progress_ = nullptr;

  QAction* openAction_ = nullptr;
  QAction* openTailAction_ = nullptr;
  QAction* openAtlasAction_ = nullptr;
  QAction* saveAction_ = nullptr;
  QAction* saveAsAction_ = nullptr;
  QAction* exportAllAction_ = nullptr;
  QAction* quitAction_ = nullptr;
  QAction* runAction_ = nullptr;
  QAction* pauseAction_ = nullptr;
  QAction* resumeAction_ = nullptr;
  QAction* stopAction_ = nullptr;
  QAction* resetZoomAction_ = nullptr;
  QMenu* recentMenu_ = nullptr;

  RunSnapshotPtr shown_;       // the snapshot on screen
  bool confirmations_ = true;
  TailEstimateController* tails_ = nullptr;
};

}  // namespace archipelago::ui
