#include "ui/window/MainWindow.hpp"

#include <QAction>
#include <QApplication>
#include <QCloseEvent>
#include <QDockWidget>
#include <QDragEnterEvent>
#include <QDropEvent>
#include <QFile>
#include <QFileDialog>
#include <QFileInfo>
#include <QFontMetrics>
#include <QHBoxLayout>
#include <QMenu>
#include <QMenuBar>
#include <QMessageBox>
#include <QMimeData>
#include <QPushButton>
#include <QScrollArea>
#include <QStatusBar>
#include <QTabWidget>
#include <QTimer>
#include <QToolBar>
#include <QToolButton>
#include <QUrl>
#include <QVBoxLayout>

#include <algorithm>

#include "ui/periodic/PeriodicOrbitDialog.hpp"
#include "ui/plots/StatisticsPlot.hpp"
#include "ui/portrait/AtlasPanel.hpp"
#include "ui/portrait/ManifoldsPanel.hpp"
#include "ui/portrait/MarkovTreePanel.hpp"
#include "ui/portrait/PortraitController.hpp"
#include "ui/portrait/PortraitPanel.hpp"
#include "ui/scan/KScanDialog.hpp"
#include "ui/segments/LongSegmentsPanel.hpp"
#include "ui/settings/SettingsController.hpp"
#include "ui/window/FileController.hpp"
#include "ui/window/HelpDialogs.hpp"
#include "ui/window/ParameterPanel.hpp"
#include "ui/window/Resources.hpp"
#include "ui/window/RunGlanceView.hpp"
#include "ui/window/RunNotes.hpp"
#include "ui/window/RunProgressLabels.hpp"
#include "ui/window/SessionController.hpp"
#include "ui/window/StatisticsView.hpp"
#include "ui/window/TailEstimateController.hpp"

namespace archipelago::ui {

namespace {
constexpr int kRefreshIntervalMs = 66;  // 15 Hz: live, yet far from saturating the GUI thread
/// The left panel's width (parameters, long segments): fixed, so that nothing on it widens the window; 48 digits
/// of the font (the long segments' seven columns with their margins: no horizontal scroll bar), at least 360 pixels
/// and at most 390, so that the window still fits a 1024-pixel screen (from about 11 points, as Qt 5's offscreen
/// platform's 12, the table scrolls instead).
int leftPanelWidth(const QFontMetrics& metrics) {
  return std::clamp(48 * metrics.horizontalAdvance(QLatin1Char('0')), 360, 390);
}

/// An action of `window`: its text, key (none: empty), status tip (none: empty), what it does, and its themed icon.
template <class Slot>
QAction* newAction(QMainWindow* window, const QString& text, const QKeySequence& key, const QString& tip, Slot slot,
                   const char* icon = nullptr) {
  auto* action = icon ? new QAction(QIcon::fromTheme(QString::fromLatin1(icon)), text, window) : new QAction(text, window);
  if (!key.isEmpty()) action->setShortcut(key);
  if (!tip.isEmpty()) action->setStatusTip(tip);
  QObject::connect(action, &QAction::triggered, window, slot);
  return action;
}

/// A dialog shown, raised and given the keyboard.
void present(QWidget* dialog) {
  dialog->show();
  dialog->raise();
  dialog->activateWindow();
}
}  // namespace

MainWindow::MainWindow(QWidget* parent) : QMainWindow(parent) {
  initResources();
  setWindowTitle(tr("Archipelago"));
  setWindowIcon(QIcon(QStringLiteral(":/icons/archipelago.svg")));
  setAcceptDrops(true);

  createRunController();
  createTabs();
  createCentralWidget();
  panel_ = new ParameterPanel(this);
  createActions();
  createMenus();
  createStatusBar();
  createDocks();
  createControllers();
  connectTailEstimates();
  connectAtlasPage();
  connectParameterPanel();

  refreshTimer_ = new QTimer(this);
  refreshTimer_->setInterval(kRefreshIntervalMs);
  connect(refreshTimer_, &QTimer::timeout, this, &MainWindow::refreshView);
  refreshTimer_->start();

  resize(1200, 760);
  restoreSettings();
  if (const auto p = panel_->parameters()) portrait_->controller()->setMap(p->map, p->Xr);
  onStatusChanged(run_->status());
  if (checkpointBanner_->offerIfKept())
    message(tr("A checkpoint of an unfinished run is available: Run ▸ Resume checkpoint"), 0);
}

void MainWindow::createRunController() {
  run_ = new RunController(this);
  run_->setAsk([this](const RunQuestion& q) { return askUser(q); });
  run_->setSaveHandler([this] { return run_->currentFile().isEmpty() ? files_->saveRunDialog() : saveRunFile(run_->currentFile()); });
  connect(run_, &RunController::statusChanged, this, &MainWindow::onStatusChanged);
  connect(run_, &RunController::message, this, [this](const QString& text, bool sticky) { message(text, sticky ? 0 : 6000); });
  connect(run_, &RunController::closeReady, this, &QWidget::close, Qt::QueuedConnection);
  connect(run_, &RunController::currentFileChanged, this, [this](const QString& path) {
    setWindowTitle(path.isEmpty() ? tr("Archipelago") : tr("%1 — Archipelago").arg(QFileInfo(path).fileName()));
    if (!path.isEmpty() && path != checkpointPath()) SettingsController::addRecentFile(path);
  });
  connect(run_, &RunController::runOpened, this, [this](const TrappingParameters& p) {
    panel_->setParameters(p, panel_->threads());
  });
  connect(run_, &RunController::runReplaced, this, [this] {
    shown_.reset();
    statistics_->clear();
    glance_->clear();
    segments_->clear();
  });
}

void MainWindow::createControllers() {
  tails_ = new TailEstimateController(run_, statistics_->plot(Statistic::P), this);
  sessions_ = new SessionController({panel_, run_, statistics_, portrait_, segments_, tabs_, tails_,
                                     [this] { refreshView(); }, [this](int rank) { showLongSegment(rank, false); }},
                                    this);
  const auto showNewest = [this] {
    refreshView();
    return shown_;
  };
  files_ = new FileController({this, run_, sessions_, portrait_, statistics_, panel_, tabs_, showNewest,
                               [this] { return runSettings(); }},
                              this);
  connect(files_, &FileController::statusMessage, this, &MainWindow::message);
}

void MainWindow::createTabs() {
  // The first screen is the phase portrait, accumulating, with f_t and C_τ of the run beside it (issue 25,
  // finding 5): what the program is about, seen at once; the Statistics tab has all six plots.
  tabs_ = new QTabWidget(this);
  tabs_->setDocumentMode(true);
  portrait_ = new PortraitPanel(tabs_);
  tabs_->addTab(portrait_, tr("Phase portrait"));
  statistics_ = new StatisticsView(tabs_);
  tabs_->addTab(statistics_, tr("Statistics"));
  glance_ = new RunGlanceView(portrait_->sidePages());
  portrait_->sidePages()->insertTab(0, glance_, tr("Run"));
  portrait_->sidePages()->setCurrentIndex(0);
  tabs_->setCurrentWidget(portrait_);
  // The portrait's progress belongs to the portrait: shown only while its tab is.
  connect(portrait_, &PortraitPanel::statusMessage, this, [this](const QString& text) {
    if (tabs_->currentWidget() == portrait_) statusBar()->showMessage(text, 5000);
  });
}

void MainWindow::createCentralWidget() {
  auto* central = new QWidget(this);
  auto* centralLayout = new QVBoxLayout(central);
  centralLayout->setContentsMargins(0, 0, 0, 0);
  centralLayout->setSpacing(0);
  checkpointBanner_ = new CheckpointBanner(run_, [this] { return runSettings(); }, central);
  connect(checkpointBanner_, &CheckpointBanner::statusMessage, this, &MainWindow::message);
  centralLayout->addWidget(checkpointBanner_);
  staleNote_ = new StaleRunNote(central);
  centralLayout->addWidget(staleNote_);
  centralLayout->addWidget(tabs_, 1);
  setCentralWidget(central);
}

void MainWindow::createDocks() {
  auto* dock = new QDockWidget(tr("Parameters"), this);
  dock->setObjectName(QStringLiteral("parametersDock"));
  parametersDock_ = dock;
  dock->setFeatures(QDockWidget::DockWidgetMovable | QDockWidget::DockWidgetFloatable);
  dock->setWidget(createParameterDock());
  addDockWidget(Qt::LeftDockWidgetArea, dock);
  createLongSegmentsDock(dock);
}

void MainWindow::connectTailEstimates() {
  connect(tails_, &TailEstimateController::pendingChanged, openTailAction_, [this](bool pending) {
    openTailAction_->setEnabled(!pending);
  });
  connect(tails_, &TailEstimateController::refused, files_, &FileController::showOpenError);
  connect(tails_, &TailEstimateController::statusMessage, this, &MainWindow::message);
}

void MainWindow::connectAtlasPage() {
  AtlasPanel* atlas = portrait_->atlasPanel();
  atlas->setConfirmDiscard([this](const QString& action) { return askAtlasDiscard(action); });
  MarkovTreePanel* model = atlas->markovTreePanel();
  model->setSources({[this]() -> MarkovTreePanel::RunShown {
                       const RunSnapshotPtr& shown = run_->latest();
                       if (!shown || !shown->hasStatistics) return {};
                       return {&shown->state, &shown->statistics};
                     },
                     [this]() -> std::optional<MapParameters> {
                       if (const auto p = panel_->parameters()) return p->map;
                       return std::nullopt;
                     },
                     [this] { return tails_->file(); }});
  // The model's P_t on the P_t plot; a tail drawn there sets the model against it.
  connect(model, &MarkovTreePanel::curveReady, this, [this](const Series& curve, const QString& title) {
    StatisticsPlot* p = statistics_->plot(Statistic::P);
    p->setModel(curve, title);
    p->refresh();
  });
  connect(model, &MarkovTreePanel::statusMessage, this, [this](const QString& text) { message(text, 0); });
  connect(tails_, &TailEstimateController::shown, model, &MarkovTreePanel::redrawAgainstTail);
}

bool MainWindow::askAtlasDiscard(const QString& action) {
  // A run's question and answers (Save, Discard, Cancel; nothing asked without confirmations): Save is Export JSON.
  const RunQuestion q{RunQuestion::Kind::discardUnsaved, tr("Unsaved atlas"),
                      tr("The atlas on the Atlas page was computed here and is in no file. Save it as JSON before %1?")
                          .arg(action)};
  switch (askUser(q)) {
    case RunAnswer::cancel: return false;
    case RunAnswer::discard: return true;
    case RunAnswer::save: return portrait_->atlasPanel()->exportWithDialog(true);
  }
  return false;
}

void MainWindow::connectParameterPanel() {
  connect(panel_, &ParameterPanel::validityChanged, this, [this] { updateActions(); });
  connect(panel_, &ParameterPanel::parametersChanged, this, [this] {
    if (const auto p = panel_->parameters()) portrait_->controller()->setMap(p->map, p->Xr);
    if (!panel_->isValid()) statusBar()->showMessage(panel_->validationMessage());
    else statusBar()->clearMessage();
    updateStaleNote();
  });
}

MainWindow::~MainWindow() = default;  // the controller (a child) stops its worker before the views go

// ---------------------------------------------------------------------------------------------- layout

void MainWindow::createActions() {
  createFileActions();
  createRunActions();
  resetZoomAction_ = newAction(this, tr("Reset &Zoom"), QKeySequence(QStringLiteral("Ctrl+0")),
                               tr("Let every plot follow its data again"), [this] {
                                 for (StatisticsPlot* p : statistics_->plots()) p->resetZoom();
                                 for (StatisticsPlot* p : {glance_->fPlot(), glance_->cPlot()})  // the Run page's too
                                   p->resetZoom();
                               });
}

void MainWindow::createFileActions() {
  openAction_ = newAction(this, tr("&Open Run File…"), QKeySequence::Open,
                          tr("Open a run file (.json): show its statistics, resume it if unfinished"),
                          [this] { files_->openRunDialog(); }, "document-open");
  openTailAction_ = newAction(this, tr("Open &Tail Estimate…"), {},
                              tr("Draw P_t beyond the run's data from a tail file (archipelago-cli tail): "
                                 "splitting on segment age, for the run's process"),
                              [this] {
                                const QString path = QFileDialog::getOpenFileName(
                                    this, tr("Open Tail Estimate"), QString(), tr("Tail files (*.json);;All files (*)"));
                                if (!path.isEmpty()) tails_->open(path);
                              });
  openAtlasAction_ = newAction(this, tr("Open &Atlas…"), {},
                               tr("Show an atlas file (archipelago-cli atlas --json) on the portrait's Atlas page; "
                                  "its Markov tree draws a model of P_t"),
                               [this] { files_->openAtlasDialog(); });
  saveAction_ = newAction(this, tr("&Save Run File"), QKeySequence::Save,
                          tr("Save the run (parameters, histograms, orbit states) so it can be resumed"),
                          [this] { files_->save(); }, "document-save");
  saveAsAction_ = newAction(this, tr("Save Run File &As…"), {}, {}, [this] { files_->saveRunDialog(); });
  // The platform's Save As, else Ctrl+Shift+S (some platforms define none: issue 25, finding 14).
  saveAsAction_->setShortcuts(QKeySequence::keyBindings(QKeySequence::SaveAs).isEmpty()
                                  ? QList<QKeySequence>{QKeySequence(QStringLiteral("Ctrl+Shift+S"))}
                                  : QKeySequence::keyBindings(QKeySequence::SaveAs));
  exportAllAction_ = newAction(this, tr("&Export All Plots…"), QKeySequence(QStringLiteral("Ctrl+E")),
                               tr("Write every plot (PNG, SVG, PDF), its numbers (CSV), the phase portrait, the "
                                  "longest segments and the run's parameters into a folder"),
                               [this] { files_->exportAllDialog(); });
  quitAction_ = newAction(this, tr("&Quit"), QKeySequence::Quit, {}, [this] { close(); });
  quitAction_->setMenuRole(QAction::QuitRole);
}

void MainWindow::createRunActions() {
  runAction_ = newAction(this, tr("&Run"), QKeySequence(Qt::Key_F5), tr("Start a new trapping run with these parameters"),
                         [this] { startRun(); }, "media-playback-start");
  pauseAction_ = newAction(this, tr("&Pause"), QKeySequence(Qt::Key_F6),
                           tr("Pause at the next chunk boundary, keeping the state"), [this] { pauseRun(); },
                           "media-playback-pause");
  resumeAction_ = newAction(this, tr("Res&ume"), QKeySequence(Qt::Key_F7),
                            tr("Continue the paused, stopped or opened run where it ended"), [this] { resumeRun(); },
                            "media-seek-forward");
  stopAction_ = newAction(this, tr("&Stop Run"), QKeySequence(QStringLiteral("Shift+F5")),
                          tr("End the run at the next chunk boundary; its state can still be saved"),
                          [this] { stopRun(); }, "media-playback-stop");
  stopAction_->setIconText(tr("Stop"));  // beside Run, Pause, Resume; the menu and tooltip say "Stop Run"
  stopAction_->setToolTip(tr("Stop Run (Shift+F5): end the run; the portrait's drawing has its own Stop Drawing"));
}

void MainWindow::createMenus() {
  createFileMenu();
  QMenu* run = menuBar()->addMenu(tr("&Run"));
  run->addActions({runAction_, pauseAction_, resumeAction_, stopAction_});
  run->addSeparator();
  run->addAction(tr("Resume &Checkpoint"), checkpointBanner_, &CheckpointBanner::resume);
  QMenu* view = menuBar()->addMenu(tr("&View"));
  view->addAction(resetZoomAction_);
  view->addSeparator();
  for (int i = 0; i < tabs_->count(); ++i) {
    QAction* a = view->addAction(tabs_->tabText(i), this, [this, i] { tabs_->setCurrentIndex(i); });
    a->setShortcut(QKeySequence(QStringLiteral("Alt+%1").arg(i + 1)));
  }
  addSidePageActions(view);
  menuBar()->addMenu(portrait_->menu());
  createToolsAndHelpMenus();
  createToolBar();
}

void MainWindow::createFileMenu() {
  QMenu* file = menuBar()->addMenu(tr("&File"));
  file->addActions({openAction_, openTailAction_, openAtlasAction_});
  recentMenu_ = file->addMenu(tr("Open &Recent"));
  connect(recentMenu_, &QMenu::aboutToShow, this, [this] { files_->fillRecentMenu(recentMenu_); });
  file->addActions({saveAction_, saveAsAction_});
  file->addSeparator();
  file->addAction(newAction(this, tr("Open Sess&ion…"), QKeySequence(QStringLiteral("Ctrl+Shift+O")),
                            tr("Restore a saved window: parameters, run, portrait view, segment, plot zooms"),
                            [this] { files_->openSessionDialog(); }));
  file->addAction(newAction(this, tr("Save Sessio&n…"), QKeySequence(QStringLiteral("Ctrl+Alt+S")),
                            tr("Save the window as it is (an .archipelago file) to open it again later"),
                            [this] { files_->saveSessionDialog(); }));
  file->addSeparator();
  file->addAction(exportAllAction_);
  QMenu* exportMenu = file->addMenu(tr("Export &Plot"));
  for (StatisticsPlot* plot : statistics_->plots()) {
    exportMenu->addAction(plot->displayName() + QStringLiteral("…"), this, [this, plot] { files_->exportPlotDialog(plot); });
    connect(plot, &StatisticsPlot::exportRequested, this, [this, plot] { files_->exportPlotDialog(plot); });
  }
  file->addSeparator();
  file->addAction(quitAction_);
}

void MainWindow::createToolsAndHelpMenus() {
  QMenu* tools = menuBar()->addMenu(tr("&Tools"));
  addAtlasActions(tools);
  tools->addAction(newAction(this, tr("Find &Periodic Orbit…"), QKeySequence(QStringLiteral("Ctrl+Shift+P")),
                             tr("Periodic orbits of Q with their residues; overlay them on the phase portrait"),
                             [this] { showPeriodicOrbitDialog(); }));
  tools->addAction(newAction(this, tr("&K Scan…"), {}, tr("The K scan of sec. 5: a resumable run per K, f_t and D over K"),
                             [this] { showKScanDialog(); }));
  QMenu* help = menuBar()->addMenu(tr("&Help"));
  help->addAction(newAction(this, tr("&Keyboard Shortcuts"), QKeySequence(QStringLiteral("Ctrl+/")),
                            tr("Every key of every menu, and the mouse on the portrait"),
                            [this] { showKeyboardShortcuts(); }));
  help->addAction(tr("&About Archipelago"), this, &MainWindow::showAbout);
  help->addAction(tr("About &Qt"), qApp, &QApplication::aboutQt);
}

void MainWindow::createToolBar() {
  QToolBar* bar = addToolBar(tr("Run"));
  bar->setObjectName(QStringLiteral("runToolBar"));
  bar->setToolButtonStyle(Qt::ToolButtonTextBesideIcon);
  bar->addActions({openAction_, saveAction_});
  bar->addSeparator();
  bar->addActions({runAction_, pauseAction_, resumeAction_, stopAction_});
  bar->addSeparator();
  bar->addAction(exportAllAction_);
}

void MainWindow::addSidePageActions(QMenu* view) {
  // The pages beside the portrait by the keyboard (issue 53, missing): Ctrl+1 … Ctrl+5, the portrait's tab shown.
  view->addSeparator();
  QTabWidget* side = portrait_->sidePages();
  for (int i = 0; i < side->count(); ++i) {
    QAction* a = view->addAction(tr("%1 Page").arg(QString(side->tabText(i)).remove(QLatin1Char('&'))), this, [this, i] {
      tabs_->setCurrentWidget(portrait_);
      portrait_->sidePages()->setCurrentIndex(i);
    });
    a->setShortcut(QKeySequence(QStringLiteral("Ctrl+%1").arg(i + 1)));
  }
}

void MainWindow::addAtlasActions(QMenu* tools) {
  // The Atlas page's Compute and Model P_t… by the menu and the keyboard (issue 53, missing): the page is shown and
  // its button pressed; a button that cannot be pressed says why in the status bar (its tooltip).
  const auto press = [this](QPushButton* button) {
    tabs_->setCurrentWidget(portrait_);
    portrait_->sidePages()->setCurrentWidget(portrait_->atlasPanel());
    if (button->isEnabled()) button->click();
    else message(tr("%1: %2").arg(button->text(), button->toolTip()), 10000);
  };
  tools->addSeparator();
  tools->addAction(newAction(this, tr("Compute &Atlas"), QKeySequence(QStringLiteral("Ctrl+Shift+A")),
                             tr("The Atlas page's Compute: the islands around islands of the portrait's K"),
                             [this, press] { press(portrait_->atlasPanel()->computeButton()); }));
  tools->addAction(newAction(this, tr("&Model P_t of the Atlas…"), QKeySequence(QStringLiteral("Ctrl+Shift+M")),
                             tr("The Atlas page's Model P_t…: the Markov tree of the atlas drawn on P_t"),
                             [this, press] { press(portrait_->atlasPanel()->markovTreePanel()->button()); }));
}

void MainWindow::createStatusBar() {
  progress_ = new RunProgressLabels(statusBar());
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
  scroll->setHorizontalScrollBarPolicy(Qt::ScrollBarAlwaysOff);  // the fields fit the width: no second bar
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
  // A fixed width: the panel never widens by itself (issue 25, finding 4); its texts wrap or elide.
  box->setFixedWidth(leftPanelWidth(fontMetrics()));
  return box;
}

// ----------------------------------------------------------------------------------------- run control

RunSettings MainWindow::runSettings() const {
  RunSettings settings;
  settings.threads = panel_->threads();
  if (const auto spec = panel_->spec()) settings.companion = spec->companion;  // the preset's q = 1 companion
  return settings;
}

void MainWindow::setThreads(int threads) {
  auto spec = panel_->spec();
  if (!spec) return;
  spec->threads = threads;
  panel_->setSpec(*spec);
}

bool MainWindow::startRun() {
  const auto params = panel_->parameters();
  if (!params) {
    message(panel_->validationMessage());
    return false;
  }
  if (!run_->start(*params, runSettings())) return false;
  saveSettings();
  return true;
}

bool MainWindow::pauseRun() { return run_->pause(); }
bool MainWindow::stopRun() { return run_->stop(); }
bool MainWindow::resumeRun() { return run_->resume(runSettings()); }

RunAnswer MainWindow::askUser(const RunQuestion& q) {
  return confirmations_ ? askRunQuestion(this, q) : RunAnswer::discard;
}

void MainWindow::onStatusChanged(RunStatus status) {
  // The panel shows the parameters of the run on screen, and is read-only while that run computes or can be
  // resumed: an edit could not apply to it.
  const bool locked = isLive(status) || status == RunStatus::paused;
  if (locked) {
    if (const auto& latest = run_->latest()) panel_->setParameters(latest->state.params, panel_->threads());
  }
  panel_->setEditable(!locked);
  if (!isLive(status)) progress_->clearRate();
  refreshView();
  updateActions();
  updateStaleNote();
  Q_EMIT runStatusChanged(status);
}

void MainWindow::refreshView() {
  const RunSnapshotPtr& latest = run_->latest();
  if (!latest || latest == shown_) return;
  shown_ = latest;
  statistics_->showSnapshot(*shown_);
  glance_->showSnapshot(shown_);
  segments_->updateSegments(shown_->state.params, shown_->state.longest);
  progress_->show(*shown_, isLive(run_->status()));
  updateStaleNote();
}

QString MainWindow::staleRunNote() const { return staleNote_->note(); }

void MainWindow::updateStaleNote() { staleNote_->showFor(*run_, panel_->parameters()); }

void MainWindow::createLongSegmentsDock(QDockWidget* parametersDock) {
  segments_ = new LongSegmentsPanel(this);
  segments_->setPortraitController(portrait_->controller());
  connect(segments_, &LongSegmentsPanel::statusMessage, this, [this](const QString& text) { message(text); });
  // Before a segment is drawn: show the portrait (the panel sets the run's map through the controller).
  connect(segments_, &LongSegmentsPanel::aboutToDraw, this, [this](const TrappingParameters&) {
    tabs_->setCurrentWidget(portrait_);
  });
  segmentsDock_ = new QDockWidget(tr("Long segments"), this);
  segmentsDock_->setObjectName(QStringLiteral("longSegmentsDock"));
  segmentsDock_->setFeatures(QDockWidget::DockWidgetMovable | QDockWidget::DockWidgetFloatable);
  segments_->setFixedWidth(leftPanelWidth(fontMetrics()));
  segmentsDock_->setWidget(segments_);
  // A tab beside the parameters: the portrait keeps the width it needs.
  addDockWidget(Qt::LeftDockWidgetArea, segmentsDock_);
  tabifyDockWidget(parametersDock, segmentsDock_);
  parametersDock->raise();
  // The tab behind is moved off the window, not hidden: its widgets stayed in the Tab chain, and Tab from the last
  // parameter went into the Long segments table unseen, replaying its rows (issue 53, finding 1).  A page behind is
  // disabled, so that none of its widgets takes the focus (Qt says which page is shown by visibilityChanged).
  for (QDockWidget* d : {parametersDock, segmentsDock_})
    connect(d, &QDockWidget::visibilityChanged, d, [d](bool shown) { d->widget()->setEnabled(shown); });
}

void MainWindow::showLongSegment(int rank, bool island) {
  segmentsDock_->raise();
  segments_->selectWhenListed(rank, island);
}

void MainWindow::showPeriodicOrbitDialog() {
  if (periodicDialog_ == nullptr) {
    periodicDialog_ = new PeriodicOrbitDialog(this);
    connect(periodicDialog_, &PeriodicOrbitDialog::overlayRequested, this, [this](const PeriodicOrbit& orbit) {
      tabs_->setCurrentWidget(portrait_);
      portrait_->controller()->showPeriodicOrbit(orbit);
    });
    connect(periodicDialog_, &PeriodicOrbitDialog::manifoldsRequested, this, [this](const PeriodicOrbit& orbit) {
      tabs_->setCurrentWidget(portrait_);
      portrait_->controller()->setManifoldOrbit(orbit);
      portrait_->sidePages()->setCurrentWidget(portrait_->manifoldsPanel());
    });
  }
  if (const auto p = panel_->parameters()) periodicDialog_->setK(p->map.K);
  present(periodicDialog_);
}

void MainWindow::showKScanDialog() {
  if (kScanDialog_ == nullptr) kScanDialog_ = new KScanDialog(panel_->spec().value_or(RunSpec{}), this);
  present(kScanDialog_);
}

void MainWindow::updateActions() {
  const RunStatus status = run_->status();
  const bool live = isLive(status);
  runAction_->setEnabled(!live && panel_->isValid());
  pauseAction_->setEnabled(status == RunStatus::running);
  stopAction_->setEnabled(status == RunStatus::running || status == RunStatus::pausing || status == RunStatus::paused);
  resumeAction_->setEnabled(run_->canResume());
  const bool haveRun = run_->latest() != nullptr;
  saveAction_->setEnabled(haveRun);
  saveAsAction_->setEnabled(haveRun);
  exportAllAction_->setEnabled(haveRun);
  openAction_->setEnabled(!live);
}

// ----------------------------------------------------------------------------------------------- files

bool MainWindow::openRunFile(const QString& path, QString* error) { return files_->openRunFile(path, error); }
bool MainWindow::openAtlasFile(const QString& path, QString* error) { return files_->openAtlasFile(path, error); }
bool MainWindow::saveRunFile(const QString& path, QString* error) { return files_->saveRunFile(path, error); }
bool MainWindow::saveSession(const QString& path, QString* error) { return files_->saveSession(path, error); }
bool MainWindow::openSession(const QString& path, QString* error) { return files_->openSession(path, error); }
bool MainWindow::exportAllTo(const QString& folder, QString* error) { return files_->exportAllTo(folder, error); }
void MainWindow::openInteractively(const QString& path) { files_->openInteractively(path); }

// ------------------------------------------------------------------------------------ window behaviour

void MainWindow::closeEvent(QCloseEvent* event) {
  // The controller asks what to do with a live or unsaved run; when it must first stop the run, it calls close()
  // again (closeReady) once the checkpoint is kept.  Then the Atlas page asks for an unsaved atlas (once: after the
  // run's stop).
  if (!run_->requestClose() || !portrait_->atlasPanel()->confirmDiscard(tr("quitting"))) {
    event->ignore();
    return;
  }
  saveSettings();
  event->accept();
}

void MainWindow::dragEnterEvent(QDragEnterEvent* event) {
  const QList<QUrl> urls = event->mimeData()->urls();
  if (urls.size() == 1 && urls.front().isLocalFile() && FileController::opens(urls.front().toLocalFile()))
    event->acceptProposedAction();
}

void MainWindow::dropEvent(QDropEvent* event) {
  const QList<QUrl> urls = event->mimeData()->urls();
  if (urls.isEmpty()) return;
  event->acceptProposedAction();
  const QString path = urls.front().toLocalFile();
  QTimer::singleShot(0, this, [this, path] { openInteractively(path); });  // no modal dialog inside a drop
}

void MainWindow::restoreSettings() {
  SettingsController::restoreWindow(*this);
  // The last parameters, as a run spec through core's codec; absent on the first start (the panel then keeps
  // the default preset), ignored with a note when a hand edit or another version made it unreadable.
  QString error;
  if (const auto spec = SettingsController::lastSpec(&error)) panel_->setSpec(*spec);
  else if (!error.isEmpty()) message(tr("The saved parameters were not restored: %1").arg(error), 10000);
}

void MainWindow::saveSettings() const {
  SettingsController::saveWindow(*this);
  if (const auto spec = panel_->spec()) SettingsController::setLastSpec(*spec);
}

void MainWindow::showAbout() {
  const RunSnapshotPtr& latest = run_->latest();
  ui::showAbout(this, latest && !latest->kernel.empty() ? QString::fromStdString(latest->kernel) : RunWorker::kernelName());
}

void MainWindow::message(const QString& text, int timeoutMs) { statusBar()->showMessage(text, timeoutMs); }

QList<QPair<QString, QString>> MainWindow::keyboardShortcuts() const { return ui::keyboardShortcuts(*menuBar()); }

void MainWindow::showKeyboardShortcuts() { ui::showKeyboardShortcuts(this, keyboardShortcuts()); }

}  // namespace archipelago::ui
