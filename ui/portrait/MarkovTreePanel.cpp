#include "ui/portrait/MarkovTreePanel.hpp"

#include <QDialog>
#include <QDialogButtonBox>
#include <QFileInfo>
#include <QFormLayout>
#include <QHBoxLayout>
#include <QHeaderView>
#include <QLabel>
#include <QLineEdit>
#include <QLocale>
#include <QMessageBox>
#include <QPushButton>
#include <QStringList>
#include <QTableWidget>
#include <QVBoxLayout>

#include <cmath>
#include <exception>
#include <stop_token>
#include <string>
#include <utility>

#include "core/io/NumberText.hpp"
#include "core/periodic/PeriodicOrbitFinder.hpp"  // OperationStopped
#include "core/stats/RunStatistics.hpp"
#include "core/tail/TailFile.hpp"
#include "ui/jobs/BackgroundJobs.hpp"

namespace archipelago::ui {

namespace {
QString number(long double v, int digits = 4) {
  return std::isfinite(v) ? QString::number(static_cast<double>(v), 'g', digits) : QStringLiteral("–");
}

QTableWidget* readOnlyTable(const QString& name, const QString& tip, QWidget* parent) {
  auto* table = new QTableWidget(parent);
  table->setObjectName(name);
  table->setEditTriggers(QAbstractItemView::NoEditTriggers);
  table->setSelectionMode(QAbstractItemView::NoSelection);
  table->setToolTip(tip);
  table->horizontalHeader()->setSectionResizeMode(QHeaderView::Stretch);
  table->hide();
  return table;
}

/// The Markov tree of `atlas` for `r`, set against the tail file `file` when it is one of the atlas's map (on a worker
/// thread).  Throws core's reason; nothing when stopped (Cancel or closing the window: within milliseconds, issue 54).
std::optional<std::shared_ptr<const MarkovTreeResult>> modelOf(const Atlas& atlas, const MarkovTreeRequest& r,
                                                                const std::string& file, std::stop_token stop) {
  std::optional<TailState> tail;
  if (!file.empty()) {
    try {
      tail = loadTailFile(file);
    } catch (const std::exception&) {  // its own reading said why when it was opened: the model alone
    }
    if (tail && !(tail->request.run.map == atlas.request.map)) tail.reset();
  }
  try {
    return std::make_shared<const MarkovTreeResult>(computeMarkovTree(atlas, r, tail ? &*tail : nullptr, stop));
  } catch (const OperationStopped&) {
    return std::nullopt;
  }
}

/// A number field of the dialog with where its value comes from below it.
QLineEdit* entryField(QFormLayout* form, const QString& label, const QString& symbol, double value,
                      const QString& source, QWidget* dialog) {
  auto* field = new QLineEdit(value > 0 ? QLocale::c().toString(value, 'g', 8) : QString(), dialog);
  field->setToolTip(QObject::tr("%1: %2").arg(symbol, source));
  form->addRow(label, field);
  form->addRow(QString(), new QLabel(QStringLiteral("<small>%1</small>").arg(source.toHtmlEscaped()), dialog));
  return field;
}
}  // namespace

MarkovTreePanel::MarkovTreePanel(std::function<std::shared_ptr<const Atlas>()> atlas, std::function<bool()> computing,
                                 QWidget* parent)
    : QWidget(parent),
      atlas_(std::move(atlas)),
      computing_(std::move(computing)),
      jobs_(std::make_unique<BackgroundJobs>(this, 1, JobPriority::background)) {
  button_ = new QPushButton(tr("Model P_t…"), this);
  button_->setObjectName(QStringLiteral("atlasMarkovTree"));
  button_->setToolTip(tip());
  connect(button_, &QPushButton::clicked, this, &MarkovTreePanel::ask);
  text_ = new QLabel(this);
  text_->setObjectName(QStringLiteral("atlasMarkovTreeText"));
  text_->setWordWrap(true);
  text_->hide();
  shares_ = readOnlyTable(QStringLiteral("atlasMarkovTreeShares"),
                          tr("Where the model's survivors sit: each atlas level's share of S(t) at t steps"), this);
  shares_->verticalHeader()->setSectionResizeMode(QHeaderView::ResizeToContents);
  comparison_ = readOnlyTable(QStringLiteral("atlasMarkovTreeComparison"),
                              tr("The model's P_t = w S(t) at each reliable level of the tail file, as archipelago-cli "
                                 "markov-tree --tail prints it"),
                              this);
  comparison_->verticalHeader()->hide();

  auto* layout = new QVBoxLayout(this);
  layout->setContentsMargins(0, 0, 0, 0);
  auto* row = new QHBoxLayout;
  row->addWidget(button_);
  row->addStretch(1);
  layout->addLayout(row);
  layout->addWidget(text_);
  layout->addWidget(shares_);
  layout->addWidget(comparison_, 1);
  // Taller than its contents only with the comparison shown (the page's other parts take the rest).
  setSizePolicy(QSizePolicy::Preferred, QSizePolicy::Maximum);

  atlasChanged();
}

MarkovTreePanel::~MarkovTreePanel() { jobs_.reset(); }

std::vector<std::uint64_t> MarkovTreePanel::shareTimes() { return {10'000, 100'000, 1'000'000}; }

QString MarkovTreePanel::missing(const Atlas* atlas, bool computing) {
  if (!atlas) return tr("there is no atlas: compute or open one first");
  if (computing) return tr("the atlas is still being computed");
  if (const auto e = markovTreeAtlasError(*atlas))  // core's rule: a stopped atlas, one without the centre's flux
    return tr("%1 (Compute measures it to its end)").arg(QString::fromStdString(*e));
  return {};
}

QString MarkovTreePanel::tip() {
  return tr("The Meiss–Ott Markov tree of this atlas (states between barriers, rates flux / area, "
            "docs/markov-tree.md): its P_t drawn on the P_t plot, each level's share below");
}

QString MarkovTreePanel::text() const { return text_->text(); }

void MarkovTreePanel::atlasChanged() {
  const std::shared_ptr<const Atlas> atlas = atlas_();
  if (atlas != shownAtlas_ && (model_ || request_ || !text_->text().isEmpty())) {  // another atlas's model
    jobs_->cancel();
    request_ = 0;
    model_.reset();
    inputs_.reset();
    fillShares();
    fillComparison();
  }
  shownAtlas_ = atlas;
  updateButton();
}

void MarkovTreePanel::updateButton() {
  const QString why = missing(atlas_().get(), computing_());
  button_->setEnabled(why.isEmpty() && !pending());
  button_->setToolTip(why.isEmpty() ? tip() : tr("No model of P_t: %1").arg(why));
}

MarkovTreePanel::Entry MarkovTreePanel::entry() const {
  // The atlas's map (the one the parameters show when no atlas is on the page), the shown run's map and α: core
  // decides what may be offered (markovTreeEntryOffer: never a number of another map).
  const std::shared_ptr<const Atlas> atlas = atlas_();
  const std::optional<MapParameters> given = sources_.parametersMap ? sources_.parametersMap() : std::nullopt;
  const MapParameters atlasMap = atlas ? atlas->request.map : given ? *given : MapParameters{};
  const auto [state, statistics] = sources_.run ? sources_.run() : RunShown{};
  std::optional<MapParameters> runMap;
  double runAlpha = 0, splicedAlpha = 0;
  if (state && statistics) {
    runMap = state->params.map;
    runAlpha = statistics->alpha;
    // Spliced statistics' α is the q = 1 companion's: the model, a tail file and `markov-tree --alpha` want the α of
    // the run's own process, blocks of q steps (issue 53, finding 12: 2.72 was offered where the tail's is 18.9).
    if (statistics->splicedAt > 0) {
      splicedAlpha = runAlpha;
      runAlpha = statisticsOf(*state).alpha;
    }
  }
  const MarkovTreeEntryOffer o = markovTreeEntryOffer(atlasMap, runMap, runAlpha);
  QString alphaSource = QString::fromStdString(o.alphaSource);
  if (runAlpha > 0 && o.alpha == runAlpha) {
    const QLocale c = QLocale::c();
    alphaSource += tr(", of the q = %1 process, the one a tail file of this run samples (archipelago-cli markov-tree "
                      "--alpha %2)")
                       .arg(state->params.q)
                       .arg(c.toString(runAlpha, 'g', 8));
    if (splicedAlpha > 0)
      alphaSource += tr("; the spliced statistics' α, %1, is the q = 1 companion's").arg(c.toString(splicedAlpha, 'g', 4));
  }
  return {o.alpha, o.b2, alphaSource, QString::fromStdString(o.b2Source)};
}

void MarkovTreePanel::ask() {
  const Entry e = entry();
  QDialog dialog(window());
  dialog.setWindowTitle(tr("Markov tree of the atlas"));
  auto* intro = new QLabel(tr("The model's P_t = w S(t) with w = α Φ_centre / b₂ visits per segment "
                              "(docs/markov-tree.md)."), &dialog);
  intro->setWordWrap(true);
  auto* form = new QFormLayout;
  QLineEdit* alpha = entryField(form, tr("α (steps)"), tr("α"), e.alpha, e.alphaSource, &dialog);
  QLineEdit* b2 = entryField(form, tr("b₂ (area)"), tr("b₂"), e.b2, e.b2Source, &dialog);
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
  else if (draw(a, b, &why)) return;
  QMessageBox::warning(window(), tr("Markov tree"), tr("Cannot draw the Markov tree: %1").arg(why));
}

bool MarkovTreePanel::draw(double alpha, double b2, QString* error) {
  QString why;
  if (!compute(alpha, b2, &why, sources_.tailFile ? sources_.tailFile() : QString())) {
    if (error) *error = why;
    Q_EMIT statusMessage(tr("Cannot draw the Markov tree: %1").arg(why));
    return false;
  }
  Q_EMIT statusMessage(tr("Computing the Markov tree of the atlas…"));
  return true;
}

void MarkovTreePanel::redrawAgainstTail() {
  if (inputs_) draw(inputs_->first, inputs_->second);
}

bool MarkovTreePanel::compute(double alpha, double b2, QString* error, const QString& tailFile) {
  MarkovTreeRequest r;
  r.alpha = alpha;
  r.b2 = b2;
  r.needsP = true;  // the page draws P_t: core refuses a missing, impossible or absurd α or b₂ (issue 54)
  r.at = shareTimes();
  r.atlasSource = "the Atlas page";
  r.tailSource = QFileInfo(tailFile).fileName().toStdString();
  const std::shared_ptr<const Atlas> atlas = atlas_();
  QString why = missing(atlas.get(), computing_());
  if (why.isEmpty())
    if (const auto e = validationError(r)) why = QString::fromStdString(*e);
  if (!why.isEmpty()) {
    if (error) *error = why;
    Q_EMIT pageMessage(tr("Markov tree: %1").arg(why));
    showRefusal(why);
    return false;
  }
  Job<std::shared_ptr<const MarkovTreeResult>> job;  // latest wins
  job.work = [atlas, r, file = tailFile.toStdString()](JobContext<NoProgress>& context) {
    return modelOf(*atlas, r, file, context.stopToken());
  };
  job.done = [this](JobResult<std::shared_ptr<const MarkovTreeResult>> result) {
    if (result.id != request_) return;
    request_ = 0;
    if (result.ok()) finish(*result.value, QString());
    else finish(nullptr, result.error);
  };
  request_ = jobs_->submit(std::move(job));
  inputs_ = std::pair{alpha, b2};
  text_->setText(tr("Computing the Markov tree…"));
  text_->show();
  updateButton();
  return true;
}

void MarkovTreePanel::finish(std::shared_ptr<const MarkovTreeResult> model, const QString& failure) {
  model_ = std::move(model);
  fillShares();
  fillComparison();
  if (!failure.isEmpty()) showRefusal(failure);
  updateButton();
  Q_EMIT pageMessage(failure.isEmpty() ? tr("Markov tree of the atlas: %1 states").arg(model_->tree.states.size())
                                       : tr("Markov tree: %1").arg(failure));
  if (!model_ || !failure.isEmpty()) {
    Q_EMIT statusMessage(tr("Cannot draw the Markov tree: %1").arg(failure));
    Q_EMIT drawn(failure.isEmpty() ? tr("no model") : failure);
    return;
  }
  Q_EMIT curveReady(markovTreeCurve(*model_), tr("Markov tree (atlas depth %1)").arg(model_->atlasDepth));  // core's
  Q_EMIT statusMessage(tr("Drew the Markov tree's P_t (%1 states, w = %2 visits per segment, α = %3, b₂ = %4) on P_t")
                           .arg(model_->tree.states.size())
                           .arg(QLocale::c().toString(static_cast<double>(model_->weight.value_or(0)), 'g', 4))
                           .arg(QLocale::c().toString(model_->request.alpha, 'g', 6))
                           .arg(QLocale::c().toString(model_->request.b2, 'g', 7)));
  Q_EMIT drawn(QString());
}

void MarkovTreePanel::showRefusal(const QString& why) {
  text_->setText(tr("No model: %1").arg(why));
  text_->show();
}

void MarkovTreePanel::fillShares() {
  shares_->clear();
  if (!model_) {
    shares_->hide();
    text_->setText(QString());
    text_->hide();
    return;
  }
  text_->show();
  const MarkovTreeResult& m = *model_;
  text_->setText(tr("Markov tree: %1 states (chains lumped: %2), mean visit %3 steps, w = %4 visits per segment. "
                    "Each level's share of the survivors at t steps:")
                     .arg(m.tree.states.size())
                     .arg(m.tree.lumped.size())
                     .arg(number(m.survival.meanVisit, 6))
                     .arg(m.weight ? number(*m.weight, 4) : QStringLiteral("–")));
  const std::vector<std::uint64_t> times = shareTimes();
  const auto levels = static_cast<int>(m.survival.level.size());
  shares_->setRowCount(levels);
  shares_->setColumnCount(static_cast<int>(times.size()));
  QStringList heads, rows;
  static const QString powers[] = {QStringLiteral("10⁴"), QStringLiteral("10⁵"), QStringLiteral("10⁶")};
  for (std::size_t c = 0; c < times.size(); ++c)
    heads << tr("t = %1").arg(c < 3 ? powers[c] : QString::number(times[c]));
  for (int l = 0; l < levels; ++l) rows << (l == 0 ? tr("level 0 (centre)") : tr("level %1").arg(l));
  shares_->setHorizontalHeaderLabels(heads);
  shares_->setVerticalHeaderLabels(rows);
  for (std::size_t c = 0; c < times.size(); ++c) {
    const auto shares = markovTreeLevelShares(m.survival, times[c]);
    for (int l = 0; l < levels; ++l) {
      auto* cell = new QTableWidgetItem;
      cell->setTextAlignment(Qt::AlignRight | Qt::AlignVCenter);
      if (shares && l < static_cast<int>(shares->size())) {
        const double v = (*shares)[static_cast<std::size_t>(l)];
        cell->setText(QStringLiteral("%1 %").arg(100 * v, 0, 'f', 1));
        cell->setData(Qt::UserRole, v);
      } else {
        cell->setText(QStringLiteral("–"));
      }
      shares_->setItem(l, static_cast<int>(c), cell);
    }
  }
  shares_->setFixedHeight(shares_->horizontalHeader()->sizeHint().height() +
                          levels * shares_->verticalHeader()->defaultSectionSize() + 2 * shares_->frameWidth());
  shares_->show();
}

void MarkovTreePanel::fillComparison() {
  comparison_->clear();
  if (!model_ || !model_->comparison) {
    comparison_->hide();
    setSizePolicy(QSizePolicy::Preferred, QSizePolicy::Maximum);
    return;
  }
  const MarkovTreeComparison& c = *model_->comparison;
  // The CLI's line and table (MarkovTreeCommand's printTree): the numbers are core's, the page only formats them.
  text_->setText(text_->text() + QLatin1Char('\n') +
                 tr("Against the tail %1: model / measured within a factor %2 last at t = %3 (the reach).")
                     .arg(QString::fromStdString(model_->request.tailSource))
                     .arg(c.factor)
                     .arg(c.reach > 0 ? QString::fromStdString(io::shortestText(c.reach)) : tr("none")));
  comparison_->setColumnCount(5);
  comparison_->setHorizontalHeaderLabels({tr("t"), tr("measured"), tr("model"), tr("ratio"), tr("level (share)")});
  comparison_->setRowCount(static_cast<int>(c.levels.size()));
  for (int row = 0; row < static_cast<int>(c.levels.size()); ++row) {
    const MarkovTreeLevelComparison& m = c.levels[static_cast<std::size_t>(row)];
    const QString cells[] = {QString::number(m.t, 'f', 0), tr("%1 ± %2").arg(number(m.measured, 4), number(m.measuredError, 2)),
                             number(m.model, 4), number(m.ratio, 3),
                             m.holdingLevel >= 0 ? tr("%1 (%2 %)").arg(m.holdingLevel).arg(100 * m.holdingShare, 0, 'f', 0)
                                                 : QStringLiteral("–")};
    for (int col = 0; col < 5; ++col) {
      auto* cell = new QTableWidgetItem(cells[col]);
      cell->setTextAlignment(Qt::AlignRight | Qt::AlignVCenter);
      comparison_->setItem(row, col, cell);
    }
    comparison_->item(row, 3)->setData(Qt::UserRole, static_cast<double>(m.ratio));
  }
  comparison_->show();
  setSizePolicy(QSizePolicy::Preferred, QSizePolicy::Preferred);
}

}  // namespace archipelago::ui
