#include "ui/portrait/OverlayLayer.hpp"

#include <QColor>

#include "core/io/NumberText.hpp"
#include "ui/jobs/BackgroundJobs.hpp"
#include "ui/portrait/PortraitLayers.hpp"
#include "ui/portrait/PortraitView.hpp"
#include "ui/portrait/SegmentOverlay.hpp"
#include "ui/portrait/ViewLayer.hpp"

namespace archipelago::ui {

namespace {
using FoundPtr = std::shared_ptr<const PeriodicOrbitAt>;
}  // namespace

OverlayLayer::OverlayLayer(const ViewLayer& view) : viewLayer_(view), view_(view.view()) {
  jobs_ = std::make_unique<BackgroundJobs>(this, 1);
}

OverlayLayer::~OverlayLayer() { jobs_.reset(); }

void OverlayLayer::showSegment(const SegmentReplayPtr& replay) {
  replay_ = replay;
  chain_.reset();
  if (!view_) return;
  view_->setLayer(PortraitLayer::segment, SegmentOverlay::segmentItems(replay_));
  view_->setLayer(PortraitLayer::segmentChain, {});
  view_->setLayer(PortraitLayer::segmentStep, {});
  Q_EMIT legendChanged();
}

void OverlayLayer::showSegmentChain(const ChainResultPtr& chain) {
  chain_ = chain;
  if (!view_) return;
  view_->setLayer(PortraitLayer::segmentChain, SegmentOverlay::chainItems(chain_));
  Q_EMIT legendChanged();
}

void OverlayLayer::showSegmentStep(std::size_t index) {
  if (view_ && replay_) view_->setLayer(PortraitLayer::segmentStep, SegmentOverlay::stepItems(replay_, index));
}

void OverlayLayer::clearSegment() {
  replay_.reset();
  chain_.reset();
  if (!view_) return;
  for (PortraitLayer layer : {PortraitLayer::segment, PortraitLayer::segmentChain, PortraitLayer::segmentStep})
    view_->setLayer(layer, {});
  Q_EMIT legendChanged();
}

void OverlayLayer::showPeriodicOrbit(const PeriodicOrbit& orbit) {
  if (clickedPeriodic_ && &orbit != &clickedPeriodic_->orbit) clickedPeriodic_.reset();  // another's overlay
  periodic_ = orbit;
  if (!view_) return;
  view_->setLayer(PortraitLayer::periodicOrbits, SegmentOverlay::periodicItems(orbit));
  Q_EMIT legendChanged();
}

void OverlayLayer::clearPeriodicOrbit() {
  clickedPeriodic_.reset();
  periodic_.reset();
  if (view_) view_->setLayer(PortraitLayer::periodicOrbits, {});
  Q_EMIT legendChanged();
}

QString OverlayLayer::periodicOrbitText(const PeriodicOrbitAt& found) {
  const PeriodicOrbit& o = found.orbit;
  const OrbitClassification kind = o.classification();
  return tr("Periodic orbit of period %1, %2 (residue %3), near (%4, %5): %6 — as archipelago-cli periodic --period "
            "%1 --near=%4,%5 --stable finds it")
      .arg(o.period)
      .arg(QString::fromLatin1(toString(kind.stability)))
      .arg(static_cast<double>(o.residue), 0, 'g', 10)
      .arg(QString::fromStdString(io::shortestText(static_cast<double>(found.search.near.x))),
           QString::fromStdString(io::shortestText(static_cast<double>(found.search.near.y))),
           QString::fromStdString(found.chain.summary));
}

void OverlayLayer::findPeriodicOrbitAt(long double x, long double y) {
  const MapParameters map = viewLayer_.map();
  Job<FoundPtr> job;  // latest wins: another click replaces this search
  job.order = JobOrder::latest;
  job.work = [map, x, y](JobContext<NoProgress>& context) -> std::optional<FoundPtr> {
    ChainRequest request;
    request.map = map;
    request = chainRequestAt(request, {x, y});  // the rotation instrument's request for this start
    return std::make_shared<const PeriodicOrbitAt>(periodicOrbitAt(request, context.stopToken()));
  };
  job.done = [this, x, y](JobResult<FoundPtr> r) { onPeriodicOrbitFound(x, y, r.value.value_or(nullptr), r.error); };
  Q_EMIT statusMessage(tr("Finding the periodic orbit at (%1, %2): naming its chain, then Newton…")
                           .arg(static_cast<double>(x), 0, 'g', 10)
                           .arg(static_cast<double>(y), 0, 'g', 10));
  periodicRequest_ = jobs_->submit(std::move(job));
}

void OverlayLayer::onPeriodicOrbitFound(long double x, long double y, const FoundPtr& found, const QString& error) {
  periodicRequest_ = 0;
  if (!found) {
    clickedPeriodic_.reset();
    const QString text = tr("No periodic orbit found at (%1, %2): %3")
                             .arg(static_cast<double>(x), 0, 'g', 10)
                             .arg(static_cast<double>(y), 0, 'g', 10)
                             .arg(error);
    Q_EMIT statusMessage(text);
    Q_EMIT periodicOrbitFound(text);
    return;
  }
  clickedPeriodic_ = found;
  showPeriodicOrbit(clickedPeriodic_->orbit);
  const QString text = periodicOrbitText(*clickedPeriodic_);
  Q_EMIT statusMessage(text);
  Q_EMIT periodicOrbitFound(text);
}

void OverlayLayer::showProfileLine(std::optional<std::pair<PhysicalPoint, PhysicalPoint>> line) {
  if (!view_) return;
  std::vector<QwtPlotItem*> items;
  if (line) {
    auto* item = new PointsItem(PointsItem::Style::polyline, toQt({line->first, line->second}), QColor(0, 255, 160));
    item->setPenWidth(4);
    item->setZ(36);
    items.push_back(item);
  }
  view_->setLayer(PortraitLayer::profileLine, std::move(items));
}

std::vector<LegendLine> OverlayLayer::legendLines() const {
  std::vector<LegendLine> lines;
  const auto add = [&lines](PortraitLayer layer, const QStringList& texts) {
    for (const QString& text : texts) lines.push_back({layer, text});
  };
  add(PortraitLayer::segment, SegmentOverlay::legendLines(replay_, nullptr, 0));
  add(PortraitLayer::segmentChain, SegmentOverlay::legendLines(nullptr, chain_, 0));
  add(PortraitLayer::periodicOrbits, SegmentOverlay::legendLines(nullptr, nullptr, periodic_ ? periodic_->period : 0));
  if (clickedPeriodic_) {  // the chain a click named (issue 37, finding 16), its phrases one per line
    QStringList found;
    found << tr("&nbsp;&nbsp;&nbsp;%1, residue %2, found at a click in the chain:")
                 .arg(QString::fromLatin1(toString(clickedPeriodic_->orbit.classification().stability)))
                 .arg(static_cast<double>(clickedPeriodic_->orbit.residue), 0, 'g', 6);
    // Each phrase on a line of its own, a long one cut (the legend is not wrapped; the status bar has it whole).
    for (QString phrase : QString::fromStdString(clickedPeriodic_->chain.summary).split(QStringLiteral("; "))) {
      if (phrase.size() > 52) phrase = phrase.left(51) + QStringLiteral("…");
      found << QStringLiteral("&nbsp;&nbsp;&nbsp;") + phrase.toHtmlEscaped();
    }
    add(PortraitLayer::periodicOrbits, found);
  }
  return lines;
}

}  // namespace archipelago::ui
