#pragma once
/// \file MainWindow.hpp
/// \brief The main window of `archipelago`: parameters, run control, live statistics plots, files.
///
/// Threads: a RunWorker owns every computation.  The window hands it a TrappingState and receives
/// immutable RunSnapshots through queued signals; snapshots of any other run id are dropped.  Only the
/// refresh timer (15 Hz) draws: a snapshot that arrives is stored, and the timer shows the newest one, so the
/// event loop stays free however fast chunks end.  Pause ends the worker's session at a chunk boundary and
/// keeps the state it returns; resume hands that state back.  Closing during a run asks, stops at the next
/// chunk boundary, writes a checkpoint run file in the application's data folder and then closes; the next
/// start offers to resume it.
///
/// The central area is a tab widget: "Statistics" is the first tab; tabs() lets the application add more
/// (phase portrait, longest segments).

#include <QMainWindow>
#include <QPointer>

#include "ui/RunSnapshot.hpp"
#include "ui/RunWorker.hpp"

class QAction;
class QDockWidget;
class QFrame;
class QLabel;
class QMenu;
class QProgressBar;
class QTabWidget;
class QTimer;

namespace archipelago::ui {

class LongSegmentsPanel;
class PeriodicOrbitDialog;
class PortraitPanel;

class ParameterPanel;
class StatisticsView;

/// Where the run shown in the window stands.
enum class RunStatus { idle, running, pausing, paused, stopping, stopped, finished, failed };

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
  [[nodiscard]] RunStatus runStatus() const noexcept { return status_; }

  // Files.  Errors go to the status bar and, when `error` is given, to it.
  bool openRunFile(const QString& path, QString* error = nullptr);
  bool saveRunFile(const QString& path, QString* error = nullptr);
  /// Writes every plot (PNG, SVG, PDF) and every CSV file of the run on screen (as `stats --csv` does) into `folder`.
  bool exportAllTo(const QString& folder, QString* error = nullptr);
  /// Where a run interrupted by closing the window is kept.
  [[nodiscard]] static QString checkpointPath();

  /// Dialogs that ask the user (closing during a run, overwriting) are skipped when false (tests, scripts).
  void setConfirmations(bool on) noexcept { confirmations_ = on; }

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
  [[nodiscard]] QTabWidget* tabs() const noexcept { return tabs_; }
  [[nodiscard]] RunSnapshotPtr latestSnapshot() const { return latest_; }
  [[nodiscard]] QAction* runAction() const noexcept { return runAction_; }
  [[nodiscard]] QAction* pauseAction() const noexcept { return pauseAction_; }
  [[nodiscard]] QAction* resumeAction() const noexcept { return resumeAction_; }
  [[nodiscard]] QAction* stopAction() const noexcept { return stopAction_; }
  [[nodiscard]] const RunWorker& worker() const noexcept { return *worker_; }

 Q_SIGNALS:
  void runStatusChanged(archipelago::ui::RunStatus status);

 protected:
  void closeEvent(QCloseEvent* event) override;
  void dragEnterEvent(QDragEnterEvent* event) override;
  void dropEvent(QDropEvent* event) override;

 private:
  void createActions();
  void createMenus();
  void createStatusBar();
  QWidget* createParameterDock();
  void createCheckpointBanner();
  void restoreSettings();
  void saveSettings() const;

  void onSnapshot(const RunSnapshotPtr& snapshot);
  void onRunEnded(quint64 runId, const RunSnapshotPtr& last, RunEnd how, const QString& message);
  void refreshView();
  void createLongSegmentsDock(QDockWidget* parametersDock);
  void showProgress(const RunSnapshot& snapshot);
  void setStatus(RunStatus status);
  void updateActions();
  void launch(TrappingState state);

  void openDialog();
  bool saveDialog();
  void exportAllDialog();
  void exportPlotDialog(int plotIndex);
  void addRecentFile(const QString& path);
  void fillRecentMenu();
  bool writeCheckpoint(QString* error = nullptr);
  void resumeCheckpoint();
  void discardCheckpoint();
  void showAbout();
  void message(const QString& text, int timeoutMs = 6000);

  ParameterPanel* panel_ = nullptr;
  StatisticsView* statistics_ = nullptr;
  PortraitPanel* portrait_ = nullptr;
  LongSegmentsPanel* segments_ = nullptr;
  QDockWidget* segmentsDock_ = nullptr;
  PeriodicOrbitDialog* periodicDialog_ = nullptr;
  int pendingSegment_ = -1;       // showLongSegment(): the rank to select when the table has it
  bool pendingIsland_ = false;
  QTabWidget* tabs_ = nullptr;
  RunWorker* worker_ = nullptr;
  QTimer* refreshTimer_ = nullptr;
  QFrame* checkpointBanner_ = nullptr;
  QLabel* checkpointLabel_ = nullptr;

  QProgressBar* progress_ = nullptr;
  QLabel* rateLabel_ = nullptr;
  QLabel* etaLabel_ = nullptr;
  QLabel* kernelLabel_ = nullptr;

  QAction* openAction_ = nullptr;
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

  RunStatus status_ = RunStatus::idle;
  quint64 runId_ = 0;          // the run whose snapshots are shown; others are stale
  RunSnapshotPtr latest_;      // newest snapshot of runId_
  RunSnapshotPtr shown_;       // the one on screen
  QString currentFile_;
  bool closeAfterStop_ = false;
  bool confirmations_ = true;
};

}  // namespace archipelago::ui

Q_DECLARE_METATYPE(archipelago::ui::RunStatus)
