#include "ui/portrait/ManifoldsPanel.hpp"

#include <QCheckBox>
#include <QComboBox>
#include <QDir>
#include <QFileDialog>
#include <QLabel>
#include <QPushButton>
#include <QSignalBlocker>
#include <QVBoxLayout>

#include <cmath>
#include <limits>

#include "core/manifolds/ManifoldExport.hpp"
#include "ui/files/OutputFiles.hpp"
#include "ui/portrait/PortraitController.hpp"
#include "ui/settings/SettingsController.hpp"

namespace archipelago::ui {

namespace {
QString quad(archipelago::quad v, int digits = 15) { return QString::fromStdString(quadText(v, digits)); }
/// A coordinate beside the point's other one (core's quadCoordinateText: a round-off zero is "0", issue 37,
/// finding 14).
QString coordinate(archipelago::quad v, archipelago::quad other, int digits) {
  return QString::fromStdString(quadCoordinateText(v, other, digits));
}
QString ld(long double v, int digits = 15) { return QString::number(static_cast<double>(v), 'g', digits); }
QString agreeing(long double d) {
  return std::isfinite(static_cast<double>(d)) ? QString::number(static_cast<double>(d), 'f', 1) : QObject::tr("all");
}
}  // namespace

ManifoldsPanel::ManifoldsPanel(PortraitController* controller, QWidget* parent)
    : QWidget(parent), controller_(controller), lobeArea_(std::numeric_limits<double>::quiet_NaN()) {
  shown_ = new QCheckBox(tr("Draw the manifolds (Ctrl+M)"), this);
  shown_->setToolTip(tr("Unstable (red) and stable (blue) manifolds, refined in the view shown; the turnstile's "
                        "lobes shaded with their area"));
  connect(shown_, &QCheckBox::toggled, controller_, &PortraitController::setManifoldsShown);
  orbit_ = new QComboBox(this);
  orbit_->setSizeAdjustPolicy(QComboBox::AdjustToMinimumContentsLengthWithIcon);
  orbit_->setMinimumContentsLength(12);
  orbit_->setToolTip(tr("Whose manifolds: the hyperbolic fixed point (√K, 0), or a hyperbolic orbit from Tools ▸ "
                        "Find Periodic Orbit (which also offers the hyperbolic partner of an island chain)"));
  connect(orbit_, qOverload<int>(&QComboBox::activated), this, [this](int index) {
    if (index == 0) controller_->setManifoldOrbit(std::nullopt);
  });
  numbers_ = new QLabel(this);
  numbers_->setObjectName(QStringLiteral("fluxNumbers"));
  numbers_->setWordWrap(true);
  numbers_->setTextInteractionFlags(Qt::TextSelectableByMouse);
  numbers_->setAlignment(Qt::AlignTop | Qt::AlignLeft);
  export_ = new QPushButton(tr("Export JSON…"), this);
  export_->setToolTip(tr("The flux as `archipelago-cli flux --json` writes it"));
  connect(export_, &QPushButton::clicked, this, [this] {
    const QString path = QFileDialog::getSaveFileName(this, tr("Export the flux as JSON"),
                                                      QDir(SettingsController::lastFolder()).filePath(QStringLiteral("flux.json")),
                                                      tr("JSON files (*.json)"));
    if (path.isEmpty()) return;
    SettingsController::rememberFolder(path);
    QString error;
    Q_EMIT statusMessage(exportJson(path, &error) ? tr("Wrote %1").arg(path) : tr("Export failed: %1").arg(error));
  });
  connect(controller_, &PortraitController::manifoldsChanged, this, &ManifoldsPanel::refresh);
  connect(controller_, &PortraitController::mapChanged, this, &ManifoldsPanel::refresh);

  auto* layout = new QVBoxLayout(this);
  layout->setContentsMargins(2, 4, 2, 2);
  layout->addWidget(shown_);
  layout->addWidget(orbit_);
  layout->addWidget(numbers_, 1);
  layout->addWidget(export_);
  refresh();
}

QString ManifoldsPanel::numbersText() const { return numbers_->text(); }

bool ManifoldsPanel::exportJson(const QString& path, QString* error) {
  const FluxPtr flux = controller_->flux();
  if (!flux || !flux->flux) {
    if (error) *error = tr("no flux computed (show the manifolds first)");
    return false;
  }
  const std::string json = turnstileJson(flux->request, *flux->flux, nullptr, nullptr, flux->seconds) + "\n";
  return publishBytes(QByteArray::fromStdString(json), path, error);
}

void ManifoldsPanel::refresh() {
  {
    const QSignalBlocker block(shown_);
    shown_->setChecked(controller_->manifoldsShown());
  }
  {
    const QSignalBlocker block(orbit_);
    orbit_->clear();
    orbit_->addItem(tr("Hyperbolic fixed point (√K, 0)"));
    if (const auto& o = controller_->manifoldOrbit()) {
      orbit_->addItem(tr("Hyperbolic orbit of period %1 (R = %2)").arg(o->period).arg(static_cast<double>(o->residue), 0, 'g', 4));
      orbit_->setCurrentIndex(1);
    }
  }
  lobeArea_ = std::numeric_limits<double>::quiet_NaN();
  export_->setEnabled(false);
  if (!controller_->manifoldsShown()) {
    numbers_->setText(tr("The stable and unstable manifolds of a hyperbolic orbit form turnstiles: lobes of equal "
                         "area that carry orbits into and out of a resonance zone each step (MacKay, Meiss & "
                         "Percival 1984). Tick the box to draw them and measure the flux."));
    return;
  }
  const FluxPtr flux = controller_->flux();
  const ManifoldsPtr curves = controller_->manifolds();
  QString text;
  if (!flux) {
    text = tr("Computing the flux…");
  } else if (!flux->flux) {
    text = tr("No flux: %1").arg(flux->error.toHtmlEscaped());
  } else {
    const TurnstileFlux& f = *flux->flux;
    lobeArea_ = static_cast<double>(f.lobeArea);
    export_->setEnabled(true);
    const HeteroclinicPoint& h = f.intersections.first;
    const HeteroclinicPoint& h2 = f.intersections.second;
    const QString kind = f.orbit.fixedPoint ? tr("homoclinic") : tr("heteroclinic");
    text = tr("<b>%1</b>, K = %2<br>"
              "multiplier λ = %3<br>"
              "%4 points h, h′: (%5, %6), (%7, %8)<br>"
              "<b>flux per step (lobe area)</b><br>"
              "&nbsp;by actions: %9<br>"
              "&nbsp;by polygon: %10 ± %11<br>"
              "&nbsp;agreeing digits: %12<br>"
              "<b>resonance zone area</b><br>"
              "&nbsp;by actions: %13<br>"
              "&nbsp;by polygon: %14<br>"
              "&nbsp;agreeing digits: %15<br>"
              "computed in %16 s")
               .arg(f.orbit.fixedPoint ? tr("Hyperbolic fixed point (√K, 0)") : tr("Hyperbolic orbit of period %1").arg(f.orbit.period))
               .arg(ld(f.orbit.K, 12))
               .arg(quad(f.orbit.multiplier, 12))
               .arg(kind)
               .arg(coordinate(h.point.x, h.point.y, 12), coordinate(h.point.y, h.point.x, 12),
                    coordinate(h2.point.x, h2.point.y, 12), coordinate(h2.point.y, h2.point.x, 12))
               .arg(quad(f.lobeAction < 0 ? -f.lobeAction : f.lobeAction, 16))
               .arg(ld(std::fabs(f.lobePolygon.area), 16))
               .arg(ld(f.lobePolygon.error, 2))
               .arg(agreeing(f.lobeDigits()))
               .arg(quad(f.zoneAction < 0 ? -f.zoneAction : f.zoneAction, 16))
               .arg(ld(std::fabs(f.zonePolygon.area), 16))
               .arg(agreeing(f.zoneDigits()))
               .arg(flux->seconds, 0, 'f', 3);
  }
  if (curves) {
    std::size_t points = 0;
    for (const auto* list : {&curves->unstable, &curves->stable})
      for (const ManifoldCurve& c : *list) points += c.points;
    text += tr("<br>manifolds in this view: %1 points in %2 s").arg(points).arg(curves->seconds, 0, 'f', 2);
  } else {
    text += tr("<br>refining the manifolds in this view…");
  }
  numbers_->setText(text);
}

}  // namespace archipelago::ui
