#pragma once
/// \file ManifoldsLayer.hpp
/// \brief The stable and unstable manifolds of a hyperbolic orbit in the visible view, and its turnstile's lobes with
/// their area (one layer of PortraitController, issue 51).
///
/// Its jobs (ui/jobs/BackgroundJobs), one channel each, latest request wins: the manifolds of the view shown (core's
/// plan, manifoldPlanForView: a zoom refines them anew) and the flux (once per orbit, as `archipelago-cli flux`).

#include <QObject>
#include <QPointer>
#include <QString>

#include <memory>
#include <optional>
#include <vector>

#include "core/manifolds/ManifoldCurve.hpp"
#include "core/manifolds/TurnstileFlux.hpp"
#include "core/periodic/PeriodicOrbit.hpp"
#include "ui/portrait/PortraitLayers.hpp"

namespace archipelago::ui {

class BackgroundJobs;
class PortraitView;
class ViewLayer;

/// The manifolds of one hyperbolic orbit in the visible view, and the flux through its turnstile.
struct ManifoldsResult {
  std::vector<ManifoldCurve> unstable;  ///< every branch drawn, both sides at every orbit point drawn
  std::vector<ManifoldCurve> stable;
  double seconds = 0;
};
using ManifoldsPtr = std::shared_ptr<const ManifoldsResult>;
struct FluxResult {
  TurnstileRequest request;           ///< what was asked (as `archipelago-cli flux` asks it)
  std::optional<TurnstileFlux> flux;
  QString error;
  double seconds = 0;
};
using FluxPtr = std::shared_ptr<const FluxResult>;

class ManifoldsLayer : public QObject {
  Q_OBJECT
 public:
  /// `view` gives the map and the view the manifolds are refined in; it outlives this layer.
  explicit ManifoldsLayer(const ViewLayer& view);
  ~ManifoldsLayer() override;

  /// Shows the manifolds of the hyperbolic orbit (none: the fixed point (√K, 0)) and the turnstile's lobes.
  void setManifoldsShown(bool shown);
  [[nodiscard]] bool manifoldsShown() const noexcept { return shown_; }
  /// The hyperbolic orbit whose manifolds are drawn (none: the fixed point).  Shows the layer.
  void setManifoldOrbit(std::optional<PeriodicOrbit> orbit);
  [[nodiscard]] const std::optional<PeriodicOrbit>& manifoldOrbit() const noexcept { return orbit_; }
  [[nodiscard]] ManifoldsPtr manifolds() const noexcept { return manifolds_; }
  [[nodiscard]] FluxPtr flux() const noexcept { return flux_; }
  /// Nothing computing (tests).
  [[nodiscard]] bool manifoldsSettled() const;
  /// A new map: the orbit (of another K), the curves and the flux go (recompute() computes the fixed point's).
  void forgetMap();
  /// The flux and the manifolds computed anew, when shown.
  void recompute();
  /// The view changed: the manifolds are refined anew in it, when shown.
  void followView();
  /// The legend's line for the manifolds drawn (none when none are).
  [[nodiscard]] std::vector<LegendLine> legendLines() const;

 Q_SIGNALS:
  /// The manifolds or the flux changed (computed, cleared).
  void manifoldsChanged();
  /// What the legend lists of this layer changed.
  void legendChanged();
  void statusMessage(const QString& text);

 private:
  void requestManifolds();
  void requestFlux();
  void drawManifolds();

  const ViewLayer& viewLayer_;
  QPointer<PortraitView> view_;
  bool shown_ = false;
  std::optional<PeriodicOrbit> orbit_;
  ManifoldsPtr manifolds_;
  FluxPtr flux_;
  quint64 manifoldsRequest_ = 0;
  quint64 fluxRequest_ = 0;
  // Last member: destroyed first, it stops the jobs and joins their threads while everything they use lives.
  std::unique_ptr<BackgroundJobs> jobs_;  // channels: the manifolds, the flux
};

}  // namespace archipelago::ui
