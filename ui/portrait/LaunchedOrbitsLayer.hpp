#pragma once
/// \file LaunchedOrbitsLayer.hpp
/// \brief The orbits launched on the portrait (one layer of PortraitController, issue 51): launched, traced,
/// measured, highlighted with their chain's elliptic orbit, removed, cleared and brought back.
///
/// Its jobs (ui/jobs/BackgroundJobs): each orbit is traced once on a queue (drawn as it arrives, never recomputing
/// the earlier ones — issue #23, finding 5) and measured on a niced queue (the rotation number and chain, issue
/// #27), exactly as `archipelago-cli orbit` and `rotation` compute them.  No maths here.

#include <QObject>
#include <QPointer>
#include <QString>

#include <cstdint>
#include <memory>
#include <vector>

#include "core/session/OrbitFamily.hpp"
#include "ui/portrait/LaunchedOrbits.hpp"

class QwtPlotItem;

namespace archipelago::ui {

class BackgroundJobs;
class PortraitView;
class ViewLayer;

class LaunchedOrbitsLayer : public QObject {
  Q_OBJECT
 public:
  /// `view` gives the map the orbits are of and the PortraitView they are drawn on; it outlives this layer.
  explicit LaunchedOrbitsLayer(const ViewLayer& view);
  ~LaunchedOrbitsLayer() override;

  /// Launches an orbit of N from (x, y), `steps` long (N⁻¹ when `backward`); returns its id, 0 when refused
  /// (kMaxLaunchedOrbits shown).  `number`: the number (and so the colour) to give it (issue 53, finding 2).
  quint64 launchOrbit(long double x, long double y, std::uint64_t steps = kLaunchedOrbitSteps, bool backward = false,
                      quint64 number = 0);
  /// A line or a grid of orbits at once (core's orbitFamilyStarts); how many were launched.
  int launchOrbitFamily(const OrbitFamily& family, std::uint64_t steps = kLaunchedOrbitSteps, bool backward = false);
  void setClickOrbit(std::uint64_t steps, bool backward);
  [[nodiscard]] std::uint64_t clickSteps() const noexcept { return clickSteps_; }
  [[nodiscard]] bool clickBackward() const noexcept { return clickBackward_; }
  /// One launched orbit as CSV (core's writeOrbitCsv); false with the reason.
  bool exportOrbitCsv(quint64 id, const QString& path, QString* error = nullptr) const;
  [[nodiscard]] int orbitCount() const noexcept { return static_cast<int>(orbits_.size()); }
  [[nodiscard]] const std::vector<LaunchedOrbit>& launchedOrbits() const noexcept { return orbits_; }
  [[nodiscard]] std::vector<PhysicalPoint> launchedOrbitStarts() const;
  bool removeOrbit(quint64 id);
  /// Removes the last orbit, or, right after clearOrbits(), brings the cleared ones back.
  bool undoLastOrbit();
  [[nodiscard]] bool canUndoClear() const noexcept { return !cleared_.empty(); }
  void highlightOrbit(quint64 id);
  [[nodiscard]] quint64 highlightedOrbit() const noexcept { return highlighted_; }
  [[nodiscard]] bool orbitsSettled() const;
  /// Removes every orbit; undoLastOrbit() brings them back until another orbit is launched.
  void clearOrbits();
  /// Removes every orbit with no undo, and forgets what a Clear removed (a new map, a session).
  void discardOrbits();

 Q_SIGNALS:
  /// One added, removed, traced or measured; the highlight.
  void orbitsChanged();
  void statusMessage(const QString& text);

 private:
  void traceOrbit(const LaunchedOrbit& orbit);
  void measureOrbit(const LaunchedOrbit& orbit);
  /// Removes every orbit without an undo and without forgetting the cleared ones.
  void dropOrbits();
  void onOrbitTraced(quint64 id, std::shared_ptr<const std::vector<QPointF>> points, const QString& error);
  void onOrbitMeasured(quint64 id, const OrbitMeasuresPtr& measures);
  void redrawOrbit(std::size_t index);
  void updateOrbitChain();
  LaunchedOrbit* findOrbit(quint64 id);

  const ViewLayer& viewLayer_;
  QPointer<PortraitView> view_;
  std::vector<LaunchedOrbit> orbits_;
  std::vector<QwtPlotItem*> orbitItems_;            // orbitItems_[i] draws orbits_[i] (owned by the view), or null
  quint64 nextOrbitId_ = 0;
  quint64 highlighted_ = 0;
  std::vector<LaunchedOrbit> cleared_;              // what Clear Orbits removed (undoLastOrbit brings it back)
  std::uint64_t clickSteps_ = kLaunchedOrbitSteps;
  bool clickBackward_ = false;
  quint64 generation_ = 0;                          // bumped by clear and by a new map: older results are dropped
  // Last members: destroyed first, they stop the jobs and join their threads while everything they use lives.
  std::unique_ptr<BackgroundJobs> traceJobs_;       // one channel, a queue: each orbit once, in launch order
  std::unique_ptr<BackgroundJobs> measureJobs_;     // niced: the measures of launched orbits, a queue
};

}  // namespace archipelago::ui
