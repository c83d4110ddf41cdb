#pragma once
/// \file PortraitController.hpp
/// \brief The one owner of the phase portrait: it wires its layers and is the face the rest of the GUI asks.
///
/// Everything that changes the portrait asks this object: the main window sets the map from the parameter
/// panel, the long-segment panel draws a segment and zooms to it, the periodic-orbit dialog's orbit is
/// drawn here, and the portrait panel's actions navigate.  The PortraitView only draws and renders what the
/// layers hand it (its setters are private to them) and turns mouse and keys into requests that come back here.
///
/// The portrait is split by layer (issue 51), each a class that owns its state and its job channel
/// (ui/jobs/BackgroundJobs): the view (ViewLayer: the map, the viewport and its history, zoom, pan, the render's
/// settings, the fixed points), the launched orbits (LaunchedOrbitsLayer: traced on a queue, measured on a niced
/// one), the manifolds and the flux (ManifoldsLayer), the atlas island (AtlasIslandLayer: core's atlasIslandView)
/// and the overlays (OverlayLayer: the long segment, periodic orbits, a click's search, the profile line).  This
/// object creates them, forwards to them, carries a new map and a session through all of them, and composes the
/// legend from theirs.  No maths here, nor in the layers: viewport maths, orbits, measures, manifolds, flux and the
/// atlas island's plan are core's.

#include <QObject>
#include <QPointer>

#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

#include "core/map/MapParameters.hpp"
#include "core/session/OrbitFamily.hpp"
#include "core/session/SessionFile.hpp"
#include "ui/portrait/AtlasIslandLayer.hpp"
#include "ui/portrait/LaunchedOrbitsLayer.hpp"
#include "ui/portrait/ManifoldsLayer.hpp"
#include "ui/portrait/OverlayLayer.hpp"
#include "ui/portrait/PortraitView.hpp"
#include "ui/portrait/ViewLayer.hpp"

class QWidget;

namespace archipelago::ui {

class PortraitController : public QObject {
  Q_OBJECT
 public:
  /// Creates the view as a child of `viewParent` (which also parents the controller).
  explicit PortraitController(QWidget* viewParent);
  ~PortraitController() override;

  [[nodiscard]] PortraitView* view() const noexcept { return view_; }
  /// The layers (their headers document each call forwarded below).
  [[nodiscard]] ViewLayer& viewLayer() noexcept { return *viewLayer_; }
  [[nodiscard]] LaunchedOrbitsLayer& orbitsLayer() noexcept { return *orbits_; }
  [[nodiscard]] ManifoldsLayer& manifoldsLayer() noexcept { return *manifolds_; }
  [[nodiscard]] AtlasIslandLayer& atlasIslandLayer() noexcept { return *atlas_; }
  [[nodiscard]] OverlayLayer& overlayLayer() noexcept { return *overlay_; }

  // --- The map -----------------------------------------------------------------------------------------
  /// Shows the portrait of this map (and randomizing zone Xr, for the b₂ dialog).  A new map shows the whole
  /// box, clears the history, the launched orbits, the segment, the overlays, the atlas island and the manifolds'
  /// orbit; the same map and Xr change nothing (the zoom stays).  Invalid parameters are refused: returns false,
  /// statusMessage says why.  The work of the map left is kept, and setting that map again brings it back (issue
  /// 37, finding 3).  While the view is hidden its render waits and starts when it is shown, at its real size.
  bool setMap(const MapParameters& map, double Xr);
  [[nodiscard]] const MapParameters& map() const noexcept { return viewLayer_->map(); }
  [[nodiscard]] double Xr() const noexcept { return Xr_; }
  /// The map whose views and orbits a change of map kept (issue 37, finding 3): setting it again restores them.
  [[nodiscard]] std::optional<MapParameters> keptMap() const;

  // --- The view (ViewLayer) ----------------------------------------------------------------------------
  void setViewport(const Viewport& view) { viewLayer_->setViewport(view); }
  [[nodiscard]] const Viewport& viewport() const noexcept { return viewLayer_->viewport(); }
  void zoomAt(double fx, double fy, double factor) { viewLayer_->zoomAt(fx, fy, factor); }
  void crop(double fx0, double fx1, double fy0, double fy1) { viewLayer_->crop(fx0, fx1, fy0, fy1); }
  bool zoomToRegion(const SegmentRegion& region) { return viewLayer_->zoomToRegion(region); }
  bool goTo(long double x, long double y, long double width, QString* error = nullptr) {
    return viewLayer_->goTo(x, y, width, error);
  }
  [[nodiscard]] bool shows(long double x, long double y) const noexcept { return viewLayer_->shows(x, y); }
  [[nodiscard]] const std::vector<Viewport>& history() const noexcept { return viewLayer_->history(); }
  [[nodiscard]] std::size_t historyIndex() const noexcept { return viewLayer_->historyIndex(); }
  bool restoreHistory(std::vector<Viewport> views, std::size_t current) {
    return viewLayer_->restoreHistory(std::move(views), current);
  }
  [[nodiscard]] bool canGoBack() const noexcept { return viewLayer_->canGoBack(); }
  [[nodiscard]] bool canGoForward() const noexcept { return viewLayer_->canGoForward(); }
  [[nodiscard]] bool equalAspect() const noexcept { return viewLayer_->equalAspect(); }
  void setMode(PortraitMode mode) { viewLayer_->setMode(mode); }
  [[nodiscard]] PortraitMode mode() const noexcept { return viewLayer_->mode(); }
  [[nodiscard]] std::optional<IndicatorKind> indicator() const noexcept { return viewLayer_->indicator(); }
  void setColourMap(ColourMapName colours) { viewLayer_->setColourMap(colours); }
  [[nodiscard]] ColourMapName colourMap() const noexcept { return viewLayer_->colourMap(); }
  void setPointBudget(std::uint64_t points) { viewLayer_->setPointBudget(points); }
  [[nodiscard]] std::uint64_t pointBudget() const noexcept { return viewLayer_->pointBudget(); }
  void stopRendering() { viewLayer_->stopRendering(); }

  // --- Launched orbits (LaunchedOrbitsLayer) -------------------------------------------------------------
  quint64 launchOrbit(long double x, long double y, std::uint64_t steps = kLaunchedOrbitSteps, bool backward = false,
                      quint64 number = 0) {
    return orbits_->launchOrbit(x, y, steps, backward, number);
  }
  int launchOrbitFamily(const OrbitFamily& family, std::uint64_t steps = kLaunchedOrbitSteps, bool backward = false) {
    return orbits_->launchOrbitFamily(family, steps, backward);
  }
  bool exportOrbitCsv(quint64 id, const QString& path, QString* error = nullptr) const {
    return orbits_->exportOrbitCsv(id, path, error);
  }
  [[nodiscard]] int orbitCount() const noexcept { return orbits_->orbitCount(); }
  [[nodiscard]] const std::vector<LaunchedOrbit>& launchedOrbits() const noexcept { return orbits_->launchedOrbits(); }
  [[nodiscard]] std::vector<PhysicalPoint> launchedOrbitStarts() const { return orbits_->launchedOrbitStarts(); }
  bool removeOrbit(quint64 id) { return orbits_->removeOrbit(id); }
  bool undoLastOrbit() { return orbits_->undoLastOrbit(); }
  [[nodiscard]] bool canUndoClear() const noexcept { return orbits_->canUndoClear(); }
  void highlightOrbit(quint64 id) { orbits_->highlightOrbit(id); }
  [[nodiscard]] quint64 highlightedOrbit() const noexcept { return orbits_->highlightedOrbit(); }
  [[nodiscard]] bool orbitsSettled() const { return orbits_->orbitsSettled(); }

  // --- Overlays (OverlayLayer) -----------------------------------------------------------------------------
  void showSegment(const SegmentReplayPtr& replay) { overlay_->showSegment(replay); }
  void showSegmentChain(const ChainResultPtr& chain) { overlay_->showSegmentChain(chain); }
  void showSegmentStep(std::size_t index) { overlay_->showSegmentStep(index); }
  void showPeriodicOrbit(const PeriodicOrbit& orbit) { overlay_->showPeriodicOrbit(orbit); }
  [[nodiscard]] const std::optional<PeriodicOrbit>& shownPeriodicOrbit() const noexcept {
    return overlay_->shownPeriodicOrbit();
  }
  void clearSegment() { overlay_->clearSegment(); }
  void findPeriodicOrbitAt(long double x, long double y) { overlay_->findPeriodicOrbitAt(x, y); }
  [[nodiscard]] std::shared_ptr<const PeriodicOrbitAt> clickedPeriodicOrbit() const noexcept {
    return overlay_->clickedPeriodicOrbit();
  }
  [[nodiscard]] bool periodicSearchPending() const noexcept { return overlay_->periodicSearchPending(); }
  void showProfileLine(std::optional<std::pair<PhysicalPoint, PhysicalPoint>> line) {
    overlay_->showProfileLine(std::move(line));
  }

  // --- Manifolds (ManifoldsLayer) ----------------------------------------------------------------------------
  void setManifoldsShown(bool shown) { manifolds_->setManifoldsShown(shown); }
  [[nodiscard]] bool manifoldsShown() const noexcept { return manifolds_->manifoldsShown(); }
  void setManifoldOrbit(std::optional<PeriodicOrbit> orbit) { manifolds_->setManifoldOrbit(std::move(orbit)); }
  [[nodiscard]] const std::optional<PeriodicOrbit>& manifoldOrbit() const noexcept { return manifolds_->manifoldOrbit(); }
  [[nodiscard]] ManifoldsPtr manifolds() const noexcept { return manifolds_->manifolds(); }
  [[nodiscard]] FluxPtr flux() const noexcept { return manifolds_->flux(); }
  [[nodiscard]] bool manifoldsSettled() const { return manifolds_->manifoldsSettled(); }

  // --- The atlas (AtlasIslandLayer, issue 38) -----------------------------------------------------------------
  /// Shows an island of an atlas of this map: framed, its boundary circle drawn, its chain as the periodic-orbit
  /// overlay and its partner's manifolds (the fixed point's at the centre; the layer off when there is no partner).
  void showAtlasIsland(const AtlasNode& node, const QString& label, const SegmentRegion& fallback) {
    atlas_->showAtlasIsland(node, label, fallback);
  }
  void clearAtlasIsland() { atlas_->clearAtlasIsland(); }
  [[nodiscard]] AtlasIslandPtr atlasIsland() const noexcept { return atlas_->atlasIsland(); }
  [[nodiscard]] bool atlasIslandSettled() const noexcept { return atlas_->atlasIslandSettled(); }

  // --- Sessions (core/session) -------------------------------------------------------------------------
  /// The portrait's part of a session: the view history and its current entry, mode, colour map, points
  /// budget, the launched orbits, the periodic-orbit overlay and the manifolds.
  [[nodiscard]] SessionPortrait sessionState() const;
  /// Shows `state` for this map: the map first (a new map clears), then the views, orbits and overlay.
  void restoreSession(const SessionPortrait& state, const MapParameters& map, double Xr);

 public Q_SLOTS:
  void back() { viewLayer_->back(); }
  void forward() { viewLayer_->forward(); }
  void resetView() { viewLayer_->resetView(); }
  void clearOrbits() { orbits_->clearOrbits(); }
  void zoomIn() { zoomAt(0.5, 0.5, 2.0); }
  void zoomOut() { zoomAt(0.5, 0.5, 0.5); }

 Q_SIGNALS:
  /// A new map is shown (setMap with other parameters).
  void mapChanged();
  /// The view changed (zoom, pan, history, reset, map).
  void viewportChanged();
  /// The mode, colour map, points budget or aspect changed (the panel's controls follow).
  void settingsChanged();
  void statusMessage(const QString& text);
  /// The list of launched orbits changed (one added, removed, traced or measured; the highlight).
  void orbitsChanged();
  /// The manifolds or the flux changed (computed, cleared).
  void manifoldsChanged();
  /// A click's periodic-orbit search ended: `text` says what it found, or why nothing (findPeriodicOrbitAt).
  void periodicOrbitFound(const QString& text);
  /// An island of the atlas is drawn (showAtlasIsland's result arrived).
  void atlasIslandShown();

 private:
  void wireView();
  void wireLayers();
  void updateLegend();
  /// The atlas island's chain drawn as the overlay and its barrier's manifolds (its partner's; the fixed point's at
  /// the centre; none without a partner).
  void showIslandChain(const AtlasIslandPtr& island, bool centre);
  /// Every layer cleared for a new map.
  void clearLayers();
  /// The views, launched orbits, periodic overlay and manifolds of `state` (after a map change cleared them).
  void restoreWork(const SessionPortrait& state, const MapParameters& map);
  /// The manifolds layer of `state`: hidden, of the fixed point, or of its orbit found again at map.K.
  void restoreManifolds(const SessionPortrait& state, const MapParameters& map);
  [[nodiscard]] bool hasWork() const;

  QPointer<PortraitView> view_;
  double Xr_ = 0.02;
  // The work of the last map left (views, orbits, overlay): a change of map keeps it, and setting that map again
  // brings it back (issue 37, finding 3: typing in K discarded it without a word).
  struct KeptWork {
    MapParameters map;
    SessionPortrait portrait;
  };
  std::optional<KeptWork> kept_;
  // The layers, the view first: destroyed last, after the layers whose jobs read its map.
  std::unique_ptr<ViewLayer> viewLayer_;
  std::unique_ptr<LaunchedOrbitsLayer> orbits_;
  std::unique_ptr<ManifoldsLayer> manifolds_;
  std::unique_ptr<AtlasIslandLayer> atlas_;
  std::unique_ptr<OverlayLayer> overlay_;
};

}  // namespace archipelago::ui
