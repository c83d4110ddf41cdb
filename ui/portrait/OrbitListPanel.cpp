#include "ui/portrait/OrbitListPanel.hpp"

#include <QCheckBox>
#include <QFileDialog>
#include <QFormLayout>
#include <QHBoxLayout>
#include <QLineEdit>
#include <QSpinBox>
#include <QHeaderView>
#include <QLabel>
#include <QLocale>
#include <QPainter>
#include <QPixmap>
#include <QPushButton>
#include <QSet>
#include <QTimer>
#include <QSignalBlocker>
#include <QTreeWidget>
#include <QVBoxLayout>

#include <cmath>
#include <functional>
#include <optional>

#include "core/io/NumberText.hpp"
#include "core/limits/Limits.hpp"
#include "core/measures/OrbitMeasures.hpp"
#include "ui/portrait/PortraitController.hpp"

namespace archipelago::ui {

namespace {
QIcon swatch(const QColor& colour) {
  QPixmap p(12, 12);
  p.fill(Qt::transparent);
  QPainter painter(&p);
  painter.setRenderHint(QPainter::Antialiasing);
  painter.setPen(QPen(Qt::black, 1));
  painter.setBrush(colour);
  painter.drawEllipse(QRectF(1, 1, 10, 10));
  return QIcon(p);
}

QString number(long double v) { return QString::number(static_cast<double>(v), 'g', 9); }

/// A field of a physical coordinate, typed as text (every digit kept): its object name and its placeholder.
QLineEdit* coordinateField(QWidget* parent, const QString& name, const QString& placeholder) {
  auto* field = new QLineEdit(parent);
  field->setObjectName(name);
  field->setPlaceholderText(placeholder);
  return field;
}

/// Steps: a whole number beyond the range is taken as typed, then set to the largest with core's reason (issue 53,
/// finding 21: QSpinBox refused the ninth digit of 999999999, leaving 99,999,999 without a word).
class StepsBox : public QSpinBox {
 public:
  using QSpinBox::QSpinBox;
  std::function<void(const QString&)> onClamped;

 protected:
  QValidator::State validate(QString& text, int& pos) const override {
    const QValidator::State state = QSpinBox::validate(text, pos);
    if (state != QValidator::Invalid) return state;
    return typedBeyond(text) ? QValidator::Intermediate : QValidator::Invalid;
  }
  void fixup(QString& text) const override {
    if (const auto typed = typedBeyond(text)) {
      text = locale().toString(maximum());
      if (onClamped)
        onClamped(QString::fromStdString(
            rangeError("steps", *typed, minimum(), maximum(), "points of one orbit held in memory").value_or(std::string())));
      return;
    }
    QSpinBox::fixup(text);
  }

 private:
  /// The whole number typed (group separators allowed) when it is above the maximum.
  std::optional<unsigned long long> typedBeyond(const QString& text) const {
    QString digits = text;
    digits.remove(locale().groupSeparator()).remove(QLatin1Char(',')).remove(QLatin1Char(' ')).remove(QChar(0x202F));
    bool ok = false;
    const unsigned long long v = digits.toULongLong(&ok);
    if (!ok || v <= static_cast<unsigned long long>(maximum())) return std::nullopt;
    return v;
  }
};
}  // namespace

OrbitListPanel::OrbitListPanel(PortraitController* controller, QWidget* parent)
    : QWidget(parent), controller_(controller) {
  createList();
  createListButtons();
  createClickControls();
  createStartFields();
  createFamilyControls();
  connectList();
  layOut();
  refresh();
}

void OrbitListPanel::createList() {
  empty_ = new QLabel(tr("Click the portrait to launch an orbit: it is listed here with its rotation number about "
                         "the centre, the digits it converged to and its island chain."),
                      this);
  empty_->setWordWrap(true);
  list_ = new QTreeWidget(this);
  list_->setObjectName(QStringLiteral("launchedOrbits"));
  list_->setRootIsDecorated(false);
  list_->setUniformRowHeights(true);
  list_->setAlternatingRowColors(true);
  list_->setColumnCount(5);
  list_->setHeaderLabels({tr("#"), tr("start (x, y)"), tr("steps"), tr("rotation"), tr("chain")});
  list_->header()->setSectionResizeMode(QHeaderView::ResizeToContents);
  list_->header()->setStretchLastSection(false);
  list_->setSelectionMode(QAbstractItemView::SingleSelection);
  list_->setToolTip(tr("Select an orbit to highlight it and draw its chain's elliptic orbit"));
  details_ = new QLabel(this);
  details_->setWordWrap(true);
  details_->setTextInteractionFlags(Qt::TextSelectableByMouse);
  details_->setObjectName(QStringLiteral("orbitDetails"));
}

void OrbitListPanel::createListButtons() {
  undo_ = new QPushButton(tr("Undo"), this);
  undo_->setToolTip(tr("Remove the orbit launched last (Ctrl+Z)"));
  remove_ = new QPushButton(tr("Remove"), this);
  remove_->setToolTip(tr("Remove the selected orbit"));
  clear_ = new QPushButton(tr("Clear"), this);
  clear_->setToolTip(tr("Remove every launched orbit"));
  connect(undo_, &QPushButton::clicked, controller_, &PortraitController::undoLastOrbit);
  connect(remove_, &QPushButton::clicked, this, [this] {
    if (QTreeWidgetItem* item = list_->currentItem()) controller_->removeOrbit(item->data(0, Qt::UserRole).toULongLong());
  });
  connect(clear_, &QPushButton::clicked, this, [this] {
    // Undo takes the focus before Clear is disabled: else it fell to Steps, whose own undo took Ctrl+Z (issue 53,
    // finding 10), and Ctrl+Z right after Clear did nothing.
    if (clear_->hasFocus()) undo_->setFocus(Qt::OtherFocusReason);
    controller_->clearOrbits();
  });
  csv_ = new QPushButton(tr("CSV…"), this);
  csv_->setToolTip(tr("Write the selected orbit's points as CSV (as archipelago-cli orbit writes them)"));
  connect(csv_, &QPushButton::clicked, this, [this] {
    const QString path = QFileDialog::getSaveFileName(this, tr("Export the orbit as CSV"), QString(), tr("CSV (*.csv)"));
    if (path.isEmpty()) return;
    QString error;
    if (!exportSelectedCsv(path, &error)) Q_EMIT statusMessage(tr("Export failed: %1").arg(error));
    else Q_EMIT statusMessage(tr("Wrote %1").arg(path));
  });
}

void OrbitListPanel::createClickControls() {
  // What a click launches, and a start typed exactly (issue 37, finding 15).
  auto* steps = new StepsBox(this);
  steps->setCorrectionMode(QAbstractSpinBox::CorrectToNearestValue);
  steps->onClamped = [this](const QString& why) {
    Q_EMIT statusMessage(tr("%1: set to %2").arg(why, QLocale().toString(static_cast<qlonglong>(limits::kOrbitLength))));
  };
  steps_ = steps;
  steps_->setObjectName(QStringLiteral("orbitSteps"));
  steps_->setRange(1, static_cast<int>(limits::kOrbitLength));  // core's one table
  steps_->setValue(static_cast<int>(controller_->orbitsLayer().clickSteps()));
  steps_->setGroupSeparatorShown(true);
  steps_->setToolTip(tr("Steps of each launched orbit (a click or Launch)"));
  backward_ = new QCheckBox(tr("backward (N⁻¹)"), this);
  backward_->setObjectName(QStringLiteral("orbitBackward"));
  backward_->setToolTip(tr("Iterate the inverse map: the orbit's past"));
  const auto applyClick = [this] {
    controller_->orbitsLayer().setClickOrbit(static_cast<std::uint64_t>(steps_->value()), backward_->isChecked());
  };
  connect(steps_, qOverload<int>(&QSpinBox::valueChanged), this, applyClick);
  connect(backward_, &QCheckBox::toggled, this, applyClick);
}

void OrbitListPanel::createStartFields() {
  startX_ = coordinateField(this, QStringLiteral("orbitStartX"), QStringLiteral("x"));
  startY_ = coordinateField(this, QStringLiteral("orbitStartY"), QStringLiteral("y"));
  for (QLineEdit* e : {startX_, startY_}) {
    e->setToolTip(tr("The start, physical coordinates, as many digits as you like"));
    connect(e, &QLineEdit::returnPressed, this, &OrbitListPanel::launchTyped);
  }
  launch_ = new QPushButton(tr("Launch"), this);
  launch_->setToolTip(tr("Launch an orbit from the typed start"));
  connect(launch_, &QPushButton::clicked, this, &OrbitListPanel::launchTyped);
}

void OrbitListPanel::createFamilyControls() {
  // A line or a grid at once (issue 37, finding 15): from the start above to this point; rows = 1 is a line.
  endX_ = coordinateField(this, QStringLiteral("orbitEndX"), tr("to x"));
  endY_ = coordinateField(this, QStringLiteral("orbitEndY"), tr("to y"));
  for (QLineEdit* e : {endX_, endY_}) {
    e->setToolTip(tr("The line's other end, or the grid's opposite corner (physical coordinates)"));
    connect(e, &QLineEdit::returnPressed, this, &OrbitListPanel::launchFamily);
  }
  columns_ = new QSpinBox(this);
  columns_->setObjectName(QStringLiteral("orbitColumns"));
  rows_ = new QSpinBox(this);
  rows_->setObjectName(QStringLiteral("orbitRows"));
  for (QSpinBox* b : {columns_, rows_}) {
    b->setRange(0, 99999);  // the field's width; the count's rule is core's (orbitFamilyStarts), its message shown
    b->setValue(1);
  }
  columns_->setValue(10);
  columns_->setToolTip(tr("Orbits along the line, or per row of the grid"));
  rows_->setToolTip(tr("Rows of the grid (1: a line from the start to the other end)"));
  columns_->setPrefix(QStringLiteral("n "));
  rows_->setPrefix(QStringLiteral("× "));
  family_ = new QPushButton(tr("Line/Grid"), this);
  family_->setObjectName(QStringLiteral("launchFamily"));
  family_->setToolTip(tr("Launch n orbits on the line from the start to the other end, or n × rows over the rectangle "
                      "the two span; each is measured and listed"));
  connect(family_, &QPushButton::clicked, this, &OrbitListPanel::launchFamily);
}

void OrbitListPanel::connectList() {
  connect(list_, &QTreeWidget::currentItemChanged, this, [this](QTreeWidgetItem* item) {
    controller_->highlightOrbit(item ? item->data(0, Qt::UserRole).toULongLong() : 0);
  });
  // Many changes in a burst (a session's orbits arriving one by one): one refresh when the event loop is free.
  refreshTimer_ = new QTimer(this);
  refreshTimer_->setSingleShot(true);
  refreshTimer_->setInterval(30);
  connect(refreshTimer_, &QTimer::timeout, this, &OrbitListPanel::refresh);
  connect(controller_, &PortraitController::orbitsChanged, this, [this] {
    if (!refreshTimer_->isActive()) refreshTimer_->start();
  });
}

void OrbitListPanel::layOut() {
  auto* buttons = new QHBoxLayout;
  buttons->addWidget(undo_);
  buttons->addWidget(remove_);
  buttons->addWidget(clear_);
  buttons->addWidget(csv_);
  auto* launchRow = new QHBoxLayout;
  launchRow->addWidget(steps_, 1);
  launchRow->addWidget(backward_);
  auto* startRow = new QHBoxLayout;
  startRow->addWidget(startX_, 1);
  startRow->addWidget(startY_, 1);
  startRow->addWidget(launch_);
  auto* endRow = new QHBoxLayout;
  endRow->addWidget(endX_, 1);
  endRow->addWidget(endY_, 1);
  auto* countRow = new QHBoxLayout;
  countRow->addWidget(columns_, 1);
  countRow->addWidget(rows_, 1);
  countRow->addWidget(family_);
  auto* form = new QFormLayout;
  form->setContentsMargins(0, 0, 0, 0);
  form->addRow(tr("Steps"), launchRow);
  form->addRow(tr("Start"), startRow);
  form->addRow(tr("To"), endRow);
  form->addRow(tr("Orbits"), countRow);
  auto* layout = new QVBoxLayout(this);
  layout->setContentsMargins(2, 4, 2, 2);
  layout->addLayout(form);
  layout->addWidget(empty_);
  layout->addWidget(list_, 1);
  layout->addWidget(details_);
  layout->addLayout(buttons);
}

void OrbitListPanel::refresh() {
  const auto& orbits = controller_->launchedOrbits();
  // Rows follow the controller's list: the rows of removed orbits go, new ones are appended, the others are
  // updated in place (a session's 500 orbits arrive one by one).
  const QSignalBlocker block(list_);
  refreshTimer_->stop();
  QSet<quint64> ids;
  for (const LaunchedOrbit& o : orbits) ids.insert(o.id);
  for (int row = list_->topLevelItemCount() - 1; row >= 0; --row)
    if (!ids.contains(list_->topLevelItem(row)->data(0, Qt::UserRole).toULongLong())) delete list_->takeTopLevelItem(row);
  const QLocale locale;
  for (std::size_t i = 0; i < orbits.size(); ++i) {
    const LaunchedOrbit& o = orbits[i];
    QTreeWidgetItem* item = static_cast<int>(i) < list_->topLevelItemCount() ? list_->topLevelItem(static_cast<int>(i)) : nullptr;
    if (!item || item->data(0, Qt::UserRole).toULongLong() != o.id) {
      item = new QTreeWidgetItem;
      item->setData(0, Qt::UserRole, QVariant::fromValue<qulonglong>(o.id));
      item->setIcon(0, swatch(o.colour));
      item->setText(0, QString::number(o.id));
      item->setText(1, QStringLiteral("%1, %2").arg(static_cast<double>(o.x), 0, 'g', 6).arg(static_cast<double>(o.y), 0, 'g', 6));
      item->setText(2, locale.toString(static_cast<qulonglong>(o.steps)) + (o.backward ? tr(" (N⁻¹)") : QString()));
      list_->insertTopLevelItem(static_cast<int>(i), item);
    }
    const QString rotation = !o.error.isEmpty() ? tr("failed")
                             : o.measures      ? rotationText(*o.measures)
                                               : tr("measuring…");
    const QString chain = o.measures ? chainText(*o.measures) : QString();
    if (item->text(3) != rotation) item->setText(3, rotation);
    if (item->text(4) != chain) item->setText(4, chain);
    const QString tip = o.measures && o.measures->error.isEmpty() ? QString::fromStdString(o.measures->chain.summary) : chain;
    for (int c = 0; c < 5; ++c) item->setToolTip(c, tip);
    if (o.id == controller_->highlightedOrbit()) list_->setCurrentItem(item);
  }
  if (controller_->highlightedOrbit() == 0) list_->clearSelection(), list_->setCurrentItem(nullptr);
  const bool any = !orbits.empty();
  empty_->setVisible(!any);
  undo_->setEnabled(any || controller_->canUndoClear());
  undo_->setToolTip(!any && controller_->canUndoClear() ? tr("Bring back the cleared orbits (Ctrl+Z)")
                                                        : tr("Remove the orbit launched last (Ctrl+Z)"));
  clear_->setEnabled(any);
  remove_->setEnabled(controller_->highlightedOrbit() != 0);
  csv_->setEnabled(controller_->highlightedOrbit() != 0);
  updateDetails();
}

QString OrbitListPanel::detailsText() const { return details_->text(); }

bool OrbitListPanel::launchTyped() {
  const auto x = io::parseLongDoubleC(startX_->text().trimmed().toStdString());
  const auto y = io::parseLongDoubleC(startY_->text().trimmed().toStdString());
  if (!x || !y) {
    Q_EMIT statusMessage(tr("The start's %1 is not a number").arg(!x ? QStringLiteral("x") : QStringLiteral("y")));
    return false;
  }
  if (const auto e = boxPointError("the start", controller_->map(), {*x, *y})) {
    Q_EMIT statusMessage(QString::fromStdString(*e));
    return false;
  }
  return controller_->launchOrbit(*x, *y, static_cast<std::uint64_t>(steps_->value()), backward_->isChecked()) != 0;
}

int OrbitListPanel::launchFamily() {
  OrbitFamily family;
  const QLineEdit* fields[] = {startX_, startY_, endX_, endY_};
  long double* values[] = {&family.from.x, &family.from.y, &family.to.x, &family.to.y};
  const QString names[] = {tr("start's x"), tr("start's y"), tr("other end's x"), tr("other end's y")};
  for (int i = 0; i < 4; ++i) {
    const auto v = io::parseLongDoubleC(fields[i]->text().trimmed().toStdString());
    if (!v) {
      Q_EMIT statusMessage(tr("The %1 is not a number").arg(names[i]));
      return 0;
    }
    *values[i] = *v;
  }
  family.columns = static_cast<std::uint64_t>(columns_->value());
  family.rows = static_cast<std::uint64_t>(rows_->value());
  return controller_->launchOrbitFamily(family, static_cast<std::uint64_t>(steps_->value()), backward_->isChecked());
}

bool OrbitListPanel::exportSelectedCsv(const QString& path, QString* error) {
  return controller_->exportOrbitCsv(controller_->highlightedOrbit(), path, error);
}

void OrbitListPanel::updateDetails() {
  const quint64 id = controller_->highlightedOrbit();
  const LaunchedOrbit* orbit = nullptr;
  for (const LaunchedOrbit& o : controller_->launchedOrbits())
    if (o.id == id) orbit = &o;
  if (!orbit) {
    details_->setText(controller_->launchedOrbits().empty() ? QString() : tr("Select an orbit for its details."));
    return;
  }
  QString text = tr("<b>Orbit %1</b> from (%2, %3), %4 steps%5")
                     .arg(orbit->id)
                     .arg(number(orbit->x), number(orbit->y))
                     .arg(QLocale().toString(static_cast<qulonglong>(orbit->steps)))
                     .arg(orbit->backward ? tr(" of N⁻¹ (measured forward from its start)") : QString());
  if (!orbit->measures) {
    text += tr("<br>Measuring its rotation number and chain…");
  } else if (!orbit->measures->error.isEmpty()) {
    text += tr("<br>No measures: %1").arg(orbit->measures->error.toHtmlEscaped());
  } else {
    const ChainIdentification& c = orbit->measures->chain;
    const RotationMeasurement& r = c.levels.front().rotation;
    text += tr("<br>Rotation number about (−√K, 0): %1").arg(rotationText(*orbit->measures).toHtmlEscaped());
    if (std::isfinite(r.digits)) text += tr("<br>Digits: %1 (verdict: %2)").arg(r.digits, 0, 'f', 2).arg(QString::fromLatin1(toString(r.verdict).data()));
    text += tr("<br>%1").arg(QString::fromStdString(c.summary).toHtmlEscaped());
    for (auto it = c.levels.rbegin(); it != c.levels.rend(); ++it)
      if (it->orbit) {
        text += tr("<br>Drawn: its elliptic orbit of period %1 (residue %2)")
                    .arg(it->orbit->period)
                    .arg(static_cast<double>(it->orbit->residue), 0, 'g', 6);
        break;
      }
  }
  details_->setText(text);
}

}  // namespace archipelago::ui
