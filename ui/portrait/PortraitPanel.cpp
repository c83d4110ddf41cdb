#include "ui/portrait/PortraitPanel.hpp"

#include <QAction>
#include <QActionGroup>
#include <QComboBox>
#include <QDialog>
#include <QDialogButtonBox>
#include <QFormLayout>
#include <QLineEdit>
#include <QDir>
#include <QFileDialog>
#include <QFontMetrics>
#include <QHBoxLayout>
#include <QLabel>
#include <QLocale>
#include <QMenu>
#include <QResizeEvent>
#include <QSignalBlocker>
#include <QSplitter>
#include <QTabWidget>
#include <QToolButton>
#include <QVBoxLayout>

#include <algorithm>

#include "core/io/NumberText.hpp"
#include "core/colour/ColourMap.hpp"
#include "core/limits/Limits.hpp"
#include "core/stochasticarea/StochasticArea.hpp"
#include "ui/portrait/AtlasPanel.hpp"
#include "ui/portrait/ManifoldsPanel.hpp"
#include "ui/portrait/OrbitListPanel.hpp"
#include "ui/portrait/OverflowToolBar.hpp"
#include "ui/portrait/PortraitController.hpp"
#include "ui/portrait/PortraitView.hpp"
#include "ui/portrait/RotationProfilePanel.hpp"
#include "ui/portrait/StochasticAreaDialog.hpp"
#include "ui/settings/SettingsController.hpp"

namespace archipelago::ui {

namespace {
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

struct DisplayInfo {
  PortraitDisplay display;
  const char* label;
  const char* tip;
};

const std::vector<DisplayInfo>& displayTable() {
  static const std::vector<DisplayInfo> table = {
      {{PortraitMode::Orbits, std::nullopt}, QT_TRANSLATE_NOOP("PortraitPanel", "Island orbits"),
       QT_TRANSLATE_NOOP("PortraitPanel", "Orbits from seeds in the view (KAM curves, islands around islands); the "
                                          "sea is shaded by its visits")},
      {{PortraitMode::Density, std::nullopt}, QT_TRANSLATE_NOOP("PortraitPanel", "Density of the sea"),
       QT_TRANSLATE_NOOP("PortraitPanel", "Where long orbits of the chaotic sea go (the islands stay dark)")},
      {{PortraitMode::Stickiness, std::nullopt}, QT_TRANSLATE_NOOP("PortraitPanel", "Stickiness (mean trapped length)"),
       QT_TRANSLATE_NOOP("PortraitPanel", "Each pixel coloured by the mean length of the trapped segments through it (§3)")},
      {{PortraitMode::Orbits, IndicatorKind::Dig}, QT_TRANSLATE_NOOP("PortraitPanel", "Convergence digits (dig)"),
       QT_TRANSLATE_NOOP("PortraitPanel", "Digits of the weighted Birkhoff average of an orbit from each pixel: ~14 "
                                          "regular, a few chaotic")},
      {{PortraitMode::Orbits, IndicatorKind::Rotation}, QT_TRANSLATE_NOOP("PortraitPanel", "Rotation number"),
       QT_TRANSLATE_NOOP("PortraitPanel", "Rotation number about the central fixed point of each regular orbit "
                                          "(plateaus: island chains)")},
      {{PortraitMode::Orbits, IndicatorKind::Fli}, QT_TRANSLATE_NOOP("PortraitPanel", "Fast Lyapunov indicator"),
       QT_TRANSLATE_NOOP("PortraitPanel", "FLI: max ln |v_n| of the tangent vector; grows like ln T on regular orbits")},
      {{PortraitMode::Orbits, IndicatorKind::Megno}, QT_TRANSLATE_NOOP("PortraitPanel", "MEGNO"),
       QT_TRANSLATE_NOOP("PortraitPanel", "Mean exponential growth of nearby orbits: 2 on invariant curves, 0 at "
                                          "stable periodic orbits, large if chaotic")},
      {{PortraitMode::Orbits, IndicatorKind::Lyapunov}, QT_TRANSLATE_NOOP("PortraitPanel", "Lyapunov exponent"),
       QT_TRANSLATE_NOOP("PortraitPanel", "Finite-time maximal Lyapunov exponent ln |v_T| / T, per step")},
  };
  return table;
}

QString budgetLabel(std::uint64_t points) {
  static const char* const kExponents[] = {"⁰", "¹", "²", "³", "⁴", "⁵", "⁶", "⁷", "⁸", "⁹", "¹⁰", "¹¹", "¹²"};
  std::uint64_t p = 1;
  for (int e = 0; e <= 12; ++e, p *= 10)
    if (p == points) return QStringLiteral("10%1").arg(QString::fromUtf8(kExponents[e]));
  return QLocale().toString(static_cast<double>(points), 'g', 3);
}

constexpr std::uint64_t kMaxBudget = limits::kPortraitBudget;  // the most offered (core's table)
}  // namespace

PortraitPanel::PortraitPanel(QWidget* parent) : QWidget(parent) {
  controller_ = new PortraitController(this);
  createActions();
  createMenu();
  createDisplayBoxes();
  createToolBar();
  createReadout();
  connectController();
  createHint();
  createSidePages();
  layOut();
  syncControls();
  updateReadout();
  updateActions();
}

void PortraitPanel::createDisplayBoxes() {
  mode_ = new QComboBox(this);
  for (const DisplayInfo& d : displayTable()) {
    mode_->addItem(tr(d.label));
    mode_->setItemData(mode_->count() - 1, tr(d.tip), Qt::ToolTipRole);
  }
  mode_->insertSeparator(3);
  mode_->setToolTip(tr("What the portrait shows: orbits, the sea's density, stickiness, or a chaos-indicator map"));
  // The longest item need not set the bar's (and so the window's) minimum width.
  mode_->setSizeAdjustPolicy(QComboBox::AdjustToMinimumContentsLengthWithIcon);
  mode_->setMinimumContentsLength(14);
  connect(mode_, qOverload<int>(&QComboBox::currentIndexChanged), this, [this](int index) {
    const int row = index > 3 ? index - 1 : index;  // the separator
    if (row >= 0 && row < static_cast<int>(displayTable().size())) setDisplay(displayTable()[row].display);
  });

  colours_ = new QComboBox(this);
  for (ColourMapName name : allColourMaps())
    colours_->addItem(QString::fromLatin1(toString(name).data(), static_cast<int>(toString(name).size())),
                      static_cast<int>(name));
  connect(colours_, qOverload<int>(&QComboBox::currentIndexChanged), this,
          [this] { controller_->setColourMap(static_cast<ColourMapName>(colours_->currentData().toInt())); });

  budget_ = new QComboBox(this);
  for (std::uint64_t points = 10'000'000; points <= 100'000'000'000; points *= 10)
    budget_->addItem(budgetLabel(points), QVariant::fromValue<qulonglong>(points));
  budget_->setToolTip(tr("Points budget: the portrait of a view keeps accumulating map steps until it has done "
                         "this many (or the view changes, or Stop)"));
  connect(budget_, qOverload<int>(&QComboBox::currentIndexChanged), this,
          [this] { controller_->setPointBudget(budget_->currentData().toULongLong()); });
}

void PortraitPanel::createToolBar() {
  // The tool bar: the same actions; what does not fit its width is behind », whose menu offers it.
  bar_ = new OverflowToolBar(this);
  bar_->setObjectName(QStringLiteral("portraitToolBar"));
  auto* modeLabel = new QLabel(tr("Mode: "), this);
  bar_->addItem(modeLabel, nullptr);
  bar_->addItem(mode_, modeMenu_->menuAction());
  bar_->addItem(new QLabel(tr(" Colours: "), this), nullptr);
  bar_->addItem(colours_, colourMenu_->menuAction());
  bar_->addItem(new QLabel(tr(" Points: "), this), nullptr);
  bar_->addItem(budget_, budgetMenu_->menuAction());
  bar_->addSeparator();
  stopButton_ = bar_->addAction(stop_);
  for (QAction* a : {back_, forward_, reset_, zoomIn_, zoomOut_}) bar_->addAction(a);
  bar_->addSeparator();
  for (QAction* a : {undoOrbit_, clearOrbits_, manifolds_, profileTool_, findPeriodic_}) bar_->addAction(a);
  bar_->addSeparator();
  for (QAction* a : {exportPng_, exportNpy_, b2_}) bar_->addAction(a);
}

void PortraitPanel::createReadout() {
  auto* readout = new ElidedLabel(this);
  readout_ = readout;
  readout->setObjectName(QStringLiteral("portraitReadout"));
  auto* cursor = new ElidedLabel(this);
  cursor_ = cursor;
  cursor->setTextInteractionFlags(Qt::TextSelectableByMouse);
  connect(view(), &PortraitView::cursorMoved, this, [cursor](const QString& text) { cursor->setFullText(text); });
  connect(view(), &PortraitView::renderStateChanged, this, &PortraitPanel::updateReadout);
}

void PortraitPanel::connectController() {
  PortraitController* c = controller_;
  connect(c, &PortraitController::statusMessage, this, &PortraitPanel::statusMessage);
  connect(c, &PortraitController::settingsChanged, this, &PortraitPanel::syncControls);
  connect(c, &PortraitController::viewportChanged, this, &PortraitPanel::updateActions);
  connect(c, &PortraitController::orbitsChanged, this, &PortraitPanel::updateActions);
  connect(c, &PortraitController::manifoldsChanged, this, &PortraitPanel::updateActions);
}

void PortraitPanel::createHint() {
  // The legend of the marks and the mouse: wrapped, never elided (issue 37, finding 13: at the window's first size
  // it read "○ elliptic, × hyperbolic fixed point · cl…").
  hint_ = new QLabel(this);
  hint_->setObjectName(QStringLiteral("portraitHint"));
  hint_->setWordWrap(true);
  hint_->setText(tr("○ elliptic, × hyperbolic fixed point · click: launch an orbit · Shift+click: its periodic orbit · "
                    "drag: zoom · wheel: zoom at the cursor · middle-drag or arrows: pan"));
  hint_->setToolTip(hint_->text());
  hint_->setStyleSheet(QStringLiteral("color: palette(mid);"));
}

void PortraitPanel::createSidePages() {
  PortraitController* c = controller_;
  // The side pages: launched orbits, manifolds and flux, rotation profile, the atlas (and the window's own).
  side_ = new QTabWidget(this);
  side_->setObjectName(QStringLiteral("portraitSidePages"));
  side_->setDocumentMode(true);
  orbitList_ = new OrbitListPanel(c, side_);
  manifoldsPanel_ = new ManifoldsPanel(c, side_);
  profilePanel_ = new RotationProfilePanel(c, side_);
  atlasPanel_ = new AtlasPanel(c, side_);
  side_->addTab(orbitList_, tr("Orbits"));
  side_->addTab(manifoldsPanel_, tr("Manifolds"));
  side_->addTab(profilePanel_, tr("Profile"));
  side_->addTab(atlasPanel_, tr("Atlas"));
  connect(orbitList_, &OrbitListPanel::statusMessage, this, &PortraitPanel::statusMessage);
  connect(manifoldsPanel_, &ManifoldsPanel::statusMessage, this, &PortraitPanel::statusMessage);
  connect(profilePanel_, &RotationProfilePanel::statusMessage, this, &PortraitPanel::statusMessage);
  connect(atlasPanel_, &AtlasPanel::statusMessage, this, &PortraitPanel::statusMessage);
  connect(profilePanel_, &RotationProfilePanel::toolChanged, this, [this](bool on) {
    const QSignalBlocker block(profileTool_);
    profileTool_->setChecked(on);
  });
}

void PortraitPanel::layOut() {
  auto* left = new QWidget(this);
  auto* leftLayout = new QVBoxLayout(left);
  leftLayout->setContentsMargins(0, 0, 0, 0);
  leftLayout->setSpacing(2);
  leftLayout->addWidget(view(), 1);
  leftLayout->addWidget(readout_);
  leftLayout->addWidget(cursor_);
  leftLayout->addWidget(hint_);
  splitter_ = new QSplitter(Qt::Horizontal, this);
  splitter_->setObjectName(QStringLiteral("portraitSplitter"));
  splitter_->setChildrenCollapsible(true);
  splitter_->addWidget(left);
  splitter_->addWidget(side_);
  splitter_->setStretchFactor(0, 3);
  splitter_->setStretchFactor(1, 1);
  side_->setMinimumWidth(0);

  auto* layout = new QVBoxLayout(this);
  layout->setContentsMargins(4, 2, 4, 2);
  layout->setSpacing(2);
  layout->addWidget(bar_);
  layout->addWidget(splitter_, 1);
}

QAction* PortraitPanel::viewAction(const QString& text, const QList<QKeySequence>& keys, const QString& tip) {
  // Keys that move the view act where the portrait has the focus: elsewhere (a field, the orbit list) the same
  // keys keep their own meaning.
  auto* a = new QAction(text, this);
  a->setShortcuts(keys);
  a->setShortcutContext(Qt::WidgetWithChildrenShortcut);
  a->setToolTip(keys.isEmpty() ? tip : QStringLiteral("%1 (%2)").arg(tip, keys.front().toString(QKeySequence::NativeText)));
  a->setStatusTip(tip);
  return a;
}

void PortraitPanel::createActions() {
  createViewActions();
  createViewOptionActions();
  createOrbitActions();
  createExportActions();
  // Window-wide keys (not tied to the portrait's focus) need their actions in a visible widget too.
  for (QAction* a : {raiseBudget_, undoOrbit_, clearOrbits_, manifolds_, profileTool_, exportPng_}) addAction(a);
}

void PortraitPanel::createViewActions() {
  PortraitController* c = controller_;
  PortraitView* v = view();
  // "Stop Drawing": the run's Stop is on the window's tool bar beside it (issue 37, finding 6).
  stop_ = viewAction(tr("Stop Drawing"), {QKeySequence(Qt::Key_Escape)},
                     tr("Stop accumulating the portrait's points (the run goes on); the portrait so far stays"));
  back_ = viewAction(tr("◀ Back"), {QKeySequence(Qt::ALT | Qt::Key_Left), QKeySequence(Qt::Key_Backspace)}, tr("Previous view"));
  forward_ = viewAction(tr("Forward ▶"), {QKeySequence(Qt::ALT | Qt::Key_Right)}, tr("Next view"));
  reset_ = viewAction(tr("Reset"), {QKeySequence(Qt::Key_Home)}, tr("The whole box, drawn anew"));
  zoomIn_ = viewAction(tr("+"), {QKeySequence(Qt::Key_Plus), QKeySequence(Qt::Key_Equal)}, tr("Zoom in about the centre"));
  zoomOut_ = viewAction(tr("−"), {QKeySequence(Qt::Key_Minus)}, tr("Zoom out about the centre"));
  panLeft_ = viewAction(tr("Pan Left"), {QKeySequence(Qt::Key_Left)}, tr("Move the view left by a tenth"));
  panRight_ = viewAction(tr("Pan Right"), {QKeySequence(Qt::Key_Right)}, tr("Move the view right by a tenth"));
  panUp_ = viewAction(tr("Pan Up"), {QKeySequence(Qt::Key_Up)}, tr("Move the view up by a tenth"));
  panDown_ = viewAction(tr("Pan Down"), {QKeySequence(Qt::Key_Down)}, tr("Move the view down by a tenth"));
  for (QAction* a : {stop_, back_, forward_, reset_, zoomIn_, zoomOut_, panLeft_, panRight_, panUp_, panDown_})
    v->addAction(a);
  zoomIn_->setText(tr("Zoom In (+)"));
  zoomIn_->setIconText(tr("+"));
  zoomOut_->setText(tr("Zoom Out (−)"));
  zoomOut_->setIconText(tr("−"));
  reset_->setText(tr("Reset View"));
  reset_->setIconText(tr("Reset"));
  connect(stop_, &QAction::triggered, c, &PortraitController::stopRendering);
  connect(back_, &QAction::triggered, c, &PortraitController::back);
  connect(forward_, &QAction::triggered, c, &PortraitController::forward);
  connect(reset_, &QAction::triggered, c, &PortraitController::resetView);
  connect(zoomIn_, &QAction::triggered, c, &PortraitController::zoomIn);
  connect(zoomOut_, &QAction::triggered, c, &PortraitController::zoomOut);
  connect(panLeft_, &QAction::triggered, c, [c] { c->viewLayer().panBy(-0.1, 0); });
  connect(panRight_, &QAction::triggered, c, [c] { c->viewLayer().panBy(0.1, 0); });
  connect(panUp_, &QAction::triggered, c, [c] { c->viewLayer().panBy(0, 0.1); });
  connect(panDown_, &QAction::triggered, c, [c] { c->viewLayer().panBy(0, -0.1); });
}

void PortraitPanel::createViewOptionActions() {
  PortraitController* c = controller_;
  equalAspect_ = new QAction(tr("Equal Aspect Ratio"), this);
  equalAspect_->setCheckable(true);
  equalAspect_->setChecked(true);
  equalAspect_->setStatusTip(tr("A unit of x as long on screen as a unit of y (rectangle zooms keep their shape)"));
  connect(equalAspect_, &QAction::toggled, &c->viewLayer(), &ViewLayer::setEqualAspect);

  raiseBudget_ = new QAction(tr("Raise Points Budget ×10"), this);
  raiseBudget_->setShortcut(QKeySequence(QStringLiteral("Ctrl+B")));
  raiseBudget_->setStatusTip(tr("Ten times more points for this view (a deep, sparse view fills in)"));
  connect(raiseBudget_, &QAction::triggered, this, [c] {
    c->setPointBudget(std::min<std::uint64_t>(c->pointBudget() * 10, kMaxBudget));
  });

  goTo_ = new QAction(tr("&Go to View…"), this);
  goTo_->setShortcut(QKeySequence(QStringLiteral("Ctrl+G")));
  goTo_->setStatusTip(tr("Type the view's centre and width"));
  connect(goTo_, &QAction::triggered, this, &PortraitPanel::goToDialog);
}

void PortraitPanel::goToDialog() {
  // The fields start at the current view, with every digit of its centre.
  const PhysicalRect r = controller_->viewport().physical(controller_->map());
  const PhysicalPoint centre = controller_->viewport().physicalCentre(controller_->map());
  QDialog dialog(this);
  dialog.setWindowTitle(tr("Go to View"));
  auto* form = new QFormLayout(&dialog);
  auto* x = new QLineEdit(QString::number(static_cast<double>(centre.x), 'g', 17), &dialog);
  auto* y = new QLineEdit(QString::number(static_cast<double>(centre.y), 'g', 17), &dialog);
  auto* width = new QLineEdit(QString::number(static_cast<double>(r.x1 - r.x0), 'g', 6), &dialog);
  form->addRow(tr("Centre x"), x);
  form->addRow(tr("Centre y"), y);
  form->addRow(tr("Width"), width);
  // A refused view keeps the dialog open with the reason and the typed values (issue 53, finding 21: a NaN or
  // negative width closed it, the values lost, the reason only in the status bar).
  auto* reason = new QLabel(&dialog);
  reason->setObjectName(QStringLiteral("goToViewError"));
  reason->setWordWrap(true);
  reason->setStyleSheet(QStringLiteral("color: #b00020"));
  reason->hide();
  form->addRow(reason);
  auto* buttons = new QDialogButtonBox(QDialogButtonBox::Ok | QDialogButtonBox::Cancel, &dialog);
  form->addRow(buttons);
  connect(buttons, &QDialogButtonBox::accepted, &dialog, [&] {
    QString error;
    if (goTo(x->text(), y->text(), width->text(), &error)) return dialog.accept();
    reason->setText(error);
    reason->show();
  });
  connect(buttons, &QDialogButtonBox::rejected, &dialog, &QDialog::reject);
  dialog.exec();
}

void PortraitPanel::createOrbitActions() {
  PortraitController* c = controller_;
  undoOrbit_ = new QAction(tr("Undo Last Orbit"), this);
  undoOrbit_->setShortcut(QKeySequence::Undo);
  undoOrbit_->setIconText(tr("Undo orbit"));
  undoOrbit_->setStatusTip(tr("Remove the orbit launched last"));
  connect(undoOrbit_, &QAction::triggered, c, &PortraitController::undoLastOrbit);
  clearOrbits_ = new QAction(tr("Clear Orbits"), this);
  clearOrbits_->setShortcut(QKeySequence(QStringLiteral("Ctrl+Shift+Del")));
  clearOrbits_->setStatusTip(tr("Remove every orbit launched by clicks"));
  connect(clearOrbits_, &QAction::triggered, c, [c] {
    c->clearOrbits();
    Q_EMIT c->statusMessage(tr("Launched orbits cleared"));
  });

  manifolds_ = new QAction(tr("Manifolds and Flux"), this);
  manifolds_->setCheckable(true);
  manifolds_->setShortcut(QKeySequence(QStringLiteral("Ctrl+M")));
  manifolds_->setIconText(tr("Manifolds"));
  manifolds_->setStatusTip(tr("Stable and unstable manifolds of the hyperbolic fixed point (or of the orbit found by "
                              "Tools ▸ Find Periodic Orbit), the turnstile's lobes and the flux"));
  connect(manifolds_, &QAction::toggled, this, [this](bool on) {
    controller_->setManifoldsShown(on);
    if (on) side_->setCurrentWidget(manifoldsPanel_);
  });
  // Issue 37, finding 16: the periodic orbit at a click (Shift+click always; a plain click in this mode).
  findPeriodic_ = new QAction(tr("Click Finds Periodic Orbits"), this);
  findPeriodic_->setCheckable(true);
  findPeriodic_->setIconText(tr("Find orbit"));
  findPeriodic_->setStatusTip(tr("A click (or Shift+click at any time) finds the periodic orbit there: its island chain "
                                 "named, its elliptic orbit found by Newton and drawn"));
  connect(findPeriodic_, &QAction::toggled, &c->overlayLayer(), &OverlayLayer::setClickFindsPeriodicOrbit);
  profileTool_ = new QAction(tr("Rotation Profile Tool"), this);
  profileTool_->setCheckable(true);
  profileTool_->setShortcut(QKeySequence(QStringLiteral("Ctrl+L")));
  profileTool_->setIconText(tr("Profile"));
  profileTool_->setStatusTip(tr("Drag a line on the portrait: the rotation number along it (plateaus are island chains)"));
  connect(profileTool_, &QAction::toggled, this, [this](bool on) {
    profilePanel_->setToolActive(on);
    if (on) side_->setCurrentWidget(profilePanel_);
  });
}

void PortraitPanel::createExportActions() {
  exportPng_ = new QAction(tr("Export PNG…"), this);
  exportPng_->setShortcut(QKeySequence(QStringLiteral("Ctrl+Shift+E")));
  exportPng_->setStatusTip(tr("The view with its axes and colour bar as PNG, rendered anew at the image's size"));
  connect(exportPng_, &QAction::triggered, this, &PortraitPanel::exportPngDialog);
  exportNpy_ = new QAction(tr("Export .npy…"), this);
  exportNpy_->setStatusTip(tr("The raw raster as NumPy .npy with a JSON sidecar"));
  connect(exportNpy_, &QAction::triggered, this, &PortraitPanel::exportNpyDialog);
  b2_ = new QAction(tr("b₂…"), this);
  b2_->setText(tr("Stochastic Area b₂…"));
  b2_->setIconText(tr("b₂…"));
  b2_->setStatusTip(tr("Stochastic area b₂ of the sea (§5), with its convergence"));
  connect(b2_, &QAction::triggered, this, &PortraitPanel::showStochasticArea);
}

void PortraitPanel::createMenu() {
  menu_ = new QMenu(tr("&Portrait"), this);
  modeMenu_ = menu_->addMenu(tr("&Mode"));
  modeGroup_ = new QActionGroup(this);
  int row = 0;
  for (const DisplayInfo& d : displayTable()) {
    if (row == 3) modeMenu_->addSeparator();
    QAction* a = modeMenu_->addAction(tr(d.label));
    a->setCheckable(true);
    a->setStatusTip(tr(d.tip));
    a->setData(row++);
    modeGroup_->addAction(a);
  }
  connect(modeGroup_, &QActionGroup::triggered, this,
          [this](QAction* a) { setDisplay(displayTable()[static_cast<std::size_t>(a->data().toInt())].display); });
  colourMenu_ = menu_->addMenu(tr("&Colours"));
  colourGroup_ = new QActionGroup(this);
  for (ColourMapName name : allColourMaps()) {
    QAction* a = colourMenu_->addAction(QString::fromLatin1(toString(name).data(), static_cast<int>(toString(name).size())));
    a->setCheckable(true);
    a->setData(static_cast<int>(name));
    colourGroup_->addAction(a);
  }
  connect(colourGroup_, &QActionGroup::triggered, this,
          [this](QAction* a) { controller_->setColourMap(static_cast<ColourMapName>(a->data().toInt())); });
  budgetMenu_ = menu_->addMenu(tr("Points &Budget"));
  budgetGroup_ = new QActionGroup(this);
  for (std::uint64_t points = 10'000'000; points <= 100'000'000'000; points *= 10) {
    QAction* a = budgetMenu_->addAction(budgetLabel(points));
    a->setCheckable(true);
    a->setData(QVariant::fromValue<qulonglong>(points));
    budgetGroup_->addAction(a);
  }
  connect(budgetGroup_, &QActionGroup::triggered, this,
          [this](QAction* a) { controller_->setPointBudget(a->data().toULongLong()); });
  menu_->addAction(raiseBudget_);
  menu_->addAction(stop_);
  menu_->addSeparator();
  menu_->addAction(back_);
  menu_->addAction(forward_);
  menu_->addAction(reset_);
  menu_->addAction(zoomIn_);
  menu_->addAction(zoomOut_);
  menu_->addAction(goTo_);
  QMenu* pan = menu_->addMenu(tr("P&an"));
  for (QAction* a : {panLeft_, panRight_, panUp_, panDown_}) pan->addAction(a);
  menu_->addAction(equalAspect_);
  menu_->addSeparator();
  menu_->addAction(undoOrbit_);
  menu_->addAction(clearOrbits_);
  menu_->addAction(manifolds_);
  menu_->addAction(profileTool_);
  menu_->addAction(findPeriodic_);
  menu_->addSeparator();
  menu_->addAction(exportPng_);
  menu_->addAction(exportNpy_);
  menu_->addAction(b2_);
}

PortraitView* PortraitPanel::view() const noexcept { return controller_->view(); }

bool PortraitPanel::goTo(const QString& x, const QString& y, const QString& width, QString* why) {
  const auto cx = io::parseLongDoubleC(x.trimmed().toStdString());
  const auto cy = io::parseLongDoubleC(y.trimmed().toStdString());
  const auto w = io::parseLongDoubleC(width.trimmed().toStdString());
  QString error;
  if (!cx || !cy || !w) error = tr("%1 is not a number").arg(!cx ? tr("the centre's x") : !cy ? tr("the centre's y") : tr("the width"));
  else if (controller_->goTo(*cx, *cy, *w, &error)) return true;
  if (why) *why = error;
  Q_EMIT statusMessage(tr("Go to View: %1").arg(error));
  return false;
}

QString PortraitPanel::readoutText() const { return static_cast<ElidedLabel*>(readout_)->fullText(); }

std::vector<PortraitDisplay> PortraitPanel::displays() {
  std::vector<PortraitDisplay> all;
  for (const DisplayInfo& d : displayTable()) all.push_back(d.display);
  return all;
}

PortraitDisplay PortraitPanel::display() const { return {controller_->mode(), controller_->indicator()}; }

void PortraitPanel::setDisplay(const PortraitDisplay& d) {
  if (d.indicator) {
    controller_->viewLayer().setIndicator(d.indicator);
  } else {
    controller_->viewLayer().setIndicator(std::nullopt);
    controller_->setMode(d.mode);
  }
  syncControls();
}

void PortraitPanel::updateReadout() {
  static_cast<ElidedLabel*>(readout_)->setFullText(view()->readout());
  updateActions();
}

void PortraitPanel::updateActions() {
  stop_->setEnabled(view()->isRendering());
  back_->setEnabled(controller_->canGoBack());
  forward_->setEnabled(controller_->canGoForward());
  undoOrbit_->setEnabled(controller_->orbitCount() > 0 || controller_->canUndoClear());
  undoOrbit_->setText(controller_->orbitCount() == 0 && controller_->canUndoClear() ? tr("Undo Clear Orbits")
                                                                                   : tr("Undo Last Orbit"));
  clearOrbits_->setEnabled(controller_->orbitCount() > 0);
  const bool indicator = controller_->indicator().has_value();
  raiseBudget_->setEnabled(!indicator && controller_->pointBudget() < kMaxBudget);
  budget_->setEnabled(!indicator);
  budgetMenu_->setEnabled(!indicator);
  {
    const QSignalBlocker block(manifolds_);
    manifolds_->setChecked(controller_->manifoldsShown());
  }
}

void PortraitPanel::syncControls() {
  const QSignalBlocker b1(mode_), b2(colours_), b3(budget_);
  const PortraitDisplay shown = display();
  const auto& table = displayTable();
  for (std::size_t i = 0; i < table.size(); ++i)
    if (table[i].display == shown) {
      mode_->setCurrentIndex(static_cast<int>(i >= 3 ? i + 1 : i));
      modeGroup_->actions().at(static_cast<int>(i))->setChecked(true);
    }
  colours_->setCurrentIndex(colours_->findData(static_cast<int>(controller_->colourMap())));
  for (QAction* a : colourGroup_->actions())
    if (a->data().toInt() == static_cast<int>(controller_->colourMap())) a->setChecked(true);
  const qulonglong points = controller_->pointBudget();
  int budget = budget_->findData(QVariant::fromValue(points));
  if (budget < 0) {  // a budget set by a script, a session or ×10: shown as itself
    budget_->addItem(budgetLabel(points), QVariant::fromValue(points));
    budget = budget_->count() - 1;
  }
  budget_->setCurrentIndex(budget);
  bool listed = false;
  for (QAction* a : budgetGroup_->actions())
    if (a->data().toULongLong() == points) {
      a->setChecked(true);
      listed = true;
    }
  if (!listed && budgetGroup_->checkedAction()) budgetGroup_->checkedAction()->setChecked(false);
  {
    const QSignalBlocker block(equalAspect_);
    equalAspect_->setChecked(controller_->equalAspect());
  }
  updateColourControl();
  updateActions();
}

void PortraitPanel::updateColourControl() {
  // In Orbits mode the colour map shades the sea (the island orbits keep their own hues).
  colours_->setToolTip(controller_->mode() == PortraitMode::Orbits && !controller_->indicator()
                           ? tr("Colour map of the sea's shading (island orbits keep their own hues)")
                           : tr("Colour map of the raster"));
}

void PortraitPanel::exportPngDialog() {
  const QString path = QFileDialog::getSaveFileName(this, tr("Export portrait as PNG"),
                                                    QDir(SettingsController::lastFolder()).filePath(QStringLiteral("portrait.png")),
                                                    tr("PNG images (*.png)"));
  if (path.isEmpty()) return;
  SettingsController::rememberFolder(path);
  if (!view()->exportPng(path)) Q_EMIT statusMessage(tr("Could not write %1").arg(path));
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
  controller_->viewLayer().setIndicator(std::nullopt);
  controller_->restoreSession(state, map, Xr);
  syncControls();
}

}  // namespace archipelago::ui
