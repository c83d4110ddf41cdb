#include "ui/portrait/PortraitController.hpp"

#include <QBrush>
#include <QPen>
#include <QWidget>
#include <qwt_plot_marker.h>
#include <qwt_symbol.h>
#include <qwt_text.h>

#include <algorithm>
#include <exception>

#include "core/periodic/SegmentAnalysis.hpp"
#include "core/portrait/MapOverlays.hpp"
#include "ui/portrait/PortraitLayers.hpp"
#include "ui/portrait/PortraitView.hpp"
#include "ui/portrait/SegmentOverlay.hpp"

namespace archipelago::ui {

PortraitController::PortraitController(QWidget* viewParent) : QObject(viewParent) {
  view_ = new PortraitView(viewParent);
  PortraitView* v = view_;
  connect(v, &PortraitView::zoomRequested, this, &PortraitController::zoomAt);
  connect(v, &PortraitView::panRequested, this, &PortraitController::panBy);
  connect(v, &PortraitView::cropRequested, this, &PortraitController::crop);
  connect(v, &PortraitView::clicked, this, [this](double x, double y) { launchOrbit(x, y); });
  connect(v, &PortraitView::backRequested, this, &PortraitController::back);
  connect(v, &PortraitView::forwardRequested, this, &PortraitController::forward);
  connect(v, &PortraitView::resetRequested, this, &PortraitController::resetView);
  connect(v, &PortraitView::statusMessage, this, &PortraitController::statusMessage);
  updateFixedPoints();
  view_->display(map_, viewport());
}

PortraitController::~PortraitController() = default;

bool PortraitController::setMap(const MapParameters& map, double Xr) {
  if (auto e = validationError(map)) {
    Q_EMIT statusMessage(tr("Invalid parameters: %1").arg(QString::fromStdString(*e)));
    return false;
  }
  if (map == map_) {
    Xr_ = Xr;  // the portrait does not depend on Xr (only the b₂ dialog does)
    return true;
  }
  map_ = map;
  Xr_ = Xr;
  history_.assign(1, Viewport());
  historyIndex_ = 0;
  orbits_.clear();
  if (view_) view_->setLayer(PortraitLayer::launchedOrbits, {});
  clearSegment();
  updateFixedPoints();
  if (view_) view_->display(map_, viewport());
  Q_EMIT mapChanged();
  Q_EMIT viewportChanged();
  return true;
}

void PortraitController::setViewport(const Viewport& view) { show(true, view); }

void PortraitController::zoomAt(double fx, double fy, double factor) {
  show(true, viewport().zoomedAboutFraction(fx, fy, factor));
}

void PortraitController::panBy(double fx, double fy) { show(true, viewport().panned(fx, fy)); }

void PortraitController::crop(double fx0, double fx1, double fy0, double fy1) {
  show(true, viewport().cropped(fx0, fx1, fy0, fy1));
}

bool PortraitController::zoomToRegion(const SegmentRegion& region) {
  if (!view_) return false;
  // At least 2^16 grid units: a few pixels of the finest view the portrait allows, far below any island.
  const long double minSize = map_.width() * 0x1p-36L;
  try {
    const SegmentRegion framed = framedInBox(region, map_, view_->canvasAspect(), minSize);
    show(true, Viewport::fromPhysical(map_, {framed.x0, framed.x1, framed.y0, framed.y1}));
  } catch (const std::exception&) {
    return false;  // a region outside this map's box: leave the view alone
  }
  return true;
}

bool PortraitController::shows(long double x, long double y) const noexcept {
  const PhysicalRect r = viewport().physical(map_);
  return x >= r.x0 && x <= r.x1 && y >= r.y0 && y <= r.y1;
}

void PortraitController::ensureVisible(long double x, long double y) {
  if (shows(x, y)) return;
  const Viewport& v = viewport();
  const PhysicalPoint offset = v.unitOffset(map_, x, y);
  history_[historyIndex_] = v.panned(offset.x / v.widthUnits(), offset.y / v.heightUnits());
  show(false, viewport());
}

bool PortraitController::restoreHistory(std::vector<Viewport> views, std::size_t current) {
  if (views.empty() || current >= views.size()) return false;
  history_ = std::move(views);
  historyIndex_ = current;
  show(false, viewport());
  return true;
}

void PortraitController::back() {
  if (!canGoBack()) return;
  --historyIndex_;
  show(false, viewport());
}

void PortraitController::forward() {
  if (!canGoForward()) return;
  ++historyIndex_;
  show(false, viewport());
}

void PortraitController::resetView() {
  if (viewport() == Viewport()) {
    if (view_) view_->rerender();  // Reset always draws anew (e.g. after a render at a smaller size)
    return;
  }
  show(true, Viewport());
}

void PortraitController::show(bool record, const Viewport& view) {
  if (record) {
    if (view == viewport()) return;
    history_.resize(historyIndex_ + 1);
    history_.push_back(view);
    historyIndex_ = history_.size() - 1;
  }
  if (view_) view_->display(map_, viewport());
  Q_EMIT viewportChanged();
}

void PortraitController::setMode(PortraitMode mode) {
  if (!view_ || view_->mode() == mode) return;
  view_->setMode(mode);
  Q_EMIT settingsChanged();
}

PortraitMode PortraitController::mode() const noexcept { return view_ ? view_->mode() : PortraitMode::Orbits; }

void PortraitController::setColourMap(ColourMapName colours) {
  if (!view_ || view_->colourMap() == colours) return;
  view_->setColourMap(colours);
  Q_EMIT settingsChanged();
}

ColourMapName PortraitController::colourMap() const noexcept {
  return view_ ? view_->colourMap() : ColourMapName::Inferno;
}

void PortraitController::setPointBudget(std::uint64_t points) {
  if (!view_ || view_->pointBudget() == points) return;
  view_->setPointBudget(points);
  Q_EMIT settingsChanged();
}

std::vector<PhysicalPoint> PortraitController::launchedOrbitStarts() const {
  std::vector<PhysicalPoint> starts;
  for (const auto& orbit : orbits_)
    if (!orbit.empty()) starts.push_back(orbit.front());
  return starts;
}

std::uint64_t PortraitController::pointBudget() const noexcept { return view_ ? view_->pointBudget() : 0; }

void PortraitController::stopRendering() {
  if (view_) view_->stopRender();
}

void PortraitController::launchOrbit(double x, double y, int steps) {
  std::vector<PhysicalPoint> points;
  try {
    points = traceOrbit(map_, x, y, static_cast<std::uint64_t>(std::max(steps, 0)));
  } catch (const std::exception& e) {
    Q_EMIT statusMessage(tr("Orbit: %1").arg(QString::fromUtf8(e.what())));
    return;
  }
  orbits_.push_back(std::move(points));
  std::vector<QwtPlotItem*> items;
  for (std::size_t i = 0; i < orbits_.size(); ++i) {
    std::vector<QPointF> samples;
    samples.reserve(orbits_[i].size());
    for (const PhysicalPoint& p : orbits_[i]) samples.emplace_back(static_cast<double>(p.x), static_cast<double>(p.y));
    const Rgb c = orbitColour(static_cast<std::uint32_t>(i + 1));
    auto* item = new PointsItem(PointsItem::Style::dots, std::move(samples), QColor(c.r, c.g, c.b));
    item->setTitle(tr("orbit %1").arg(i + 1));
    items.push_back(item);
  }
  if (view_) view_->setLayer(PortraitLayer::launchedOrbits, std::move(items));
  Q_EMIT statusMessage(
      tr("Orbit %1 from (%2, %3): %4 steps").arg(orbits_.size()).arg(x, 0, 'g', 17).arg(y, 0, 'g', 17).arg(steps));
}

void PortraitController::clearOrbits() {
  orbits_.clear();
  if (view_) view_->setLayer(PortraitLayer::launchedOrbits, {});
}

void PortraitController::showSegment(const SegmentReplayPtr& replay) {
  replay_ = replay;
  chain_.reset();
  if (!view_) return;
  view_->setLayer(PortraitLayer::segment, SegmentOverlay::segmentItems(replay_));
  view_->setLayer(PortraitLayer::segmentChain, {});
  view_->setLayer(PortraitLayer::segmentStep, {});
  updateLegend();
}

void PortraitController::showSegmentChain(const ChainResultPtr& chain) {
  chain_ = chain;
  if (!view_) return;
  view_->setLayer(PortraitLayer::segmentChain, SegmentOverlay::chainItems(chain_));
  updateLegend();
}

void PortraitController::showSegmentStep(std::size_t index) {
  if (view_ && replay_) view_->setLayer(PortraitLayer::segmentStep, SegmentOverlay::stepItems(replay_, index));
}

void PortraitController::showPeriodicOrbit(const PeriodicOrbit& orbit) {
  periodicPeriod_ = orbit.period;
  periodic_ = orbit;
  if (!view_) return;
  view_->setLayer(PortraitLayer::periodicOrbits, SegmentOverlay::periodicItems(orbit));
  updateLegend();
}

void PortraitController::clearSegment() {
  replay_.reset();
  chain_.reset();
  periodicPeriod_ = 0;
  periodic_.reset();
  if (!view_) return;
  for (PortraitLayer layer : {PortraitLayer::segment, PortraitLayer::segmentChain, PortraitLayer::segmentStep,
                              PortraitLayer::periodicOrbits})
    view_->setLayer(layer, {});
  updateLegend();
}

void PortraitController::updateLegend() {
  if (view_) view_->setLegend(SegmentOverlay::legendLines(replay_, chain_, periodicPeriod_).join(QStringLiteral("<br>")));
}

void PortraitController::updateFixedPoints() {
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

SessionPortrait PortraitController::sessionState() const {
  SessionPortrait state;
  state.history = history_;
  state.current = historyIndex_;
  state.mode = mode();
  state.colours = view_ ? view_->colourMap() : ColourMapName::Inferno;
  state.budget = pointBudget();
  for (const auto& orbit : orbits_)
    if (!orbit.empty()) state.orbits.push_back({static_cast<double>(orbit.front().x), static_cast<double>(orbit.front().y)});
  if (periodic_ && periodicPeriod_ > 0) {
    SessionPeriodicOverlay overlay;
    overlay.label = "period " + std::to_string(periodic_->period);
    for (const PhysicalPoint& p : periodic_->points)
      overlay.points.push_back({static_cast<double>(p.x), static_cast<double>(p.y)});
    state.periodic.push_back(std::move(overlay));
  }
  return state;
}

void PortraitController::restoreSession(const SessionPortrait& state, const MapParameters& map, double Xr) {
  setMap(map, Xr);
  clearOrbits();
  clearSegment();
  setMode(state.mode);
  setColourMap(state.colours);
  if (state.budget > 0) setPointBudget(state.budget);
  if (!state.history.empty()) restoreHistory(state.history, std::min(state.current, state.history.size() - 1));
  for (const auto& start : state.orbits) launchOrbit(start[0], start[1]);
  for (const SessionPeriodicOverlay& overlay : state.periodic) {
    PeriodicOrbit orbit;
    orbit.K = map.K;
    orbit.period = static_cast<int>(overlay.points.size());
    for (const auto& p : overlay.points) orbit.points.push_back({p[0], p[1]});
    showPeriodicOrbit(orbit);
  }
}

}  // namespace archipelago::ui
