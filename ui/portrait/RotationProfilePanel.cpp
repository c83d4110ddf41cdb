#include "ui/portrait/RotationProfilePanel.hpp"

#include <QComboBox>
#include <QDir>
#include <QFileDialog>
#include <QHBoxLayout>
#include <QLabel>
#include <QPainter>
#include <QPushButton>
#include <QSpinBox>
#include <QVBoxLayout>
#include <qwt_plot.h>
#include <qwt_plot_curve.h>
#include <qwt_plot_grid.h>
#include <qwt_plot_marker.h>
#include <qwt_plot_renderer.h>
#include <qwt_symbol.h>
#include <qwt_text.h>

#include <cmath>

#include "core/kernels/KernelDispatch.hpp"
#include "core/measures/PeriodicOrbitAt.hpp"
#include "core/measures/RotationPlateaus.hpp"
#include "ui/files/OutputFiles.hpp"
#include "ui/jobs/BackgroundJobs.hpp"
#include "ui/portrait/PortraitController.hpp"
#include "ui/settings/SettingsController.hpp"

namespace archipelago::ui {

RotationProfilePanel::RotationProfilePanel(PortraitController* controller, QWidget* parent)
    : QWidget(parent), controller_(controller), jobs_(std::make_unique<BackgroundJobs>(this)) {
  tool_ = new QPushButton(tr("Drag a line on the portrait (Ctrl+L)"), this);
  tool_->setCheckable(true);
  tool_->setToolTip(tr("While on, a drag on the portrait draws the line to profile instead of zooming"));
  connect(tool_, &QPushButton::toggled, this, &RotationProfilePanel::setToolActive);
  points_ = new QSpinBox(this);
  points_->setRange(2, 100000);
  points_->setValue(400);
  points_->setToolTip(tr("Orbits started along the line, each measured over 2 × 10⁴ steps"));
  about_ = new QComboBox(this);
  about_->setObjectName(QStringLiteral("profileAbout"));
  about_->addItem(tr("the centre (−√K, 0)"));
  about_->addItem(tr("the periodic orbit drawn (Shift+click an island)"));
  // Sized by a few characters, not by its longest item: the side column must not widen the window (gui.window at
  // Qt 5's 12-point font: 1108 px with the item's length).
  about_->setSizeAdjustPolicy(QComboBox::AdjustToMinimumContentsLengthWithIcon);
  about_->setMinimumContentsLength(12);
  about_->setToolTip(tr("The rotation about the central fixed point, or about an island's own centre: the member "
                        "nearest the line of the elliptic periodic orbit drawn on the portrait (Qⁿ for period n)"));
  info_ = new QLabel(tr("The rotation number about the centre of orbits started along a line: plateaus are island "
                        "chains (p/q: a chain of period q)."),
                     this);
  info_->setWordWrap(true);
  info_->setObjectName(QStringLiteral("profileInfo"));
  plot_ = new QwtPlot(this);
  plot_->setAutoReplot(false);
  plot_->setCanvasBackground(Qt::white);
  QFont small = plot_->font();
  small.setPointSizeF(small.pointSizeF() * 0.85);
  for (int axis : {QwtPlot::xBottom, QwtPlot::yLeft}) plot_->setAxisFont(axis, small);
  QwtText x(tr("position along the line (0 … 1)"));
  x.setFont(small);
  QwtText y(tr("rotation number (turns/step)"));
  y.setFont(small);
  plot_->setAxisTitle(QwtPlot::xBottom, x);
  plot_->setAxisTitle(QwtPlot::yLeft, y);
  plot_->setMinimumSize(160, 160);
  auto* grid = new QwtPlotGrid;
  grid->setMajorPen(QPen(QColor(210, 210, 210), 0));
  grid->attach(plot_);
  curve_ = new QwtPlotCurve;
  curve_->setStyle(QwtPlotCurve::Dots);
  curve_->setPen(QPen(QColor(31, 78, 154), 3));
  curve_->attach(plot_);
  csv_ = new QPushButton(tr("Export CSV…"), this);
  png_ = new QPushButton(tr("Export PNG…"), this);
  const auto exportDialog = [this](bool csv) {
    const QString suffix = csv ? QStringLiteral("csv") : QStringLiteral("png");
    const QString path = QFileDialog::getSaveFileName(
        this, csv ? tr("Export the profile as CSV") : tr("Export the profile plot as PNG"),
        QDir(SettingsController::lastFolder()).filePath(QStringLiteral("rotation_profile.") + suffix),
        csv ? tr("CSV files (*.csv)") : tr("PNG images (*.png)"));
    if (path.isEmpty()) return;
    SettingsController::rememberFolder(path);
    QString error;
    const bool ok = csv ? exportCsv(path, &error) : exportPng(path, &error);
    Q_EMIT statusMessage(ok ? tr("Wrote %1").arg(path) : tr("Export failed: %1").arg(error));
  };
  connect(csv_, &QPushButton::clicked, this, [exportDialog] { exportDialog(true); });
  connect(png_, &QPushButton::clicked, this, [exportDialog] { exportDialog(false); });
  connect(controller_->view(), &PortraitView::lineSelected, this, [this](PhysicalPoint from, PhysicalPoint to) {
    if (active_) profile(from, to, static_cast<std::uint32_t>(points_->value()));
  });
  connect(controller_, &PortraitController::mapChanged, this, [this] {
    jobs_->cancel();
    request_ = 0;
    profile_.reset();
    controller_->showProfileLine(std::nullopt);
    show();
  });

  auto* row = new QHBoxLayout;
  row->addWidget(new QLabel(tr("Orbits:"), this));
  row->addWidget(points_, 1);
  auto* aboutRow = new QHBoxLayout;
  aboutRow->addWidget(new QLabel(tr("About:"), this));
  aboutRow->addWidget(about_, 1);
  auto* exports = new QHBoxLayout;
  exports->addWidget(csv_);
  exports->addWidget(png_);
  auto* layout = new QVBoxLayout(this);
  layout->setContentsMargins(2, 4, 2, 2);
  layout->addWidget(tool_);
  layout->addLayout(row);
  layout->addLayout(aboutRow);
  layout->addWidget(info_);
  layout->addWidget(plot_, 1);
  layout->addLayout(exports);
  show();
}

RotationProfilePanel::~RotationProfilePanel() { jobs_.reset(); }

void RotationProfilePanel::setToolActive(bool on) {
  if (on == active_) return;
  active_ = on;
  {
    const QSignalBlocker block(tool_);
    tool_->setChecked(on);
  }
  controller_->view()->setLineTool(on);
  Q_EMIT statusMessage(on ? tr("Rotation profile: drag a line on the portrait") : tr("Rotation profile tool off"));
  Q_EMIT toolChanged(on);
}

bool RotationProfilePanel::profile(PhysicalPoint from, PhysicalPoint to, std::uint32_t points) {
  RotationProfileRequest r;
  r.measure.map = controller_->map();
  r.measure.kind = IndicatorKind::Rotation;
  r.from = from;
  r.to = to;
  r.points = points;
  if (about_->currentIndex() == 1) {
    const std::optional<PeriodicOrbit>& orbit = controller_->shownPeriodicOrbit();
    if (!orbit || !orbit->classification().stable()) {
      Q_EMIT statusMessage(tr("Rotation profile: no elliptic periodic orbit is drawn to measure about; Shift+click an "
                              "island to find its orbit, or measure about the centre"));
      return false;
    }
    r.about = nearestMember(*orbit, {(from.x + to.x) / 2, (from.y + to.y) / 2});
    r.power = static_cast<std::uint64_t>(orbit->period);
  }
  if (auto e = validationError(r)) {
    Q_EMIT statusMessage(tr("Rotation profile: %1").arg(QString::fromStdString(*e)));
    return false;
  }
  controller_->showProfileLine(std::make_pair(from, to));
  lastRequest_ = r;
  Job<std::shared_ptr<const RotationProfile>, double> job;  // latest wins: a new line replaces this one
  job.work = [r](JobContext<double>& context) mutable -> std::optional<std::shared_ptr<const RotationProfile>> {
    r.measure.kernel = &selectKernel();
    auto profile = std::make_shared<RotationProfile>(computeRotationProfile(
        r, [&](std::uint64_t done, std::uint64_t total) { context.progress(total ? double(done) / double(total) : 0); },
        context.stopToken()));
    if (profile->cancelled) return std::nullopt;
    return profile;
  };
  job.progress = [this](quint64 id, double fraction) {
    if (id == request_) info_->setText(tr("Measuring… %1 %").arg(100 * fraction, 0, 'f', 0));
  };
  job.done = [this](JobResult<std::shared_ptr<const RotationProfile>> result) {
    if (result.id != request_) return;
    request_ = 0;
    if (!result.ok()) {
      Q_EMIT statusMessage(tr("Rotation profile failed: %1").arg(result.error));
      return;
    }
    profile_ = *result.value;
    show();
    Q_EMIT profileReady();
  };
  request_ = jobs_->submit(std::move(job));
  info_->setText(tr("Measuring…"));
  return true;
}

void RotationProfilePanel::show() {
  QVector<QPointF> samples;
  std::size_t regular = 0, chaotic = 0, escaping = 0;
  if (profile_) {
    const std::size_t n = profile_->points.size();
    for (std::size_t i = 0; i < n; ++i) {
      const RotationProfilePoint& p = profile_->points[i];
      regular += p.measure.verdict == OrbitVerdict::Regular;
      chaotic += p.measure.verdict == OrbitVerdict::Chaotic;
      escaping += p.measure.verdict == OrbitVerdict::Escaping;
      if (std::isfinite(p.measure.value))
        samples.append(QPointF(n > 1 ? static_cast<double>(i) / static_cast<double>(n - 1) : 0.0, p.measure.value));
    }
    info_->setText(tr("%1 orbits: %2 regular (a rotation number), %3 chaotic, %4 leave the box. From (%5, %6) to (%7, %8).")
                       .arg(n)
                       .arg(regular)
                       .arg(chaotic)
                       .arg(escaping)
                       .arg(static_cast<double>(lastRequest_.from.x), 0, 'g', 8)
                       .arg(static_cast<double>(lastRequest_.from.y), 0, 'g', 8)
                       .arg(static_cast<double>(lastRequest_.to.x), 0, 'g', 8)
                       .arg(static_cast<double>(lastRequest_.to.y), 0, 'g', 8) +
                   (lastRequest_.about
                        ? tr(" About the period-%1 orbit's point (%2, %3): the rotation of Q^%1, turns per %1 steps.")
                              .arg(lastRequest_.power)
                              .arg(static_cast<double>(lastRequest_.about->x), 0, 'g', 10)
                              .arg(static_cast<double>(lastRequest_.about->y), 0, 'g', 10)
                        : QString()));
  }
  curve_->setSamples(samples);
  QwtText yTitle = plot_->axisTitle(QwtPlot::yLeft);
  yTitle.setText(profile_ && lastRequest_.about ? tr("rotation of Q^%1 about the island (turns)").arg(lastRequest_.power)
                                                : tr("rotation number (turns/step)"));
  plot_->setAxisTitle(QwtPlot::yLeft, yTitle);
  // The plateaus' p/q (issue 37, finding 17): core finds them, the plot names each above its middle.
  for (QwtPlotMarker* m : plateauMarkers_) {
    m->detach();
    delete m;
  }
  plateauMarkers_.clear();
  if (profile_) {
    const std::size_t n = profile_->points.size();
    for (const RotationPlateau& p : rotationPlateaus(*profile_)) {
      auto* marker = new QwtPlotMarker;
      QwtText label(QString::fromStdString(toString(p.rational)));
      QFont font = plot_->font();
      font.setBold(true);
      font.setPointSizeF(font.pointSizeF() * 0.85);
      label.setFont(font);
      label.setColor(QColor(160, 30, 30));
      marker->setLabel(label);
      marker->setLabelAlignment(Qt::AlignHCenter | Qt::AlignTop);
      const double mid = n > 1 ? 0.5 * static_cast<double>(p.first + p.last) / static_cast<double>(n - 1) : 0.0;
      marker->setValue(mid, p.rotation);
      marker->setSymbol(nullptr);
      marker->attach(plot_);
      plateauMarkers_.push_back(marker);
    }
  }
  csv_->setEnabled(profile_ != nullptr);
  png_->setEnabled(profile_ != nullptr);
  plot_->setAxisAutoScale(QwtPlot::yLeft, true);
  plot_->setAxisScale(QwtPlot::xBottom, 0, 1);
  plot_->replot();
}

QStringList RotationProfilePanel::plateauLabels() const {
  QStringList labels;
  for (const QwtPlotMarker* m : plateauMarkers_) labels << m->label().text();
  return labels;
}

bool RotationProfilePanel::exportCsv(const QString& path, QString* error) {
  if (!profile_) {
    if (error) *error = tr("no profile yet");
    return false;
  }
  try {
    writeRotationProfileCsv(path.toStdString(), lastRequest_, *profile_);
  } catch (const std::exception& e) {
    if (error) *error = QString::fromUtf8(e.what());
    return false;
  }
  return true;
}

bool RotationProfilePanel::exportPng(const QString& path, QString* error) {
  if (!profile_) {
    if (error) *error = tr("no profile yet");
    return false;
  }
  QImage image(QSize(900, 600), QImage::Format_ARGB32);
  image.fill(Qt::white);
  {
    QPainter painter(&image);
    QwtPlotRenderer renderer;
    renderer.render(plot_, &painter, QRectF(0, 0, 900, 600));
  }
  return writePngFile(image, path, error, rotationProfileProvenance(lastRequest_));  // its parameters (issue 54)
}

}  // namespace archipelago::ui
