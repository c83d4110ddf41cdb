#include "ui/window/MainWindow.hpp"

#include <algorithm>

#include <QFontMetrics>
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
#include <QHeaderView>
#include <QTableWidget>
#include <QDialog>
#include <QDialogButtonBox>
#include <QFormLayout>
#include <QLineEdit>
#include <QTabBar>
#include <QStandardPaths>
#include <QStatusBar>
#include <QScreen>
#include <QTabWidget>
#include <QTimer>
#include <QToolBar>
#include <QToolButton>
#include <QUrl>
#include <QVBoxLayout>
#include <qwt_global.h>

#include <exception>
#include <functional>

#include "core/markovtree/MarkovTreeExport.hpp"
#include "core/stats/RunStatistics.hpp"
#include "core/tail/BruteForceSurvival.hpp"
#include "core/tail/TailFile.hpp"
#include "core/tail/TailResult.hpp"
#include "ui/jobs/BackgroundJobs.hpp"
#include "ui/jobs/DurationText.hpp"
#include "ui/window/ExportActions.hpp"
#include "ui/window/Resources.hpp"
#include "ui/window/SessionController.hpp"
#include "ui/settings/SettingsController.hpp"
#include "ui/window/ParameterPanel.hpp"
#include "ui/window/RunGlanceView.hpp"
#include "ui/window/StatisticsView.hpp"
#include "ui/periodic/PeriodicOrbitDialog.hpp"
#include "ui/scan/KScanDialog.hpp"
#include "ui/portrait/PortraitController.hpp"
#include "ui/portrait/AtlasPanel.hpp"
#include "ui/portrait/ManifoldsPanel.hpp"
#include "ui/portrait/PortraitPanel.hpp"
#include "ui/segments/LongSegmentsPanel.hpp"
#include "ui/plots/StatisticsPlot.hpp"
#include "core/runfile/RunFile.hpp"

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

QString formatRate(double stepsPerSecond) {
  if (stepsPerSecond >= 1e9) return QObject::tr("%1 G steps/s").arg(stepsPerSecond / 1e9, 0, 'f', 2);
  if (stepsPerSecond >= 1e6) return QObject::tr("%1 M steps/s").arg(stepsPerSecond / 1e6, 0, 'f', 1);
  return QObject::tr("%1 steps/s").arg(stepsPerSecond, 0, 'f', 0);
}


bool isRunFile(const QString& path) { return path.endsWith(QLatin1String(".json"), Qt::CaseInsensitive); }
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
  sessions_ = new SessionController({panel_, run_, statistics_, portrait_, segments_, tabs_, [this] { refreshView(); },
                                     [this](int rank) { showLongSegment(rank, false); },
                                     [this] { return tailFile_; }, [this](const QString& path) { openTailEstimate(path); }},
                                    this);
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
  if (QFileInfo::exists(checkpointPath())) {
    checkpointLabel_->setText(tr("An unfinished run was kept when the window closed: %1").arg(checkpointPath()));
    checkpointBanner_->show();
    message(tr("A checkpoint of an unfinished run is available: Run ▸ Resume checkpoint"), 0);
  }
}

void MainWindow::createRunController() {
  run_ = new RunController(this);
  run_->setAsk([this](const RunQuestion& q) { return askUser(q); });
  run_->setSaveHandler([this] { return run_->currentFile().isEmpty() ? saveDialog() : saveRunFile(run_->currentFile()); });
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
    tailFile_.clear();
    glance_->clear();
    segments_->clear();
  });
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
  createCheckpointBanner();
  centralLayout->addWidget(checkpointBanner_);
  staleNote_ = new QLabel(central);
  staleNote_->setObjectName(QStringLiteral("staleRunNote"));
  staleNote_->setWordWrap(true);
  staleNote_->setContentsMargins(8, 4, 8, 4);
  staleNote_->setStyleSheet(QStringLiteral("#staleRunNote { background: #eef3fb; border-bottom: 1px solid #b8c8e0; }"));
  staleNote_->hide();
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

void MainWindow::connectAtlasPage() {
  AtlasPanel* atlas = portrait_->atlasPanel();
  connect(atlas, &AtlasPanel::markovTreeAsked, this, &MainWindow::askMarkovTree);
  connect(atlas, &AtlasPanel::markovTreeFinished, this, &MainWindow::onMarkovTreeFinished);
  atlas->setConfirmDiscard([this](const QString& action) { return askAtlasDiscard(action); });
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

void MainWindow::onMarkovTreeFinished(std::shared_ptr<const MarkovTreeResult> model, const QString& error) {
  StatisticsPlot* p = statistics_->plot(Statistic::P);
  if (!model || !error.isEmpty() || !p) {
    message(tr("Cannot draw the Markov tree: %1").arg(error), 0);
    Q_EMIT markovTreeDrawn(error.isEmpty() ? tr("no model") : error);
    return;
  }
  const Series curve = markovTreeCurve(*model);  // P_t = w S(t): core's
  p->setModel(curve, tr("Markov tree (atlas depth %1)").arg(model->atlasDepth));
  p->refresh();
  message(tr("Drew the Markov tree's P_t (%1 states, w = %2 visits per segment, α = %3, b₂ = %4) on P_t")
              .arg(model->tree.states.size())
              .arg(QLocale::c().toString(static_cast<double>(model->weight.value_or(0)), 'g', 4))
              .arg(QLocale::c().toString(model->request.alpha, 'g', 6))
              .arg(QLocale::c().toString(model->request.b2, 'g', 7)));
  Q_EMIT markovTreeDrawn(QString());
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
  openAction_ = new QAction(QIcon::fromTheme(QStringLiteral("document-open")), tr("&Open Run File…"), this);
  openAction_->setShortcut(QKeySequence::Open);
  openAction_->setStatusTip(tr("Open a run file (.json): show its statistics, resume it if unfinished"));
  connect(openAction_, &QAction::triggered, this, &MainWindow::openDialog);

  openTailAction_ = new QAction(tr("Open &Tail Estimate…"), this);
  openTailAction_->setStatusTip(tr("Draw P_t beyond the run's data from a tail file (archipelago-cli tail): "
                                   "splitting on segment age, for the run's process"));
  connect(openTailAction_, &QAction::triggered, this, [this] {
    const QString path = QFileDialog::getOpenFileName(this, tr("Open Tail Estimate"), QString(),
                                                      tr("Tail files (*.json);;All files (*)"));
    if (!path.isEmpty()) openTailEstimate(path);
  });

  openAtlasAction_ = new QAction(tr("Open &Atlas…"), this);
  openAtlasAction_->setStatusTip(tr("Show an atlas file (archipelago-cli atlas --json) on the portrait's Atlas page; "
                                    "its Markov tree draws a model of P_t"));
  connect(openAtlasAction_, &QAction::triggered, this, [this] {
    if (!portrait_->atlasPanel()->confirmDiscard(tr("opening another atlas"))) return;
    const QString path = QFileDialog::getOpenFileName(this, tr("Open Atlas"), SettingsController::lastFolder(),
                                                      tr("Atlas files (*.json);;All files (*)"));
    if (path.isEmpty()) return;
    SettingsController::rememberFolder(path);
    QString error;
    if (!openAtlasFile(path, &error)) showOpenError(tr("Cannot open the atlas"), path, error);
  });

  saveAction_ = new QAction(QIcon::fromTheme(QStringLiteral("document-save")), tr("&Save Run File"), this);
  saveAction_->setShortcut(QKeySequence::Save);
  saveAction_->setStatusTip(tr("Save the run (parameters, histograms, orbit states) so it can be resumed"));
  connect(saveAction_, &QAction::triggered, this, [this] {
    if (run_->currentFile().isEmpty() || run_->currentFile() == checkpointPath()) saveDialog();
    else saveRunFile(run_->currentFile());
  });
  saveAsAction_ = new QAction(tr("Save Run File &As…"), this);
  // The platform's Save As, else Ctrl+Shift+S (some platforms define none: issue 25, finding 14).
  saveAsAction_->setShortcuts(QKeySequence::keyBindings(QKeySequence::SaveAs).isEmpty()
                                  ? QList<QKeySequence>{QKeySequence(QStringLiteral("Ctrl+Shift+S"))}
                                  : QKeySequence::keyBindings(QKeySequence::SaveAs));
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

  stopAction_ = new QAction(QIcon::fromTheme(QStringLiteral("media-playback-stop")), tr("&Stop Run"), this);
  stopAction_->setIconText(tr("Stop"));  // beside Run, Pause, Resume; the menu and tooltip say "Stop Run"
  stopAction_->setToolTip(tr("Stop Run (Shift+F5): end the run; the portrait's drawing has its own Stop Drawing"));
  stopAction_->setShortcut(QKeySequence(QStringLiteral("Shift+F5")));
  stopAction_->setStatusTip(tr("End the run at the next chunk boundary; its state can still be saved"));
  connect(stopAction_, &QAction::triggered, this, &MainWindow::stopRun);

  resetZoomAction_ = new QAction(tr("Reset &Zoom"), this);
  resetZoomAction_->setShortcut(QKeySequence(QStringLiteral("Ctrl+0")));
  resetZoomAction_->setStatusTip(tr("Let every plot follow its data again"));
  connect(resetZoomAction_, &QAction::triggered, this, [this] {
    for (StatisticsPlot* p : statistics_->plots()) p->resetZoom();
    for (StatisticsPlot* p : {glance_->fPlot(), glance_->cPlot()}) p->resetZoom();  // the Run page's too
  });
}

void MainWindow::createMenus() {
  QMenu* file = menuBar()->addMenu(tr("&File"));
  file->addAction(openAction_);
  file->addAction(openTailAction_);
  file->addAction(openAtlasAction_);
  recentMenu_ = file->addMenu(tr("Open &Recent"));
  connect(recentMenu_, &QMenu::aboutToShow, this, &MainWindow::fillRecentMenu);
  file->addAction(saveAction_);
  file->addAction(saveAsAction_);
  file->addSeparator();
  QAction* openSession = file->addAction(tr("Open Sess&ion…"), this, &MainWindow::openSessionDialog);
  openSession->setShortcut(QKeySequence(QStringLiteral("Ctrl+Shift+O")));
  openSession->setStatusTip(tr("Restore a saved window: parameters, run, portrait view, segment, plot zooms"));
  QAction* saveSession = file->addAction(tr("Save Sessio&n…"), this, &MainWindow::saveSessionDialog);
  saveSession->setShortcut(QKeySequence(QStringLiteral("Ctrl+Alt+S")));
  saveSession->setStatusTip(tr("Save the window as it is (an .archipelago file) to open it again later"));
  file->addSeparator();
  file->addAction(exportAllAction_);
  QMenu* exportMenu = file->addMenu(tr("Export &Plot"));
  for (int i = 0; i < statistics_->plots().size(); ++i) {
    exportMenu->addAction(statistics_->plots().at(i)->displayName() + QStringLiteral("…"), this,
                          [this, i] { exportPlotDialog(i); });
    connect(statistics_->plots().at(i), &StatisticsPlot::exportRequested, this, [this, i] { exportPlotDialog(i); });
  }
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
  view->addSeparator();
  for (int i = 0; i < tabs_->count(); ++i) {
    QAction* a = view->addAction(tabs_->tabText(i), this, [this, i] { tabs_->setCurrentIndex(i); });
    a->setShortcut(QKeySequence(QStringLiteral("Alt+%1").arg(i + 1)));
  }

  addSidePageActions(view);

  menuBar()->addMenu(portrait_->menu());

  QMenu* tools = menuBar()->addMenu(tr("&Tools"));
  addAtlasActions(tools);
  QAction* periodic = tools->addAction(tr("Find &Periodic Orbit…"), this, &MainWindow::showPeriodicOrbitDialog);
  periodic->setShortcut(QKeySequence(QStringLiteral("Ctrl+Shift+P")));
  periodic->setStatusTip(tr("Periodic orbits of Q with their residues; overlay them on the phase portrait"));
  QAction* kScan = tools->addAction(tr("&K Scan…"), this, &MainWindow::showKScanDialog);
  kScan->setStatusTip(tr("The K scan of sec. 5: a resumable run per K, f_t and D over K"));

  QMenu* help = menuBar()->addMenu(tr("&Help"));
  QAction* keys = help->addAction(tr("&Keyboard Shortcuts"), this, &MainWindow::showKeyboardShortcuts);
  keys->setShortcut(QKeySequence(QStringLiteral("Ctrl+/")));
  keys->setStatusTip(tr("Every key of every menu, and the mouse on the portrait"));
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
  QAction* compute = tools->addAction(tr("Compute &Atlas"), this,
                                      [this, press] { press(portrait_->atlasPanel()->computeButton()); });
  compute->setShortcut(QKeySequence(QStringLiteral("Ctrl+Shift+A")));
  compute->setStatusTip(tr("The Atlas page's Compute: the islands around islands of the portrait's K"));
  QAction* model = tools->addAction(tr("&Model P_t of the Atlas…"), this,
                                    [this, press] { press(portrait_->atlasPanel()->markovTreeButton()); });
  model->setShortcut(QKeySequence(QStringLiteral("Ctrl+Shift+M")));
  model->setStatusTip(tr("The Atlas page's Model P_t…: the Markov tree of the atlas drawn on P_t"));
}

void MainWindow::createStatusBar() {
  progress_ = new QProgressBar(this);
  progress_->setRange(0, 1000);
  progress_->setValue(0);
  progress_->setFormat(QStringLiteral("%p%"));
  progress_->setMinimumWidth(150);
  progress_->setMaximumWidth(320);
  progress_->setToolTip(tr("Blocks done / T"));
  rateLabel_ = new QLabel(this);
  rateLabel_->setObjectName(QStringLiteral("rateLabel"));
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
  if (!confirmations_) return RunAnswer::discard;
  if (q.kind == RunQuestion::Kind::quitWhileLive) {
    const auto answer = QMessageBox::question(this, q.title, q.text, QMessageBox::Yes | QMessageBox::Cancel,
                                              QMessageBox::Cancel);
    return answer == QMessageBox::Yes ? RunAnswer::discard : RunAnswer::cancel;
  }
  const auto answer = QMessageBox::warning(this, q.title, q.text,
                                           QMessageBox::Save | QMessageBox::Discard | QMessageBox::Cancel,
                                           QMessageBox::Save);
  if (answer == QMessageBox::Save) return RunAnswer::save;
  if (answer == QMessageBox::Discard) return RunAnswer::discard;
  return RunAnswer::cancel;
}

void MainWindow::onStatusChanged(RunStatus status) {
  // The panel shows the parameters of the run on screen, and is read-only while that run computes or can be
  // resumed: an edit could not apply to it.
  const bool locked = isLive(status) || status == RunStatus::paused;
  if (locked) {
    if (const auto& latest = run_->latest()) panel_->setParameters(latest->state.params, panel_->threads());
  }
  panel_->setEditable(!locked);
  if (!isLive(status)) {
    etaLabel_->clear();
    rateLabel_->clear();  // a rate belongs to a computing run
  }
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
  if (pendingSegment_ >= 0 && pendingSegment_ < segments_->model()->rowCount()) {
    segments_->selectRow(pendingSegment_);
    pendingSegment_ = -1;
  }
  showProgress(*shown_);
  updateStaleNote();
}

QString MainWindow::staleRunNote() const { return staleNote_->isHidden() ? QString() : staleNote_->text(); }

void MainWindow::updateStaleNote() {
  const RunSnapshotPtr& latest = run_->latest();
  const auto params = panel_->parameters();
  const bool stale = latest && !isLive(run_->status()) && run_->status() != RunStatus::paused &&
                     (!params || !(*params == latest->state.params));
  if (stale) {
    const TrappingParameters& p = latest->state.params;
    staleNote_->setText(tr("The plots show the %1 run of K = %2 (T = %3, M = %4); the parameters have changed since. "
                           "Run (F5) starts a run with the new ones.")
                            .arg(statusName(run_->status()), QString::number(p.map.K, 'g', 6))
                            .arg(p.T).arg(p.M));
  }
  staleNote_->setVisible(stale);
}

void MainWindow::createLongSegmentsDock(QDockWidget* parametersDock) {
  segments_ = new LongSegmentsPanel(this);
  segments_->setPortraitController(portrait_->controller());
  connect(segments_, &LongSegmentsPanel::statusMessage, this, [this](const QString& text) { message(text); });
  // Before a segment is drawn: show the portrait (the panel sets the run's map through the controller).
  connect(segments_, &LongSegmentsPanel::aboutToDraw, this, [this](const TrappingParameters&) {
    tabs_->setCurrentWidget(portrait_);
  });
  connect(segments_, &LongSegmentsPanel::chainReady, this, [this](const ChainResultPtr&) {
    if (!pendingIsland_) return;
    pendingIsland_ = false;
    segments_->zoomToIsland();
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
      portrait_->controller()->showPeriodicOrbit(orbit);
    });
    connect(periodicDialog_, &PeriodicOrbitDialog::manifoldsRequested, this, [this](const PeriodicOrbit& orbit) {
      tabs_->setCurrentWidget(portrait_);
      portrait_->controller()->setManifoldOrbit(orbit);
      portrait_->sidePages()->setCurrentWidget(portrait_->manifoldsPanel());
    });
  }
  if (const auto p = panel_->parameters()) periodicDialog_->setK(p->map.K);
  periodicDialog_->show();
  periodicDialog_->raise();
  periodicDialog_->activateWindow();
}

void MainWindow::showKScanDialog() {
  if (kScanDialog_ == nullptr) kScanDialog_ = new KScanDialog(panel_->spec().value_or(RunSpec{}), this);
  kScanDialog_->show();
  kScanDialog_->raise();
  kScanDialog_->activateWindow();
}

void MainWindow::showProgress(const RunSnapshot& s) {
  const QLocale c = QLocale::c();
  const bool live = isLive(run_->status());
  if (s.companionRunning && live) {
    // The run is done; its q = 1 companion gives the statistics below 10 q steps (issue 37, finding 7).
    progress_->setValue(static_cast<int>(1000 * s.companionFraction + 0.5));
    // A short label: the bar is at most 320 pixels (issue 53, finding 19: the longer one was clipped at 1280×800).
    progress_->setFormat(tr("q = 1 companion: %p %"));
    progress_->setToolTip(tr("The run has finished; its q = 1 companion (a fraction of its steps) now runs, so that "
                             "the statistics below 10 q steps are not those of blocks of q steps: t < %1 steps will "
                             "come from it. When it ends, the plots and α show the spliced statistics.")
                              .arg(10 * s.state.params.q));
    rateLabel_->setText(QString());
    etaLabel_->setText(tr("companion run"));
    if (!s.kernel.empty()) kernelLabel_->setText(tr("kernel: %1").arg(QString::fromStdString(s.kernel)));
    return;
  }
  progress_->setToolTip(tr("Blocks done / T"));
  progress_->setValue(static_cast<int>(1000 * s.progress.fraction + 0.5));
  progress_->setFormat(tr("%p % · block %1 of %2")
                           .arg(c.toString(static_cast<double>(s.state.blocksDone), 'g', 3),
                                c.toString(static_cast<double>(s.state.params.T), 'g', 3)));
  rateLabel_->setText(live && s.progress.stepsPerSecond > 0 ? formatRate(s.progress.stepsPerSecond) : QString());
  etaLabel_->setText(live && s.progress.stepsPerSecond > 0 ? tr("ETA %1").arg(formatDuration(s.progress.etaSeconds))
                                                           : QString());
  if (!s.kernel.empty()) kernelLabel_->setText(tr("kernel: %1").arg(QString::fromStdString(s.kernel)));
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

bool MainWindow::openRunFile(const QString& path, QString* error) {
  QString why;
  if (!run_->open(path, &why, false, runSettings())) {
    if (error) *error = why;
    if (why != tr("Cancelled")) showOpenError(tr("Cannot open run file"), path, why);
    return false;
  }
  return true;
}

namespace {
/// What the tail estimate's job found (on a worker thread, from the file and the run's immutable snapshot).
struct TailEstimate {
  QString refusal;  // why it is not drawn (empty: drawn)
  TailRequest request;
  Series levels;    // the reliable levels, in the run's units
  double factor = 1;
  double largestReliableT = 0;
};
using TailEstimatePtr = std::shared_ptr<const TailEstimate>;
}  // namespace

bool MainWindow::openTailEstimate(const QString& path, QString* error) {
  const RunSnapshotPtr shown = run_->latest();
  if (!shown || !shown->hasStatistics) {
    const QString why = tr("there is no run to compare it with: open or start the run first");
    if (error) *error = why;
    showOpenError(tr("Cannot draw the tail estimate"), path, why);
    return false;
  }
  if (!jobs_) jobs_ = std::make_unique<BackgroundJobs>(this);
  Job<TailEstimatePtr> job;  // latest wins: a second file replaces the first
  const std::string file = path.toStdString();
  job.work = [file, shown](JobContext<NoProgress>&) -> std::optional<TailEstimatePtr> {
    auto e = std::make_shared<TailEstimate>();
    const TailState tail = loadTailFile(file);  // throws: the failure's message is core's
    e->request = tail.request;
    if (const auto mismatch = tailRunMismatch(tail.request, shown->state)) {
      e->refusal = MainWindow::tr("it samples another process than the run's: %1").arg(QString::fromStdString(*mismatch));
      return e;
    }
    const TailResult result = tailResult(tail);
    e->levels = reliableSurvivalIn(result, shown->state, shown->statistics, &e->factor);
    e->largestReliableT = largestReliableT(result);
    if (e->levels.x.empty()) e->refusal = MainWindow::tr("it has no reliable level yet");
    return e;
  };
  job.done = [this, path](JobResult<TailEstimatePtr> r) {
    tailRequest_ = 0;
    openTailAction_->setEnabled(true);
    QString why;
    const RunSnapshotPtr now = run_->latest();
    if (!r.ok()) {
      why = r.error;
    } else if (!(*r.value)->refusal.isEmpty()) {
      why = (*r.value)->refusal;
    } else if (!now || !now->hasStatistics) {  // the run was closed while the file was read
      why = tr("there is no run to compare it with: open or start the run first");
    } else if (const auto mismatch = tailRunMismatch((*r.value)->request, now->state)) {  // or another opened
      why = tr("it samples another process than the run's: %1").arg(QString::fromStdString(*mismatch));
    } else if (StatisticsPlot* p = statistics_->plot(Statistic::P)) {
      const TailEstimate& e = **r.value;
      // A short legend entry (issue 37, finding 5: the whole description was cut off at the canvas' edge);
      // the details go to the status bar.
      QString details = tr("tail %1 × %2, %3 reliable levels")
                            .arg(e.request.population)
                            .arg(e.request.replicas)
                            .arg(e.levels.x.size());
      if (e.factor != 1)  // spliced statistics count the q = 1 process's segments
        details += tr(", × %1 (α₁/α_q)").arg(QLocale::c().toString(e.factor, 'g', 3));
      p->setEstimate(e.levels, tr("P_t by splitting (tail)"));
      tailFile_ = QFileInfo(path).absoluteFilePath();
      // A model drawn already, or still computing without the tail, is set against this tail now (the Atlas page's
      // comparison, issue 53, missing; a model asked for before the tail was read came back without a comparison).
      if (const auto inputs = portrait_->atlasPanel()->markovTreeInputs()) drawMarkovTree(inputs->first, inputs->second);
      p->refresh();
      message(tr("Drew %1 levels of %2 to t = %3 steps on P_t (%4)")
                  .arg(e.levels.x.size())
                  .arg(QFileInfo(path).fileName())
                  .arg(QLocale::c().toString(e.largestReliableT, 'g', 3))
                  .arg(details));
      Q_EMIT tailEstimateFinished(path, QString());
      return;
    }
    showOpenError(tr("Cannot draw the tail estimate"), path, why);
    Q_EMIT tailEstimateFinished(path, why);
  };
  tailRequest_ = jobs_->submit(std::move(job));
  openTailAction_->setEnabled(false);
  message(tr("Reading the tail estimate %1…").arg(QFileInfo(path).fileName()), 0);
  return true;
}

bool MainWindow::openAtlasFile(const QString& path, QString* error) {
  AtlasPanel* atlas = portrait_->atlasPanel();
  if (!atlas->openAtlasFile(path, error)) return false;
  tabs_->setCurrentWidget(portrait_);
  portrait_->sidePages()->setCurrentWidget(atlas);
  return true;
}

MainWindow::MarkovTreeEntry MainWindow::markovTreeEntry() const {
  // The atlas's map (the one the parameters show when no atlas is on the page), the shown run's map and α: core
  // decides what may be offered (markovTreeEntryOffer: never a number of another map).
  const std::shared_ptr<const Atlas> atlas = portrait_->atlasPanel()->atlas();
  const std::optional<TrappingParameters> given = panel_->parameters();
  const MapParameters atlasMap = atlas ? atlas->request.map : given ? given->map : MapParameters{};
  const RunSnapshotPtr shown = run_->latest();
  std::optional<MapParameters> runMap;
  double runAlpha = 0, splicedAlpha = 0;
  if (shown && shown->hasStatistics) {
    runMap = shown->state.params.map;
    runAlpha = shown->statistics.alpha;
    // Spliced statistics' α is the q = 1 companion's: the model, a tail file and `markov-tree --alpha` want the α of
    // the run's own process, blocks of q steps (issue 53, finding 12: 2.72 was offered where the tail's is 18.9).
    if (shown->statistics.splicedAt > 0) {
      splicedAlpha = runAlpha;
      runAlpha = statisticsOf(shown->state).alpha;
    }
  }
  const MarkovTreeEntryOffer o = markovTreeEntryOffer(atlasMap, runMap, runAlpha);
  QString alphaSource = QString::fromStdString(o.alphaSource);
  if (runAlpha > 0 && o.alpha == runAlpha) {
    const QLocale c = QLocale::c();
    alphaSource += tr(", of the q = %1 process, the one a tail file of this run samples (archipelago-cli markov-tree "
                      "--alpha %2)")
                       .arg(shown->state.params.q)
                       .arg(c.toString(runAlpha, 'g', 8));
    if (splicedAlpha > 0)
      alphaSource += tr("; the spliced statistics' α, %1, is the q = 1 companion's").arg(c.toString(splicedAlpha, 'g', 4));
  }
  return {o.alpha, o.b2, alphaSource, QString::fromStdString(o.b2Source)};
}

bool MainWindow::drawMarkovTree(double alpha, double b2, QString* error) {
  QString why;
  if (!portrait_->atlasPanel()->computeMarkovTree(alpha, b2, &why, tailFile_)) {
    if (error) *error = why;
    message(tr("Cannot draw the Markov tree: %1").arg(why), 0);
    return false;
  }
  message(tr("Computing the Markov tree of the atlas…"), 0);
  return true;
}

void MainWindow::askMarkovTree() {
  const MarkovTreeEntry e = markovTreeEntry();
  QDialog dialog(this);
  dialog.setWindowTitle(tr("Markov tree of the atlas"));
  auto* intro = new QLabel(tr("The model's P_t = w S(t) with w = α Φ_centre / b₂ visits per segment "
                              "(docs/markov-tree.md)."), &dialog);
  intro->setWordWrap(true);
  auto* alpha = new QLineEdit(e.alpha > 0 ? QLocale::c().toString(e.alpha, 'g', 8) : QString(), &dialog);
  alpha->setToolTip(tr("α: %1").arg(e.alphaSource));
  auto* b2 = new QLineEdit(e.b2 > 0 ? QLocale::c().toString(e.b2, 'g', 8) : QString(), &dialog);
  b2->setToolTip(tr("b₂: %1").arg(e.b2Source));
  auto* form = new QFormLayout;
  form->addRow(tr("α (steps)"), alpha);
  form->addRow(QString(), new QLabel(QStringLiteral("<small>%1</small>").arg(e.alphaSource.toHtmlEscaped()), &dialog));
  form->addRow(tr("b₂ (area)"), b2);
  form->addRow(QString(), new QLabel(QStringLiteral("<small>%1</small>").arg(e.b2Source.toHtmlEscaped()), &dialog));
  auto* buttons = new QDialogButtonBox(QDialogButtonBox::Ok | QDialogButtonBox::Cancel, &dialog);
  connect(buttons, &QDialogButtonBox::accepted, &dialog, &QDialog::accept);
  connect(buttons, &QDialogButtonBox::rejected, &dialog, &QDialog::reject);
  auto* layout = new QVBoxLayout(&dialog);
  layout->addWidget(intro);
  layout->addLayout(form);
  layout->addWidget(buttons);
  if (dialog.exec() != QDialog::Accepted) return;
  bool okA = false, okB = false;
  const double a = QLocale::c().toDouble(alpha->text().trimmed(), &okA);
  const double b = QLocale::c().toDouble(b2->text().trimmed(), &okB);
  QString why;
  if (!okA) why = tr("α '%1' is not a number").arg(alpha->text());
  else if (!okB) why = tr("b₂ '%1' is not a number").arg(b2->text());
  else if (drawMarkovTree(a, b, &why)) return;
  QMessageBox::warning(this, tr("Markov tree"), tr("Cannot draw the Markov tree: %1").arg(why));
}

bool MainWindow::saveRunFile(const QString& path, QString* error) { return run_->save(path, error); }

bool MainWindow::saveSession(const QString& path, QString* error) {
  QString why;
  if (!sessions_->save(path, &why)) {
    if (error) *error = why;
    message(tr("Cannot save the session: %1").arg(why), 0);
    return false;
  }
  portrait_->atlasPanel()->markSaved();  // the session holds the atlas
  message(tr("Session saved to %1").arg(path));
  return true;
}

bool MainWindow::openSession(const QString& path, QString* error) {
  QString why;
  if (!sessions_->open(path, &why)) {
    if (error) *error = why;
    return false;
  }
  message(tr("Session %1 opened").arg(path));
  return true;
}

void MainWindow::openSessionDialog() {
  const QString path = QFileDialog::getOpenFileName(this, tr("Open Session"), SettingsController::lastFolder(),
                                                    tr("Archipelago sessions (*.archipelago);;All files (*)"));
  if (path.isEmpty()) return;
  SettingsController::rememberFolder(path);
  openInteractively(path);
}

bool MainWindow::saveSessionDialog() {
  const QString start = QDir(SettingsController::lastFolder()).filePath(QStringLiteral("session.archipelago"));
  QString path = QFileDialog::getSaveFileName(this, tr("Save Session"), start, tr("Archipelago sessions (*.archipelago)"));
  if (path.isEmpty()) return false;
  if (!path.endsWith(QLatin1String(".archipelago"))) path += QStringLiteral(".archipelago");
  SettingsController::rememberFolder(path);
  QString error;
  if (saveSession(path, &error)) return true;
  QMessageBox::warning(this, tr("Cannot save the session"), tr("%1\n\n%2").arg(path, error));
  return false;
}

bool MainWindow::exportAllTo(const QString& folder, QString* error) {
  refreshView();  // export what the newest snapshot holds
  const ExportResult r = exportAll(statistics_->plots(), shown_, folder, portrait_->view(), panel_->spec());
  if (!r.ok()) {
    if (error) *error = r.error;
    message(tr("Export failed: %1").arg(r.error), 0);
    return false;
  }
  message(tr("Wrote %1 files to %2").arg(r.written.size()).arg(folder));  // every file, sidecars included
  return true;
}

void MainWindow::openDialog() {
  const QString path = QFileDialog::getOpenFileName(this, tr("Open Run File"), SettingsController::lastFolder(),
                                                    tr("Run files (*.json);;All files (*)"));
  if (path.isEmpty()) return;
  SettingsController::rememberFolder(path);
  openInteractively(path);
}

void MainWindow::openInteractively(const QString& path) {
  if (path.endsWith(QLatin1String(".archipelago"), Qt::CaseInsensitive)) {
    if (!portrait_->atlasPanel()->confirmDiscard(tr("opening the session"))) return;
    QString error;
    if (!openSession(path, &error) && error != tr("Cancelled"))
      showOpenError(tr("Cannot open session"), path, tr("%1\n\nNothing was changed.").arg(error));
    return;
  }
  openRunFile(path);  // a failure shows its reason
}

void MainWindow::showOpenError(const QString& title, const QString& path, const QString& reason) {
  // The status bar cuts long reasons off: the whole reason in a dialog (window-modal, not blocking).
  message(tr("%1: %2").arg(title, reason), 0);
  auto* box = new QMessageBox(QMessageBox::Warning, title, tr("Cannot open %1").arg(QFileInfo(path).fileName()),
                              QMessageBox::Ok, this);
  box->setObjectName(QStringLiteral("openErrorDialog"));
  box->setInformativeText(reason);
  box->setAttribute(Qt::WA_DeleteOnClose);
  box->open();
}

bool MainWindow::saveDialog() {
  const QString start = QDir(SettingsController::lastFolder()).filePath(QStringLiteral("run.json"));
  QString path = QFileDialog::getSaveFileName(this, tr("Save Run File"), start, tr("Run files (*.json)"));
  if (path.isEmpty()) return false;
  if (!isRunFile(path)) path += QStringLiteral(".json");
  SettingsController::rememberFolder(path);
  QString error;
  if (saveRunFile(path, &error)) return true;
  QMessageBox::warning(this, tr("Cannot save the run file"), tr("%1\n\n%2").arg(path, error));
  return false;
}

void MainWindow::exportAllDialog() {
  const QString folder = QFileDialog::getExistingDirectory(this, tr("Export All To"),
                                                           SettingsController::lastFolder());
  if (folder.isEmpty()) return;
  SettingsController::rememberFolder(folder);
  exportAllTo(folder);
}

void MainWindow::exportPlotDialog(int plotIndex) {
  StatisticsPlot* plot = statistics_->plots().at(plotIndex);
  const QString start = QDir(SettingsController::lastFolder())
                            .filePath(plot->fileName() + QStringLiteral(".png"));
  const QString path = QFileDialog::getSaveFileName(
      this, tr("Export %1").arg(plot->displayName()), start,
      tr("PNG image (*.png);;SVG drawing (*.svg);;PDF document (*.pdf);;CSV data (*.csv)"));
  if (path.isEmpty()) return;
  SettingsController::rememberFolder(path);
  refreshView();
  const ExportResult r = exportPlot(*plot, shown_, path);
  message(r.ok() ? tr("Wrote %1").arg(path) : tr("Export failed: %1").arg(r.error));
}

void MainWindow::fillRecentMenu() {
  recentMenu_->clear();
  const QStringList files = SettingsController::recentFiles();
  for (const QString& f : files) recentMenu_->addAction(QFileInfo(f).fileName(), this, [this, f] { openInteractively(f); })
                                     ->setToolTip(f);
  if (files.isEmpty()) recentMenu_->addAction(tr("(none)"))->setEnabled(false);
}

void MainWindow::resumeCheckpoint() {
  if (!QFileInfo::exists(checkpointPath())) {
    message(tr("There is no checkpoint"));
    return;
  }
  QString error;
  if (!run_->open(checkpointPath(), &error, /*resumeWhenReady=*/true, runSettings())) {
    if (error != tr("Cancelled")) QMessageBox::warning(this, tr("Cannot resume the checkpoint"), error);
    return;
  }
  // Once resumed, the window holds the run; closing again mid-run writes a fresh checkpoint.
  checkpointBanner_->hide();
  QFile::remove(checkpointPath());
}

void MainWindow::discardCheckpoint() {
  QFile::remove(checkpointPath());
  checkpointBanner_->hide();
  message(tr("Checkpoint discarded"));
}

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
  if (urls.size() == 1 && urls.front().isLocalFile() &&
      (isRunFile(urls.front().toLocalFile()) || urls.front().toLocalFile().endsWith(QLatin1String(".archipelago"))))
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
               run_->latest() && !run_->latest()->kernel.empty() ? QString::fromStdString(run_->latest()->kernel) : RunWorker::kernelName(),
               RunWorker::kernelDescription()));
}

void MainWindow::message(const QString& text, int timeoutMs) { statusBar()->showMessage(text, timeoutMs); }

QList<QPair<QString, QString>> MainWindow::keyboardShortcuts() const {
  QList<QPair<QString, QString>> rows;
  // Every action of every menu, by its menu path: the one list of keys (a menu item shows its key too).
  std::function<void(const QMenu*, const QString&)> walk = [&](const QMenu* menu, const QString& path) {
    for (QAction* a : menu->actions()) {
      if (a->isSeparator()) continue;
      const QString name = path + QStringLiteral(" ▸ ") + QString(a->text()).remove(QLatin1Char('&'));
      if (a->menu()) {
        walk(a->menu(), name);
        continue;
      }
      QStringList keys;
      for (const QKeySequence& k : a->shortcuts()) keys << k.toString(QKeySequence::NativeText);
      if (!keys.isEmpty()) rows.append({name, keys.join(QStringLiteral(", "))});
    }
  };
  for (QAction* a : menuBar()->actions())
    if (a->menu()) walk(a->menu(), QString(a->text()).remove(QLatin1Char('&')));
  rows.append({tr("Portrait: click"), tr("launch an orbit (listed under Orbits with its rotation number and chain)")});
  rows.append({tr("Portrait: Shift+click"), tr("find the periodic orbit there: its island chain named, its elliptic orbit "
                                                "drawn (Portrait ▸ Click Finds Periodic Orbits: a plain click too)")});
  rows.append({tr("Portrait: drag"), tr("zoom to the rectangle (with the profile tool: draw the line)")});
  rows.append({tr("Portrait: wheel"), tr("zoom about the cursor")});
  rows.append({tr("Portrait: middle-drag"), tr("pan")});
  rows.append({tr("Plots: drag / right click / wheel"), tr("zoom / zoom back / zoom about the cursor")});
  return rows;
}

void MainWindow::showKeyboardShortcuts() {
  auto* dialog = new QDialog(this);
  dialog->setObjectName(QStringLiteral("keyboardShortcutsDialog"));
  dialog->setWindowTitle(tr("Keyboard Shortcuts"));
  dialog->setAttribute(Qt::WA_DeleteOnClose);
  const auto rows = keyboardShortcuts();
  auto* table = new QTableWidget(static_cast<int>(rows.size()), 2, dialog);
  table->setHorizontalHeaderLabels({tr("Action"), tr("Keys")});
  table->verticalHeader()->hide();
  table->setEditTriggers(QAbstractItemView::NoEditTriggers);
  for (int i = 0; i < rows.size(); ++i) {
    table->setItem(i, 0, new QTableWidgetItem(rows[i].first));
    table->setItem(i, 1, new QTableWidgetItem(rows[i].second));
  }
  // The Action column as wide as its longest entry, the Keys column the rest, its long entries (the mouse's) wrapped
  // onto more lines (issue 53, finding 23: the Action column was squeezed and cut).
  table->setWordWrap(true);
  table->horizontalHeader()->setSectionResizeMode(0, QHeaderView::ResizeToContents);
  table->horizontalHeader()->setSectionResizeMode(1, QHeaderView::Stretch);
  table->verticalHeader()->setSectionResizeMode(QHeaderView::ResizeToContents);
  table->setHorizontalScrollBarPolicy(Qt::ScrollBarAlwaysOff);
  auto* buttons = new QDialogButtonBox(QDialogButtonBox::Close, dialog);
  connect(buttons, &QDialogButtonBox::rejected, dialog, &QDialog::close);
  auto* layout = new QVBoxLayout(dialog);
  layout->addWidget(table);
  layout->addWidget(buttons);
  const int actions = static_cast<QAbstractItemView*>(table)->sizeHintForColumn(0);
  const QRect screen = this->screen() ? this->screen()->availableGeometry() : QRect(0, 0, 1280, 800);
  dialog->resize(std::min(actions + fontMetrics().horizontalAdvance(QLatin1Char('x')) * 50 + 60, screen.width() * 9 / 10),
                 std::min(640, screen.height() * 8 / 10));
  dialog->show();
}

}  // namespace archipelago::ui
