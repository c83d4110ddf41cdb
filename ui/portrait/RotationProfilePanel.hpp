#pragma once
/// \file RotationProfilePanel.hpp
/// \brief The "Profile" page beside the portrait: the rotation-profile tool (issue 27, deliverable 3).  With the
/// tool on, a line dragged on the portrait gives the rotation number about the centre of the orbits started
/// along it, against the position on the line; plateaus are island chains (1/6: the paper's six islands).
///
/// The profile is core's (core/measures/RotationProfile: computeRotationProfile, writeRotationProfileCsv, the same
/// as `archipelago-cli rotation --line … --csv`), computed by a background job of this page (ui/jobs; a new line
/// replaces the profile in progress).  The line is drawn on the portrait by its controller.  Exports: the CSV
/// (core's writer) and the plot as PNG.

#include <QWidget>

#include <memory>
#include <optional>
#include <vector>

#include <QStringList>

#include "core/measures/RotationProfile.hpp"

class QComboBox;
class QLabel;
class QPushButton;
class QSpinBox;
class QwtPlot;
class QwtPlotCurve;
class QwtPlotMarker;

namespace archipelago::ui {

class BackgroundJobs;
class PortraitController;

class RotationProfilePanel : public QWidget {
  Q_OBJECT
 public:
  RotationProfilePanel(PortraitController* controller, QWidget* parent = nullptr);
  ~RotationProfilePanel() override;

  /// While active, a drag on the portrait draws a line and profiles it (instead of zooming).
  void setToolActive(bool on);
  [[nodiscard]] bool toolActive() const noexcept { return active_; }
  /// Profiles the line from `from` to `to` (physical coordinates) with `points` starts, about the centre the
  /// About box names: (−√K, 0), or the member nearest the line's middle of the elliptic periodic orbit drawn on the
  /// portrait (a Shift+click finds one; issue 37, finding 17).  False (the reason in the status bar) when the
  /// request is refused, e.g. no elliptic periodic orbit is drawn.
  bool profile(PhysicalPoint from, PhysicalPoint to, std::uint32_t points);
  /// The About box: 0 the centre (−√K, 0), 1 the periodic orbit drawn.
  [[nodiscard]] QComboBox* aboutBox() const noexcept { return about_; }
  /// The request of the profile shown or computing (its `about` and `power` when about an island).
  [[nodiscard]] const RotationProfileRequest& lastRequest() const noexcept { return lastRequest_; }
  /// The profile shown (null while none), and whether a computation is running (tests).
  [[nodiscard]] const RotationProfile* currentProfile() const noexcept { return profile_.get(); }
  [[nodiscard]] bool busy() const noexcept { return request_ != 0; }
  [[nodiscard]] QwtPlot* plot() const noexcept { return plot_; }
  /// The p/q labels drawn on the plateaus (core's rotationPlateaus; issue 37, finding 17), left to right.
  [[nodiscard]] QStringList plateauLabels() const;
  bool exportCsv(const QString& path, QString* error = nullptr);
  bool exportPng(const QString& path, QString* error = nullptr);

 Q_SIGNALS:
  void statusMessage(const QString& text);
  void toolChanged(bool on);
  void profileReady();

 private:
  void show();

  PortraitController* controller_;
  bool active_ = false;
  QPushButton* tool_ = nullptr;
  QSpinBox* points_ = nullptr;
  QComboBox* about_ = nullptr;
  QLabel* info_ = nullptr;
  QwtPlot* plot_ = nullptr;
  QwtPlotCurve* curve_ = nullptr;
  std::vector<QwtPlotMarker*> plateauMarkers_;  // owned by plot_
  QPushButton* csv_ = nullptr;
  QPushButton* png_ = nullptr;
  RotationProfileRequest lastRequest_;
  std::shared_ptr<const RotationProfile> profile_;
  quint64 request_ = 0;
  std::unique_ptr<BackgroundJobs> jobs_;  // last: stopped and joined first
};

}  // namespace archipelago::ui
