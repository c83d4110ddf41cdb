#include "ui/segments/SegmentOverlay.hpp"

#include <QLocale>
#include <QPainter>
#include <qwt_plot.h>
#include <qwt_plot_item.h>
#include <qwt_plot_textlabel.h>
#include <qwt_text.h>
#include <qwt_scale_map.h>

#include <algorithm>

#include "core/portrait/ColourMap.hpp"
#include "ui/portrait/PortraitView.hpp"
#include "core/portrait/Viewport.hpp"

namespace archipelago::ui {

/// Points in physical coordinates drawn as dots (coloured by their position in the list), a polyline, or
/// symbols.  (A plain QwtPlotItem, like the portrait's orbits: Qwt 6.1's curve headers are not C++20.)
class PointsItem : public QwtPlotItem {
 public:
  enum class Style { timeDots, trail, discs, diamonds };

  PointsItem(Style style, double z) : style_(style) {
    setZ(z);
    setItemAttribute(QwtPlotItem::AutoScale, false);
  }
  int rtti() const override { return QwtPlotItem::Rtti_PlotUserItem + 40; }
  void setPoints(std::vector<QPointF> points) { points_ = std::move(points); }
  [[nodiscard]] std::size_t size() const noexcept { return points_.size(); }

  void draw(QPainter* painter, const QwtScaleMap& xMap, const QwtScaleMap& yMap,
            const QRectF& canvasRect) const override {
    if (points_.empty()) return;
    const QRectF clip = canvasRect.adjusted(-8, -8, 8, 8);
    auto toCanvas = [&](const QPointF& p) { return QPointF(xMap.transform(p.x()), yMap.transform(p.y())); };
    painter->save();
    painter->setRenderHint(QPainter::Antialiasing, style_ != Style::timeDots);
    switch (style_) {
      case Style::timeDots: {
        // Time runs from dark blue to yellow in kBins groups, so each group is one drawPoints call.
        constexpr std::size_t kBins = 48;
        const ColourMap colours(ColourMapName::Viridis);
        QVector<QPointF> visible;
        for (std::size_t b = 0; b < kBins; ++b) {
          const std::size_t begin = points_.size() * b / kBins, end = points_.size() * (b + 1) / kBins;
          visible.clear();
          for (std::size_t i = begin; i < end; ++i) {
            const QPointF q = toCanvas(points_[i]);
            if (clip.contains(q)) visible.append(q);
          }
          const Rgb c = colours.at(0.15 + 0.85 * static_cast<double>(b) / (kBins - 1));
          painter->setPen(QPen(QColor(c.r, c.g, c.b), 1.2));
          painter->drawPoints(visible.constData(), static_cast<int>(visible.size()));
        }
        break;
      }
      case Style::trail: {
        // Consecutive steps jump across the island, so the trail is dots (a line would zigzag), growing
        // towards the step shown, which gets a ring.
        painter->setPen(Qt::NoPen);
        const std::size_t n = points_.size();
        for (std::size_t i = 0; i < n; ++i) {
          const QPointF q = toCanvas(points_[i]);
          if (!clip.contains(q)) continue;
          const double age = static_cast<double>(n - 1 - i) / static_cast<double>(std::max<std::size_t>(n, 2) - 1);
          painter->setBrush(QColor(255, 255, 255, static_cast<int>(255 - 175 * age)));
          const double r = 3.2 - 1.6 * age;
          painter->drawEllipse(q, r, r);
        }
        painter->setBrush(Qt::NoBrush);
        painter->setPen(QPen(QColor(0, 0, 0, 200), 4.5));
        painter->drawEllipse(toCanvas(points_.back()), 8, 8);
        painter->setPen(QPen(QColor(255, 70, 70), 2.5));
        painter->drawEllipse(toCanvas(points_.back()), 8, 8);
        break;
      }
      case Style::discs:
      case Style::diamonds: {
        const bool discs = style_ == Style::discs;
        painter->setPen(QPen(Qt::black, 1.5));
        painter->setBrush(discs ? QColor(0, 230, 255) : QColor(255, 60, 220));
        for (const QPointF& p : points_) {
          const QPointF q = toCanvas(p);
          if (!clip.contains(q)) continue;
          if (discs) {
            painter->drawEllipse(q, 5.5, 5.5);
          } else {
            const QPointF d[4] = {q + QPointF(0, -7), q + QPointF(7, 0), q + QPointF(0, 7), q + QPointF(-7, 0)};
            painter->drawPolygon(d, 4);
          }
        }
        break;
      }
    }
    painter->restore();
  }

 private:
  Style style_;
  std::vector<QPointF> points_;
};

namespace {
/// Steps of the trail drawn behind the step shown (kept states).
constexpr std::size_t kTrailStates = 200;

std::vector<QPointF> toQt(const std::vector<PhysicalPoint>& points, std::size_t begin, std::size_t end) {
  std::vector<QPointF> out;
  out.reserve(end - begin);
  for (std::size_t i = begin; i < end; ++i)
    out.emplace_back(static_cast<double>(points[i].x), static_cast<double>(points[i].y));
  return out;
}
}  // namespace

SegmentOverlay::SegmentOverlay(PortraitView* view, QObject* parent) : QObject(parent), view_(view) {
  segment_ = new PointsItem(PointsItem::Style::timeDots, 30);
  trail_ = new PointsItem(PointsItem::Style::trail, 32);
  centre_ = new PointsItem(PointsItem::Style::discs, 34);
  periodic_ = new PointsItem(PointsItem::Style::diamonds, 35);
  for (PointsItem* item : {segment_, trail_, centre_, periodic_}) item->attach(plot());
  legend_ = new QwtPlotTextLabel;
  legend_->setZ(40);
  legend_->attach(plot());
  // The plot deletes attached items when it goes: detach ours first if it goes before us.
  connect(plot(), &QObject::destroyed, this, [this] {
    for (PointsItem** item : {&segment_, &trail_, &centre_, &periodic_}) *item = nullptr;
    legend_ = nullptr;
  });
}

SegmentOverlay::~SegmentOverlay() {
  if (legend_ != nullptr) {
    legend_->detach();
    delete legend_;
  }
  for (PointsItem* item : {segment_, trail_, centre_, periodic_}) {
    if (item == nullptr) continue;
    item->detach();
    delete item;
  }
}

QwtPlot* SegmentOverlay::plot() const { return view_ ? view_->plot() : nullptr; }

void SegmentOverlay::updateLegend() {
  if (legend_ == nullptr) return;
  QStringList lines;
  if (replay_) {
    const SegmentTrace& t = replay_->trace;
    lines << tr("<span style='color:#35b779'>●</span><span style='color:#fde725'>●</span> segment of orbit %1, "
                "%2 steps (colour: time)")
                 .arg(t.record.orbit)
                 .arg(QLocale().toString(static_cast<qulonglong>(t.steps)));
  }
  if (chain_ && chain_->chain && chain_->chain->centre) {
    const PeriodicOrbit& o = *chain_->chain->centre;
    lines << tr("<span style='color:#00e6ff'>⬤</span> centre of its chain: period %1, R = %2 (%3)")
                 .arg(o.period)
                 .arg(static_cast<double>(o.residue), 0, 'g', 4)
                 .arg(QString::fromLatin1(toString(o.classification().stability)));
  }
  if (periodicPeriod_ > 0)
    lines << tr("<span style='color:#ff3cdc'>◆</span> periodic orbit of period %1").arg(periodicPeriod_);
  if (lines.isEmpty()) {
    legend_->setText(QwtText());
    return;
  }
  QwtText text(lines.join(QStringLiteral("<br>")), QwtText::RichText);
  text.setRenderFlags(Qt::AlignTop | Qt::AlignLeft);
  text.setBackgroundBrush(QColor(255, 255, 255, 215));
  text.setBorderRadius(4);
  text.setBorderPen(QPen(QColor(0, 0, 0, 120)));
  QFont font = text.font();
  font.setPointSizeF(font.pointSizeF() * 1.05);
  text.setFont(font);
  legend_->setText(text);
  legend_->setMargin(10);
}

void SegmentOverlay::replot() {
  updateLegend();
  if (QwtPlot* p = plot(); p != nullptr && segment_ != nullptr) p->replot();
}

void SegmentOverlay::showReplay(const SegmentReplayPtr& replay) {
  if (segment_ == nullptr) return;
  replay_ = replay;
  chain_.reset();
  centre_->setPoints({});
  trail_->setPoints({});
  if (!replay_) {
    segment_->setPoints({});
    replot();
    return;
  }
  segment_->setPoints(toQt(replay_->trace.points, 0, replay_->trace.points.size()));
  zoomToSegment();
  replot();
}

void SegmentOverlay::showChain(const ChainResultPtr& chain) {
  if (centre_ == nullptr) return;
  chain_ = chain;
  if (chain_ && chain_->chain && chain_->chain->centre)
    centre_->setPoints(toQt(chain_->chain->centre->points, 0, chain_->chain->centre->points.size()));
  else
    centre_->setPoints({});
  replot();
}

void SegmentOverlay::showStep(std::size_t index) {
  if (trail_ == nullptr || !replay_) return;
  const auto& points = replay_->trace.points;
  index = std::min(index, points.size() - 1);
  const std::size_t begin = index >= kTrailStates ? index - kTrailStates : 0;
  trail_->setPoints(toQt(points, begin, index + 1));
  replot();
}

void SegmentOverlay::showPeriodicOrbit(const PeriodicOrbit& orbit) {
  if (periodic_ == nullptr) return;
  periodic_->setPoints(toQt(orbit.points, 0, orbit.points.size()));
  periodicPeriod_ = orbit.period;
  replot();
}

void SegmentOverlay::clear() {
  replay_.reset();
  chain_.reset();
  for (PointsItem* item : {segment_, trail_, centre_, periodic_})
    if (item != nullptr) item->setPoints({});
  periodicPeriod_ = 0;
  replot();
}

void SegmentOverlay::zoomToSegment() {
  if (replay_) zoomTo(replay_->region);
}

void SegmentOverlay::zoomToIsland() {
  if (chain_ && chain_->chain)
    zoomTo(chain_->island);
  else
    zoomToSegment();
}

void SegmentOverlay::zoomTo(const SegmentRegion& region) {
  if (!view_ || plot() == nullptr) return;
  const MapParameters& map = view_->parameters();
  const QWidget* canvas = plot()->canvas();
  const double aspect = canvas->height() > 0 ? static_cast<double>(canvas->width()) / canvas->height() : 1.0;
  // At least 2^16 grid units: a few pixels of the finest view the portrait allows, far below any island.
  const long double minSize = map.width() * 0x1p-36L;
  try {
    const SegmentRegion framed = framedInBox(region, map, aspect, minSize);
    view_->setViewport(Viewport::fromPhysical(map, {framed.x0, framed.x1, framed.y0, framed.y1}));
  } catch (const std::exception&) {
    // A region outside this view's map (its parameters differ from the run's): leave the view alone.
  }
}

}  // namespace archipelago::ui
