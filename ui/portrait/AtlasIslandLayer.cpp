#include "ui/portrait/AtlasIslandLayer.hpp"

#include <QColor>

#include <utility>

#include "core/atlas/AtlasIslandView.hpp"
#include "ui/jobs/BackgroundJobs.hpp"
#include "ui/portrait/PortraitLayers.hpp"
#include "ui/portrait/PortraitView.hpp"
#include "ui/portrait/ViewLayer.hpp"

namespace archipelago::ui {

AtlasIslandLayer::AtlasIslandLayer(ViewLayer& view) : viewLayer_(view), view_(view.view()) {
  jobs_ = std::make_unique<BackgroundJobs>(this, 1);
}

AtlasIslandLayer::~AtlasIslandLayer() { jobs_.reset(); }

void AtlasIslandLayer::showAtlasIsland(const AtlasNode& node, const QString& label, const SegmentRegion& fallback) {
  const MapParameters map = viewLayer_.map();
  const bool centre = node.parent < 0;
  Job<AtlasIslandPtr> job;  // latest wins: another island replaces this one
  job.work = [map, node](JobContext<NoProgress>&) -> std::optional<AtlasIslandPtr> {
    AtlasIslandView plan = atlasIslandView(map, node);
    auto result = std::make_shared<AtlasIslandResult>();
    result->boundary = toQt(plan.boundary);
    result->island = plan.island;
    result->chain = std::move(plan.chain);
    result->partner = std::move(plan.partner);
    result->error = QString::fromStdString(plan.missing);
    return result;
  };
  job.done = [this, label, centre, fallback](JobResult<AtlasIslandPtr> r) {
    request_ = 0;
    if (!r.ok()) {
      viewLayer_.zoomToRegion(fallback);
      Q_EMIT statusMessage(tr("Atlas island %1: %2").arg(label, r.error));
      return;
    }
    island_ = *r.value;
    viewLayer_.zoomToRegion(island_->island.value_or(fallback));
    drawBoundary(label);
    Q_EMIT islandDrawn(island_, centre);
    Q_EMIT legendChanged();
    if (!island_->error.isEmpty()) Q_EMIT statusMessage(tr("Atlas island %1: not drawn: %2").arg(label, island_->error));
    Q_EMIT atlasIslandShown();
  };
  request_ = jobs_->submit(std::move(job));
}

void AtlasIslandLayer::drawBoundary(const QString& label) {
  label_ = island_->boundary.empty() ? QString() : label;
  if (!view_) return;
  std::vector<QwtPlotItem*> items;
  if (!island_->boundary.empty()) {
    auto* item = new PointsItem(PointsItem::Style::dots, island_->boundary, QColor(120, 255, 80));
    item->setPenWidth(3);  // a solid ring, thicker than the portrait's orbits about it
    item->setTitle(tr("boundary circle of %1").arg(label));
    items.push_back(item);
  }
  view_->setLayer(PortraitLayer::atlasIsland, std::move(items));
}

void AtlasIslandLayer::clearAtlasIsland() {
  if (jobs_) jobs_->cancel();
  request_ = 0;
  island_.reset();
  label_.clear();
  if (view_) view_->setLayer(PortraitLayer::atlasIsland, {});
  Q_EMIT legendChanged();
}

std::vector<LegendLine> AtlasIslandLayer::legendLines() const {
  if (label_.isEmpty()) return {};
  return {{PortraitLayer::atlasIsland,
           tr("<span style='color:#78ff50'>●</span> boundary circle of the atlas island %1").arg(label_.toHtmlEscaped())}};
}

}  // namespace archipelago::ui
