#include "ui/portrait/ViewLayer.hpp"

#include <QBrush>
#include <QPen>
#include <qwt_plot_marker.h>
#include <qwt_symbol.h>

#include <algorithm>
#include <exception>
#include <utility>

#include "core/portrait/MapOverlays.hpp"
#include "core/view/DeepestZoom.hpp"
#include "ui/portrait/PortraitLayers.hpp"
#include "ui/portrait/PortraitView.hpp"

namespace archipelago::ui {

namespace {
/// The smallest view aspect (and its inverse the largest) a rectangle zoom gives with equal aspect.
constexpr double kMinCropAspect = 0.25;
}  // namespace

ViewLayer::ViewLayer(PortraitView* view) : view_(view) { showMap(); }

void ViewLayer::setMap(const MapParameters& map) {
  map_ = map;
  history_.assign(1, Viewport());
  historyIndex_ = 0;
}

void ViewLayer::showMap() {
  updateFixedPoints();
  if (view_) view_->display(map_, viewport());
}

void ViewLayer::zoomAt(double fx, double fy, double factor) {
  show(true, viewport().zoomedAboutFraction(fx, fy, factor));
  if (factor > 1) noteDeepestZoom();
}

void ViewLayer::noteDeepestZoom() {
  if (atDeepestZoom(viewport())) Q_EMIT statusMessage(QString::fromStdString(deepestZoomNote(map_)));
}

void ViewLayer::panBy(double fx, double fy) {
  const Viewport moved = viewport().panned(fx, fy);
  if (moved == viewport()) {
    Q_EMIT statusMessage(viewport() == Viewport()
                             ? tr("The whole box is shown: zoom in (+, the wheel or a drag) before panning")
                             : tr("The view is at the edge of the box: it cannot move further that way"));
    if (view_) view_->display(map_, viewport());  // axes back where the view is, whatever moved them
    return;
  }
  show(true, moved);
}

void ViewLayer::crop(double fx0, double fx1, double fy0, double fy1) {
  cropView(fx0, fx1, fy0, fy1);
  noteDeepestZoom();
}

void ViewLayer::cropView(double fx0, double fx1, double fy0, double fy1) {
  if (!equalAspect() || !view_) {
    show(true, viewport().cropped(fx0, fx1, fy0, fy1));
    return;
  }
  // The rectangle as dragged, widened (never shrunk) so that it is no thinner than 1:4 on screen.
  const PhysicalRect r = viewport().physical(map_);
  const long double w = r.x1 - r.x0, h = r.y1 - r.y0;
  SegmentRegion region;
  region.x0 = r.x0 + fx0 * w;
  region.x1 = r.x0 + fx1 * w;
  region.y0 = r.y0 + fy0 * h;
  region.y1 = r.y0 + fy1 * h;
  const long double rw = region.x1 - region.x0, rh = region.y1 - region.y0;
  if (!(rw > 0) || !(rh > 0)) return;
  const double aspect = std::clamp(static_cast<double>(rw / rh), kMinCropAspect, 1 / kMinCropAspect);
  try {
    const SegmentRegion framed = framedInBox(region, map_, aspect, map_.width() * 0x1p-36L);
    show(true, Viewport::fromPhysical(map_, {framed.x0, framed.x1, framed.y0, framed.y1}));
  } catch (const std::exception&) {
    show(true, viewport().cropped(fx0, fx1, fy0, fy1));
  }
}

bool ViewLayer::zoomToRegion(const SegmentRegion& region) {
  if (!view_) return false;
  // At least 2^16 grid units: a few pixels of the finest view the portrait allows, far below any island.
  const long double minSize = map_.width() * 0x1p-36L;
  try {
    const SegmentRegion framed = framedInBox(region, map_, view_->targetAspect(), minSize);
    show(true, Viewport::fromPhysical(map_, {framed.x0, framed.x1, framed.y0, framed.y1}));
  } catch (const std::exception&) {
    return false;  // a region outside this map's box: leave the view alone
  }
  return true;
}

bool ViewLayer::goTo(long double x, long double y, long double width, QString* error) {
  QString why;
  if (const auto e = viewWidthError(width, map_)) why = QString::fromStdString(*e);
  else if (const auto f = boxPointError("the centre", map_, {x, y})) why = QString::fromStdString(*f);
  else if (!zoomToRegion(SegmentRegion{x - width / 2, x + width / 2, y, y, 0})) why = tr("the view does not fit the box");
  if (why.isEmpty()) return true;
  if (error) *error = why;
  return false;
}

bool ViewLayer::shows(long double x, long double y) const noexcept {
  const PhysicalRect r = viewport().physical(map_);
  return x >= r.x0 && x <= r.x1 && y >= r.y0 && y <= r.y1;
}

void ViewLayer::ensureVisible(long double x, long double y) {
  if (shows(x, y)) return;
  const Viewport& v = viewport();
  const PhysicalPoint offset = v.unitOffset(map_, x, y);
  history_[historyIndex_] = v.panned(offset.x / v.widthUnits(), offset.y / v.heightUnits());
  show(false, viewport());
}

bool ViewLayer::restoreHistory(std::vector<Viewport> views, std::size_t current) {
  if (views.empty() || current >= views.size()) return false;
  history_ = std::move(views);
  historyIndex_ = current;
  show(false, viewport());
  return true;
}

void ViewLayer::back() {
  if (!canGoBack()) return;
  --historyIndex_;
  show(false, viewport());
}

void ViewLayer::forward() {
  if (!canGoForward()) return;
  ++historyIndex_;
  show(false, viewport());
}

void ViewLayer::resetView() {
  if (viewport() == Viewport()) {
    if (view_) {
      view_->display(map_, viewport());  // axes back to the box, whatever moved them
      view_->rerender();                 // Reset always draws anew (e.g. after a render at a smaller size)
    }
    return;
  }
  show(true, Viewport());
}

void ViewLayer::show(bool record, const Viewport& view) {
  if (record) {
    if (view == viewport()) {
      if (view_) view_->display(map_, viewport());
      return;
    }
    history_.resize(historyIndex_ + 1);
    history_.push_back(view);
    historyIndex_ = history_.size() - 1;
  }
  if (view_) view_->display(map_, viewport());
  Q_EMIT viewportChanged();
}

void ViewLayer::setEqualAspect(bool on) {
  if (!view_ || view_->equalAspect() == on) return;
  view_->setEqualAspect(on);
  Q_EMIT settingsChanged();
}

bool ViewLayer::equalAspect() const noexcept { return view_ && view_->equalAspect(); }

void ViewLayer::setMode(PortraitMode mode) {
  if (!view_ || (view_->mode() == mode && !view_->indicator())) return;
  view_->setMode(mode, std::nullopt);
  Q_EMIT settingsChanged();
}

PortraitMode ViewLayer::mode() const noexcept { return view_ ? view_->mode() : PortraitMode::Orbits; }

void ViewLayer::setIndicator(std::optional<IndicatorKind> kind) {
  if (!view_ || view_->indicator() == kind) return;
  view_->setMode(view_->mode(), kind);
  Q_EMIT settingsChanged();
}

std::optional<IndicatorKind> ViewLayer::indicator() const noexcept { return view_ ? view_->indicator() : std::nullopt; }

void ViewLayer::setColourMap(ColourMapName colours) {
  if (!view_ || view_->colourMap() == colours) return;
  view_->setColourMap(colours);
  Q_EMIT settingsChanged();
}

ColourMapName ViewLayer::colourMap() const noexcept { return view_ ? view_->colourMap() : ColourMapName::Inferno; }

void ViewLayer::setPointBudget(std::uint64_t points) {
  if (!view_ || view_->pointBudget() == points) return;
  view_->setPointBudget(points);
  Q_EMIT settingsChanged();
}

std::uint64_t ViewLayer::pointBudget() const noexcept { return view_ ? view_->pointBudget() : 0; }

void ViewLayer::stopRendering() {
  if (view_) view_->stopRender();
}

void ViewLayer::setRenderPaused(bool paused) {
  if (view_) view_->setRenderPaused(paused);
}

void ViewLayer::updateFixedPoints() {
  if (!view_) return;
  std::vector<QwtPlotItem*> markers;
  for (const FixedPoint& p : fixedPoints(map_)) {
    auto* marker = new QwtPlotMarker;
    marker->setValue(static_cast<double>(p.position.x), static_cast<double>(p.position.y));
    marker->setSymbol(new QwtSymbol(p.elliptic ? QwtSymbol::Ellipse : QwtSymbol::XCross, QBrush(Qt::NoBrush),
                                    QPen(Qt::white, 1.5), QSize(9, 9)));
    marker->setZ(30);
    marker->setTitle(p.elliptic ? tr("elliptic fixed point") : tr("hyperbolic fixed point"));
    markers.push_back(marker);
  }
  view_->setLayer(PortraitLayer::fixedPoints, std::move(markers));
}

}  // namespace archipelago::ui
