#include "ui/portrait/AtlasPanel.hpp"

#include <QCheckBox>
#include <QDir>
#include <QElapsedTimer>
#include <QFileDialog>
#include <QFileInfo>
#include <QFont>
#include <QFormLayout>
#include <QHBoxLayout>
#include <QHeaderView>
#include <QLabel>
#include <QPushButton>
#include <QRegularExpression>
#include <QScrollArea>
#include <QSpinBox>
#include <QStringList>
#include <QTimer>
#include <QTreeWidget>
#include <QVBoxLayout>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "core/io/NumberText.hpp"
#include "core/atlas/AtlasExport.hpp"
#include "core/io/AtomicFile.hpp"
#include "core/manifolds/ManifoldExport.hpp"
#include "core/periodic/PeriodicOrbitFinder.hpp"
#include "core/periodic/SegmentAnalysis.hpp"
#include "ui/jobs/BackgroundJobs.hpp"
#include "ui/jobs/DurationText.hpp"
#include "ui/portrait/MarkovTreePanel.hpp"
#include "ui/portrait/PortraitController.hpp"
#include "ui/settings/SettingsController.hpp"

namespace archipelago::ui {

/// One step of the computation: the atlas so far, how many islands are finished, what core does next.
struct AtlasPanel::Snapshot {
  std::shared_ptr<const Atlas> atlas;
  int done = 0;
  std::string stage;
};

namespace {

/// The deepest level the page offers: each level multiplies the islands and the time (depth 2 at K = 0.1 takes
/// minutes on two cores, docs/atlas.md); deeper trees are `archipelago-cli atlas`'s.
constexpr int kPageMaxDepth = std::min(3, kMaxAtlasDepth);
/// The width the page asks of the side column: what the Orbits page asks (its hint is 300 px).
constexpr int kSideHintWidth = 300;

QString number(long double v, int digits = 4) {
  return std::isfinite(v) ? QString::number(static_cast<double>(v), 'g', digits) : QStringLiteral("–");
}

/// A number of steps: whole from 100 on ("15200", not "1.52e+04"), one decimal below.
QString steps(double v) {
  return std::isfinite(v) ? QString::number(v, 'f', std::fabs(v) < 100 ? 1 : 0) : QStringLiteral("–");
}

/// A point, a coordinate that is round-off beside the other shown as 0 (core's quadCoordinateText, as the Manifolds
/// page shows them).
QString point(PhysicalPoint p) {
  return QStringLiteral("(%1, %2)").arg(QString::fromStdString(quadCoordinateText(p.x, p.y, 12)),
                                        QString::fromStdString(quadCoordinateText(p.y, p.x, 12)));
}

/// Measured: its boundary circle found or refused (an island known but not reached yet has neither).
bool measured(const AtlasNode& n) { return n.boundaryFound || !n.boundaryFailure.empty(); }

QString path(const Atlas& a, int i) { return QString::fromStdString(atlasPath(a, i)); }

/// A note with its long numbers (core writes up to 20 digits) cut to 4 significant ones, for the table's cell (issue
/// 53, finding 19: notes of ~150 characters); the cell's tooltip keeps the whole.
QString shortNumbers(const QString& text) {
  static const QRegularExpression longNumber(QStringLiteral("-?\\d+\\.\\d{5,}(?:[eE][-+]?\\d+)?"));
  QString out;
  qsizetype from = 0;
  for (auto it = longNumber.globalMatch(text); it.hasNext();) {
    const QRegularExpressionMatch m = it.next();
    out += text.mid(from, m.capturedStart() - from) + QString::number(m.captured().toDouble(), 'g', 4);
    from = m.capturedEnd();
  }
  return out + text.mid(from);
}

/// What an island's "area ± error" covers (issue 53, finding 8: the ± was read as the scan's resolution).
QString areaTip(const AtlasNode& n) {
  return QObject::tr("The true area lies in [%1, %2]: from the proven circle's polygon less its convergence (%3) to "
                     "the circle scaled to the nearest orbits that leave the island; ± %4 covers both ends. A deeper "
                     "atlas may find a larger circle, inside [%1, %2].")
      .arg(QString::number(static_cast<double>(n.areaLower), 'g', 10),
           QString::number(static_cast<double>(n.areaUpper), 'g', 10),
           QString::number(static_cast<double>(n.polygonError), 'g', 2),
           QString::number(static_cast<double>(n.areaError), 'g', 2));
}

QString rotationText(const AtlasNode& n) {
  return n.aboutParent ? QString::fromStdString(toString(*n.aboutParent)) : QStringLiteral("–");
}

/// Why the recursion stopped there, and what failed (the boundary, the flux).
QString noteText(const AtlasNode& n) {
  QStringList parts;
  if (!n.note.empty()) parts << QString::fromStdString(n.note);
  if (!n.boundaryFound && !n.boundaryFailure.empty()) parts << QString::fromStdString(n.boundaryFailure);
  if (measured(n) && !n.flux.found && !n.flux.failure.empty())
    parts << QObject::tr("flux: %1").arg(QString::fromStdString(n.flux.failure));
  return parts.join(QStringLiteral("; "));
}
}  // namespace

AtlasPanel::AtlasPanel(PortraitController* controller, QWidget* parent)
    : QWidget(parent),
      controller_(controller),
      elapsed_(std::make_unique<QElapsedTimer>()),
      jobs_(std::make_unique<BackgroundJobs>(this, 1, JobPriority::background)) {
  createRequestControls();
  createIslandTree();
  createFileButtons();
  markovTree_ = new MarkovTreePanel([this] { return atlas_; }, [this] { return busy(); }, this);
  connect(this, &AtlasPanel::atlasChanged, markovTree_, &MarkovTreePanel::atlasChanged);
  connect(markovTree_, &MarkovTreePanel::pageMessage, this, &AtlasPanel::statusMessage);

  clock_ = new QTimer(this);
  clock_->setInterval(1000);
  connect(clock_, &QTimer::timeout, this, &AtlasPanel::updateProgress);
  // A new map keeps the atlas (a change of K loses no work); it says whose it is, and draws nothing of another map.
  connect(controller_, &PortraitController::mapChanged, this, [this] {
    refusal_.clear();
    updateProgress();
    updateButtons();
  });

  layOut();
  updateProgress();
  updateDetails();
  updateButtons();
}

void AtlasPanel::createRequestControls() {
  const AtlasRequest defaults;  // core's
  depth_ = new QSpinBox(this);
  depth_->setObjectName(QStringLiteral("atlasDepth"));
  depth_->setRange(0, kPageMaxDepth);
  depth_->setValue(std::min(defaults.depth, kPageMaxDepth));
  depth_->setToolTip(tr("Levels of chains below the centre (1: the chains about the central island, seconds; 2: the "
                        "chains about those, minutes); deeper trees: archipelago-cli atlas"));
  maxPeriod_ = new QSpinBox(this);
  maxPeriod_->setObjectName(QStringLiteral("atlasMaxPeriod"));
  maxPeriod_->setRange(1, PeriodicOrbitSearch::kMaxPeriod);
  maxPeriod_->setValue(static_cast<int>(defaults.maxPeriod));
  maxPeriod_->setGroupSeparatorShown(true);
  maxPeriod_->setToolTip(tr("The largest period of a chain (the product of the q's from the centre)"));
  cantori_ = new QCheckBox(tr("cantori"), this);
  cantori_->setObjectName(QStringLiteral("atlasCantori"));
  cantori_->setChecked(defaults.cantori);
  cantori_->setToolTip(tr("Once the islands are measured, the cantori about each island (between its chains, and "
                          "its boundary cantorus inside the innermost one): their MacKay–Meiss–Percival flux and "
                          "layer, barriers of the Markov tree (seconds each; docs/atlas.md)"));
  compute_ = new QPushButton(tr("Compute"), this);
  compute_->setToolTip(tr("The atlas of the portrait's K, the first levels first (the tree fills as each island is "
                          "measured)"));
  stop_ = new QPushButton(tr("Stop"), this);
  stop_->setToolTip(tr("Stop: the islands measured so far stay"));
  // An atlas computed here and in no file is asked for first, as Open… asks (issue 53: Compute replaced it silently).
  connect(compute_, &QPushButton::clicked, this, [this] {
    if (confirmDiscard(tr("computing another atlas"))) compute(request());
  });
  connect(stop_, &QPushButton::clicked, this, &AtlasPanel::stop);

  progress_ = new QLabel(this);
  progress_->setObjectName(QStringLiteral("atlasProgress"));
  progress_->setWordWrap(true);
}

void AtlasPanel::createIslandTree() {
  tree_ = new QTreeWidget(this);
  tree_->setObjectName(QStringLiteral("atlasTree"));
  tree_->setColumnCount(columns);
  tree_->setHeaderLabels({tr("island"), tr("period"), tr("p/q"), tr("area ± error"), tr("flux/step"), tr("layer"),
                          tr("residence"), tr("note")});
  tree_->headerItem()->setToolTip(island, tr("The periods from the centre down (core's atlasPath)"));
  tree_->headerItem()->setToolTip(rotation, tr("The chain's rotation about its parent island"));
  tree_->headerItem()->setToolTip(area, tr("One island's area (Green's theorem on its proven boundary circle) ± an "
                                           "error that covers its true area: the interval from the circle's polygon "
                                           "less its convergence to the circle scaled to the nearest orbits that "
                                           "leave the island (each cell's tooltip gives it)"));
  tree_->headerItem()->setToolTip(flux, tr("The turnstile's lobe area: the area crossing the chain's barrier per step"));
  tree_->headerItem()->setToolTip(layer, tr("The area inside the barrier less the islands in it"));
  tree_->headerItem()->setToolTip(residence, tr("Mean residence time inside the barrier: layer / flux, in steps (Kac)"));
  tree_->header()->setSectionResizeMode(QHeaderView::ResizeToContents);
  tree_->header()->setStretchLastSection(false);
  tree_->setUniformRowHeights(true);
  tree_->setAlternatingRowColors(true);
  tree_->setSelectionMode(QAbstractItemView::SingleSelection);
  tree_->setToolTip(tr("Click an island: the portrait zooms to it and draws its boundary circle, its chain and its "
                       "partner's manifolds"));
  const auto clicked = [this](QTreeWidgetItem* item) {
    if (item) showIsland(item->data(island, Qt::UserRole).toInt());
  };
  connect(tree_, &QTreeWidget::itemClicked, this, clicked);
  connect(tree_, &QTreeWidget::itemActivated, this, clicked);
  connect(tree_, &QTreeWidget::currentItemChanged, this, &AtlasPanel::updateDetails);

  details_ = new QLabel(this);
  details_->setObjectName(QStringLiteral("atlasDetails"));
  details_->setWordWrap(true);
  details_->setTextInteractionFlags(Qt::TextSelectableByMouse);
  details_->setAlignment(Qt::AlignTop | Qt::AlignLeft);
}

void AtlasPanel::createFileButtons() {
  json_ = new QPushButton(tr("Export JSON…"), this);
  json_->setToolTip(tr("The atlas as `archipelago-cli atlas --json` writes it"));
  csv_ = new QPushButton(tr("Export CSV…"), this);
  csv_->setToolTip(tr("One row per island, as `archipelago-cli atlas --csv` writes it"));
  connect(json_, &QPushButton::clicked, this, [this] { exportWithDialog(true); });
  connect(csv_, &QPushButton::clicked, this, [this] { exportWithDialog(false); });

  open_ = new QPushButton(tr("Open…"), this);
  open_->setToolTip(tr("Show an atlas file (archipelago-cli atlas --json, Export JSON) instead of computing one"));
  connect(open_, &QPushButton::clicked, this, [this] {
    if (!confirmDiscard(tr("opening another atlas"))) return;
    const QString path = QFileDialog::getOpenFileName(this, tr("Open an atlas"), SettingsController::lastFolder(),
                                                      tr("Atlas files (*.json);;All files (*)"));
    if (path.isEmpty()) return;
    SettingsController::rememberFolder(path);
    openAtlasFile(path);
  });
}

bool AtlasPanel::exportWithDialog(bool json) {
  const QString name = json ? QStringLiteral("atlas.json") : QStringLiteral("atlas.csv");
  const QString path = QFileDialog::getSaveFileName(
      this, json ? tr("Export the atlas as JSON") : tr("Export the atlas as CSV"),
      QDir(SettingsController::lastFolder()).filePath(name), json ? tr("JSON files (*.json)") : tr("CSV files (*.csv)"));
  if (path.isEmpty()) return false;
  SettingsController::rememberFolder(path);
  QString error;
  const bool ok = json ? exportJson(path, &error) : exportCsv(path, &error);
  Q_EMIT statusMessage(ok ? tr("Wrote %1").arg(path) : tr("Export failed: %1").arg(error));
  return ok;
}

void AtlasPanel::markSaved() {
  if (!busy()) saved_ = true;  // an atlas under way has more to come than the file holds
}

bool AtlasPanel::unsavedWork() const { return (busy() || atlas_) && !restored_ && !saved_; }

bool AtlasPanel::confirmDiscard(const QString& action) { return !unsavedWork() || !confirm_ || confirm_(action); }

void AtlasPanel::layOut() {
  auto* form = new QFormLayout;
  form->setContentsMargins(0, 0, 0, 0);
  auto* numbers = new QHBoxLayout;
  numbers->addWidget(depth_);
  numbers->addWidget(new QLabel(tr("max period"), this));
  numbers->addWidget(maxPeriod_, 1);
  numbers->addWidget(cantori_);
  form->addRow(tr("Depth"), numbers);
  auto* buttons = new QHBoxLayout;
  buttons->addWidget(compute_);
  buttons->addWidget(stop_);
  buttons->addWidget(open_);
  auto* exports = new QHBoxLayout;
  exports->addWidget(json_);
  exports->addWidget(csv_);
  // The tree above the selected island's numbers, which scroll (a long note never sets the page's, hence the
  // window's, minimum height).
  auto* detailsArea = new QScrollArea(this);
  detailsArea->setWidget(details_);
  detailsArea->setWidgetResizable(true);
  detailsArea->setFrameShape(QFrame::NoFrame);
  detailsArea->setHorizontalScrollBarPolicy(Qt::ScrollBarAlwaysOff);
  detailsArea->setMinimumHeight(40);
  tree_->setMinimumHeight(80);
  auto* layout = new QVBoxLayout(this);
  layout->setContentsMargins(2, 4, 2, 2);
  layout->addLayout(form);
  layout->addLayout(buttons);
  layout->addWidget(progress_);
  layout->addWidget(tree_, 3);
  layout->addWidget(detailsArea, 2);
  layout->addWidget(markovTree_, 1);
  layout->addLayout(exports);
}

QSize AtlasPanel::sizeHint() const {
  const QSize hint = QWidget::sizeHint();
  return {std::min(hint.width(), kSideHintWidth), hint.height()};
}

AtlasPanel::~AtlasPanel() { jobs_.reset(); }

QTreeWidgetItem* AtlasPanel::item(int index) const {
  return index >= 0 && index < static_cast<int>(items_.size()) ? items_[static_cast<std::size_t>(index)] : nullptr;
}

QString AtlasPanel::progressText() const { return progress_->text(); }
QString AtlasPanel::detailsText() const { return details_->text(); }

AtlasRequest AtlasPanel::request() const {
  AtlasRequest r;
  r.map = controller_->map();
  r.depth = depth_->value();
  r.maxPeriod = static_cast<std::uint64_t>(maxPeriod_->value());
  r.cantori = cantori_->isChecked();
  return r;
}

bool AtlasPanel::compute(const AtlasRequest& r) {
  if (const auto e = atlasRequestError(r)) {  // before the atlas shown is cleared
    refusal_ = QString::fromStdString(*e);     // on the page too: the status line cuts a long reason short
    updateProgress();
    Q_EMIT statusMessage(tr("Atlas: %1").arg(refusal_));
    return false;
  }
  refusal_.clear();
  jobs_->cancel();
  controller_->clearAtlasIsland();  // the replaced atlas's island
  tree_->clear();
  items_.clear();
  atlas_.reset();
  restored_ = false;
  saved_ = false;
  stopping_ = false;
  done_ = 0;
  stage_.clear();
  elapsed_->start();
  clock_->start();
  Job<std::shared_ptr<const Atlas>, Snapshot> job;  // latest wins: Compute again replaces this one
  job.work = [r](JobContext<Snapshot>& context) -> std::optional<std::shared_ptr<const Atlas>> {
    // Before each island core hands the atlas so far: a copy goes to the page, which shows the tree as it grows.
    Atlas atlas = computeAtlas(
        r,
        [&context](const Atlas& sofar, int done, const std::string& stage) {
          context.post(Snapshot{std::make_shared<const Atlas>(sofar), done, stage});
        },
        context.stopToken());
    return std::make_shared<const Atlas>(std::move(atlas));
  };
  job.progress = [this](quint64 id, Snapshot s) {
    if (id != request_) return;
    show(std::move(s.atlas), s.done, QString::fromStdString(s.stage));
  };
  job.done = [this](JobResult<std::shared_ptr<const Atlas>> result) {
    if (result.id != request_) return;
    request_ = 0;
    stopping_ = false;
    clock_->stop();
    if (!result.ok()) {
      Q_EMIT statusMessage(tr("Atlas failed: %1").arg(result.error));
      std::shared_ptr<Atlas> sofar;  // what was finished stays, marked incomplete
      if (atlas_) {
        sofar = std::make_shared<Atlas>(*atlas_);
        sofar->cancelled = true;
        sofar->seconds = static_cast<double>(elapsed_->elapsed()) / 1000;
      }
      show(sofar, -1, QString());
    } else {
      const std::shared_ptr<const Atlas> atlas = *result.value;
      show(atlas, -1, QString());
      Q_EMIT statusMessage(atlas->cancelled ? tr("Atlas stopped: the islands measured so far are kept")
                                            : tr("Atlas of %1 islands in %2")
                                                  .arg(atlas->nodes.size())
                                                  .arg(formatDuration(atlas->seconds)));
    }
    Q_EMIT computationEnded();
  };
  request_ = jobs_->submit(std::move(job));
  updateProgress();
  updateButtons();
  updateDetails();
  Q_EMIT atlasChanged();  // none yet (the Markov tree's button waits for it)
  Q_EMIT statusMessage(tr("Computing the atlas of K = %1 to depth %2…").arg(QString::fromStdString(io::shortestText(r.map.K))).arg(r.depth));
  return true;
}

void AtlasPanel::stop() {
  if (!request_) return;
  jobs_->requestStop(request_);
  stopping_ = true;
  updateProgress();
}

std::optional<Atlas> AtlasPanel::sessionAtlas() const {
  if (!atlas_) return std::nullopt;
  Atlas a = *atlas_;
  if (busy()) {  // the atlas so far: incomplete, as a stopped one
    a.cancelled = true;
    a.seconds = static_cast<double>(elapsed_->elapsed()) / 1000;
  }
  return a;
}

void AtlasPanel::restoreAtlas(const std::optional<Atlas>& atlas) {
  jobs_->cancel();
  controller_->clearAtlasIsland();  // the replaced atlas's island
  request_ = 0;
  stopping_ = false;
  clock_->stop();
  tree_->clear();
  items_.clear();
  restored_ = atlas.has_value();
  source_.clear();
  if (atlas) {  // the controls say what it was computed with (Compute again gives the same atlas)
    depth_->setValue(std::min(atlas->request.depth, depth_->maximum()));
    maxPeriod_->setValue(static_cast<int>(std::min<std::uint64_t>(atlas->request.maxPeriod, maxPeriod_->maximum())));
    cantori_->setChecked(atlas->request.cantori);
  }
  show(atlas ? std::make_shared<const Atlas>(*atlas) : nullptr, -1, QString());
}

void AtlasPanel::show(std::shared_ptr<const Atlas> atlas, int done, const QString& stage) {
  atlas_ = std::move(atlas);
  done_ = done;
  stage_ = stage;
  fillTree();
  updateProgress();
  updateDetails();
  updateButtons();
  Q_EMIT atlasChanged();
}

void AtlasPanel::fillTree() {
  if (!atlas_) {
    tree_->clear();
    items_.clear();
    return;
  }
  const std::vector<AtlasNode>& nodes = atlas_->nodes;
  if (nodes.size() < items_.size()) {  // another atlas
    tree_->clear();
    items_.clear();
  }
  const QFont plain = tree_->font();
  QFont italic = plain;
  italic.setItalic(true);
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    const AtlasNode& n = nodes[i];
    const int index = static_cast<int>(i);
    if (i >= items_.size()) {
      QTreeWidgetItem* parent = item(n.parent);
      auto* row = parent ? new QTreeWidgetItem(parent) : new QTreeWidgetItem(tree_);
      row->setData(island, Qt::UserRole, index);
      for (int c = period; c < note; ++c) row->setTextAlignment(c, Qt::AlignRight | Qt::AlignVCenter);
      items_.push_back(row);
      if (parent && n.level == 1) parent->setExpanded(true);  // the first level shows; deeper ones on demand
    }
    QTreeWidgetItem* row = items_[i];
    row->setText(island, path(*atlas_, index));
    row->setText(period, QString::number(n.period));
    row->setText(rotation, rotationText(n));
    const bool done = measured(n);
    // An island not measured says so where its area would be (the first columns are the ones in sight).
    const QString state = busy() && index == done_ ? tr("measuring…") : busy() ? tr("waiting") : tr("not measured");
    row->setText(area, n.boundaryFound ? tr("%1 ± %2").arg(number(n.area), number(n.areaError, 1))
                                       : done ? QStringLiteral("–") : state);
    row->setToolTip(area, n.boundaryFound ? areaTip(n) : QString());
    row->setText(flux, n.flux.found ? number(n.flux.flux) : QStringLiteral("–"));
    row->setText(layer, n.flux.found ? number(n.flux.layerArea) : QStringLiteral("–"));
    row->setText(residence, n.flux.found ? steps(n.flux.residence) : QStringLiteral("–"));
    const QString noteShown = done ? noteText(n) : busy() ? state : tr("not measured (stopped)");
    row->setText(note, shortNumbers(noteShown));
    row->setToolTip(note, noteShown);
    for (int c = 0; c < columns; ++c) row->setFont(c, done ? plain : italic);
  }
}

bool AtlasPanel::ofPortraitMap() const { return atlas_ && atlas_->request.map == controller_->map(); }

void AtlasPanel::updateProgress() {
  QString text;
  if (!atlas_ && !busy()) {
    text = tr("The islands around islands of the portrait's K, from the central island down (docs/atlas.md): each "
              "island's area, the flux through its chain's barrier and the mean residence time inside. Compute fills "
              "the tree level by level; click an island to see it.");
  } else if (busy()) {
    const int known = atlas_ ? static_cast<int>(atlas_->nodes.size()) : 0;
    const QString doing = stopping_ ? tr("Stopping (the island under way ends first)")
                                    : tr("Measuring %1").arg(stage_.isEmpty() ? tr("the centre") : stage_);
    text = tr("%1 · %2 of %3 known islands done · %4")
               .arg(doing)
               .arg(std::max(done_, 0))
               .arg(known)
               .arg(formatDuration(static_cast<double>(elapsed_->elapsed()) / 1000));
  } else {
    const Atlas& a = *atlas_;
    const auto finished = std::count_if(a.nodes.begin(), a.nodes.end(), measured);
    text = a.cancelled ? tr("Stopped: %1 of %2 known islands measured in %3").arg(finished).arg(a.nodes.size())
                             .arg(formatDuration(a.seconds))
                       : tr("%1 islands in %2").arg(a.nodes.size()).arg(formatDuration(a.seconds));
    text += tr(" (depth %1, periods ≤ %2)").arg(a.request.depth).arg(a.request.maxPeriod);
    if (restored_) text = source_.isEmpty() ? tr("From the session: %1").arg(text) : tr("From %1: %2").arg(source_, text);
    if (const QString why = MarkovTreePanel::missing(&a, false); !why.isEmpty()) text += tr(". Model P_t: %1").arg(why);
  }
  if (!refusal_.isEmpty() && !busy()) text = tr("Not computed: %1\n\n%2").arg(refusal_, text);
  if (atlas_ && !ofPortraitMap())
    text += tr(". This atlas is of K = %1; the portrait shows K = %2: set K = %1 again to draw its islands")
                .arg(QString::fromStdString(io::shortestText(atlas_->request.map.K)))
                .arg(QString::fromStdString(io::shortestText(controller_->map().K)));
  progress_->setText(text);
}

void AtlasPanel::updateDetails() {
  QTreeWidgetItem* current = tree_->currentItem();
  const int index = current ? current->data(island, Qt::UserRole).toInt() : -1;
  if (!atlas_ || index < 0 || index >= static_cast<int>(atlas_->nodes.size())) {
    details_->setText(atlas_ ? tr("Click an island for its numbers.") : QString());
    return;
  }
  const Atlas& a = *atlas_;
  const AtlasNode& n = a.nodes[static_cast<std::size_t>(index)];
  QStringList lines;
  const QString about = n.aboutParent ? tr(", %1 about %2").arg(rotationText(n), n.parent == 0 ? tr("the centre")
                                                                                                  : path(a, n.parent))
                                      : QString();
  lines << tr("<b>%1</b>: period %2%3, centre %4 on %5, residue %6")
               .arg(index == 0 ? tr("The central island") : tr("Island %1").arg(path(a, index)))
               .arg(n.period)
               .arg(about)
               .arg(point(n.centre))
               .arg(n.onS1 ? tr("S₁") : tr("S₂"))
               .arg(number(n.orbit.residue, 6));
  if (!measured(n)) {
    lines << (busy() ? tr("Not measured yet.") : tr("Not measured (the computation was stopped)."));
  } else if (n.boundaryFound) {
    lines << tr("Boundary circle through %1, rotation %2 about the centre per Qⁿ (%3 digits; proven irrational "
                "to denominators of 10⁴, its polygon converged)")
                 .arg(point(n.boundaryPoint))
                 .arg(n.boundaryRotation, 0, 'g', 10)
                 .arg(n.boundaryDigits, 0, 'f', 1);
    lines << tr("<b>Area</b> %1 ± %2: the true area lies in [%3, %4] (the circle's polygon of %5 points to %6; the "
                "circle scaled to the nearest orbits that leave the island); the chain's %7 islands: %8")
                 .arg(number(n.area, 10), number(n.areaError, 2), number(n.areaLower, 10), number(n.areaUpper, 10))
                 .arg(n.areaPoints)
                 .arg(number(n.polygonError, 2))
                 .arg(n.period)
                 .arg(number(n.area * static_cast<long double>(n.period), 10));
  } else {
    lines << tr("No boundary circle: %1").arg(QString::fromStdString(n.boundaryFailure).toHtmlEscaped());
  }
  if (n.flux.found) {
    lines << tr("<b>Flux</b> %1 per step (%2 digits agree), zone %3, islands inside %4, <b>layer</b> %5, "
                "<b>residence</b> %6 steps")
                 .arg(number(n.flux.flux, 10))
                 .arg(std::isfinite(static_cast<double>(n.flux.fluxDigits)) ? number(n.flux.fluxDigits, 3) : tr("all"))
                 .arg(number(n.flux.zoneArea, 8), number(n.flux.enclosedIslands, 8), number(n.flux.layerArea, 8))
                 .arg(number(n.flux.residence, 6));
  } else if (measured(n) && !n.flux.failure.empty()) {
    lines << tr("No flux: %1").arg(QString::fromStdString(n.flux.failure).toHtmlEscaped());
  }
  if (n.flux.partner)
    lines << tr("Barrier: the manifolds of the hyperbolic orbit through %1 (residue %2)")
                 .arg(point(n.flux.partner->points.front()))
                 .arg(number(n.flux.partner->residue, 6));
  else if (index == 0)
    lines << tr("Barrier: the loop of the hyperbolic fixed point (√K, 0)");
  if (!n.internal.empty()) {
    QStringList r;
    for (const Rational& q : n.internal) r << QString::fromStdString(toString(q));
    lines << tr("Chains inside its boundary: %1").arg(r.join(QStringLiteral(", ")));
  }
  if (!n.note.empty()) lines << QString::fromStdString(n.note).toHtmlEscaped();
  details_->setText(lines.join(QStringLiteral("<br>")));
}

void AtlasPanel::updateButtons() {
  compute_->setEnabled(!busy());
  stop_->setEnabled(busy());
  json_->setEnabled(atlas_ && !busy());
  csv_->setEnabled(atlas_ && !busy());
}

bool AtlasPanel::openAtlasFile(const QString& path, QString* error) {
  std::optional<Atlas> atlas;
  try {
    atlas = atlasFromJson(io::readRegularFile(path.toStdString(), kMaxAtlasFileBytes));
  } catch (const std::exception& e) {
    const QString why = QString::fromUtf8(e.what());
    if (error) *error = why;
    Q_EMIT statusMessage(tr("Cannot open the atlas %1: %2").arg(path, why));
    return false;
  }
  restoreAtlas(atlas);
  source_ = QFileInfo(path).fileName();
  updateProgress();
  Q_EMIT statusMessage(tr("Atlas of %1 islands read from %2").arg(atlas->nodes.size()).arg(path));
  return true;
}

bool AtlasPanel::showIsland(int index) {
  if (!atlas_ || index < 0 || index >= static_cast<int>(atlas_->nodes.size())) {
    Q_EMIT statusMessage(tr("Atlas: there is no island %1").arg(index));
    return false;
  }
  if (!ofPortraitMap()) {
    Q_EMIT statusMessage(tr("This atlas is of K = %1: set K = %1 again to see its islands")
                             .arg(QString::fromStdString(io::shortestText(atlas_->request.map.K))));
    return false;
  }
  const AtlasNode& n = atlas_->nodes[static_cast<std::size_t>(index)];
  // The view: the island's boundary circle with a margin (the controller frames it once traced); without one, a
  // square about its centre of its scan's range, else a tenth of its parent's disc of equal area.
  long double half = 0;
  if (n.scanRange > 0) half = n.scanRange;
  else if (n.parent >= 0 && atlas_->nodes[static_cast<std::size_t>(n.parent)].area > 0)
    half = std::sqrt(atlas_->nodes[static_cast<std::size_t>(n.parent)].area / std::numbers::pi_v<long double>) / 10;
  else half = controller_->map().width() / 100;
  const SegmentRegion fallback{n.centre.x - half, n.centre.x + half, n.centre.y - half, n.centre.y + half, 1.0};
  controller_->showAtlasIsland(n, path(*atlas_, index), fallback);
  Q_EMIT statusMessage(tr("Island %1: period %2, area %3").arg(path(*atlas_, index)).arg(n.period).arg(
      n.boundaryFound ? number(n.area, 6) : tr("not found")));
  return true;
}

bool AtlasPanel::exportWith(void (*write)(const std::filesystem::path&, const Atlas&), const QString& path,
                            QString* error) {
  if (!atlas_ || busy()) {
    if (error) *error = busy() ? tr("the atlas is still being computed (Stop keeps what is finished)") : tr("no atlas yet");
    return false;
  }
  try {
    write(path.toStdString(), *atlas_);
  } catch (const std::exception& e) {
    if (error) *error = QString::fromUtf8(e.what());
    return false;
  }
  return true;
}

bool AtlasPanel::exportJson(const QString& path, QString* error) {
  if (!exportWith(&writeAtlasJson, path, error)) return false;
  markSaved();  // the file reads back as this atlas
  return true;
}
bool AtlasPanel::exportCsv(const QString& path, QString* error) { return exportWith(&writeAtlasCsv, path, error); }

}  // namespace archipelago::ui
