#pragma once
/// \file AtlasIslandLayer.hpp
/// \brief The island the Atlas page selected (issue 38): its boundary circle drawn and its view framed (one layer of
/// PortraitController, issue 51).  The plan — how many boundary points, the island's circle cut out of the chain's
/// orbit, the frame, an orbit kept as one point found again — is core's (core/atlas/AtlasIslandView.hpp), computed on
/// this layer's one job channel (latest wins: another island replaces this one).

#include <QObject>
#include <QPointF>
#include <QPointer>
#include <QString>

#include <memory>
#include <optional>
#include <vector>

#include "core/atlas/Atlas.hpp"
#include "core/periodic/PeriodicOrbit.hpp"
#include "core/periodic/SegmentAnalysis.hpp"
#include "ui/portrait/PortraitLayers.hpp"

namespace archipelago::ui {

class BackgroundJobs;
class PortraitView;
class ViewLayer;

/// What the portrait draws of an island of the atlas: its boundary circle, the orbit of its boundary point under Q
/// (every island of its chain), and the chain's and its partner's orbits whole.
struct AtlasIslandResult {
  std::vector<QPointF> boundary;            ///< empty when the island has no boundary circle
  std::optional<SegmentRegion> island;      ///< the circle of the island about the node's centre, with a margin
  std::optional<PeriodicOrbit> chain;       ///< the chain's elliptic orbit (the fixed point at the centre)
  std::optional<PeriodicOrbit> partner;     ///< its hyperbolic partner (none at the centre, or when there is none)
  QString error;                            ///< what could not be drawn, if anything
};
using AtlasIslandPtr = std::shared_ptr<const AtlasIslandResult>;

class AtlasIslandLayer : public QObject {
  Q_OBJECT
 public:
  /// `view` is framed about the island; it outlives this layer.
  explicit AtlasIslandLayer(ViewLayer& view);
  ~AtlasIslandLayer() override;

  /// Computes core's atlasIslandView() of `node` in the background, then frames the island (`fallback` when it has
  /// no boundary circle) and draws its boundary circle; islandDrawn() hands the chain and its partner on.  `label`
  /// names the island in the legend ("6 > 138").
  void showAtlasIsland(const AtlasNode& node, const QString& label, const SegmentRegion& fallback);
  /// Removes the boundary circle.
  void clearAtlasIsland();
  [[nodiscard]] AtlasIslandPtr atlasIsland() const noexcept { return island_; }
  [[nodiscard]] bool atlasIslandSettled() const noexcept { return request_ == 0; }
  /// The legend's line for the boundary circle drawn (none when none is).
  [[nodiscard]] std::vector<LegendLine> legendLines() const;

 Q_SIGNALS:
  /// The island is framed and its circle drawn: `centre` when it is the central island (the fixed point's loop is
  /// its barrier), else its chain's partner (if any) bounds it.
  void islandDrawn(const archipelago::ui::AtlasIslandPtr& island, bool centre);
  /// Everything of the island is drawn (after islandDrawn's receivers).
  void atlasIslandShown();
  void legendChanged();
  void statusMessage(const QString& text);

 private:
  void drawBoundary(const QString& label);

  ViewLayer& viewLayer_;
  QPointer<PortraitView> view_;
  AtlasIslandPtr island_;
  QString label_;                          // the island whose boundary is drawn ("" : none)
  quint64 request_ = 0;
  // Last member: destroyed first, it stops the job and joins its thread while everything it uses lives.
  std::unique_ptr<BackgroundJobs> jobs_;
};

}  // namespace archipelago::ui
