#pragma once
/// \file PortraitLayers.hpp
/// \brief The overlay layers drawn over a phase portrait, and the plot item that draws points for them.
///
/// The PortraitController's layers (ViewLayer, LaunchedOrbitsLayer, ManifoldsLayer, AtlasIslandLayer, OverlayLayer)
/// own what each layer shows and hand the PortraitView fresh items for a layer (PortraitView::setLayer); the view
/// attaches them to its plot and deletes them when the layer is replaced or the view goes.  Nothing else touches the
/// view's plot.

#include <QColor>
#include <QPointF>
#include <QRectF>
#include <QString>
#include <qwt_plot_item.h>

#include <vector>

#include "core/map/FixedPointMap.hpp"

namespace archipelago::ui {

/// Physical points (long double) as the plot's points (double).
[[nodiscard]] std::vector<QPointF> toQt(const std::vector<PhysicalPoint>& points);

/// The layers, bottom to top.
enum class PortraitLayer {
  lobes,           ///< the turnstile's lobes of the manifolds layer, shaded (below every curve)
  manifolds,       ///< stable (blue) and unstable (red) manifolds of a hyperbolic orbit
  fixedPoints,     ///< the fixed points of Q* (elliptic: ring, hyperbolic: cross)
  launchedOrbits,  ///< orbits launched by clicks, one colour each
  orbitChain,      ///< the elliptic periodic orbit of the highlighted launched orbit's chain
  segment,         ///< the selected long segment (dots coloured by time)
  segmentChain,    ///< the centre orbit of its island chain
  segmentStep,     ///< the step of the segment shown, with a trail of the steps before it
  atlasIsland,     ///< the boundary circle of the island selected on the Atlas page (every island of its chain)
  periodicOrbits,  ///< orbits from the "Find periodic orbit" dialog
  profileLine,     ///< the segment of the rotation-profile tool
  lobeLabel,       ///< the lobes' area, over every curve and orbit and kept inside the canvas (issue 53, finding 16)
};

/// A line of the portrait's legend and the layer it names: listed only while that layer shows something in the view
/// (issue 53, finding 15).
struct LegendLine {
  PortraitLayer layer;
  QString text;  ///< rich text
};

/// Points in physical coordinates: dots in one colour, dots coloured by their position in the list (time),
/// a trail of growing dots ending in a ring, discs (a ring about a dot: the island inside stays visible),
/// diamonds, a polyline (a manifold's piece), a closed polygon filled with a translucent colour (a lobe), or a label at
/// the centre of the points' bounding box (a lobe's area, drawn over the orbits).  (A plain QwtPlotItem: Qwt 6.1's curve
/// headers are not C++20, and only the points inside the canvas need drawing.)
class PointsItem : public QwtPlotItem {
 public:
  enum class Style { dots, timeDots, trail, discs, diamonds, polyline, polygon, label };
  static constexpr int kRtti = QwtPlotItem::Rtti_PlotUserItem + 40;
  /// Discs: the radius (pixels) of the ring about a chain's centre; inside it only a dot of 1.5 px is drawn.
  static constexpr double kRingRadius = 7;

  PointsItem(Style style, std::vector<QPointF> points, QColor colour = Qt::white);
  /// Dots and polylines: the pen width (highlighted launched orbits are drawn wider).
  void setPenWidth(double width) noexcept { penWidth_ = width; }
  /// The text of a label (Style::label: e.g. a lobe's area).
  void setLabel(const QString& label) { label_ = label; }
  [[nodiscard]] const QString& label() const noexcept { return label_; }
  /// Where a label of `size` goes for the point `anchor` (pixels): just right of it, moved inside `canvas` whole.
  [[nodiscard]] static QRectF labelRect(const QPointF& anchor, const QSizeF& size, const QRectF& canvas);
  /// True when a point lies in `rect` (physical): the item shows something in that view.
  [[nodiscard]] bool anyPointIn(const QRectF& rect) const;
  /// Dots: a ring at the first point (a launched orbit's start, told apart from the portrait's own orbits).
  void setStartMarker(bool on) noexcept { startMarker_ = on; }
  [[nodiscard]] QColor colour() const noexcept { return colour_; }
  int rtti() const override { return kRtti; }
  [[nodiscard]] std::size_t size() const noexcept { return points_.size(); }
  [[nodiscard]] const std::vector<QPointF>& points() const noexcept { return points_; }
  void draw(QPainter* painter, const QwtScaleMap& xMap, const QwtScaleMap& yMap,
            const QRectF& canvasRect) const override;

 private:
  /// The steps of draw(), one per style (discs and diamonds: drawMarks), between its save and restore.
  struct Canvas;
  void drawDots(QPainter* painter, const Canvas& canvas) const;
  void drawTimeDots(QPainter* painter, const Canvas& canvas) const;
  void drawTrail(QPainter* painter, const Canvas& canvas) const;
  void drawMarks(QPainter* painter, const Canvas& canvas) const;
  void drawPolyline(QPainter* painter, const Canvas& canvas) const;
  void drawPolygon(QPainter* painter, const Canvas& canvas) const;
  void drawLabel(QPainter* painter, const Canvas& canvas) const;

  Style style_;
  std::vector<QPointF> points_;
  QColor colour_;
  double penWidth_ = 2;
  bool startMarker_ = false;
  QString label_;
};

}  // namespace archipelago::ui
