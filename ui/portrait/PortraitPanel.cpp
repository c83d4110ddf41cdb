#include "ui/portrait/PortraitPanel.hpp"

#include <QComboBox>
#include <QDir>
#include <QLocale>
#include <QFileDialog>
#include <QFontMetrics>
#include <QHBoxLayout>
#include <QLabel>
#include <QLocale>
#include <QSignalBlocker>
#include <QResizeEvent>
#include <QToolBar>
#include <QToolButton>
#include <QVBoxLayout>

#include "core/portrait/ColourMap.hpp"
#include "core/portrait/StochasticArea.hpp"
#include "ui/settings/SettingsController.hpp"
#include "ui/portrait/PortraitController.hpp"
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

/// A one-line label that shows its text elided to the width it is given and never asks for more: a longer
/// text does not grow the window's minimum width.
class ElidedLabel : public QLabel {
 public:
  explicit ElidedLabel(QWidget* parent) : QLabel(parent) {
    setSizePolicy(QSizePolicy::Ignored, QSizePolicy::Fixed);
    setMinimumWidth(0);
  }
  void setFullText(const QString& text) {
    full_ = text;
    setToolTip(text);
    refresh();
  }
  [[nodiscard]] const QString& fullText() const noexcept { return full_; }
  QSize minimumSizeHint() const override { return {0, QLabel::minimumSizeHint().height()}; }
  QSize sizeHint() const override { return {0, QLabel::sizeHint().height()}; }

 protected:
  void resizeEvent(QResizeEvent* event) override {
    QLabel::resizeEvent(event);
    refresh();
  }

 private:
  void refresh() { setText(fontMetrics().elidedText(full_, Qt::ElideRight, std::max(width(), 0))); }
  QString full_;
};
}  // namespace

PortraitPanel::PortraitPanel(QWidget* parent) : QWidget(parent) {
  controller_ = new PortraitController(this);
  PortraitController* c = controller_;

  mode_ = new QComboBox(this);
  mode_->addItem(tr("Island orbits"), static_cast<int>(PortraitMode::Orbits));
  mode_->addItem(tr("Density of the sea"), static_cast<int>(PortraitMode::Density));
  mode_->addItem(tr("Stickiness (mean trapped length)"), static_cast<int>(PortraitMode::Stickiness));
  mode_->setToolTip(tr("Island orbits: orbits from seeds in the view (KAM curves, islands around islands); the sea "
                       "is shaded by its visits.\n"
                       "Density: where long orbits of the chaotic sea go (the islands stay dark).\n"
                       "Stickiness: each pixel coloured by the mean length of the trapped segments through it (§3)."));
  // The longest item need not set the toolbar's (and so the window's) minimum width.
  mode_->setSizeAdjustPolicy(QComboBox::AdjustToMinimumContentsLengthWithIcon);
  mode_->setMinimumContentsLength(14);
  connect(mode_, qOverload<int>(&QComboBox::currentIndexChanged), this, [this] {
    controller_->setMode(static_cast<PortraitMode>(mode_->currentData().toInt()));
    updateColourControl();
  });

  colours_ = new QComboBox(this);
  for (ColourMapName name : allColourMaps())
    colours_->addItem(QString::fromLatin1(toString(name).data(), static_cast<int>(toString(name).size())),
                      static_cast<int>(name));
  connect(colours_, qOverload<int>(&QComboBox::currentIndexChanged), this,
          [this] { controller_->setColourMap(static_cast<ColourMapName>(colours_->currentData().toInt())); });

  budget_ = new QComboBox(this);
  qulonglong points = 1'000'000;
  for (const char* exponent : {"⁷", "⁸", "⁹", "¹⁰", "¹¹"}) {
    points *= 10;
    budget_->addItem(QStringLiteral("10%1").arg(QString::fromUtf8(exponent)), QVariant::fromValue(points));
  }
  budget_->setToolTip(tr("Points budget: the portrait of a view keeps accumulating map steps until it has done "
                         "this many (or the view changes, or Stop)"));
  budget_->setCurrentIndex(budget_->findData(QVariant::fromValue<qulonglong>(c->pointBudget())));
  connect(budget_, qOverload<int>(&QComboBox::currentIndexChanged), this,
          [this] { controller_->setPointBudget(budget_->currentData().toULongLong()); });

  stop_ = toolButton(this, tr("Stop"), tr("Stop accumulating points; the portrait so far stays"));
  connect(stop_, &QToolButton::clicked, c, &PortraitController::stopRendering);

  auto* back = toolButton(this, tr("◀ Back"), tr("Previous view"), QKeySequence(Qt::Key_Backspace));
  auto* forward = toolButton(this, tr("Forward ▶"), tr("Next view"));
  auto* reset = toolButton(this, tr("Reset"), tr("The whole box, drawn anew"), QKeySequence(Qt::Key_Home));
  auto* zoomIn = toolButton(this, tr("+"), tr("Zoom in about the centre"), QKeySequence(Qt::Key_Plus));
  auto* zoomOut = toolButton(this, tr("−"), tr("Zoom out"), QKeySequence(Qt::Key_Minus));
  auto* clear = toolButton(this, tr("Clear orbits"), tr("Remove the orbits launched by clicks"));
  auto* png = toolButton(this, tr("Export PNG…"), tr("The view with its axes, as PNG"));
  auto* npy = toolButton(this, tr("Export .npy…"), tr("The raw raster as NumPy .npy with a JSON sidecar"));
  auto* b2 = toolButton(this, tr("b₂…"), tr("Stochastic area b₂ of the sea (§5), with its convergence"));
  connect(back, &QToolButton::clicked, c, &PortraitController::back);
  connect(forward, &QToolButton::clicked, c, &PortraitController::forward);
  connect(reset, &QToolButton::clicked, c, &PortraitController::resetView);
  connect(zoomIn, &QToolButton::clicked, c, &PortraitController::zoomIn);
  connect(zoomOut, &QToolButton::clicked, c, &PortraitController::zoomOut);
  connect(clear, &QToolButton::clicked, c, &PortraitController::clearOrbits);
  connect(png, &QToolButton::clicked, this, &PortraitPanel::exportPngDialog);
  connect(npy, &QToolButton::clicked, this, &PortraitPanel::exportNpyDialog);
  connect(b2, &QToolButton::clicked, this, &PortraitPanel::showStochasticArea);
  auto updateHistory = [c, back, forward] {
    back->setEnabled(c->canGoBack());
    forward->setEnabled(c->canGoForward());
  };
  connect(c, &PortraitController::viewportChanged, this, updateHistory);
  updateHistory();

  auto* readout = new ElidedLabel(this);
  readout_ = readout;
  auto* cursor = new ElidedLabel(this);
  cursor_ = cursor;
  cursor->setTextInteractionFlags(Qt::TextSelectableByMouse);
  connect(view(), &PortraitView::cursorMoved, this, [cursor](const QString& text) { cursor->setFullText(text); });
  connect(view(), &PortraitView::renderStateChanged, this, &PortraitPanel::updateReadout);
  connect(c, &PortraitController::statusMessage, this, &PortraitPanel::statusMessage);
  connect(c, &PortraitController::settingsChanged, this, &PortraitPanel::syncControls);

  // A tool bar: what does not fit the width goes behind its » button, so the controls never set the
  // window's minimum width (a 1280 × 800 screen, or a narrow window beside another).
  auto* bar = new QToolBar(this);
  bar->setObjectName(QStringLiteral("portraitToolBar"));
  bar->setIconSize(QSize(16, 16));
  bar->addWidget(new QLabel(tr("Mode: "), this));
  bar->addWidget(mode_);
  bar->addWidget(new QLabel(tr(" Colours: "), this));
  bar->addWidget(colours_);
  bar->addWidget(new QLabel(tr(" Points: "), this));
  bar->addWidget(budget_);
  bar->addSeparator();
  for (QToolButton* w : {stop_, back, forward, reset, zoomIn, zoomOut, clear, png, npy, b2}) {
    w->setAutoRaise(true);
    bar->addWidget(w);
  }

  auto* hint = new ElidedLabel(this);
  hint->setFullText(tr("Drag: zoom to a rectangle · wheel: zoom about the cursor · middle-drag or arrows: pan · "
                       "click: launch an orbit"));
  hint->setStyleSheet(QStringLiteral("color: palette(mid);"));
  auto* footer = new QHBoxLayout;
  footer->addWidget(readout_, 3);
  footer->addWidget(cursor_, 3);
  footer->addWidget(hint, 2);

  auto* layout = new QVBoxLayout(this);
  layout->setContentsMargins(4, 4, 4, 4);
  layout->addWidget(bar);
  layout->addWidget(view(), 1);
  layout->addLayout(footer);
  updateColourControl();
  updateReadout();
}

PortraitView* PortraitPanel::view() const noexcept { return controller_->view(); }

QString PortraitPanel::readoutText() const { return static_cast<ElidedLabel*>(readout_)->fullText(); }

void PortraitPanel::updateReadout() {
  static_cast<ElidedLabel*>(readout_)->setFullText(view()->readout());
  stop_->setEnabled(view()->isRendering());
}

void PortraitPanel::syncControls() {
  const QSignalBlocker b1(mode_), b2(colours_), b3(budget_);
  mode_->setCurrentIndex(mode_->findData(static_cast<int>(controller_->mode())));
  colours_->setCurrentIndex(colours_->findData(static_cast<int>(controller_->colourMap())));
  const int budget = budget_->findData(QVariant::fromValue<qulonglong>(controller_->pointBudget()));
  if (budget < 0) {  // a budget set by a script or a session: shown as itself
    budget_->addItem(QLocale().toString(static_cast<double>(controller_->pointBudget()), 'g', 3),
                     QVariant::fromValue<qulonglong>(controller_->pointBudget()));
    budget_->setCurrentIndex(budget_->count() - 1);
  } else {
    budget_->setCurrentIndex(budget);
  }
  updateColourControl();
}

void PortraitPanel::updateColourControl() {
  // In Orbits mode the colour map shades the sea (the island orbits keep their own hues).
  colours_->setToolTip(controller_->mode() == PortraitMode::Orbits
                           ? tr("Colour map of the sea's shading (island orbits keep their own hues)")
                           : tr("Colour map of the raster"));
}

void PortraitPanel::exportPngDialog() {
  const QString path = QFileDialog::getSaveFileName(this, tr("Export portrait as PNG"),
                                                    QDir(SettingsController::lastFolder()).filePath(QStringLiteral("portrait.png")),
                                                    tr("PNG images (*.png)"));
  if (path.isEmpty()) return;
  SettingsController::rememberFolder(path);
  Q_EMIT statusMessage(view()->exportPng(path) ? tr("Wrote %1").arg(path) : tr("Could not write %1").arg(path));
}

void PortraitPanel::exportNpyDialog() {
  const QString path = QFileDialog::getSaveFileName(this, tr("Export raster as NumPy .npy"),
                                                    QDir(SettingsController::lastFolder()).filePath(QStringLiteral("portrait.npy")),
                                                    tr("NumPy arrays (*.npy)"));
  if (path.isEmpty()) return;
  SettingsController::rememberFolder(path);
  Q_EMIT statusMessage(view()->exportNpy(path) ? tr("Wrote %1 and its JSON sidecar").arg(path)
                                               : tr("Could not write %1").arg(path));
}

void PortraitPanel::showStochasticArea() {
  StochasticAreaRequest request;
  request.map = controller_->map();
  request.Xr = controller_->Xr();
  (new StochasticAreaDialog(request, this))->show();
}

SessionPortrait PortraitPanel::sessionState() const { return controller_->sessionState(); }

void PortraitPanel::restoreSessionState(const SessionPortrait& state, const MapParameters& map, double Xr) {
  const auto select = [](QComboBox* box, const QVariant& value, const QString& label) {
    int i = box->findData(value);
    if (i < 0) {
      box->addItem(label, value);
      i = box->count() - 1;
    }
    box->setCurrentIndex(i);
  };
  select(mode_, static_cast<int>(state.mode), QString::fromLatin1(toString(state.mode).data()));
  select(colours_, static_cast<int>(state.colours), QString::fromLatin1(toString(state.colours).data()));
  if (state.budget > 0)
    select(budget_, QVariant::fromValue<qulonglong>(state.budget), QLocale().toString(static_cast<qulonglong>(state.budget)));
  controller_->restoreSession(state, map, Xr);
}

}  // namespace archipelago::ui
