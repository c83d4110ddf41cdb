#include "ui/portrait/PortraitLayers.hpp"

#include <QPainter>
#include <QPen>
#include <QVector>
#include <qwt_scale_map.h>

#include <algorithm>

#include "core/colour/ColourMap.hpp"

namespace archipelago::ui {

std::vector<QPointF> toQt(const std::vector<PhysicalPoint>& points) {
  std::vector<QPointF> out;
  out.reserve(points.size());
  for (const PhysicalPoint& p : points) out.emplace_back(static_cast<double>(p.x), static_cast<double>(p.y));
  return out;
}

PointsItem::PointsItem(Style style, std::vector<QPointF> points, QColor colour)
    : style_(style), points_(std::move(points)), colour_(colour) {
  switch (style_) {
    case Style::dots: setZ(20); break;
    case Style::timeDots: setZ(30); break;
    case Style::trail: setZ(32); break;
    case Style::discs: setZ(34); break;
    case Style::diamonds: setZ(35); break;
    case Style::polyline: setZ(12); break;
    case Style::polygon: setZ(10); break;
    case Style::label: setZ(38); break;
  }
  setItemAttribute(QwtPlotItem::AutoScale, false);
}

/// The plot's maps and its canvas, for the drawing steps.
struct PointsItem::Canvas {
  const QwtScaleMap& xMap;
  const QwtScaleMap& yMap;
  QRectF rect;  ///< the canvas
  QRectF clip;  ///< the canvas with a margin of 8 pixels: a mark centred there shows in part
  [[nodiscard]] QPointF at(const QPointF& p) const { return QPointF(xMap.transform(p.x()), yMap.transform(p.y())); }
};

void PointsItem::draw(QPainter* painter, const QwtScaleMap& xMap, const QwtScaleMap& yMap,
                      const QRectF& canvasRect) const {
  if (points_.empty()) return;
  const Canvas canvas{xMap, yMap, canvasRect, canvasRect.adjusted(-8, -8, 8, 8)};
  painter->save();
  painter->setRenderHint(QPainter::Antialiasing, style_ != Style::timeDots && style_ != Style::dots);
  switch (style_) {
    case Style::dots: drawDots(painter, canvas); break;
    case Style::timeDots: drawTimeDots(painter, canvas); break;
    case Style::trail: drawTrail(painter, canvas); break;
    case Style::discs:
    case Style::diamonds: drawMarks(painter, canvas); break;
    case Style::polyline: drawPolyline(painter, canvas); break;
    case Style::polygon: drawPolygon(painter, canvas); break;
    case Style::label: drawLabel(painter, canvas); break;
  }
  painter->restore();
}

void PointsItem::drawDots(QPainter* painter, const Canvas& canvas) const {
  // One point per pixel: a launched orbit of 2·10⁴ steps covers a few thousand pixels, and 500 of them must
  // draw in a fraction of a second (issue #23, finding 5).
  const QRectF& canvasRect = canvas.rect;
  painter->setPen(QPen(colour_, penWidth_));
  const int w = static_cast<int>(canvasRect.width()) + 1, h = static_cast<int>(canvasRect.height()) + 1;
  std::vector<bool> seen(static_cast<std::size_t>(w) * static_cast<std::size_t>(h), false);
  QVector<QPointF> visible;
  for (const QPointF& p : points_) {
    const QPointF q = canvas.at(p);
    if (!canvasRect.contains(q)) continue;
    const auto col = static_cast<int>(q.x() - canvasRect.left()), row = static_cast<int>(q.y() - canvasRect.top());
    if (col < 0 || row < 0 || col >= w || row >= h) continue;
    const std::size_t cell = static_cast<std::size_t>(row) * static_cast<std::size_t>(w) + static_cast<std::size_t>(col);
    if (seen[cell]) continue;
    seen[cell] = true;
    visible.append(q);
  }
  painter->drawPoints(visible.constData(), static_cast<int>(visible.size()));
  if (startMarker_) {
    const QPointF start = canvas.at(points_.front());
    if (canvas.clip.contains(start)) {
      painter->setRenderHint(QPainter::Antialiasing, true);
      painter->setBrush(colour_);
      painter->setPen(QPen(Qt::white, 1.5));
      painter->drawEllipse(start, 4.5, 4.5);
    }
  }
}

void PointsItem::drawTimeDots(QPainter* painter, const Canvas& canvas) const {
  // Time runs from dark blue to yellow in kBins groups, so each group is one drawPoints call.
  constexpr std::size_t kBins = 48;
  const ColourMap colours(ColourMapName::Viridis);
  QVector<QPointF> visible;
  for (std::size_t b = 0; b < kBins; ++b) {
    const std::size_t begin = points_.size() * b / kBins, end = points_.size() * (b + 1) / kBins;
    visible.clear();
    for (std::size_t i = begin; i < end; ++i) {
      const QPointF q = canvas.at(points_[i]);
      if (canvas.clip.contains(q)) visible.append(q);
    }
    const Rgb c = colours.at(0.15 + 0.85 * static_cast<double>(b) / (kBins - 1));
    painter->setPen(QPen(QColor(c.r, c.g, c.b), 1.2));
    painter->drawPoints(visible.constData(), static_cast<int>(visible.size()));
  }
}

void PointsItem::drawTrail(QPainter* painter, const Canvas& canvas) const {
  // Consecutive steps jump across the island, so the trail is dots (a line would zigzag), growing
  // towards the step shown, which gets a ring.
  painter->setPen(Qt::NoPen);
  const std::size_t n = points_.size();
  for (std::size_t i = 0; i < n; ++i) {
    const QPointF q = canvas.at(points_[i]);
    if (!canvas.clip.contains(q)) continue;
    const double age = static_cast<double>(n - 1 - i) / static_cast<double>(std::max<std::size_t>(n, 2) - 1);
    painter->setBrush(QColor(255, 255, 255, static_cast<int>(255 - 175 * age)));
    const double r = 3.2 - 1.6 * age;
    painter->drawEllipse(q, r, r);
  }
  painter->setBrush(Qt::NoBrush);
  painter->setPen(QPen(QColor(0, 0, 0, 200), 4.5));
  painter->drawEllipse(canvas.at(points_.back()), 8, 8);
  painter->setPen(QPen(QColor(255, 70, 70), 2.5));
  painter->drawEllipse(canvas.at(points_.back()), 8, 8);
}

void PointsItem::drawMarks(QPainter* painter, const Canvas& canvas) const {
  const bool discs = style_ == Style::discs;
  painter->setPen(QPen(Qt::black, 1.5));
  painter->setBrush(colour_);
  for (const QPointF& p : points_) {
    const QPointF q = canvas.at(p);
    if (!canvas.clip.contains(q)) continue;
    if (discs) {
      // A ring about a small dot: the island around a chain's centre stays visible inside it at any zoom
      // (issue 37, finding 9: filled discs of 11 px hid the six islands at the full view).
      painter->setBrush(Qt::NoBrush);
      painter->setPen(QPen(QColor(0, 0, 0, 200), 3));
      painter->drawEllipse(q, kRingRadius, kRingRadius);
      painter->setPen(QPen(colour_, 1.5));
      painter->drawEllipse(q, kRingRadius, kRingRadius);
      painter->setPen(Qt::NoPen);
      painter->setBrush(colour_);
      painter->drawEllipse(q, 1.5, 1.5);
    } else {
      const QPointF d[4] = {q + QPointF(0, -7), q + QPointF(7, 0), q + QPointF(0, 7), q + QPointF(-7, 0)};
      painter->drawPolygon(d, 4);
    }
  }
}

void PointsItem::drawPolyline(QPainter* painter, const Canvas& canvas) const {
  // Only the runs of consecutive points near the canvas: a refined manifold holds 10⁵ points and more,
  // most far outside a deep view.
  const QRectF& canvasRect = canvas.rect;
  painter->setRenderHint(QPainter::Antialiasing, true);
  painter->setPen(QPen(colour_, penWidth_ / 2 + 0.5));
  QPolygonF run;
  const QRectF wide = canvasRect.adjusted(-canvasRect.width(), -canvasRect.height(), canvasRect.width(),
                                          canvasRect.height());
  const auto flush = [&] {
    if (run.size() > 1) painter->drawPolyline(run);
    run.clear();
  };
  for (const QPointF& p : points_) {
    const QPointF q = canvas.at(p);
    if (wide.contains(q)) run.append(q);
    else flush();
  }
  flush();
}

void PointsItem::drawPolygon(QPainter* painter, const Canvas& canvas) const {
  QPolygonF polygon;
  polygon.reserve(static_cast<int>(points_.size()));
  for (const QPointF& p : points_) polygon.append(canvas.at(p));
  if (!polygon.boundingRect().intersects(canvas.rect)) return;
  QColor fill = colour_;
  fill.setAlpha(90);
  painter->setRenderHint(QPainter::Antialiasing, true);
  painter->setPen(QPen(colour_, 1));
  painter->setBrush(fill);
  painter->drawPolygon(polygon);
}

QRectF PointsItem::labelRect(const QPointF& anchor, const QSizeF& size, const QRectF& canvas) {
  QRectF at(anchor.x() + 8, anchor.y() - size.height() / 2, size.width(), size.height());
  if (at.right() > canvas.right()) at.moveRight(canvas.right());
  if (at.left() < canvas.left()) at.moveLeft(canvas.left());
  if (at.bottom() > canvas.bottom()) at.moveBottom(canvas.bottom());
  if (at.top() < canvas.top()) at.moveTop(canvas.top());
  return at;
}

void PointsItem::drawLabel(QPainter* painter, const Canvas& canvas) const {
  if (label_.isEmpty()) return;
  QPolygonF polygon;
  polygon.reserve(static_cast<int>(points_.size()));
  for (const QPointF& p : points_) polygon.append(canvas.at(p));
  const QPointF c = polygon.boundingRect().center();
  if (!canvas.rect.contains(c)) return;
  const QRectF box = painter->fontMetrics().boundingRect(label_).adjusted(-4, -2, 4, 2);
  const QRectF at = labelRect(c, box.size(), canvas.rect);
  painter->setPen(Qt::NoPen);
  painter->setBrush(QColor(0, 0, 0, 170));
  painter->drawRoundedRect(at, 3, 3);
  painter->setPen(Qt::white);
  painter->drawText(at, Qt::AlignCenter, label_);
}

bool PointsItem::anyPointIn(const QRectF& rect) const {
  return std::any_of(points_.begin(), points_.end(), [&rect](const QPointF& p) { return rect.contains(p); });
}

}  // namespace archipelago::ui
