#include "ui/portrait/PortraitPanel.hpp"

#include <QComboBox>
#include <QFileDialog>
#include <QHBoxLayout>
#include <QLabel>
#include <QToolButton>
#include <QVBoxLayout>

#include "core/portrait/ColourMap.hpp"
#include "ui/portrait/PortraitView.hpp"
#include "ui/portrait/StochasticAreaDialog.hpp"

namespace archipelago::ui {

namespace {
QToolButton* toolButton(QWidget* parent, const QString& text, const QString& tip, const QKeySequence& key = {}) {
  auto* b = new QToolButton(parent);
  b->setText(text);
  b->setToolTip(key.isEmpty() ? tip : QStringLiteral("%1 (%2)").arg(tip, key.toString(QKeySequence::NativeText)));
  b->setAutoRaise(true);
  return b;
}
}  // namespace

PortraitPanel::PortraitPanel(QWidget* parent) : QWidget(parent) {
  view_ = new PortraitView(this);

  mode_ = new QComboBox(this);
  mode_->addItem(tr("Island orbits"), static_cast<int>(PortraitMode::Orbits));
  mode_->addItem(tr("Density of the sea"), static_cast<int>(PortraitMode::Density));
  mode_->addItem(tr("Stickiness (mean trapped length)"), static_cast<int>(PortraitMode::Stickiness));
  mode_->setToolTip(tr("Island orbits: orbits from seeds in the view (KAM curves, islands around islands).\n"
                       "Density: where long orbits of the chaotic sea go (the islands stay dark).\n"
                       "Stickiness: each pixel coloured by the mean length of the trapped segments through it (§3)."));
  connect(mode_, qOverload<int>(&QComboBox::currentIndexChanged), this,
          [this] { view_->setMode(static_cast<PortraitMode>(mode_->currentData().toInt())); });

  colours_ = new QComboBox(this);
  for (ColourMapName name : allColourMaps())
    colours_->addItem(QString::fromLatin1(toString(name).data(), static_cast<int>(toString(name).size())),
                      static_cast<int>(name));
  colours_->setToolTip(tr("Colour map of the raster"));
  connect(colours_, qOverload<int>(&QComboBox::currentIndexChanged), this,
          [this] { view_->setColourMap(static_cast<ColourMapName>(colours_->currentData().toInt())); });

  auto* back = toolButton(this, tr("◀ Back"), tr("Previous view"), QKeySequence(Qt::Key_Backspace));
  auto* forward = toolButton(this, tr("Forward ▶"), tr("Next view"));
  auto* reset = toolButton(this, tr("Reset"), tr("The whole box"), QKeySequence(Qt::Key_Home));
  auto* zoomIn = toolButton(this, tr("+"), tr("Zoom in about the centre"), QKeySequence(Qt::Key_Plus));
  auto* zoomOut = toolButton(this, tr("−"), tr("Zoom out"), QKeySequence(Qt::Key_Minus));
  auto* clear = toolButton(this, tr("Clear orbits"), tr("Remove the orbits launched by clicks"));
  auto* png = toolButton(this, tr("Export PNG…"), tr("The view with its axes, as PNG"));
  auto* npy = toolButton(this, tr("Export .npy…"), tr("The raw raster as NumPy .npy with a JSON sidecar"));
  auto* b2 = toolButton(this, tr("b₂…"), tr("Stochastic area b₂ of the sea (§5), with its convergence"));
  connect(back, &QToolButton::clicked, view_, &PortraitView::back);
  connect(forward, &QToolButton::clicked, view_, &PortraitView::forward);
  connect(reset, &QToolButton::clicked, view_, &PortraitView::resetView);
  connect(zoomIn, &QToolButton::clicked, view_, &PortraitView::zoomIn);
  connect(zoomOut, &QToolButton::clicked, view_, &PortraitView::zoomOut);
  connect(clear, &QToolButton::clicked, view_, &PortraitView::clearOrbits);
  connect(png, &QToolButton::clicked, this, &PortraitPanel::exportPngDialog);
  connect(npy, &QToolButton::clicked, this, &PortraitPanel::exportNpyDialog);
  connect(b2, &QToolButton::clicked, this, &PortraitPanel::showStochasticArea);
  connect(view_, &PortraitView::viewportChanged, this, [this, back, forward] {
    back->setEnabled(view_->canGoBack());
    forward->setEnabled(view_->canGoForward());
  });

  cursor_ = new QLabel(this);
  cursor_->setTextInteractionFlags(Qt::TextSelectableByMouse);
  connect(view_, &PortraitView::cursorMoved, cursor_, &QLabel::setText);
  connect(view_, &PortraitView::statusMessage, this, &PortraitPanel::statusMessage);

  auto* bar = new QHBoxLayout;
  bar->addWidget(new QLabel(tr("Mode:"), this));
  bar->addWidget(mode_);
  bar->addWidget(new QLabel(tr("Colours:"), this));
  bar->addWidget(colours_);
  for (QWidget* w : {static_cast<QWidget*>(back), static_cast<QWidget*>(forward), static_cast<QWidget*>(reset),
                     static_cast<QWidget*>(zoomIn), static_cast<QWidget*>(zoomOut), static_cast<QWidget*>(clear),
                     static_cast<QWidget*>(png), static_cast<QWidget*>(npy), static_cast<QWidget*>(b2)})
    bar->addWidget(w);
  bar->addStretch(1);

  auto* hint = new QLabel(tr("Drag: zoom to a rectangle · wheel: zoom about the cursor · middle-drag or arrows: pan · "
                             "click: launch an orbit"),
                          this);
  hint->setStyleSheet(QStringLiteral("color: palette(mid);"));
  auto* footer = new QHBoxLayout;
  footer->addWidget(cursor_, 1);
  footer->addWidget(hint);

  auto* layout = new QVBoxLayout(this);
  layout->setContentsMargins(4, 4, 4, 4);
  layout->addLayout(bar);
  layout->addWidget(view_, 1);
  layout->addLayout(footer);
}

void PortraitPanel::setParameters(const MapParameters& parameters, double Xr) {
  pending_ = std::make_pair(parameters, Xr);
  if (isVisible()) applyPending();
}

void PortraitPanel::applyParametersNow(const MapParameters& parameters, double Xr) {
  pending_ = std::make_pair(parameters, Xr);
  applyPending();
}

void PortraitPanel::showEvent(QShowEvent* event) {
  QWidget::showEvent(event);
  applyPending();
}

void PortraitPanel::applyPending() {
  if (!pending_) return;
  const auto [parameters, Xr] = *pending_;
  pending_.reset();
  if (parameters == parameters_ && Xr == Xr_ && view_->currentFrame()) return;
  if (view_->setParameters(parameters)) {
    parameters_ = parameters;
    Xr_ = Xr;
  }
}

void PortraitPanel::exportPngDialog() {
  const QString path = QFileDialog::getSaveFileName(this, tr("Export portrait as PNG"), QStringLiteral("portrait.png"),
                                                    tr("PNG images (*.png)"));
  if (path.isEmpty()) return;
  Q_EMIT statusMessage(view_->exportPng(path) ? tr("Wrote %1").arg(path) : tr("Could not write %1").arg(path));
}

void PortraitPanel::exportNpyDialog() {
  const QString path = QFileDialog::getSaveFileName(this, tr("Export raster as NumPy .npy"),
                                                    QStringLiteral("portrait.npy"), tr("NumPy arrays (*.npy)"));
  if (path.isEmpty()) return;
  Q_EMIT statusMessage(view_->exportNpy(path) ? tr("Wrote %1 and its JSON sidecar").arg(path)
                                              : tr("Could not write %1").arg(path));
}

void PortraitPanel::showStochasticArea() {
  StochasticAreaRequest request;
  request.map = parameters_;
  request.Xr = Xr_;
  (new StochasticAreaDialog(request, this))->show();
}

}  // namespace archipelago::ui
