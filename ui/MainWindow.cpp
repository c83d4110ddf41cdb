#include "ui/MainWindow.hpp"

#include <QAction>
#include <QApplication>
#include <QCloseEvent>
#include <QDir>
#include <QDockWidget>
#include <QDragEnterEvent>
#include <QDropEvent>
#include <QFileDialog>
#include <QFileInfo>
#include <QFrame>
#include <QHBoxLayout>
#include <QLabel>
#include <QLocale>
#include <QMenu>
#include <QMenuBar>
#include <QMessageBox>
#include <QMimeData>
#include <QProgressBar>
#include <QPushButton>
#include <QScrollArea>
#include <QSettings>
#include <QStandardPaths>
#include <QStatusBar>
#include <QTabWidget>
#include <QTimer>
#include <QToolBar>
#include <QToolButton>
#include <QUrl>
#include <QVBoxLayout>
#include <qwt_global.h>

#include <exception>

#include "ui/ExportActions.hpp"
#include "ui/Resources.hpp"
#include "ui/ParameterPanel.hpp"
#include "ui/StatisticsView.hpp"
#include "ui/periodic/PeriodicOrbitDialog.hpp"
#include "ui/portrait/PortraitPanel.hpp"
#include "ui/segments/LongSegmentsPanel.hpp"
#include "ui/plots/StatisticsPlot.hpp"
#include "core/runfile/RunFile.hpp"

namespace archipelago::ui {

namespace {
constexpr int kRefreshIntervalMs = 66;  // 15 Hz: live, yet far from saturating the GUI thread
constexpr int kMaxRecentFiles = 8;

QString formatRate(double stepsPerSecond) {
  if (stepsPerSecond >= 1e9) return QObject::tr("%1 G steps/s").arg(stepsPerSecond / 1e9, 0, 'f', 2);
  if (stepsPerSecond >= 1e6) return QObject::tr("%1 M steps/s").arg(stepsPerSecond / 1e6, 0, 'f', 1);
  return QObject::tr("%1 steps/s").arg(stepsPerSecond, 0, 'f', 0);
}

QString formatDuration(double seconds) {
  if (!(seconds >= 0) || seconds > 1e9) return QStringLiteral("—");
  const auto s = static_cast<qint64>(seconds + 0.5);
  if (s >= 3600) return QStringLiteral("%1:%2:%3").arg(s / 3600).arg(s / 60 % 60, 2, 10, QLatin1Char('0'))
                                                   .arg(s % 60, 2, 10, QLatin1Char('0'));
  return QStringLiteral("%1:%2").arg(s / 60).arg(s % 60, 2, 10, QLatin1Char('0'));
}

bool isRunFile(const QString& path) { return path.endsWith(QLatin1String(".json"), Qt::CaseInsensitive); }
}  // namespace

MainWindow::MainWindow(QWidget* parent) : QMainWindow(parent) {
  initResources();
  qRegisterMetaType<RunStatus>("archipelago::ui::RunStatus");
  setWindowTitle(tr("Archipelago"));
  setWindowIcon(QIcon(QStringLiteral(":/icons/archipelago.svg")));
  setAcceptDrops(true);

  worker_ = new RunWorker(this);
  connect(worker_, &RunWorker::snapshotReady, this, &MainWindow::onSnapshot, Qt::QueuedConnection);
  connect(worker_, &RunWorker::runEnded, this, &MainWindow::onRunEnded, Qt::QueuedConnection);

  tabs_ = new QTabWidget(this);
  tabs_->setDocumentMode(true);
  statistics_ = new StatisticsView(tabs_);
  tabs_->addTab(statistics_, tr("Statistics"));
  portrait_ = new PortraitPanel(tabs_);
  tabs_->addTab(portrait_, tr("Phase portrait"));
  connect(portrait_, &PortraitPanel::statusMessage, this, [this](const QString& text) { statusBar()->showMessage(text, 5000); });

  auto* central = new QWidget(this);
  auto* centralLayout = new QVBoxLayout(central);
  centralLayout->setContentsMargins(0, 0, 0, 0);
  centralLayout->setSpacing(0);
  createCheckpointBanner();
  centralLayout->addWidget(checkpointBanner_);
  centralLayout->addWidget(tabs_, 1);
  setCentralWidget(central);

  panel_ = new ParameterPanel(this);
  createActions();
  createMenus();
  createStatusBar();

  auto* dock = new QDockWidget(tr("Parameters"), this);
  dock->setObjectName(QStringLiteral("parametersDock"));
  dock->setFeatures(QDockWidget::DockWidgetMovable | QDockWidget::DockWidgetFloatable);
  dock->setWidget(createParameterDock());
  addDockWidget(Qt::LeftDockWidgetArea, dock);
  createLongSegmentsDock(dock);

  connect(panel_, &ParameterPanel::validityChanged, this, [this] { updateActions(); });
  connect(panel_, &ParameterPanel::parametersChanged, this, [this] {
    if (const auto p = panel_->parameters()) portrait_->setParameters(p->map, p->Xr);
    if (!panel_->isValid()) statusBar()->showMessage(panel_->validationMessage());
    else statusBar()->clearMessage();
  });

  refreshTimer_ = new QTimer(this);
  refreshTimer_->setInterval(kRefreshIntervalMs);
  connect(refreshTimer_, &QTimer::timeout, this, &MainWindow::refreshView);
  refreshTimer_->start();

  resize(1500, 920);
  restoreSettings();
  if (const auto p = panel_->parameters()) portrait_->setParameters(p->map, p->Xr);
  updateActions();
  if (QFileInfo::exists(checkpointPath())) {
    checkpointLabel_->setText(tr("An unfinished run was kept when the window closed: %1").arg(checkpointPath()));
    checkpointBanner_->show();
    message(tr("A checkpoint of an unfinished run is available: Run ▸ Resume checkpoint"), 0);
  }
}

MainWindow::~MainWindow() {
  delete worker_;  // aborts the session and waits for its thread before anything it reports to goes away
}

// ---------------------------------------------------------------------------------------------- layout

void MainWindow::createActions() {
  openAction_ = new QAction(QIcon::fromTheme(QStringLiteral("document-open")), tr("&Open Run File…"), this);
  openAction_->setShortcut(QKeySequence::Open);
  openAction_->setStatusTip(tr("Open a run file (.json): show its statistics, resume it if unfinished"));
  connect(openAction_, &QAction::triggered, this, &MainWindow::openDialog);

  saveAction_ = new QAction(QIcon::fromTheme(QStringLiteral("document-save")), tr("&Save Run File"), this);
  saveAction_->setShortcut(QKeySequence::Save);
  saveAction_->setStatusTip(tr("Save the run (parameters, histograms, orbit states) so it can be resumed"));
  connect(saveAction_, &QAction::triggered, this, [this] {
    if (currentFile_.isEmpty()) saveDialog();
    else saveRunFile(currentFile_);
  });
  saveAsAction_ = new QAction(tr("Save Run File &As…"), this);
  saveAsAction_->setShortcut(QKeySequence::SaveAs);
  connect(saveAsAction_, &QAction::triggered, this, &MainWindow::saveDialog);

  exportAllAction_ = new QAction(tr("&Export All Plots…"), this);
  exportAllAction_->setShortcut(QKeySequence(QStringLiteral("Ctrl+E")));
  exportAllAction_->setStatusTip(tr("Write every plot (PNG, SVG, PDF), its numbers (CSV), the phase portrait, the longest "
                                    "segments and the run's parameters into a folder"));
  connect(exportAllAction_, &QAction::triggered, this, &MainWindow::exportAllDialog);

  quitAction_ = new QAction(tr("&Quit"), this);
  quitAction_->setShortcut(QKeySequence::Quit);
  quitAction_->setMenuRole(QAction::QuitRole);
  connect(quitAction_, &QAction::triggered, this, &QWidget::close);

  runAction_ = new QAction(QIcon::fromTheme(QStringLiteral("media-playback-start")), tr("&Run"), this);
  runAction_->setShortcut(QKeySequence(Qt::Key_F5));
  runAction_->setStatusTip(tr("Start a new trapping run with these parameters"));
  connect(runAction_, &QAction::triggered, this, &MainWindow::startRun);

  pauseAction_ = new QAction(QIcon::fromTheme(QStringLiteral("media-playback-pause")), tr("&Pause"), this);
  pauseAction_->setShortcut(QKeySequence(Qt::Key_F6));
  pauseAction_->setStatusTip(tr("Pause at the next chunk boundary, keeping the state"));
  connect(pauseAction_, &QAction::triggered, this, &MainWindow::pauseRun);

  resumeAction_ = new QAction(QIcon::fromTheme(QStringLiteral("media-seek-forward")), tr("Res&ume"), this);
  resumeAction_->setShortcut(QKeySequence(Qt::Key_F7));
  resumeAction_->setStatusTip(tr("Continue the paused, stopped or opened run where it ended"));
  connect(resumeAction_, &QAction::triggered, this, &MainWindow::resumeRun);

  stopAction_ = new QAction(QIcon::fromTheme(QStringLiteral("media-playback-stop")), tr("&Stop"), this);
  stopAction_->setShortcut(QKeySequence(QStringLiteral("Shift+F5")));
  stopAction_->setStatusTip(tr("End the run at the next chunk boundary; its state can still be saved"));
  connect(stopAction_, &QAction::triggered, this, &MainWindow::stopRun);

  resetZoomAction_ = new QAction(tr("Reset &Zoom"), this);
  resetZoomAction_->setShortcut(QKeySequence(QStringLiteral("Ctrl+0")));
  resetZoomAction_->setStatusTip(tr("Let every plot follow its data again"));
  connect(resetZoomAction_, &QAction::triggered, this, [this] {
    for (StatisticsPlot* p : statistics_->plots()) p->resetZoom();
  });
}

void MainWindow::createMenus() {
  QMenu* file = menuBar()->addMenu(tr("&File"));
  file->addAction(openAction_);
  recentMenu_ = file->addMenu(tr("Open &Recent"));
  connect(recentMenu_, &QMenu::aboutToShow, this, &MainWindow::fillRecentMenu);
  file->addAction(saveAction_);
  file->addAction(saveAsAction_);
  file->addSeparator();
  file->addAction(exportAllAction_);
  QMenu* exportMenu = file->addMenu(tr("Export &Plot"));
  for (int i = 0; i < statistics_->plots().size(); ++i)
    exportMenu->addAction(statistics_->plots().at(i)->displayName() + QStringLiteral("…"), this,
                          [this, i] { exportPlotDialog(i); });
  file->addSeparator();
  file->addAction(quitAction_);

  QMenu* run = menuBar()->addMenu(tr("&Run"));
  run->addAction(runAction_);
  run->addAction(pauseAction_);
  run->addAction(resumeAction_);
  run->addAction(stopAction_);
  run->addSeparator();
  run->addAction(tr("Resume &Checkpoint"), this, &MainWindow::resumeCheckpoint);

  QMenu* view = menuBar()->addMenu(tr("&View"));
  view->addAction(resetZoomAction_);

  QMenu* tools = menuBar()->addMenu(tr("&Tools"));
  QAction* periodic = tools->addAction(tr("Find &Periodic Orbit…"), this, &MainWindow::showPeriodicOrbitDialog);
  periodic->setShortcut(QKeySequence(QStringLiteral("Ctrl+Shift+P")));
  periodic->setStatusTip(tr("Periodic orbits of Q with their residues; overlay them on the phase portrait"));

  QMenu* help = menuBar()->addMenu(tr("&Help"));
  help->addAction(tr("&About Archipelago"), this, &MainWindow::showAbout);
  help->addAction(tr("About &Qt"), qApp, &QApplication::aboutQt);

  QToolBar* bar = addToolBar(tr("Run"));
  bar->setObjectName(QStringLiteral("runToolBar"));
  bar->setToolButtonStyle(Qt::ToolButtonTextBesideIcon);
  bar->addAction(openAction_);
  bar->addAction(saveAction_);
  bar->addSeparator();
  bar->addAction(runAction_);
  bar->addAction(pauseAction_);
  bar->addAction(resumeAction_);
  bar->addAction(stopAction_);
  bar->addSeparator();
  bar->addAction(exportAllAction_);
}

void MainWindow::createStatusBar() {
  progress_ = new QProgressBar(this);
  progress_->setRange(0, 1000);
  progress_->setValue(0);
  progress_->setFormat(QStringLiteral("%p%"));
  progress_->setMinimumWidth(260);
  progress_->setMaximumWidth(320);
  progress_->setToolTip(tr("Blocks done / T"));
  rateLabel_ = new QLabel(this);
  rateLabel_->setToolTip(tr("Steps of N⁻¹ per second over all orbits (this session)"));
  etaLabel_ = new QLabel(this);
  etaLabel_->setToolTip(tr("Time left at the current rate"));
  kernelLabel_ = new QLabel(tr("kernel: %1").arg(RunWorker::kernelName()), this);
  kernelLabel_->setToolTip(tr("The block kernel that computes the run"));
  statusBar()->addPermanentWidget(rateLabel_);
  statusBar()->addPermanentWidget(etaLabel_);
  statusBar()->addPermanentWidget(progress_);
  statusBar()->addPermanentWidget(kernelLabel_);
  message(tr("Ready"));
}

QWidget* MainWindow::createParameterDock() {
  auto* box = new QWidget(this);
  auto* layout = new QVBoxLayout(box);
  layout->setContentsMargins(6, 6, 6, 6);
  auto* scroll = new QScrollArea(box);
  scroll->setWidget(panel_);
  scroll->setWidgetResizable(true);
  scroll->setFrameShape(QFrame::NoFrame);
  layout->addWidget(scroll, 1);
  auto* buttons = new QHBoxLayout;
  for (QAction* a : {runAction_, pauseAction_, resumeAction_, stopAction_}) {
    auto* b = new QToolButton(box);
    b->setDefaultAction(a);
    b->setToolButtonStyle(Qt::ToolButtonTextBesideIcon);
    b->setSizePolicy(QSizePolicy::Expanding, QSizePolicy::Fixed);
    buttons->addWidget(b);
  }
  layout->addLayout(buttons);
  box->setMinimumWidth(330);
  return box;
}

void MainWindow::createCheckpointBanner() {
  checkpointBanner_ = new QFrame(this);
  checkpointBanner_->setObjectName(QStringLiteral("checkpointBanner"));
  checkpointBanner_->setStyleSheet(
      QStringLiteral("#checkpointBanner { background: #fff6d6; border-bottom: 1px solid #e0c060; }"));
  auto* layout = new QHBoxLayout(checkpointBanner_);
  checkpointLabel_ = new QLabel(checkpointBanner_);
  checkpointLabel_->setWordWrap(true);
  auto* resume = new QPushButton(tr("Resume"), checkpointBanner_);
  auto* discard = new QPushButton(tr("Discard"), checkpointBanner_);
  connect(resume, &QPushButton::clicked, this, &MainWindow::resumeCheckpoint);
  connect(discard, &QPushButton::clicked, this, &MainWindow::discardCheckpoint);
  layout->addWidget(checkpointLabel_, 1);
  layout->addWidget(resume);
  layout->addWidget(discard);
  checkpointBanner_->hide();
}

// ----------------------------------------------------------------------------------------- run control

void MainWindow::launch(TrappingState state) {
  runId_ += 1;
  latest_.reset();
  shown_.reset();
  RunSettings settings;
  settings.threads = panel_->threads();
  worker_->startRun(runId_, std::move(state), settings);
  setStatus(RunStatus::running);
}

bool MainWindow::startRun() {
  if (status_ == RunStatus::running || status_ == RunStatus::pausing || status_ == RunStatus::stopping) return false;
  const auto params = panel_->parameters();
  if (!params) {
    message(panel_->validationMessage());
    return false;
  }
  try {
    TrappingState state = startTrapping(*params);
    statistics_->clear();
    currentFile_.clear();
    setWindowTitle(tr("Archipelago"));
    launch(std::move(state));
  } catch (const std::exception& e) {
    message(tr("Cannot start: %1").arg(QString::fromStdString(e.what())));
    return false;
  }
  saveSettings();
  message(tr("Running…"));
  return true;
}

bool MainWindow::pauseRun() {
  if (status_ != RunStatus::running) return false;
  worker_->requestEnd(runId_, RunEnd::paused);
  setStatus(RunStatus::pausing);
  message(tr("Pausing at the next chunk boundary…"));
  return true;
}

bool MainWindow::stopRun() {
  if (status_ != RunStatus::running && status_ != RunStatus::pausing) return false;
  worker_->requestEnd(runId_, RunEnd::stopped);
  setStatus(RunStatus::stopping);
  message(tr("Stopping at the next chunk boundary…"));
  return true;
}

bool MainWindow::resumeRun() {
  if (status_ != RunStatus::paused && status_ != RunStatus::stopped) return false;
  if (!latest_ || latest_->state.finished()) return false;
  const std::uint64_t at = latest_->state.blocksDone, total = latest_->state.params.T;
  launch(latest_->state);
  message(tr("Resumed at block %1 of %2").arg(at).arg(total));
  return true;
}

void MainWindow::onSnapshot(const RunSnapshotPtr& snapshot) {
  worker_->snapshotConsumed();
  if (!snapshot || snapshot->runId != runId_) return;  // a stale run: drop it
  latest_ = snapshot;
}

void MainWindow::onRunEnded(quint64 runId, const RunSnapshotPtr& last, RunEnd how, const QString& text) {
  if (runId != runId_) return;
  if (how == RunEnd::failed || !last) {
    setStatus(RunStatus::failed);
    message(tr("The run failed: %1").arg(text), 0);
    return;
  }
  latest_ = last;
  refreshView();
  const TrappingState& s = last->state;
  if (how == RunEnd::finished && s.finished()) {
    setStatus(RunStatus::finished);
    message(tr("Finished: %1 blocks × %2 orbits in %3").arg(s.params.T).arg(s.params.M)
                .arg(formatDuration(s.elapsedSeconds)), 0);
  } else if (how == RunEnd::stopped) {
    setStatus(RunStatus::stopped);
    message(tr("Stopped at block %1 of %2; save it to resume later").arg(s.blocksDone).arg(s.params.T), 0);
  } else {
    setStatus(RunStatus::paused);  // paused, or an opened run file that is not finished
    message(tr("Paused at block %1 of %2 (%3 %)").arg(s.blocksDone).arg(s.params.T)
                .arg(100.0 * last->progress.fraction, 0, 'f', 1), 0);
  }
  if (closeAfterStop_) {
    QString error;
    if (!writeCheckpoint(&error)) message(error, 0);
    closeAfterStop_ = false;
    close();
  }
}

void MainWindow::refreshView() {
  if (!latest_ || latest_ == shown_) return;
  shown_ = latest_;
  statistics_->showSnapshot(*shown_);
  segments_->updateSegments(shown_->state.params, shown_->state.longest);
  if (pendingSegment_ >= 0 && pendingSegment_ < segments_->model()->rowCount()) {
    segments_->selectRow(pendingSegment_);
    pendingSegment_ = -1;
  }
  showProgress(*shown_);
}

void MainWindow::createLongSegmentsDock(QDockWidget* parametersDock) {
  segments_ = new LongSegmentsPanel(this);
  segments_->setPortraitView(portrait_->view());
  connect(segments_, &LongSegmentsPanel::statusMessage, this, [this](const QString& text) { message(text); });
  // Before a segment is drawn: show the portrait with the run's map, so that the overlay's zoom sticks.
  connect(segments_, &LongSegmentsPanel::aboutToDraw, this, [this](const TrappingParameters& p) {
    tabs_->setCurrentWidget(portrait_);
    portrait_->applyParametersNow(p.map, p.Xr);
  });
  connect(segments_, &LongSegmentsPanel::chainReady, this, [this](const ChainResultPtr&) {
    if (!pendingIsland_) return;
    pendingIsland_ = false;
    segments_->zoomToIsland();
  });
  segmentsDock_ = new QDockWidget(tr("Long segments"), this);
  segmentsDock_->setObjectName(QStringLiteral("longSegmentsDock"));
  segmentsDock_->setFeatures(QDockWidget::DockWidgetMovable | QDockWidget::DockWidgetFloatable);
  segmentsDock_->setWidget(segments_);
  // A tab beside the parameters: the portrait keeps the width it needs.
  addDockWidget(Qt::LeftDockWidgetArea, segmentsDock_);
  tabifyDockWidget(parametersDock, segmentsDock_);
  parametersDock->raise();
}

void MainWindow::showLongSegment(int rank, bool island) {
  segmentsDock_->raise();
  pendingSegment_ = rank;
  pendingIsland_ = island;
  if (shown_ && rank < segments_->model()->rowCount()) {
    segments_->selectRow(rank);
    pendingSegment_ = -1;
  }
}

void MainWindow::showPeriodicOrbitDialog() {
  if (periodicDialog_ == nullptr) {
    periodicDialog_ = new PeriodicOrbitDialog(this);
    connect(periodicDialog_, &PeriodicOrbitDialog::overlayRequested, this, [this](const PeriodicOrbit& orbit) {
      tabs_->setCurrentWidget(portrait_);
      segments_->showPeriodicOrbit(orbit);
    });
  }
  if (const auto p = panel_->parameters()) periodicDialog_->setK(p->map.K);
  periodicDialog_->show();
  periodicDialog_->raise();
  periodicDialog_->activateWindow();
}

void MainWindow::showProgress(const RunSnapshot& s) {
  progress_->setValue(static_cast<int>(1000 * s.progress.fraction + 0.5));
  const QLocale c = QLocale::c();
  progress_->setFormat(tr("%p % · block %1 of %2")
                           .arg(c.toString(static_cast<double>(s.state.blocksDone), 'g', 3),
                                c.toString(static_cast<double>(s.state.params.T), 'g', 3)));
  const bool live = status_ == RunStatus::running || status_ == RunStatus::pausing || status_ == RunStatus::stopping;
  rateLabel_->setText(s.progress.stepsPerSecond > 0 ? formatRate(s.progress.stepsPerSecond) : QString());
  etaLabel_->setText(live && s.progress.stepsPerSecond > 0 ? tr("ETA %1").arg(formatDuration(s.progress.etaSeconds))
                                                           : QString());
  if (!s.kernel.empty()) kernelLabel_->setText(tr("kernel: %1").arg(QString::fromStdString(s.kernel)));
}

void MainWindow::setStatus(RunStatus status) {
  status_ = status;
  const bool busy = status == RunStatus::running || status == RunStatus::pausing || status == RunStatus::stopping;
  panel_->setEditable(!busy);
  updateActions();
  if (!busy) etaLabel_->clear();
  Q_EMIT runStatusChanged(status);
}

void MainWindow::updateActions() {
  const bool busy = status_ == RunStatus::running || status_ == RunStatus::pausing || status_ == RunStatus::stopping;
  runAction_->setEnabled(!busy && panel_->isValid());
  pauseAction_->setEnabled(status_ == RunStatus::running);
  stopAction_->setEnabled(status_ == RunStatus::running || status_ == RunStatus::pausing);
  resumeAction_->setEnabled((status_ == RunStatus::paused || status_ == RunStatus::stopped) && latest_ &&
                            !latest_->state.finished());
  saveAction_->setEnabled(latest_ != nullptr);
  saveAsAction_->setEnabled(latest_ != nullptr);
  openAction_->setEnabled(!busy);
}

// ----------------------------------------------------------------------------------------------- files

bool MainWindow::openRunFile(const QString& path, QString* error) {
  if (status_ == RunStatus::running || status_ == RunStatus::pausing || status_ == RunStatus::stopping) {
    const QString e = tr("Stop or pause the run before opening another");
    if (error) *error = e;
    message(e);
    return false;
  }
  try {
    TrappingState state = loadRunFile(path.toStdString());
    panel_->setParameters(state.params, panel_->threads());
    statistics_->clear();
    runId_ += 1;
    latest_.reset();
    shown_.reset();
    worker_->analyse(runId_, std::move(state));  // statistics are computed off the GUI thread
    currentFile_ = path;
    setWindowTitle(tr("%1 — Archipelago").arg(QFileInfo(path).fileName()));
    addRecentFile(path);
    message(tr("Opened %1").arg(path));
    return true;
  } catch (const std::exception& e) {
    const QString text = QString::fromStdString(e.what());
    if (error) *error = text;
    message(tr("Cannot open: %1").arg(text), 0);
    // The status bar cut long reasons off: the whole reason in a dialog (window-modal, not blocking).
    auto* box = new QMessageBox(QMessageBox::Warning, tr("Cannot open run file"),
                                tr("Cannot open %1").arg(QFileInfo(path).fileName()), QMessageBox::Ok, this);
    box->setObjectName(QStringLiteral("openErrorDialog"));
    box->setInformativeText(text);
    box->setAttribute(Qt::WA_DeleteOnClose);
    box->open();
    return false;
  }
}

bool MainWindow::saveRunFile(const QString& path, QString* error) {
  if (!latest_) {
    if (error) *error = tr("There is no run to save");
    return false;
  }
  try {
    archipelago::saveRunFile(path.toStdString(), latest_->state);
  } catch (const std::exception& e) {
    const QString text = QString::fromStdString(e.what());
    if (error) *error = text;
    message(tr("Cannot save: %1").arg(text), 0);
    return false;
  }
  currentFile_ = path;
  setWindowTitle(tr("%1 — Archipelago").arg(QFileInfo(path).fileName()));
  addRecentFile(path);
  message(tr("Saved %1 (block %2 of %3)").arg(path).arg(latest_->state.blocksDone).arg(latest_->state.params.T));
  return true;
}

bool MainWindow::exportAllTo(const QString& folder, QString* error) {
  refreshView();  // export what the newest snapshot holds
  const ExportResult r = exportAll(statistics_->plots(), shown_, folder, portrait_->view());
  if (!r.ok()) {
    if (error) *error = r.error;
    message(tr("Export failed: %1").arg(r.error), 0);
    return false;
  }
  message(tr("Wrote %1 files to %2").arg(r.written.size()).arg(folder));
  return true;
}

void MainWindow::openDialog() {
  const QString path = QFileDialog::getOpenFileName(this, tr("Open Run File"), lastFolder(),
                                                    tr("Run files (*.json);;All files (*)"));
  if (path.isEmpty()) return;
  rememberFolder(path);
  openRunFile(path);
}

bool MainWindow::saveDialog() {
  const QString start = QDir(lastFolder()).filePath(QStringLiteral("run.json"));
  QString path = QFileDialog::getSaveFileName(this, tr("Save Run File"), start, tr("Run files (*.json)"));
  if (path.isEmpty()) return false;
  if (!isRunFile(path)) path += QStringLiteral(".json");
  rememberFolder(path);
  return saveRunFile(path);
}

void MainWindow::exportAllDialog() {
  const QString folder = QFileDialog::getExistingDirectory(this, tr("Export All Plots To"), lastFolder());
  if (folder.isEmpty()) return;
  rememberFolder(folder);
  exportAllTo(folder);
}

void MainWindow::exportPlotDialog(int plotIndex) {
  StatisticsPlot* plot = statistics_->plots().at(plotIndex);
  const QString start = QDir(lastFolder()).filePath(plot->fileName() + QStringLiteral(".png"));
  const QString path = QFileDialog::getSaveFileName(
      this, tr("Export %1").arg(plot->displayName()), start,
      tr("PNG image (*.png);;SVG drawing (*.svg);;PDF document (*.pdf);;CSV data (*.csv)"));
  if (path.isEmpty()) return;
  rememberFolder(path);
  refreshView();
  const ExportResult r = exportPlot(*plot, shown_, path);
  message(r.ok() ? tr("Wrote %1").arg(path) : tr("Export failed: %1").arg(r.error));
}

void MainWindow::addRecentFile(const QString& path) {
  QSettings settings;
  QStringList files = settings.value(QStringLiteral("recentFiles")).toStringList();
  const QString absolute = QFileInfo(path).absoluteFilePath();
  files.removeAll(absolute);
  files.prepend(absolute);
  while (files.size() > kMaxRecentFiles) files.removeLast();
  settings.setValue(QStringLiteral("recentFiles"), files);
}

void MainWindow::fillRecentMenu() {
  recentMenu_->clear();
  const QStringList files = QSettings().value(QStringLiteral("recentFiles")).toStringList();
  for (const QString& f : files) recentMenu_->addAction(QFileInfo(f).fileName(), this, [this, f] { openRunFile(f); })
                                     ->setToolTip(f);
  if (files.isEmpty()) recentMenu_->addAction(tr("(none)"))->setEnabled(false);
}

QString MainWindow::checkpointPath() {
  return QDir(QStandardPaths::writableLocation(QStandardPaths::AppDataLocation))
      .filePath(QStringLiteral("checkpoint.json"));
}

bool MainWindow::writeCheckpoint(QString* error) {
  if (!latest_) return false;
  try {
    QDir().mkpath(QFileInfo(checkpointPath()).absolutePath());
    archipelago::saveRunFile(checkpointPath().toStdString(), latest_->state);
  } catch (const std::exception& e) {
    if (error) *error = tr("Could not keep a checkpoint: %1").arg(QString::fromStdString(e.what()));
    return false;
  }
  message(tr("Checkpoint kept in %1").arg(checkpointPath()), 0);
  return true;
}

void MainWindow::resumeCheckpoint() {
  if (!QFileInfo::exists(checkpointPath())) {
    message(tr("There is no checkpoint"));
    return;
  }
  checkpointBanner_->hide();
  if (!openRunFile(checkpointPath())) return;
  // The worker answers the analysis first; resume as soon as the window knows the state.
  auto connection = std::make_shared<QMetaObject::Connection>();
  *connection = connect(this, &MainWindow::runStatusChanged, this, [this, connection](RunStatus s) {
    // Once resumed, the window holds the run; closing again mid-run writes a fresh checkpoint.
    if (s == RunStatus::paused && resumeRun()) QFile::remove(checkpointPath());
    if (s != RunStatus::running) disconnect(*connection);
  });
}

void MainWindow::discardCheckpoint() {
  QFile::remove(checkpointPath());
  checkpointBanner_->hide();
  message(tr("Checkpoint discarded"));
}

// ------------------------------------------------------------------------------------ window behaviour

void MainWindow::closeEvent(QCloseEvent* event) {
  const bool busy = status_ == RunStatus::running || status_ == RunStatus::pausing || status_ == RunStatus::stopping;
  if (busy) {
    if (confirmations_ && !closeAfterStop_) {
      const auto answer = QMessageBox::question(
          this, tr("A run is in progress"),
          tr("Stop the run and quit? Its state is kept as a checkpoint that the next start offers to resume."),
          QMessageBox::Yes | QMessageBox::Cancel, QMessageBox::Cancel);
      if (answer != QMessageBox::Yes) {
        event->ignore();
        return;
      }
    }
    // Stop at the next chunk boundary; onRunEnded() writes the checkpoint and closes again.
    closeAfterStop_ = true;
    if (status_ != RunStatus::stopping) {
      worker_->requestEnd(runId_, RunEnd::stopped);
      setStatus(RunStatus::stopping);
    }
    message(tr("Stopping the run to keep a checkpoint…"), 0);
    event->ignore();
    return;
  }
  saveSettings();
  event->accept();
}

void MainWindow::dragEnterEvent(QDragEnterEvent* event) {
  const QList<QUrl> urls = event->mimeData()->urls();
  if (urls.size() == 1 && urls.front().isLocalFile() && isRunFile(urls.front().toLocalFile()))
    event->acceptProposedAction();
}

void MainWindow::dropEvent(QDropEvent* event) {
  const QList<QUrl> urls = event->mimeData()->urls();
  if (urls.isEmpty()) return;
  if (openRunFile(urls.front().toLocalFile())) event->acceptProposedAction();
}

void MainWindow::restoreSettings() {
  QSettings settings;
  restoreGeometry(settings.value(QStringLiteral("window/geometry")).toByteArray());
  restoreState(settings.value(QStringLiteral("window/state")).toByteArray());
  // The last parameters, as a run spec through core's codec; absent on the first start (the panel then keeps
  // the default preset), ignored with a note when a hand edit or another version made it unreadable.
  const QString text = settings.value(QStringLiteral("run/spec")).toString();
  if (text.isEmpty()) return;
  try {
    panel_->setSpec(parseRunSpec(text.toStdString()));
  } catch (const std::invalid_argument& e) {
    message(tr("The saved parameters were not restored: %1").arg(QString::fromStdString(e.what())), 10000);
  }
}

void MainWindow::saveSettings() const {
  QSettings settings;
  settings.setValue(QStringLiteral("window/geometry"), saveGeometry());
  settings.setValue(QStringLiteral("window/state"), saveState());
  if (const auto spec = panel_->spec()) settings.setValue(QStringLiteral("run/spec"), QString::fromStdString(runSpecJson(*spec)));
}

void MainWindow::showAbout() {
  QMessageBox::about(
      this, tr("About Archipelago"),
      tr("<h3>Archipelago %1</h3>"
         "<p>Exact trapping statistics of the quadratic map Q*: how islands around islands make "
         "chaotic orbits sticky.</p>"
         "<p>Reproduces C. F. F. Karney, <i>Long-time correlations in the stochastic regime</i>, "
         "Physica D <b>8</b>, 360–380 (1983), "
         "<a href=\"https://doi.org/10.1016/0167-2789(83)90232-6\">doi:10.1016/0167-2789(83)90232-6</a>.</p>"
         "<table>"
         "<tr><td>Qt</td><td>%2 (built with %3)</td></tr>"
         "<tr><td>Qwt</td><td>%4</td></tr>"
         "<tr><td>Kernel</td><td>%5 — %6</td></tr>"
         "</table>")
          .arg(QStringLiteral(ARCHIPELAGO_VERSION), QString::fromLatin1(qVersion()), QStringLiteral(QT_VERSION_STR),
               QStringLiteral(QWT_VERSION_STR),
               latest_ && !latest_->kernel.empty() ? QString::fromStdString(latest_->kernel) : RunWorker::kernelName(),
               RunWorker::kernelDescription()));
}

void MainWindow::message(const QString& text, int timeoutMs) { statusBar()->showMessage(text, timeoutMs); }

}  // namespace archipelago::ui
