#pragma once
/// \file OverlayLayer.hpp
/// \brief The portrait's overlays (one layer of PortraitController, issue 51): the selected long segment with its
/// chain's centre orbit and the step shown, the periodic-orbit overlay (the dialog's, a click's, an atlas island's
/// chain) and the rotation-profile line.  A click's periodic-orbit search runs on this layer's one job channel
/// (latest wins: another click replaces it); the items are SegmentOverlay's.

#include <QObject>
#include <QPointer>
#include <QString>
#include <QStringList>

#include <memory>
#include <optional>
#include <utility>

#include "core/measures/PeriodicOrbitAt.hpp"
#include "core/periodic/PeriodicOrbit.hpp"
#include "ui/portrait/PortraitLayers.hpp"
#include "ui/portrait/SegmentResults.hpp"

namespace archipelago::ui {

class BackgroundJobs;
class PortraitView;
class ViewLayer;

class OverlayLayer : public QObject {
  Q_OBJECT
 public:
  /// `view` gives the map a click's search is of; it outlives this layer.
  explicit OverlayLayer(const ViewLayer& view);
  ~OverlayLayer() override;

  void showSegment(const SegmentReplayPtr& replay);
  void showSegmentChain(const ChainResultPtr& chain);
  void showSegmentStep(std::size_t index);
  /// Removes the segment, its chain and its step.
  void clearSegment();
  /// A periodic orbit as the overlay (replacing the previous one).
  void showPeriodicOrbit(const PeriodicOrbit& orbit);
  [[nodiscard]] const std::optional<PeriodicOrbit>& shownPeriodicOrbit() const noexcept { return periodic_; }
  void clearPeriodicOrbit();
  /// Finds the periodic orbit at (x, y) off the GUI thread (core's periodicOrbitAt), drawn as the overlay.
  void findPeriodicOrbitAt(long double x, long double y);
  void setClickFindsPeriodicOrbit(bool on) { clickFindsPeriodic_ = on; }
  [[nodiscard]] bool clickFindsPeriodicOrbit() const noexcept { return clickFindsPeriodic_; }
  [[nodiscard]] std::shared_ptr<const PeriodicOrbitAt> clickedPeriodicOrbit() const noexcept { return clickedPeriodic_; }
  [[nodiscard]] bool periodicSearchPending() const noexcept { return periodicRequest_ != 0; }
  /// The words of what a click found: "Period 6, elliptic (residue 0.36): 1/6 about the centre; …".
  [[nodiscard]] static QString periodicOrbitText(const PeriodicOrbitAt& found);
  /// The rotation-profile line (none: hidden).
  void showProfileLine(std::optional<std::pair<PhysicalPoint, PhysicalPoint>> line);
  /// The legend's lines for the segment, its chain, the periodic overlay and what a click found.
  [[nodiscard]] std::vector<LegendLine> legendLines() const;

 Q_SIGNALS:
  /// A click's search ended: `text` says what it found, or why nothing.
  void periodicOrbitFound(const QString& text);
  void legendChanged();
  void statusMessage(const QString& text);

 private:
  void onPeriodicOrbitFound(long double x, long double y, const std::shared_ptr<const PeriodicOrbitAt>& found,
                            const QString& error);

  const ViewLayer& viewLayer_;
  QPointer<PortraitView> view_;
  SegmentReplayPtr replay_;
  ChainResultPtr chain_;
  std::optional<PeriodicOrbit> periodic_;                   // the overlay
  std::shared_ptr<const PeriodicOrbitAt> clickedPeriodic_;  // the last a click found
  quint64 periodicRequest_ = 0;
  bool clickFindsPeriodic_ = false;
  // Last member: destroyed first, it stops the job and joins its thread while everything it uses lives.
  std::unique_ptr<BackgroundJobs> jobs_;
};

}  // namespace archipelago::ui
