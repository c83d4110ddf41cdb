#include "ui/segments/LongSegmentsPanel.hpp"

#include <QDir>

#include "ui/settings/SettingsController.hpp"

#include <QComboBox>
#include <QElapsedTimer>
#include <QFileDialog>
#include <QGridLayout>
#include <QHBoxLayout>
#include <QHeaderView>
#include <QScrollBar>
#include <QItemSelectionModel>
#include <QLabel>
#include <QLocale>
#include <QPushButton>
#include <QSlider>
#include <QSpinBox>
#include <QTableView>
#include <QTimer>
#include <QToolButton>
#include <QVBoxLayout>

#include "ui/portrait/PortraitController.hpp"

#include <algorithm>
#include <exception>

namespace archipelago::ui {

namespace {
/// Play through a segment in about this many timer ticks (30 Hz: ~15 s), whatever its length.
constexpr std::size_t kPlayTicks = 450;
/// The job channels: replays (the latest selection wins) and chain identifications (a queue, urgent first),
/// in the order of the priorities given to jobs_.
constexpr int kReplayChannel = 0;
constexpr int kChainChannel = 1;
}  // namespace

LongSegmentsPanel::LongSegmentsPanel(QWidget* parent) : QWidget(parent) {
  qRegisterMetaType<SegmentReplayPtr>();
  qRegisterMetaType<ChainResultPtr>();
  model_ = new LongestSegmentsModel(this);
  // Replays at normal priority (the user waits for the one selected); chain identifications, which run beside
  // a live run for every new top segment, at the portrait's idle priority, so that the run keeps the cores
  // (issue 41: at normal priority they took half the CPU of two cores from a run at nice 10).
  jobs_ = std::make_unique<BackgroundJobs>(this, std::vector<JobPriority>{JobPriority::normal, JobPriority::idle});
  connect(this, &LongSegmentsPanel::chainReady, this, [this] {
    if (!pendingIsland_) return;
    pendingIsland_ = false;
    zoomToIsland();
  });

  createTable();
  createInfoLabels();
  createStepControls();
  createExportButtons();
  createSpeedBox();
  QLayout* steps = layOutStepControls();
  createZoomButtons();
  layOut(steps);

  playTimer_ = new QTimer(this);
  playTimer_->setInterval(33);
  connect(playTimer_, &QTimer::timeout, this, &LongSegmentsPanel::advancePlay);
  updateStepControls();
}

void LongSegmentsPanel::createTable() {
  table_ = new QTableView(this);
  table_->setModel(model_);
  table_->setSelectionBehavior(QAbstractItemView::SelectRows);
  table_->setSelectionMode(QAbstractItemView::SingleSelection);
  table_->setAlternatingRowColors(true);
  // Tab leaves the table (one stop in the window's Tab chain): moving from cell to cell, it replayed a row every
  // 7 presses (issue 53, finding 1).  The arrows move between rows.
  table_->setTabKeyNavigation(false);
  table_->verticalHeader()->hide();
  // Compact columns that fit the dock (issue 13, finding 14): short headers and 6-decimal coordinates, every
  // column sized to its contents, so the table needs no horizontal scroll bar at the dock's default width.
  table_->horizontalHeader()->setSectionResizeMode(QHeaderView::ResizeToContents);
  table_->horizontalHeader()->setStretchLastSection(false);
  table_->horizontalHeader()->setMinimumSectionSize(24);
  table_->setToolTip(tr("Select a segment to replay it exactly from its recorded start state"));
  connect(table_->selectionModel(), &QItemSelectionModel::selectionChanged, this,
          &LongSegmentsPanel::onSelectionChanged);
}

void LongSegmentsPanel::createInfoLabels() {
  hint_ = new QLabel(tr("Run or open a run file; the longest trapped segments appear here."), this);
  hint_->setWordWrap(true);
  info_ = new QLabel(this);
  info_->setWordWrap(true);
  info_->hide();
  info_->setTextInteractionFlags(Qt::TextSelectableByMouse);
}

void LongSegmentsPanel::createStepControls() {
  playButton_ = new QToolButton(this);
  playButton_->setText(tr("Play"));
  playButton_->setCheckable(true);
  playButton_->setToolTip(tr("Play through the segment"));
  connect(playButton_, &QToolButton::clicked, this, &LongSegmentsPanel::togglePlay);
  slider_ = new QSlider(Qt::Horizontal, this);
  slider_->setToolTip(tr("Step through the segment"));
  connect(slider_, &QSlider::valueChanged, this, [this](int v) { setCurrentIndex(static_cast<std::size_t>(v)); });
  stepBox_ = new QSpinBox(this);
  stepBox_->setToolTip(tr("Step of N\u207B\u00B9 shown (snapped to the kept states)"));
  stepBox_->setKeyboardTracking(false);
  connect(stepBox_, qOverload<int>(&QSpinBox::valueChanged), this, [this](int step) {
    if (replay_) setCurrentIndex(replay_->trace.indexNear(static_cast<std::uint64_t>(std::max(step, 0))));
  });
  stepLabel_ = new QLabel(this);
}

void LongSegmentsPanel::createExportButtons() {
  csvButton_ = new QPushButton(tr("Export CSV\u2026"), this);
  npyButton_ = new QPushButton(tr("Export .npy\u2026"), this);
  connect(csvButton_, &QPushButton::clicked, this, [this] { exportDialog(false); });
  connect(npyButton_, &QPushButton::clicked, this, [this] { exportDialog(true); });
}

void LongSegmentsPanel::createSpeedBox() {
  // Replay speed: a multiple of the base pace (the whole segment in ~15 s); 64× is a glance, ¼× a close look.
  speedBox_ = new QComboBox(this);
  speedBox_->setObjectName(QStringLiteral("replaySpeed"));
  for (const auto& [label, factor] : std::initializer_list<std::pair<const char*, double>>{
           {"¼×", 0.25}, {"½×", 0.5}, {"1×", 1}, {"2×", 2}, {"4×", 4}, {"16×", 16}, {"64×", 64}})
    speedBox_->addItem(QString::fromUtf8(label), factor);
  speedBox_->setCurrentIndex(2);
  speedBox_->setToolTip(tr("Replay speed (1×: the whole segment in about 15 s)"));
}

QLayout* LongSegmentsPanel::layOutStepControls() {
  // The slider has a row of its own, so that it keeps its length whatever the other controls show (issue 25,
  // finding 3: a restored session once squeezed it to a handle); the coordinates wrap below.
  playButton_->setMinimumWidth(playButton_->fontMetrics().horizontalAdvance(tr("Pause")) + 24);
  stepLabel_->setWordWrap(true);
  slider_->setMinimumWidth(120);
  auto* steps = new QVBoxLayout;
  auto* playRow = new QHBoxLayout;
  playRow->addWidget(playButton_);
  playRow->addWidget(slider_, 1);
  auto* stepRow = new QHBoxLayout;
  stepRow->addWidget(new QLabel(tr("Step"), this));
  stepRow->addWidget(stepBox_, 1);
  stepRow->addWidget(new QLabel(tr("Speed"), this));
  stepRow->addWidget(speedBox_);
  steps->addLayout(playRow);
  steps->addLayout(stepRow);
  steps->addWidget(stepLabel_);
  return steps;
}

void LongSegmentsPanel::createZoomButtons() {
  zoomSegmentButton_ = new QPushButton(tr("Zoom to segment"), this);
  zoomSegmentButton_->setToolTip(tr("Show the region where the segment spent 90 % of its time"));
  zoomIslandButton_ = new QPushButton(tr("Zoom to island"), this);
  zoomIslandButton_->setToolTip(tr("Show one island of its chain with the satellites the segment winds around"));
  connect(zoomSegmentButton_, &QPushButton::clicked, this, &LongSegmentsPanel::zoomToSegment);
  connect(zoomIslandButton_, &QPushButton::clicked, this, &LongSegmentsPanel::zoomToIsland);
}

void LongSegmentsPanel::layOut(QLayout* steps) {
  // Two rows of two: the dock (and so the window) stays narrow enough for a 1280 × 800 screen.
  auto* exports = new QGridLayout;
  exports->addWidget(zoomSegmentButton_, 0, 0);
  exports->addWidget(zoomIslandButton_, 0, 1);
  exports->addWidget(csvButton_, 1, 0);
  exports->addWidget(npyButton_, 1, 1);
  auto* layout = new QVBoxLayout(this);
  layout->setContentsMargins(4, 4, 4, 4);
  layout->addWidget(table_, 1);
  layout->addWidget(hint_);
  layout->addWidget(info_);
  layout->addLayout(steps);
  layout->addLayout(exports);
}

QSize LongSegmentsPanel::sizeHint() const {
  QSize hint = QWidget::sizeHint();
  int columns = table_->verticalHeader()->isVisible() ? table_->verticalHeader()->width() : 0;
  for (int c = 0; c < table_->horizontalHeader()->count(); ++c)
    columns += std::max(table_->horizontalHeader()->sectionSizeHint(c), table_->horizontalHeader()->sectionSize(c));
  const QMargins m = contentsMargins();
  hint.setWidth(std::max(hint.width(), columns + 2 * table_->frameWidth() + m.left() + m.right() +
                                           table_->verticalScrollBar()->sizeHint().width() + 12));
  return hint;
}

LongSegmentsPanel::~LongSegmentsPanel() {
  // Stop the jobs and join their threads first, while everything they report to is still there.
  jobs_.reset();
}

void LongSegmentsPanel::updateSegments(const TrappingParameters& params, const LongestSegments& longest) {
  showSegments(params, longest);
  selectPending();
}

void LongSegmentsPanel::selectWhenListed(int rank, bool island) {
  pendingRow_ = rank;
  pendingIsland_ = island;
  selectPending();
}

void LongSegmentsPanel::selectPending() {
  if (pendingRow_ < 0 || pendingRow_ >= model_->rowCount()) return;
  selectRow(pendingRow_);
  pendingRow_ = -1;
}

void LongSegmentsPanel::showSegments(const TrappingParameters& params, const LongestSegments& longest) {
  const quint64 generation = model_->generation();
  const bool changed = model_->setSegments(params, longest.items());
  hint_->setVisible(model_->rowCount() == 0);
  if (!changed) return;
  if (model_->generation() != generation) jobs_->cancel(kChainChannel);  // chains of another run are useless now
  // Keep the selection on the segment, wherever it moved.
  const int row = model_->rowOf(wantedKey_);
  if (row >= 0) {
    const QSignalBlocker block(table_->selectionModel());
    table_->selectRow(row);
  }
  requestTopChains();
}

void LongSegmentsPanel::clear() {
  jobs_->cancelAll();
  replayRequest_ = 0;
  replayPending_ = false;
  model_->clear();
  wantedKey_ = {UINT64_MAX, UINT64_MAX};
  replay_.reset();
  chain_.reset();
  index_ = 0;
  playTimer_->stop();
  if (portrait_) portrait_->clearSegment();
  updateStepControls();
  updateInfo();
}

void LongSegmentsPanel::selectRow(int row) { table_->selectRow(row); }

int LongSegmentsPanel::selectedRow() const {
  const QModelIndexList rows = table_->selectionModel()->selectedRows();
  return rows.isEmpty() ? -1 : rows.front().row();
}

void LongSegmentsPanel::onSelectionChanged() {
  const SegmentRecord* record = model_->record(selectedRow());
  if (record == nullptr) return;
  if (SegmentKey::of(*record) == wantedKey_ && (replay_ || replayPending_)) return;
  requestReplay(*record);
}

void LongSegmentsPanel::requestReplay(const SegmentRecord& record) {
  wantedKey_ = SegmentKey::of(record);
  replayPending_ = true;
  chain_ = model_->chain(wantedKey_);
  const TrappingParameters params = model_->parameters();
  const std::uint64_t maxPoints = maxReplayPoints_;
  Job<SegmentReplayPtr> job;
  job.channel = kReplayChannel;  // JobOrder::latest: the replay running is stopped, its result dropped
  job.work = [params, record, maxPoints](JobContext<NoProgress>& context) -> std::optional<SegmentReplayPtr> {
    QElapsedTimer clock;
    clock.start();
    auto trace = traceSegment(params, record, maxPoints, context.stopToken());
    if (!trace) return std::nullopt;  // cancelled: a newer request is coming
    auto replay = std::make_shared<SegmentReplay>();
    replay->params = params;
    replay->region = dwellRegion(trace->points, 0.9);
    replay->trace = std::move(*trace);
    replay->seconds = static_cast<double>(clock.nsecsElapsed()) * 1e-9;
    return replay;
  };
  job.done = [this](const JobResult<SegmentReplayPtr>& r) { onReplay(r.id, r.value.value_or(nullptr), r.error); };
  replayRequest_ = jobs_->submit(std::move(job));
  requestChain(record, true);
  updateInfo();
}

void LongSegmentsPanel::requestChain(const SegmentRecord& record, bool urgent) {
  const SegmentKey key = SegmentKey::of(record);
  if (model_->chainStatus(key) != LongestSegmentsModel::ChainStatus::unknown) {
    if (!urgent || model_->chainStatus(key) == LongestSegmentsModel::ChainStatus::done) return;
  }
  model_->setChainPending(key);
  const quint64 generation = model_->generation();
  const TrappingParameters params = model_->parameters();
  const std::uint64_t points = chainPoints_;
  Job<ChainResultPtr> job;
  job.channel = kChainChannel;
  job.order = urgent ? JobOrder::urgent : JobOrder::queued;
  job.work = [params, record, points](JobContext<NoProgress>& context) -> std::optional<ChainResultPtr> {
    QElapsedTimer clock;
    clock.start();
    auto found = identifySegmentChain(params, record, points, {}, context.stopToken());
    if (!found) return std::nullopt;  // cancelled with its run
    auto result = std::make_shared<ChainResult>();
    result->chain = std::move(found->chain);
    result->island = found->island;
    result->seconds = static_cast<double>(clock.nsecsElapsed()) * 1e-9;
    return result;
  };
  job.done = [this, generation, key](const JobResult<ChainResultPtr>& r) {
    ChainResultPtr done = r.value.value_or(nullptr);
    if (!done) {  // it failed: the chain stays unknown, with the reason
      auto failed = std::make_shared<ChainResult>();
      failed->error = r.error;
      done = std::move(failed);
    }
    onChain(generation, key, done);
  };
  jobs_->submit(std::move(job));
}

void LongSegmentsPanel::requestTopChains() {
  const auto& items = model_->segments();
  const std::size_t n = std::min(items.size(), static_cast<std::size_t>(std::max(autoRows_, 0)));
  for (std::size_t i = 0; i < n; ++i) requestChain(items[i], false);
}

void LongSegmentsPanel::onReplay(quint64 requestId, const SegmentReplayPtr& replay, const QString& error) {
  if (requestId != replayRequest_) return;  // stale: the user selected another segment since
  replayPending_ = false;
  if (!replay) {
    Q_EMIT statusMessage(tr("Replay failed: %1").arg(error));
    updateInfo();
    return;
  }
  replay_ = replay;
  index_ = 0;
  updateStepControls();
  updateInfo();
  showOnPortrait();
  Q_EMIT replayReady(replay_);
  if (chain_) Q_EMIT chainReady(chain_);
  Q_EMIT currentIndexChanged(index_);
  Q_EMIT statusMessage(tr("Replayed %1 steps bit for bit in %2 s")
                           .arg(QLocale().toString(static_cast<qulonglong>(replay_->trace.steps)))
                           .arg(replay_->seconds, 0, 'f', 2));
}

void LongSegmentsPanel::onChain(quint64 generation, SegmentKey key, const ChainResultPtr& chain) {
  if (generation != model_->generation()) return;  // a chain of a previous run
  model_->setChain(key, chain);
  if (key == wantedKey_) {
    chain_ = chain;
    updateInfo();
    if (replay_ && SegmentKey::of(replay_->trace.record) == key) {
      if (portrait_) portrait_->showSegmentChain(chain_);
      updateStepControls();
      Q_EMIT chainReady(chain_);
    }
  }
}

void LongSegmentsPanel::setCurrentIndex(std::size_t index) {
  if (!replay_) return;
  index = std::min(index, replay_->trace.states.size() - 1);
  if (index == index_ && slider_->value() == static_cast<int>(index)) return;
  index_ = index;
  {
    const QSignalBlocker b1(slider_);
    const QSignalBlocker b2(stepBox_);
    slider_->setValue(static_cast<int>(index_));
    stepBox_->setValue(static_cast<int>(std::min<std::uint64_t>(replay_->trace.stepAt(index_), INT32_MAX)));
  }
  const PhysicalPoint& p = replay_->trace.points[index_];
  stepLabel_->setText(tr("(%1, %2)").arg(static_cast<double>(p.x), 0, 'f', 9).arg(static_cast<double>(p.y), 0, 'f', 9));
  if (portrait_) {
    portrait_->showSegmentStep(index_);
    // During Play the step shown leaves a zoomed island at once (the segment hops around its chain): the
    // view widens to where the segment spent its time, or follows the point when it is outside that too.
    if (playTimer_->isActive() && !portrait_->shows(p.x, p.y)) {
      const SegmentRegion& region = replay_->region;
      if (p.x >= region.x0 && p.x <= region.x1 && p.y >= region.y0 && p.y <= region.y1)
        portrait_->zoomToRegion(region);
      if (!portrait_->shows(p.x, p.y)) portrait_->viewLayer().ensureVisible(p.x, p.y);
    }
  }
  Q_EMIT currentIndexChanged(index_);
}

void LongSegmentsPanel::updateStepControls() {
  const bool have = replay_ != nullptr;
  for (QWidget* w : std::initializer_list<QWidget*>{slider_, stepBox_, playButton_, csvButton_, npyButton_})
    w->setEnabled(have);
  zoomSegmentButton_->setEnabled(have && portrait_);
  zoomIslandButton_->setEnabled(have && portrait_ && chain_ && chain_->chain);
  const QSignalBlocker b1(slider_);
  const QSignalBlocker b2(stepBox_);
  if (!have) {
    slider_->setRange(0, 0);
    stepBox_->setRange(0, 0);
    stepLabel_->clear();
    return;
  }
  const SegmentTrace& t = replay_->trace;
  slider_->setRange(0, static_cast<int>(t.states.size() - 1));
  slider_->setValue(static_cast<int>(index_));
  stepBox_->setRange(0, static_cast<int>(std::min<std::uint64_t>(t.steps, INT32_MAX)));
  stepBox_->setSingleStep(static_cast<int>(std::min<std::uint64_t>(t.stride, INT32_MAX)));
  stepBox_->setValue(static_cast<int>(std::min<std::uint64_t>(t.stepAt(index_), INT32_MAX)));
  const PhysicalPoint& p = t.points[index_];
  stepLabel_->setText(tr("(%1, %2)").arg(static_cast<double>(p.x), 0, 'f', 9).arg(static_cast<double>(p.y), 0, 'f', 9));
}

void LongSegmentsPanel::updateInfo() {
  const SegmentRecord* shown = replay_ ? &replay_->trace.record : nullptr;
  hint_->setVisible(model_->rowCount() == 0);
  if (replayPending_) {
    info_->setText(tr("Replaying\u2026"));
    info_->show();
    return;
  }
  if (shown == nullptr) {
    info_->hide();
    return;
  }
  info_->show();
  const QLocale locale;
  const SegmentTrace& t = replay_->trace;
  QString text = tr("Orbit %1, block %2: %3 steps replayed exactly")
                     .arg(t.record.orbit)
                     .arg(locale.toString(static_cast<qulonglong>(t.record.start.block)))
                     .arg(locale.toString(static_cast<qulonglong>(t.steps)));
  if (t.stride > 1) text += tr(" (one in %1 kept)").arg(locale.toString(static_cast<qulonglong>(t.stride)));
  text += tr("; %1 % of its time in x \u2208 [%2, %3], y \u2208 [%4, %5].")
              .arg(100 * replay_->region.fraction, 0, 'f', 0)
              .arg(static_cast<double>(replay_->region.x0), 0, 'f', 5)
              .arg(static_cast<double>(replay_->region.x1), 0, 'f', 5)
              .arg(static_cast<double>(replay_->region.y0), 0, 'f', 5)
              .arg(static_cast<double>(replay_->region.y1), 0, 'f', 5);
  if (!chain_) {
    text += tr("<br>Identifying its island chain\u2026");
  } else if (!chain_->chain) {
    text += tr("<br>Island chain: %1").arg(chain_->error.toHtmlEscaped());
  } else {
    const IslandChain& c = *chain_->chain;
    QStringList levels;
    for (int level : c.hierarchy) levels << QString::number(level);
    text += tr("<br>Sticks to a chain of period <b>%1</b> (%2)").arg(c.period).arg(levels.join(QStringLiteral(" \u2192 ")));
    if (c.centre)
      text += tr("; centre orbit: residue %1, %2, rotation number %3")
                  .arg(static_cast<double>(c.centre->residue), 0, 'g', 6)
                  .arg(QString::fromLatin1(toString(c.centre->classification().stability)))
                  .arg(QString::fromStdString(rotationNumberText(*c.centre, 6)).toHtmlEscaped());
  }
  info_->setText(text);
}

void LongSegmentsPanel::togglePlay() {
  if (!replay_ || playTimer_->isActive()) {
    playTimer_->stop();
    playButton_->setChecked(false);
    playButton_->setText(tr("Play"));
    return;
  }
  if (index_ + 1 >= replay_->trace.states.size()) setCurrentIndex(0);
  playTimer_->start();
  playButton_->setChecked(true);
  playButton_->setText(tr("Pause"));
}

void LongSegmentsPanel::advancePlay() {
  if (!replay_) return;
  const std::size_t n = replay_->trace.states.size();
  const double speed = speedBox_->currentData().toDouble();
  const auto advance = static_cast<std::size_t>(std::max(1.0, speed * static_cast<double>(n) / kPlayTicks));
  std::size_t next = std::min(index_ + advance, n - 1);
  if (portrait_ && islandView_ && portrait_->viewport() == *islandView_) {
    // The next step shown on the island in view, if the segment comes back to it; else the view widens
    // (setCurrentIndex) as before.
    const auto& points = replay_->trace.points;
    std::size_t i = next;
    while (i < n && !portrait_->shows(points[i].x, points[i].y)) ++i;
    if (i < n) next = i;
  }
  setCurrentIndex(next);
  if (index_ + 1 >= n) togglePlay();
}

bool LongSegmentsPanel::exportCsv(const QString& path, QString* error) {
  if (!replay_) {
    if (error != nullptr) *error = tr("no segment replayed");
    return false;
  }
  try {
    writeSegmentCsv(path.toStdString(), replay_->trace);
  } catch (const std::exception& e) {
    if (error != nullptr) *error = QString::fromStdString(e.what());
    return false;
  }
  return true;
}

bool LongSegmentsPanel::exportNpy(const QString& path, QString* error) {
  if (!replay_) {
    if (error != nullptr) *error = tr("no segment replayed");
    return false;
  }
  try {
    writeSegmentNpy(path.toStdString(), replay_->trace);
  } catch (const std::exception& e) {
    if (error != nullptr) *error = QString::fromStdString(e.what());
    return false;
  }
  return true;
}

void LongSegmentsPanel::exportDialog(bool npy) {
  if (!replay_) return;
  const SegmentRecord& r = replay_->trace.record;
  const QString suggested =
      QStringLiteral("segment-orbit%1-block%2.%3").arg(r.orbit).arg(r.start.block).arg(npy ? "npy" : "csv");
  const QString path = QFileDialog::getSaveFileName(this, npy ? tr("Export segment as .npy") : tr("Export segment as CSV"),
                                                    QDir(SettingsController::lastFolder()).filePath(suggested),
                                                    npy ? tr("NumPy arrays (*.npy)") : tr("CSV files (*.csv)"));
  if (path.isEmpty()) return;
  SettingsController::rememberFolder(path);
  QString error;
  const bool ok = npy ? exportNpy(path, &error) : exportCsv(path, &error);
  Q_EMIT statusMessage(ok ? tr("Wrote %1").arg(path) : tr("Export failed: %1").arg(error));
}

void LongSegmentsPanel::setPortraitController(PortraitController* portrait) {
  portrait_ = portrait;
  if (portrait_ && replay_) showOnPortrait();
  updateStepControls();
}

void LongSegmentsPanel::showOnPortrait() {
  if (!portrait_ || !replay_) return;
  Q_EMIT aboutToDraw(replay_->params);
  // Draw over a portrait of the run's own map (the controller keeps the zoom when it is already shown).
  portrait_->setMap(replay_->params.map, replay_->params.Xr);
  portrait_->showSegment(replay_);
  portrait_->zoomToRegion(replay_->region);
  portrait_->showSegmentChain(chain_);
  portrait_->showSegmentStep(index_);
}

void LongSegmentsPanel::zoomToSegment() {
  if (portrait_ && replay_) portrait_->zoomToRegion(replay_->region);
}

void LongSegmentsPanel::zoomToIsland() {
  if (!portrait_ || !replay_) return;
  if (chain_ && chain_->chain)
    portrait_->zoomToRegion(chain_->island);
  else
    portrait_->zoomToRegion(replay_->region);
  islandView_ = portrait_->viewport();
}

}  // namespace archipelago::ui
