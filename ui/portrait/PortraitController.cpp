#include "ui/portrait/PortraitController.hpp"

#include <QStringList>
#include <QWidget>

#include <algorithm>
#include <string>
#include <utility>

#include "core/io/NumberText.hpp"
#include "core/periodic/PeriodicOrbitFinder.hpp"

namespace archipelago::ui {

namespace {
QString kText(double K) { return QString::fromStdString(io::shortestText(K)); }
}  // namespace

PortraitController::PortraitController(QWidget* viewParent) : QObject(viewParent) {
  view_ = new PortraitView(viewParent);
  viewLayer_ = std::make_unique<ViewLayer>(view_);
  orbits_ = std::make_unique<LaunchedOrbitsLayer>(*viewLayer_);
  manifolds_ = std::make_unique<ManifoldsLayer>(*viewLayer_);
  atlas_ = std::make_unique<AtlasIslandLayer>(*viewLayer_);
  overlay_ = std::make_unique<OverlayLayer>(*viewLayer_);
  wireView();
  wireLayers();
}

PortraitController::~PortraitController() {
  // The layers stop their jobs and join their threads, the view's last (the others read its map).
  overlay_.reset();
  atlas_.reset();
  manifolds_.reset();
  orbits_.reset();
  viewLayer_.reset();
}

void PortraitController::wireView() {
  PortraitView* v = view_;
  ViewLayer* layer = viewLayer_.get();
  connect(v, &PortraitView::zoomRequested, layer, &ViewLayer::zoomAt);
  connect(v, &PortraitView::panRequested, layer, &ViewLayer::panBy);
  connect(v, &PortraitView::cropRequested, layer, &ViewLayer::crop);
  // A click launches an orbit and ends the selection: the new orbit is drawn in full, as are the others (issue 37,
  // finding 8: orbits clicked while one was selected were drawn dimmed, nearly invisible).
  connect(v, &PortraitView::periodicOrbitRequested, overlay_.get(), &OverlayLayer::findPeriodicOrbitAt);
  connect(v, &PortraitView::clicked, this, [this](long double x, long double y) {
    if (overlay_->clickFindsPeriodicOrbit()) return overlay_->findPeriodicOrbitAt(x, y);
    orbits_->highlightOrbit(0);
    orbits_->launchOrbit(x, y, orbits_->clickSteps(), orbits_->clickBackward());
  });
  connect(v, &PortraitView::backRequested, layer, &ViewLayer::back);
  connect(v, &PortraitView::forwardRequested, layer, &ViewLayer::forward);
  connect(v, &PortraitView::resetRequested, layer, &ViewLayer::resetView);
  connect(v, &PortraitView::statusMessage, this, &PortraitController::statusMessage);
}

void PortraitController::wireLayers() {
  // A new view refines the manifolds in it before anyone hears of it.
  connect(viewLayer_.get(), &ViewLayer::viewportChanged, this, [this] {
    manifolds_->followView();
    updateLegend();
    Q_EMIT viewportChanged();
  });
  connect(viewLayer_.get(), &ViewLayer::settingsChanged, this, &PortraitController::settingsChanged);
  connect(orbits_.get(), &LaunchedOrbitsLayer::orbitsChanged, this, &PortraitController::orbitsChanged);
  connect(manifolds_.get(), &ManifoldsLayer::manifoldsChanged, this, &PortraitController::manifoldsChanged);
  connect(overlay_.get(), &OverlayLayer::periodicOrbitFound, this, &PortraitController::periodicOrbitFound);
  connect(atlas_.get(), &AtlasIslandLayer::islandDrawn, this, &PortraitController::showIslandChain);
  connect(atlas_.get(), &AtlasIslandLayer::atlasIslandShown, this, &PortraitController::atlasIslandShown);
  connect(viewLayer_.get(), &ViewLayer::statusMessage, this, &PortraitController::statusMessage);
  connect(orbits_.get(), &LaunchedOrbitsLayer::statusMessage, this, &PortraitController::statusMessage);
  connect(manifolds_.get(), &ManifoldsLayer::statusMessage, this, &PortraitController::statusMessage);
  connect(atlas_.get(), &AtlasIslandLayer::statusMessage, this, &PortraitController::statusMessage);
  connect(overlay_.get(), &OverlayLayer::statusMessage, this, &PortraitController::statusMessage);
  connect(manifolds_.get(), &ManifoldsLayer::legendChanged, this, &PortraitController::updateLegend);
  connect(atlas_.get(), &AtlasIslandLayer::legendChanged, this, &PortraitController::updateLegend);
  connect(overlay_.get(), &OverlayLayer::legendChanged, this, &PortraitController::updateLegend);
}

bool PortraitController::setMap(const MapParameters& map, double Xr) {
  if (auto e = validationError(map)) {
    Q_EMIT statusMessage(tr("Invalid parameters: %1").arg(QString::fromStdString(*e)));
    return false;
  }
  if (map == this->map()) {
    Xr_ = Xr;  // the portrait does not depend on Xr (only the b₂ dialog does)
    return true;
  }
  // Returning to the map left last brings its work back; leaving a map with work keeps it (one map deep).
  std::optional<KeptWork> back;
  if (kept_ && kept_->map == map) back = std::exchange(kept_, std::nullopt);
  if (hasWork()) {
    const int orbits = orbitCount();
    kept_ = KeptWork{this->map(), sessionState()};
    if (!back)
      Q_EMIT statusMessage(tr("A new map: the %1 launched orbits and %2 views of K = %3 are kept; set K = %3 again "
                              "to have them back")
                               .arg(orbits)
                               .arg(history().size())
                               .arg(kText(this->map().K)));
  }
  viewLayer_->setMap(map);
  Xr_ = Xr;
  clearLayers();
  viewLayer_->showMap();
  if (manifolds_->manifoldsShown()) manifolds_->recompute();
  Q_EMIT manifoldsChanged();
  Q_EMIT mapChanged();
  if (back) {
    restoreWork(back->portrait, map);
    Q_EMIT statusMessage(tr("K = %1 again: its %2 launched orbits and %3 views are back")
                             .arg(kText(map.K))
                             .arg(back->portrait.orbits.size())
                             .arg(back->portrait.history.size()));
  }
  Q_EMIT viewportChanged();
  return true;
}

void PortraitController::clearLayers() {
  orbits_->discardOrbits();
  overlay_->clearSegment();
  overlay_->clearPeriodicOrbit();
  atlas_->clearAtlasIsland();
  overlay_->showProfileLine(std::nullopt);
  manifolds_->forgetMap();
}

bool PortraitController::hasWork() const {
  return orbitCount() > 0 || history().size() > 1 || shownPeriodicOrbit().has_value() || manifoldOrbit().has_value();
}

std::optional<MapParameters> PortraitController::keptMap() const {
  return kept_ ? std::optional<MapParameters>(kept_->map) : std::nullopt;
}

void PortraitController::showIslandChain(const AtlasIslandPtr& island, bool centre) {
  if (island->chain) overlay_->showPeriodicOrbit(*island->chain);
  // The barrier about the island's chain: the partner's manifolds (at the centre, the fixed point's loop).
  if (centre) manifolds_->setManifoldOrbit(std::nullopt);
  else if (island->partner) manifolds_->setManifoldOrbit(island->partner);
  else manifolds_->setManifoldsShown(false);
}

void PortraitController::updateLegend() {
  if (!view_) return;
  // Only what the view shows (issue 53, finding 15: five layers were listed in a view containing none of them).
  QStringList lines;
  for (const auto& layer : {overlay_->legendLines(), atlas_->legendLines(), manifolds_->legendLines()})
    for (const LegendLine& line : layer)
      if (view_->layerInView(line.layer)) lines << line.text;
  view_->setLegend(lines.join(QStringLiteral("<br>")));
}

// ------------------------------------------------------------------------------------------------- sessions

SessionPortrait PortraitController::sessionState() const {
  SessionPortrait state;
  state.history = history();
  state.current = historyIndex();
  state.mode = mode();
  state.colours = view_ ? view_->colourMap() : ColourMapName::Inferno;
  state.budget = pointBudget();
  for (const LaunchedOrbit& orbit : launchedOrbits())
    state.orbits.push_back({{static_cast<double>(orbit.x), static_cast<double>(orbit.y)}, orbit.steps, orbit.backward, orbit.id});
  if (const auto& periodic = shownPeriodicOrbit(); periodic && periodic->period > 0) {
    SessionPeriodicOverlay overlay;
    overlay.label = "period " + std::to_string(periodic->period);
    for (const PhysicalPoint& p : periodic->points)
      overlay.points.push_back({static_cast<double>(p.x), static_cast<double>(p.y)});
    state.periodic.push_back(std::move(overlay));
  }
  state.manifolds = manifoldsShown();
  if (manifoldsShown() && manifoldOrbit())
    for (const PhysicalPoint& p : manifoldOrbit()->points)
      state.manifoldOrbit.push_back({static_cast<double>(p.x), static_cast<double>(p.y)});
  return state;
}

void PortraitController::restoreSession(const SessionPortrait& state, const MapParameters& map, double Xr) {
  setMap(map, Xr);
  orbits_->discardOrbits();
  overlay_->clearSegment();
  overlay_->clearPeriodicOrbit();
  atlas_->clearAtlasIsland();
  setMode(state.mode);
  setColourMap(state.colours);
  if (state.budget > 0) setPointBudget(state.budget);
  restoreWork(state, map);
}

void PortraitController::restoreManifolds(const SessionPortrait& state, const MapParameters& map) {
  // The manifolds layer (issue 37, finding 4): of the fixed point, or of the orbit found again by core's Newton
  // from its first point (the session keeps double coordinates; the manifolds need the orbit to quad precision).
  if (!state.manifolds) {
    setManifoldsShown(false);
  } else if (state.manifoldOrbit.empty()) {
    setManifoldOrbit(std::nullopt);
  } else {
    const auto& z = state.manifoldOrbit.front();
    const int period = static_cast<int>(state.manifoldOrbit.size());
    if (auto orbit = refinePeriodicOrbit(map.K, period, PhysicalPoint{z[0], z[1]})) {
      setManifoldOrbit(std::move(orbit));
    } else {
      setManifoldsShown(false);
      Q_EMIT statusMessage(tr("The session's manifolds are of a period-%1 orbit that is not found at K = %2: not drawn")
                               .arg(period)
                               .arg(kText(map.K)));
    }
  }
}

void PortraitController::restoreWork(const SessionPortrait& state, const MapParameters& map) {
  if (!state.history.empty()) restoreHistory(state.history, std::min(state.current, state.history.size() - 1));
  // Each orbit is traced and measured once, in the background (the codec bounds them by kMaxSessionOrbits,
  // which is kMaxLaunchedOrbits).
  for (const SessionOrbit& o : state.orbits) launchOrbit(o.start[0], o.start[1], o.steps, o.backward, o.number);
  for (const SessionPeriodicOverlay& overlay : state.periodic) {
    PeriodicOrbit orbit;
    orbit.K = map.K;
    orbit.period = static_cast<int>(overlay.points.size());
    for (const auto& p : overlay.points) orbit.points.push_back({p[0], p[1]});
    showPeriodicOrbit(orbit);
  }
  // The manifolds of the orbit they were of (issue 53, finding 13: after K 0.1 → 0.15 → 0.1 the period-13 orbit
  // came back with the fixed point's manifolds).
  restoreManifolds(state, map);
}

}  // namespace archipelago::ui
