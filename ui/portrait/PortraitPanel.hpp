#pragma once
// The "Phase portrait" tab: the PortraitView with its controls (mode, colour map, history, exports) and the
// stochastic-area (b₂) dialog.  The map parameters follow the main window's parameter panel.

#include <QWidget>
#include <optional>
#include <utility>

#include "core/map/MapParameters.hpp"

class QComboBox;
class QLabel;

namespace archipelago::ui {

class PortraitView;

class PortraitPanel : public QWidget {
  Q_OBJECT
 public:
  explicit PortraitPanel(QWidget* parent = nullptr);

  [[nodiscard]] PortraitView* view() const noexcept { return view_; }
  /// Shows the portrait of these parameters (ignored when invalid; the panel keeps the last valid map).
  /// While the panel is hidden the parameters wait, so no portrait is computed for nothing.
  void setParameters(const MapParameters& parameters, double Xr);
  /// The same, applied at once even while hidden (a caller that zooms the view right after needs the map set
  /// first, or the pending parameters would later reset its zoom).
  void applyParametersNow(const MapParameters& parameters, double Xr);

 public Q_SLOTS:
  void exportPngDialog();
  void exportNpyDialog();
  void showStochasticArea();

 Q_SIGNALS:
  void statusMessage(const QString& text);

 protected:
  void showEvent(QShowEvent* event) override;

 private:
  void applyPending();

  PortraitView* view_ = nullptr;
  QComboBox* mode_ = nullptr;
  QComboBox* colours_ = nullptr;
  QLabel* cursor_ = nullptr;
  MapParameters parameters_;
  double Xr_ = 0.02;
  std::optional<std::pair<MapParameters, double>> pending_;
};

}  // namespace archipelago::ui
