#include "ui/scan/KScanDialog.hpp"

#include <QDialogButtonBox>
#include <QFileDialog>
#include <QFormLayout>
#include <QHBoxLayout>
#include <QLabel>
#include <QLineEdit>
#include <QLocale>
#include <QMessageBox>
#include <QProgressBar>
#include <QPushButton>
#include <QStringList>
#include <QTabWidget>
#include <QVBoxLayout>

#include <cmath>
#include <utility>

#include "core/kernels/KernelDispatch.hpp"
#include "ui/jobs/DurationText.hpp"
#include "core/io/NumberText.hpp"
#include "core/runspec/InputRules.hpp"
#include "ui/scan/KScanPlots.hpp"
#include "ui/scan/TailScanPlots.hpp"

#include <variant>

namespace archipelago::ui {

namespace {

/// A field's number through core's one input layer (core/runspec/InputRules.hpp): its value, or its message.
std::variant<ParameterValue, QString> input(const char* key, const QLineEdit* edit) {
  try {
    return readInput(key, edit->text().trimmed().toStdString());
  } catch (const std::exception& e) {
    return QString::fromStdString(e.what());
  }
}

}  // namespace

KScanDialog::KScanDialog(const RunSpec& base, QWidget* parent) : QDialog(parent), base_(base) {
  setWindowTitle(tr("K scan (§5)"));
  setObjectName(QStringLiteral("kScanDialog"));

  // The settings.
  auto* settings = new QWidget(this);
  auto* form = new QFormLayout(settings);
  kValues_ = new QLineEdit(QString::fromLatin1(kPaperScanValuesText), settings);
  kValues_->setToolTip(tr("FROM:TO:STEP or K1, K2, …; each K in [0, %1]. The paper's list: 0.05 to 1.3 by 0.05.")
                           .arg(kScanMaxK));
  form->addRow(tr("&K values"), kValues_);
  const TrappingParameters& p = base.parameters;
  auto addField = [&](const QString& label, const QString& name, const QString& value, const QString& tip) {
    auto* edit = new QLineEdit(value, settings);
    edit->setObjectName(name);
    edit->setToolTip(tip);
    form->addRow(label, edit);
    return edit;
  };
  M_ = addField(tr("&M (orbits)"), QStringLiteral("M"), QString::number(p.M), tr("orbits per K"));
  T_ = addField(tr("&T (blocks)"), QStringLiteral("T"), QString::number(p.T), tr("blocks of q steps per orbit"));
  q_ = addField(tr("&q"), QStringLiteral("q"), QString::number(p.q), tr("steps of N⁻¹ per block"));
  seed_ = addField(tr("See&d"), QStringLiteral("seed"), QString::number(p.seed), tr("seed of the random numbers"));
  threads_ = addField(tr("T&hreads"), QStringLiteral("threads"), QString::number(base.threads),
                      tr("OpenMP threads (0: one per core)"));
  b2Iterations_ = addField(tr("&b₂ steps"), QStringLiteral("b2Iterations"), QStringLiteral("0"),
                           tr("b₂, the area of the sea (appendix A), of every box with this many steps, e.g. "
                              "134217728 (0: not computed; recomputed at every start)"));
  auto* folderRow = new QHBoxLayout;
  folder_ = new QLineEdit(QStringLiteral("scan"), settings);
  folder_->setToolTip(tr("a run file per K (K0.05.json, …) and the summaries; a folder already holding a scan of "
                         "the same settings is resumed"));
  auto* browseButton = new QPushButton(tr("&Browse…"), settings);
  browseButton->setAutoDefault(false);
  connect(browseButton, &QPushButton::clicked, this, &KScanDialog::browse);
  folderRow->addWidget(folder_, 1);
  folderRow->addWidget(browseButton);
  auto* folderLabel = new QLabel(tr("&Folder"), settings);
  folderLabel->setBuddy(folder_);
  form->addRow(folderLabel, folderRow);
  auto* rule = new QLabel(tr("Box of each K: xmin = −2√K − %1, xmax = √K + %1. Xr, subsets and longest kept are "
                             "the main window's.")
                              .arg(kScanBoxMargin),
                          settings);
  rule->setWordWrap(true);
  form->addRow(rule);

  // Progress.
  kProgress_ = new QProgressBar(settings);
  kProgress_->setRange(0, 1000);
  kProgress_->setFormat(tr("this K"));
  scanProgress_ = new QProgressBar(settings);
  scanProgress_->setRange(0, 1000);
  scanProgress_->setFormat(tr("whole scan"));
  kEta_ = new QLabel(settings);
  scanEta_ = new QLabel(settings);
  form->addRow(tr("This K"), kProgress_);
  form->addRow(QString(), kEta_);
  form->addRow(tr("Whole scan"), scanProgress_);
  form->addRow(QString(), scanEta_);
  message_ = new QLabel(settings);
  message_->setWordWrap(true);
  message_->setTextInteractionFlags(Qt::TextSelectableByMouse);
  form->addRow(message_);

  // Buttons: Enter starts, Esc closes.
  auto* buttons = new QDialogButtonBox(this);
  startButton_ = buttons->addButton(tr("&Start"), QDialogButtonBox::ActionRole);
  startButton_->setDefault(true);
  stopButton_ = buttons->addButton(tr("S&top"), QDialogButtonBox::ActionRole);
  stopButton_->setAutoDefault(false);
  exportButton_ = buttons->addButton(tr("&Export CSV…"), QDialogButtonBox::ActionRole);
  exportButton_->setAutoDefault(false);
  tailButton_ = buttons->addButton(tr("Open t&ail scan…"), QDialogButtonBox::ActionRole);
  tailButton_->setAutoDefault(false);
  tailButton_->setToolTip(tr("Show γ(t, K) of a folder written by archipelago-cli tail-scan"));
  QPushButton* closeButton = buttons->addButton(QDialogButtonBox::Close);
  closeButton->setAutoDefault(false);
  connect(startButton_, &QPushButton::clicked, this, [this] { start(); });
  connect(stopButton_, &QPushButton::clicked, this, &KScanDialog::stop);
  connect(exportButton_, &QPushButton::clicked, this, &KScanDialog::exportInteractively);
  connect(tailButton_, &QPushButton::clicked, this, &KScanDialog::openTailScanInteractively);
  connect(closeButton, &QPushButton::clicked, this, &KScanDialog::reject);

  createResults();
  auto* left = new QVBoxLayout;
  left->addWidget(settings);
  left->addStretch(1);
  auto* top = new QHBoxLayout;
  settings->setMaximumWidth(420);
  top->addLayout(left);
  top->addWidget(results_, 1);
  auto* layout = new QVBoxLayout(this);
  layout->addLayout(top, 1);
  layout->addWidget(buttons);
  resize(1200, 740);  // fits 1280 × 800 with the window frame
  setRunning(false);
  exportButton_->setEnabled(false);
}

void KScanDialog::createResults() {
  // KScanPlots (the report draws its figures with it too) and the tail scan's figure, a tab each.
  plots_ = new KScanPlots(this);
  plots_->clear();  // the fixed typical ranges until a K finishes (issue 37, finding 12: an empty log axis spanned
                    // 10⁻¹⁵⁰ … 1)
  tailPlots_ = new TailScanPlots(this);
  tailPlots_->clear();
  results_ = new QTabWidget(this);
  results_->setObjectName(QStringLiteral("resultTabs"));
  results_->addTab(plots_, tr("K scan"));
  results_->addTab(tailPlots_, tr("Tail scan γ(t, K)"));
}

KScanDialog::~KScanDialog() = default;  // jobs_ stops the scan (its K saved) and waits for it

QLineEdit* KScanDialog::field(const QString& name) const {
  return findChild<QLineEdit*>(name);
}

QString KScanDialog::message() const { return message_->text(); }

std::optional<KScanRequest> KScanDialog::request(QString* error) const {
  auto fail = [&](const QString& text) -> std::optional<KScanRequest> {
    if (error) *error = text;
    return std::nullopt;
  };
  KScanRequest r;
  r.base = base_;
  try {
    r.K = parseScanValues(kValues_->text().toStdString());
  } catch (const std::exception& e) {
    return fail(QString::fromStdString(e.what()));
  }
  const std::pair<QLineEdit*, const char*> counts[] = {{M_, "M"}, {T_, "T"}, {q_, "q"}, {seed_, "seed"}};
  for (const auto& [edit, key] : counts) {
    const auto v = input(key, edit);
    if (const QString* message = std::get_if<QString>(&v)) return fail(*message);
    try {
      setParameterValue(r.base.parameters, key, std::get<ParameterValue>(v));
    } catch (const std::exception& e) {
      return fail(QString::fromStdString(e.what()));
    }
  }
  const auto threads = input("threads", threads_);
  if (const QString* message = std::get_if<QString>(&threads)) return fail(*message);
  r.base.threads = static_cast<int>(std::get<std::uint64_t>(std::get<ParameterValue>(threads)));
  try {  // core's reader and its message
    r.b2Iterations = io::parseNumber<std::uint64_t>("b₂ steps", b2Iterations_->text().trimmed().toStdString());
  } catch (const std::exception& e) {
    return fail(QString::fromStdString(e.what()));
  }
  r.dir = folder_->text().trimmed().toStdString();
  if (auto e = kScanValidationError(r)) return fail(QString::fromStdString(*e));
  if (auto e = scanFolderError(r.dir)) return fail(QString::fromStdString(*e));
  return r;
}

bool KScanDialog::start() {
  if (running_) return false;
  QString error;
  std::optional<KScanRequest> r = request(&error);
  if (!r) {
    showMessage(error, true);
    return false;
  }
  try {
    r->kernel = &selectKernel(base_.kernel == "auto" ? std::string() : base_.kernel);
  } catch (const std::exception& e) {
    showMessage(QString::fromStdString(e.what()), true);
    return false;
  }
  clearResults();
  shown_.assign(r->K.size(), std::nullopt);
  Job<KScanOutcome, Update> job;
  job.work = [request = *r](JobContext<Update>& context) -> std::optional<KScanOutcome> {
    KScanObserver observer;
    observer.progress = [&](const KScanProgress& p) { context.progress(Update{p, std::nullopt, {}}); };
    observer.finished = [&](std::size_t index, const ScanRunSummary& run) {
      context.post(Update{std::nullopt, std::make_pair(index, run), {}});
    };
    observer.warning = [&](const std::string& text) {
      context.post(Update{std::nullopt, std::nullopt, QString::fromStdString(text)});
    };
    return runKScan(request, observer, context.stopToken());
  };
  job.progress = [this](quint64, Update u) {
    if (u.progress) showProgress(*u.progress);
    if (u.finished) addResult(u.finished->first, u.finished->second);
    if (!u.warning.isEmpty()) showMessage(tr("Warning: %1").arg(u.warning), true);
  };
  job.done = [this, dir = QString::fromStdString(r->dir.string())](JobResult<KScanOutcome> result) {
    setRunning(false);
    if (!result.ok()) {
      showMessage(tr("Error: %1").arg(result.error), true);
      Q_EMIT scanEnded(false);
      return;
    }
    if (!result.value->finished) {
      showMessage(tr("Stopped: %1 holds the checkpoint; Start resumes the scan.")
                      .arg(QString::fromStdString(result.value->stoppedFile.string())),
                  false);
      Q_EMIT scanEnded(false);
      return;
    }
    finishedRuns_ = std::move(result.value->runs);
    kProgress_->setValue(1000);
    kProgress_->setFormat(tr("every K finished"));
    scanProgress_->setValue(1000);
    scanProgress_->setFormat(tr("100%"));
    kEta_->clear();
    scanEta_->clear();
    exportButton_->setEnabled(true);
    showMessage(tr("Finished: %1 K; the summaries (%2, %3, %4) are in %5.")
                    .arg(finishedRuns_.size())
                    .arg(QLatin1String(scanSummaryCsvFileName), QLatin1String(scanFtCsvFileName),
                         QLatin1String(scanLocalExponentCsvFileName), dir),
                false);
    Q_EMIT scanEnded(true);
  };
  jobId_ = jobs_.submit(std::move(job));
  setRunning(true);
  showMessage(tr("Scanning %1 K into %2…").arg(r->K.size()).arg(QString::fromStdString(r->dir.string())), false);
  return true;
}

void KScanDialog::stop() {
  if (!running_) return;
  jobs_.requestStop(jobId_);
  showMessage(tr("Stopping at the end of the current chunk…"), false);
}

void KScanDialog::reject() {
  if (running_) {
    const auto answer = QMessageBox::question(
        this, tr("K scan running"),
        tr("A K scan is running. Stop it and close? The K running is saved in its run file; Start resumes it."),
        QMessageBox::Yes | QMessageBox::No, QMessageBox::No);
    if (answer != QMessageBox::Yes) return;
    stop();
  }
  QDialog::reject();
}

void KScanDialog::setRunning(bool running) {
  running_ = running;
  startButton_->setEnabled(!running);
  stopButton_->setEnabled(running);
  for (QLineEdit* edit : {kValues_, M_, T_, q_, seed_, threads_, b2Iterations_, folder_}) edit->setEnabled(!running);
}

void KScanDialog::showMessage(const QString& text, bool error) {
  message_->setText(text);
  message_->setStyleSheet(error ? QStringLiteral("color: #b00020;") : QString());
}

void KScanDialog::showProgress(const KScanProgress& p) {
  kProgress_->setValue(static_cast<int>(std::lround(1000 * p.fractionK())));
  scanProgress_->setValue(static_cast<int>(std::lround(1000 * p.fractionScan())));
  kProgress_->setFormat(tr("K = %1 (%2 of %3): %4%")
                            .arg(QString::fromStdString(scanKText(p.K)))
                            .arg(p.index + 1)
                            .arg(p.count)
                            .arg(100 * p.fractionK(), 0, 'f', 1));
  scanProgress_->setFormat(tr("%1%").arg(100 * p.fractionScan(), 0, 'f', 1));
  kEta_->setText(tr("ETA this K %1").arg(formatDuration(p.etaK)));
  scanEta_->setText(tr("ETA whole scan %1  (%2 steps/s)").arg(formatDuration(p.etaScan))
                        .arg(p.stepsPerSecond, 0, 'g', 3));
  Q_EMIT progressed(p.fractionScan());
}

void KScanDialog::clearResults() {
  shown_.clear();
  finishedRuns_.clear();
  exportButton_->setEnabled(false);
  kProgress_->setValue(0);
  scanProgress_->setValue(0);
  plots_->clear();
}

void KScanDialog::addResult(std::size_t index, const ScanRunSummary& run) {
  if (index >= shown_.size()) return;
  shown_[index] = run;
  plots_->showRuns(shown_);
}

void KScanDialog::browse() {
  const QString dir = QFileDialog::getExistingDirectory(this, tr("Scan folder"), folder_->text());
  if (!dir.isEmpty()) folder_->setText(dir);
}

bool KScanDialog::exportCsv(const QString& dir) {
  if (finishedRuns_.empty()) {
    showMessage(tr("Nothing to export: no scan has finished yet."), true);
    return false;
  }
  const std::filesystem::path path = dir.toStdString();
  std::error_code ec;
  if (!std::filesystem::is_directory(path, ec)) {
    showMessage(tr("Cannot export into %1: it is not a folder").arg(dir), true);
    return false;
  }
  try {
    writeScanSummaries(path, finishedRuns_);
  } catch (const std::exception& e) {
    showMessage(tr("Export failed: %1").arg(QString::fromStdString(e.what())), true);
    return false;
  }
  showMessage(tr("Exported the scan CSVs into %1.").arg(dir), false);
  return true;
}

void KScanDialog::exportInteractively() {
  const QString dir = QFileDialog::getExistingDirectory(this, tr("Export the scan CSVs into"), folder_->text());
  if (!dir.isEmpty()) exportCsv(dir);
}

void KScanDialog::openTailScan(const QString& dir) {
  tailFolder_ = dir;
  Job<TailScanFolder> job;
  job.channel = 1;
  job.work = [path = std::filesystem::path(dir.toStdString())](JobContext<NoProgress>&) -> std::optional<TailScanFolder> {
    return loadTailScan(path);
  };
  job.done = [this, dir](JobResult<TailScanFolder> result) {
    tailButton_->setEnabled(true);
    if (!result.ok()) {
      showMessage(tr("Tail scan not shown: %1").arg(result.error), true);
      Q_EMIT tailScanOpened(false);
      return;
    }
    showTailScan(dir, *result.value);
    Q_EMIT tailScanOpened(true);
  };
  tailButton_->setEnabled(false);
  showMessage(tr("Reading the tail scan in %1…").arg(dir), false);
  jobs_.submit(std::move(job));
}

void KScanDialog::showTailScan(const QString& dir, const TailScanFolder& folder) {
  const TailScanSummary& s = folder.summary;
  tailPlots_->showSummary(s);
  results_->setCurrentWidget(tailPlots_);
  QString text = tr("Tail scan %1: %2 K (%3 to %4), %5 windows of a decade.")
                     .arg(dir)
                     .arg(s.K.size())
                     .arg(QString::fromStdString(scanKText(s.K.front())), QString::fromStdString(scanKText(s.K.back())))
                     .arg(s.windows.size());
  if (!folder.unfinished.empty()) {
    QStringList K;
    for (const double k : folder.unfinished) K << QString::fromStdString(scanKText(k));
    text += tr(" Not finished yet, not shown: K = %1.").arg(K.join(QStringLiteral(", ")));
  }
  if (!s.outOfReach.empty()) {
    QStringList K;
    for (const TailScanRefusal& k : s.outOfReach) K << QString::fromStdString(scanKText(k.K));
    text += tr(" First level out of reach (no tail there), not shown: K = %1.").arg(K.join(QStringLiteral(", ")));
  }
  showMessage(text, false);
}

void KScanDialog::openTailScanInteractively() {
  const QString dir = QFileDialog::getExistingDirectory(this, tr("Tail scan folder (archipelago-cli tail-scan --dir)"),
                                                        tailFolder_.isEmpty() ? folder_->text() : tailFolder_);
  if (!dir.isEmpty()) openTailScan(dir);
}

}  // namespace archipelago::ui
