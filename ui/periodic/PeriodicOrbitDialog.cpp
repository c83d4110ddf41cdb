#include "ui/periodic/PeriodicOrbitDialog.hpp"

#include <stdexcept>
#include <string>

#include "core/periodic/HyperbolicPartner.hpp"

#include <QCheckBox>
#include <QDialogButtonBox>
#include <QDoubleSpinBox>
#include <QDoubleValidator>
#include <QFormLayout>
#include <QHBoxLayout>
#include <QHeaderView>
#include <QLabel>
#include <QLineEdit>
#include <QPushButton>
#include <QSpinBox>
#include <QTableWidget>
#include <QVBoxLayout>

#include <exception>

#include "core/periodic/PeriodicOrbitFinder.hpp"
#include "ui/jobs/BackgroundJobs.hpp"

namespace archipelago::ui {

namespace {
/// The shortest text that reads back as `value` (0.1, not 0.10000000000000001).
QString shortest(double value) { return QLocale::c().toString(value, 'g', QLocale::FloatingPointShortest); }

QLineEdit* numberEdit(QWidget* parent, double value) {
  auto* edit = new QLineEdit(shortest(value), parent);
  auto* validator = new QDoubleValidator(edit);
  validator->setLocale(QLocale::c());
  edit->setValidator(validator);
  return edit;
}
double numberOf(const QLineEdit* edit, bool* ok) { return QLocale::c().toDouble(edit->text().trimmed(), ok); }
}  // namespace

PeriodicOrbitDialog::PeriodicOrbitDialog(QWidget* parent) : QDialog(parent) {
  qRegisterMetaType<PeriodicOrbit>();
  setWindowTitle(tr("Find periodic orbit"));
  jobs_ = std::make_unique<BackgroundJobs>(this);

  kEdit_ = numberEdit(this, 0.1);
  kEdit_->setToolTip(tr("The map parameter K of Q (from the current run parameters)"));
  periodBox_ = new QSpinBox(this);
  periodBox_->setRange(1, PeriodicOrbitSearch::kMaxPeriod);
  periodBox_->setValue(6);
  periodBox_->setToolTip(tr("Minimal period n of the orbit (e.g. 6 or 138 at K = 0.1)"));
  xEdit_ = numberEdit(this, 0.0509);
  yEdit_ = numberEdit(this, 0.0974);
  auto* nearRow = new QHBoxLayout;
  nearRow->addWidget(xEdit_);
  nearRow->addWidget(yEdit_);
  radiusBox_ = new QDoubleSpinBox(this);
  radiusBox_->setDecimals(6);
  radiusBox_->setRange(1e-6, 1.0);
  radiusBox_->setSingleStep(0.001);
  radiusBox_->setValue(0.01);
  radiusBox_->setToolTip(tr("How far from the guess's iterates the symmetry lines are scanned"));
  stableBox_ = new QCheckBox(tr("Stable (elliptic) orbits only"), this);
  stableBox_->setChecked(true);

  // Positions are those of the portrait's axes: the map Q in (x, y), the central island about x = −√K.  The
  // paper quotes positions from that centre, x + √K (issue 25, finding 10).
  note_ = new QLabel(tr("Coordinates are those of the portrait: (x, y) of the map Q, whose central island lies "
                        "around (−√K, 0). The paper quotes positions from that centre, x + √K: its period-138 orbit "
                        "at x + √K = 0.352 is at x = 0.352 − √0.1 = 0.036 here."),
                     this);
  note_->setWordWrap(true);
  note_->setObjectName(QStringLiteral("coordinatesNote"));
  auto* form = new QFormLayout;
  form->addRow(tr("&K:"), kEdit_);
  form->addRow(tr("&Period n:"), periodBox_);
  // A row whose field is a layout gets no buddy from QFormLayout, and its "&" showed literally: the label
  // names the x field as its buddy.
  auto* nearLabel = new QLabel(tr("&Near (x, y):"), this);
  nearLabel->setBuddy(xEdit_);
  form->addRow(nearLabel, nearRow);
  form->addRow(tr("Search &radius:"), radiusBox_);
  form->addRow(QString(), stableBox_);

  summary_ = new QLabel(tr("Enter a period and a point near the orbit, then Find."), this);
  summary_->setWordWrap(true);
  summary_->setTextInteractionFlags(Qt::TextSelectableByMouse);
  points_ = new QTableWidget(0, 3, this);
  points_->setHorizontalHeaderLabels({tr("k"), tr("x"), tr("y")});
  points_->verticalHeader()->hide();
  points_->horizontalHeader()->setStretchLastSection(true);
  points_->setEditTriggers(QAbstractItemView::NoEditTriggers);

  findButton_ = new QPushButton(tr("&Find"), this);
  findButton_->setDefault(true);
  overlayButton_ = new QPushButton(tr("&Overlay"), this);
  overlayButton_->setToolTip(tr("Draw the orbit on the phase portrait"));
  overlayButton_->setEnabled(false);
  partnerButton_ = new QPushButton(tr("Hyperbolic &Partner"), this);
  partnerButton_->setToolTip(tr("The unstable orbit of the same period between the islands of this elliptic orbit: "
                                "its manifolds are the chain's separatrices"));
  manifoldsButton_ = new QPushButton(tr("&Manifolds"), this);
  manifoldsButton_->setToolTip(tr("Draw the stable and unstable manifolds of this hyperbolic orbit on the portrait, "
                                  "with its turnstile and the flux (Portrait ▸ Manifolds and Flux)"));
  auto* buttons = new QDialogButtonBox(QDialogButtonBox::Close, this);
  buttons->addButton(findButton_, QDialogButtonBox::ActionRole);
  buttons->addButton(overlayButton_, QDialogButtonBox::ActionRole);
  buttons->addButton(partnerButton_, QDialogButtonBox::ActionRole);
  buttons->addButton(manifoldsButton_, QDialogButtonBox::ActionRole);
  connect(partnerButton_, &QPushButton::clicked, this, &PeriodicOrbitDialog::findPartner);
  connect(manifoldsButton_, &QPushButton::clicked, this, [this] {
    if (orbit_) Q_EMIT manifoldsRequested(*orbit_);
  });
  connect(buttons, &QDialogButtonBox::rejected, this, &QDialog::reject);
  connect(findButton_, &QPushButton::clicked, this, &PeriodicOrbitDialog::find);
  connect(overlayButton_, &QPushButton::clicked, this, [this] {
    if (orbit_) Q_EMIT overlayRequested(*orbit_);
  });

  auto* layout = new QVBoxLayout(this);
  layout->addWidget(note_);
  layout->addLayout(form);
  layout->addWidget(summary_);
  layout->addWidget(points_, 1);
  layout->addWidget(buttons);
  resize(560, 600);
  updateButtons();
}

QString PeriodicOrbitDialog::coordinatesNote() const { return note_->text(); }

void PeriodicOrbitDialog::updateButtons() {
  const bool have = orbit_.has_value() && !searching_;
  const bool elliptic = have && orbit_->classification().stable();
  overlayButton_->setEnabled(have);
  partnerButton_->setEnabled(elliptic && orbit_->period >= 1);
  manifoldsButton_->setEnabled(have && !elliptic);
}

void PeriodicOrbitDialog::findPartner() {
  if (!orbit_ || !orbit_->classification().stable()) return;
  const PeriodicOrbit chain = *orbit_;
  searching_ = true;
  findButton_->setEnabled(false);
  updateButtons();
  summary_->setText(tr("Searching for the hyperbolic partner of the period-%1 orbit\u2026").arg(chain.period));
  Job<PeriodicOrbit> job;
  job.work = [chain](JobContext<NoProgress>&) -> std::optional<PeriodicOrbit> {
    if (auto partner = findHyperbolicPartner(chain)) return partner;
    throw std::runtime_error("no hyperbolic orbit of period " + std::to_string(chain.period) +
                             " found between the islands");
  };
  job.done = [this](const JobResult<PeriodicOrbit>& r) { onResult(r.id, r.value, r.error); };
  request_ = jobs_->submit(std::move(job));
}

PeriodicOrbitDialog::~PeriodicOrbitDialog() {
  jobs_.reset();  // waits for a running search before the widgets it reports to go away
}

void PeriodicOrbitDialog::setK(double K) { kEdit_->setText(shortest(K)); }
void PeriodicOrbitDialog::setPeriod(int period) { periodBox_->setValue(period); }
void PeriodicOrbitDialog::setNear(double x, double y) {
  xEdit_->setText(shortest(x));
  yEdit_->setText(shortest(y));
}
void PeriodicOrbitDialog::setStableOnly(bool on) { stableBox_->setChecked(on); }
double PeriodicOrbitDialog::K() const {
  bool ok = false;
  const double K = numberOf(kEdit_, &ok);
  return ok ? K : 0.0;
}

void PeriodicOrbitDialog::find() {
  bool okK = false, okX = false, okY = false;
  const double K = numberOf(kEdit_, &okK);
  const double x = numberOf(xEdit_, &okX);
  const double y = numberOf(yEdit_, &okY);
  if (!okK || !okX || !okY) {
    summary_->setText(tr("<b>Not a number:</b> %1").arg(!okK ? tr("K") : !okX ? tr("x") : tr("y")));
    Q_EMIT searchFinished(false);
    return;
  }
  PeriodicOrbitSearch search;
  search.period = periodBox_->value();
  search.near = {x, y};
  search.searchRadius = radiusBox_->value();
  search.stableOnly = stableBox_->isChecked();
  searching_ = true;
  findButton_->setEnabled(false);
  updateButtons();
  summary_->setText(tr("Searching for an orbit of period %1 near (%2, %3)\u2026").arg(search.period).arg(x).arg(y));
  Job<PeriodicOrbit> job;  // JobOrder::latest: the answer of an older search is dropped
  job.work = [K, search](JobContext<NoProgress>&) -> std::optional<PeriodicOrbit> {
    return findPeriodicOrbit(K, search);
  };
  job.done = [this](const JobResult<PeriodicOrbit>& r) { onResult(r.id, r.value, r.error); };
  request_ = jobs_->submit(std::move(job));
}

void PeriodicOrbitDialog::onResult(quint64 requestId, const std::optional<PeriodicOrbit>& orbit, const QString& error) {
  if (requestId != request_) return;  // an older search
  searching_ = false;
  findButton_->setEnabled(true);
  orbit_ = orbit;
  updateButtons();
  if (!orbit_) {
    summary_->setText(tr("<b>No orbit found:</b> %1").arg(error.toHtmlEscaped()));
    points_->setRowCount(0);
  } else {
    showOrbit();
  }
  Q_EMIT searchFinished(orbit_.has_value());
}

void PeriodicOrbitDialog::showOrbit() {
  const PeriodicOrbit& o = *orbit_;
  // The class and the rotation number are core's words (classifyOrbit, rotationNumberText): the CLI prints the same.
  const OrbitClassification kind = o.classification();
  summary_->setText(tr("Period <b>%1</b>: residue R = <b>%2</b> (%3, %4), rotation number %5, "
                       "trace DQ<sup>n</sup> = %6, closure %7, symmetry %8")
                        .arg(o.period)
                        .arg(static_cast<double>(o.residue), 0, 'g', 10)
                        .arg(kind.stable() ? tr("stable") : tr("unstable"))
                        .arg(QString::fromLatin1(kind.description()).toHtmlEscaped())
                        .arg(QString::fromStdString(rotationNumberText(o, 8)).toHtmlEscaped())
                        .arg(static_cast<double>(o.trace), 0, 'g', 10)
                        .arg(static_cast<double>(o.closure), 0, 'g', 2)
                        .arg(QString::fromLatin1(toString(o.symmetry))));
  points_->setRowCount(static_cast<int>(o.points.size()));
  for (std::size_t k = 0; k < o.points.size(); ++k) {
    const int row = static_cast<int>(k);
    points_->setItem(row, 0, new QTableWidgetItem(QString::number(row)));
    points_->setItem(row, 1, new QTableWidgetItem(QString::number(static_cast<double>(o.points[k].x), 'g', 17)));
    points_->setItem(row, 2, new QTableWidgetItem(QString::number(static_cast<double>(o.points[k].y), 'g', 17)));
  }
  points_->resizeColumnsToContents();
}

}  // namespace archipelago::ui
