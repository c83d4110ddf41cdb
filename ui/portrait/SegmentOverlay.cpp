#include "ui/portrait/SegmentOverlay.hpp"

#include <QCoreApplication>
#include <QLocale>

#include <algorithm>

#include "ui/portrait/PortraitLayers.hpp"

namespace archipelago::ui {

namespace {
std::vector<QPointF> toQt(const std::vector<PhysicalPoint>& points, std::size_t begin, std::size_t end) {
  std::vector<QPointF> out;
  out.reserve(end - begin);
  for (std::size_t i = begin; i < end; ++i)
    out.emplace_back(static_cast<double>(points[i].x), static_cast<double>(points[i].y));
  return out;
}

QString tr(const char* text) { return QCoreApplication::translate("SegmentOverlay", text); }
}  // namespace

std::vector<QwtPlotItem*> SegmentOverlay::segmentItems(const SegmentReplayPtr& replay) {
  if (!replay || replay->trace.points.empty()) return {};
  const auto& points = replay->trace.points;
  return {new PointsItem(PointsItem::Style::timeDots, toQt(points, 0, points.size()))};
}

std::vector<QwtPlotItem*> SegmentOverlay::chainItems(const ChainResultPtr& chain) {
  if (!chain || !chain->chain || !chain->chain->centre) return {};
  const auto& points = chain->chain->centre->points;
  return {new PointsItem(PointsItem::Style::discs, toQt(points, 0, points.size()), QColor(0, 230, 255))};
}

std::vector<QwtPlotItem*> SegmentOverlay::stepItems(const SegmentReplayPtr& replay, std::size_t index) {
  if (!replay || replay->trace.points.empty()) return {};
  const auto& points = replay->trace.points;
  index = std::min(index, points.size() - 1);
  const std::size_t begin = index >= kTrailStates ? index - kTrailStates : 0;
  return {new PointsItem(PointsItem::Style::trail, toQt(points, begin, index + 1))};
}

std::vector<QwtPlotItem*> SegmentOverlay::periodicItems(const PeriodicOrbit& orbit) {
  return {new PointsItem(PointsItem::Style::diamonds, toQt(orbit.points, 0, orbit.points.size()), QColor(255, 60, 220))};
}

QStringList SegmentOverlay::legendLines(const SegmentReplayPtr& replay, const ChainResultPtr& chain, int periodicPeriod) {
  QStringList lines;
  if (replay) {
    const SegmentTrace& t = replay->trace;
    lines << tr("<span style='color:#35b779'>●</span><span style='color:#fde725'>●</span> segment of orbit %1, "
                "%2 steps (colour: time)")
                 .arg(t.record.orbit)
                 .arg(QLocale().toString(static_cast<qulonglong>(t.steps)));
  }
  if (chain && chain->chain && chain->chain->centre) {
    const PeriodicOrbit& o = *chain->chain->centre;
    lines << tr("<span style='color:#00e6ff'>⬤</span> centre of its chain: period %1, R = %2 (%3)")
                 .arg(o.period)
                 .arg(static_cast<double>(o.residue), 0, 'g', 4)
                 .arg(QString::fromLatin1(toString(o.classification().stability)));
  }
  if (periodicPeriod > 0)
    lines << tr("<span style='color:#ff3cdc'>◆</span> periodic orbit of period %1").arg(periodicPeriod);
  return lines;
}

}  // namespace archipelago::ui
