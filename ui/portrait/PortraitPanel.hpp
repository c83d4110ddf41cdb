#pragma once
// The "Phase portrait" tab: the portrait (its PortraitController and view) with its controls — mode, colour
// map, points budget, Stop, history, exports — the readout of the render (points so far, accumulating /
// done / stopped / no sea here), the cursor position and the stochastic-area (b₂) dialog.
//
// The readout and the cursor position are elided to the width they get: a longer text (more digits at a deep
// zoom) never widens the window.

#include <QWidget>

#include "core/session/SessionFile.hpp"

#include "core/map/MapParameters.hpp"

class QComboBox;
class QLabel;
class QToolButton;

namespace archipelago::ui {

class PortraitController;
class PortraitView;

class PortraitPanel : public QWidget {
  Q_OBJECT
 public:
  explicit PortraitPanel(QWidget* parent = nullptr);

  /// The owner of the portrait: set its map, view and layers through it.
  [[nodiscard]] PortraitController* controller() const noexcept { return controller_; }
  [[nodiscard]] PortraitView* view() const noexcept;
  /// The points budget choices, in points (tests).
  [[nodiscard]] QComboBox* budgetBox() const noexcept { return budget_; }
  [[nodiscard]] QToolButton* stopButton() const noexcept { return stop_; }
  [[nodiscard]] QComboBox* colourBox() const noexcept { return colours_; }
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
  void updateReadout();
  void updateColourControl();
  /// The mode, colour and budget boxes show the controller's settings.
  void syncControls();

  PortraitController* controller_ = nullptr;
  QComboBox* mode_ = nullptr;
  QComboBox* colours_ = nullptr;
  QComboBox* budget_ = nullptr;
  QToolButton* stop_ = nullptr;
  QLabel* readout_ = nullptr;
  QLabel* cursor_ = nullptr;
};

}  // namespace archipelago::ui
