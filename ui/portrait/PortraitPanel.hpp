#pragma once
// The "Phase portrait" tab: the portrait (its PortraitController and view) with its controls, its side pages
// (launched orbits, manifolds and flux, rotation profile, and any page the window adds) and its readout.
//
// Every control is a QAction of the Portrait menu (menu()): modes (the portrait's three and the chaos-indicator
// maps), colour maps, points budget, Stop, Back/Forward, Reset, zoom, pan, equal aspect, Undo/Clear orbits, the
// manifolds layer, the rotation-profile tool, Export PNG/.npy and b₂ (issue 25, deliverable 2).  The tool bar
// above the portrait shows the same actions; what does not fit its width goes behind its » button, whose menu
// offers them (issue 25, finding 1).  The keys that move the view (arrows, +, −, Home, Backspace, Alt+←/→, Esc)
// act when the portrait has the focus; the mouse entering the portrait gives it the focus.
//
// The readout and the cursor position are elided to the width they get: a longer text (more digits at a deep
// zoom) never widens the window.

#include <QWidget>

#include <optional>
#include <vector>

#include "core/map/MapParameters.hpp"
#include "core/measures/OrbitMeasures.hpp"
#include "core/portrait/PortraitRaster.hpp"
#include "core/session/SessionFile.hpp"

class QAction;
class QActionGroup;
class QComboBox;
class QLabel;
class QMenu;
class QSplitter;
class QTabWidget;
class QToolButton;

namespace archipelago::ui {

class AtlasPanel;
class ManifoldsPanel;
class OrbitListPanel;
class OverflowToolBar;
class PortraitController;
class PortraitView;
class RotationProfilePanel;

/// What the portrait shows: one of core's portrait modes, or a chaos-indicator map (core/measures).
struct PortraitDisplay {
  PortraitMode mode = PortraitMode::Orbits;
  std::optional<IndicatorKind> indicator;
  friend bool operator==(const PortraitDisplay&, const PortraitDisplay&) = default;
};

class PortraitPanel : public QWidget {
  Q_OBJECT
 public:
  explicit PortraitPanel(QWidget* parent = nullptr);

  /// The owner of the portrait: set its map, view and layers through it.
  [[nodiscard]] PortraitController* controller() const noexcept { return controller_; }
  [[nodiscard]] PortraitView* view() const noexcept;
  /// The Portrait menu: every action of the portrait (the window puts it in its menu bar).
  [[nodiscard]] QMenu* menu() const noexcept { return menu_; }
  [[nodiscard]] OverflowToolBar* toolBar() const noexcept { return bar_; }
  /// The points budget choices, in points (tests).
  [[nodiscard]] QComboBox* budgetBox() const noexcept { return budget_; }
  [[nodiscard]] QComboBox* modeBox() const noexcept { return mode_; }
  [[nodiscard]] QToolButton* stopButton() const noexcept { return stopButton_; }
  [[nodiscard]] QComboBox* colourBox() const noexcept { return colours_; }
  /// Actions by their use (tests, the window's shortcut list).
  [[nodiscard]] QAction* exportPngAction() const noexcept { return exportPng_; }
  [[nodiscard]] QAction* exportNpyAction() const noexcept { return exportNpy_; }
  [[nodiscard]] QAction* stochasticAreaAction() const noexcept { return b2_; }
  [[nodiscard]] QAction* undoOrbitAction() const noexcept { return undoOrbit_; }
  /// Portrait ▸ Go to View… (Ctrl+G): a view typed as centre and width (issue 37, finding 18).
  [[nodiscard]] QAction* goToAction() const noexcept { return goTo_; }
  /// What the dialog does with its three fields (decimal text, every digit kept): false, with the reason in the
  /// status bar and `error` (the dialog shows it and stays open), when one is not a number or the view is refused.
  bool goTo(const QString& x, const QString& y, const QString& width, QString* error = nullptr);
  [[nodiscard]] QAction* clearOrbitsAction() const noexcept { return clearOrbits_; }
  [[nodiscard]] QAction* raiseBudgetAction() const noexcept { return raiseBudget_; }
  [[nodiscard]] QAction* equalAspectAction() const noexcept { return equalAspect_; }
  [[nodiscard]] QAction* manifoldsAction() const noexcept { return manifolds_; }
  [[nodiscard]] QAction* profileToolAction() const noexcept { return profileTool_; }
  [[nodiscard]] QAction* findPeriodicAction() const noexcept { return findPeriodic_; }
  [[nodiscard]] QAction* resetAction() const noexcept { return reset_; }
  /// The modes offered (the mode box's order) and the one shown.
  [[nodiscard]] static std::vector<PortraitDisplay> displays();
  [[nodiscard]] PortraitDisplay display() const;
  void setDisplay(const PortraitDisplay& display);

  /// The side pages beside the portrait: launched orbits, manifolds and flux, rotation profile, the atlas of the
  /// islands; the window adds its own (the live f_t and C_τ of the run).
  [[nodiscard]] QTabWidget* sidePages() const noexcept { return side_; }
  [[nodiscard]] OrbitListPanel* orbitList() const noexcept { return orbitList_; }
  [[nodiscard]] ManifoldsPanel* manifoldsPanel() const noexcept { return manifoldsPanel_; }
  [[nodiscard]] RotationProfilePanel* profilePanel() const noexcept { return profilePanel_; }
  /// The Atlas page (issue 38): its atlas is part of a session (SessionController saves and restores it).
  [[nodiscard]] AtlasPanel* atlasPanel() const noexcept { return atlasPanel_; }
  /// The splitter between the portrait and the side pages.
  [[nodiscard]] QSplitter* splitter() const noexcept { return splitter_; }

  /// The readout's full text (the label may show it elided).
  [[nodiscard]] QString readoutText() const;
  /// The portrait's part of a session; restoring it sets the mode, colour and budget boxes too.
  [[nodiscard]] SessionPortrait sessionState() const;
  void restoreSessionState(const SessionPortrait& state, const MapParameters& map, double Xr);

 public Q_SLOTS:
  void exportPngDialog();
  void exportNpyDialog();
  void showStochasticArea();

 Q_SIGNALS:
  void statusMessage(const QString& text);

 private:
  /// The actions, by their use: the view's (Stop Drawing, Back/Forward, Reset, zoom, pan: keys of the portrait's
  /// focus), the view's options (equal aspect, budget ×10, Go to View…), the launched orbits' and the tools' (Undo,
  /// Clear, Manifolds, Click Finds Periodic Orbits, Rotation Profile), the exports (PNG, .npy, b₂).
  void createActions();
  void createViewActions();
  void createViewOptionActions();
  void createOrbitActions();
  void createExportActions();
  /// Portrait ▸ Go to View…: the dialog of the view's centre and width (goTo() does what it asks).
  void goToDialog();
  void createMenu();
  /// The constructor's steps after the actions and the menu, in the order the widgets are made (the order of the
  /// Tab chain): the mode, colour and budget boxes; the tool bar; the readout and the cursor position; the
  /// controller's signals; the legend of the marks; the side pages; then the splitter and the layout.
  void createDisplayBoxes();
  void createToolBar();
  void createReadout();
  void connectController();
  void createHint();
  void createSidePages();
  void layOut();
  void updateReadout();
  void updateColourControl();
  void updateActions();
  /// The mode, colour and budget boxes and actions show the controller's settings.
  void syncControls();
  QAction* viewAction(const QString& text, const QList<QKeySequence>& keys, const QString& tip);

  PortraitController* controller_ = nullptr;
  QMenu* menu_ = nullptr;
  OverflowToolBar* bar_ = nullptr;
  QComboBox* mode_ = nullptr;
  QComboBox* colours_ = nullptr;
  QComboBox* budget_ = nullptr;
  QToolButton* stopButton_ = nullptr;
  QLabel* readout_ = nullptr;
  QLabel* cursor_ = nullptr;
  QLabel* hint_ = nullptr;
  QSplitter* splitter_ = nullptr;
  QTabWidget* side_ = nullptr;
  OrbitListPanel* orbitList_ = nullptr;
  ManifoldsPanel* manifoldsPanel_ = nullptr;
  RotationProfilePanel* profilePanel_ = nullptr;
  AtlasPanel* atlasPanel_ = nullptr;

  QActionGroup* modeGroup_ = nullptr;
  QActionGroup* colourGroup_ = nullptr;
  QActionGroup* budgetGroup_ = nullptr;
  QAction* stop_ = nullptr;
  QAction* goTo_ = nullptr;
  QAction* back_ = nullptr;
  QAction* forward_ = nullptr;
  QAction* reset_ = nullptr;
  QAction* zoomIn_ = nullptr;
  QAction* zoomOut_ = nullptr;
  QAction* panLeft_ = nullptr;
  QAction* panRight_ = nullptr;
  QAction* panUp_ = nullptr;
  QAction* panDown_ = nullptr;
  QAction* equalAspect_ = nullptr;
  QAction* raiseBudget_ = nullptr;
  QAction* undoOrbit_ = nullptr;
  QAction* clearOrbits_ = nullptr;
  QAction* manifolds_ = nullptr;
  QAction* profileTool_ = nullptr;
  QAction* findPeriodic_ = nullptr;
  QAction* exportPng_ = nullptr;
  QAction* exportNpy_ = nullptr;
  QAction* b2_ = nullptr;
  QMenu* modeMenu_ = nullptr;
  QMenu* colourMenu_ = nullptr;
  QMenu* budgetMenu_ = nullptr;
};

}  // namespace archipelago::ui
