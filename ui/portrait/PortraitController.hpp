#pragma once
/// \file PortraitController.hpp
/// \brief The one owner of the phase portrait: its view, its map, its view history and its overlay layers.
///
/// Everything that changes the portrait asks this object: the main window sets the map from the parameter
/// panel, the long-segment panel draws a segment and zooms to it, the periodic-orbit dialog's orbit is
/// drawn here, and the portrait panel's actions navigate.  The PortraitView only draws and renders what this
/// controller hands it (its setters are private to it) and turns mouse and keys into requests that come back
/// here.  The layers (PortraitLayers.hpp) are: the manifolds and their lobes, fixed points, launched orbits
/// (with the chain of the highlighted one), the selected long segment (with its chain's centre orbit and the
/// step shown), periodic orbits and the rotation-profile line.  Viewport maths is core's (Viewport,
/// framedInBox), so are the orbits, their measures, the manifolds and the flux; no maths here.
///
/// Background work (ui/jobs/BackgroundJobs, values tagged with their request): launched orbits are traced on one
/// channel (a queue: each orbit once, drawn as it arrives, never recomputing the earlier ones — issue #23, finding
/// 5) and measured on a niced one (the rotation number and chain, issue #27); the manifolds of the visible view
/// (latest request wins: a zoom refines them anew) and the turnstile flux (once per orbit) on their own channels; the
/// island the Atlas page selected (its boundary circle traced, its orbits found again when the atlas came from a file)
/// on one more.

#include <QObject>
#include <QPointer>

#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

#include "core/atlas/Atlas.hpp"
#include "core/manifolds/ManifoldCurve.hpp"
#include "core/manifolds/TurnstileFlux.hpp"
#include "core/map/MapParameters.hpp"
#include "core/measures/OrbitMeasures.hpp"
#include "core/measures/PeriodicOrbitAt.hpp"
#include "core/periodic/PeriodicOrbit.hpp"
#include "core/periodic/SegmentAnalysis.hpp"
#include "core/colour/ColourMap.hpp"
#include "core/portrait/PortraitRaster.hpp"
#include "core/view/Viewport.hpp"
#include "core/session/OrbitFamily.hpp"
#include "core/session/SessionFile.hpp"
#include "ui/portrait/LaunchedOrbits.hpp"
#include "ui/portrait/PortraitView.hpp"
#include "ui/portrait/SegmentResults.hpp"

class QWidget;
class QwtPlotItem;

namespace archipelago::ui {

class BackgroundJobs;

/// The manifolds of one hyperbolic orbit in the visible view, and the flux through its turnstile.
struct ManifoldsResult {
  std::vector<ManifoldCurve> unstable;  ///< every branch drawn, both sides at every orbit point drawn
  std::vector<ManifoldCurve> stable;
  double seconds = 0;
};
using ManifoldsPtr = std::shared_ptr<const ManifoldsResult>;
struct FluxResult {
  TurnstileRequest request;           ///< what was asked (as `archipelago-cli flux` asks it)
  std::optional<TurnstileFlux> flux;
  QString error;
  double seconds = 0;
};
using FluxPtr = std::shared_ptr<const FluxResult>;

/// What the portrait draws of an island of the atlas (the Atlas page, issue 38): its boundary circle, the orbit of its
/// boundary point under Q (every island of its chain), and the chain's and its partner's orbits whole.
struct AtlasIslandResult {
  std::vector<QPointF> boundary;            ///< empty when the island has no boundary circle
  std::optional<SegmentRegion> island;      ///< the circle of the island about the node's centre, with a margin
  std::optional<PeriodicOrbit> chain;       ///< the chain's elliptic orbit (the fixed point at the centre)
  std::optional<PeriodicOrbit> partner;     ///< its hyperbolic partner (none at the centre, or when there is none)
  QString error;                            ///< what could not be drawn, if anything
};
using AtlasIslandPtr = std::shared_ptr<const AtlasIslandResult>;

class PortraitController : public QObject {
  Q_OBJECT
 public:
  /// Creates the view as a child of `viewParent` (which also parents the controller).
  explicit PortraitController(QWidget* viewParent);
  ~PortraitController() override;

  [[nodiscard]] PortraitView* view() const noexcept { return view_; }

  // --- The map -----------------------------------------------------------------------------------------
  /// Shows the portrait of this map (and randomizing zone Xr, for the b₂ dialog).  A new map shows the whole
  /// box, clears the history, the launched orbits and the segment; the same map and Xr change nothing (the
  /// zoom stays).  Invalid parameters are refused: returns false, statusMessage says why.  While the view is
  /// hidden its render waits and starts when it is shown, at its real size.
  bool setMap(const MapParameters& map, double Xr);
  [[nodiscard]] const MapParameters& map() const noexcept { return map_; }
  [[nodiscard]] double Xr() const noexcept { return Xr_; }

  // --- The view ----------------------------------------------------------------------------------------
  /// Shows `view` and records it in the history (a new view drops the forward history, as in a browser).
  void setViewport(const Viewport& view);
  [[nodiscard]] const Viewport& viewport() const noexcept { return history_[historyIndex_]; }
  /// Zoom by `factor` (> 1 in) about the point at fractions (fx, fy) of the view (0,0 bottom-left).
  void zoomAt(double fx, double fy, double factor);
  /// Move by fractions of the view.  A pan that cannot move (the whole box is shown, or the view is at the
  /// box's edge) says so in statusMessage rather than doing nothing silently (issue 25, finding 12).
  void panBy(double fx, double fy);
  /// The sub-rectangle [fx0, fx1] × [fy0, fy1] of the view, in fractions.  With equal aspect, a rectangle
  /// thinner than 1:4 is widened to 1:4 (core's framedInBox), so that no drag gives a sliver of a view.
  void crop(double fx0, double fx1, double fy0, double fy1);
  /// Frames `region` to the canvas's aspect ratio inside the box (core's framedInBox) and shows it.
  /// False when the region does not fit this map (the view is left alone).
  bool zoomToRegion(const SegmentRegion& region);
  /// Shows the view of centre (x, y) and width `width` (physical), its height from the canvas's aspect, inside the
  /// box (issue 37, finding 18: typed view coordinates).  False with the reason when the centre is not in the box
  /// or the width is not in (0, L] (core's viewWidthError).
  bool goTo(long double x, long double y, long double width, QString* error = nullptr);
  /// Re-centres the view on (x, y) when that point lies outside it (the zoom stays; the move replaces the
  /// current history entry, so that following a moving point does not fill the history).
  void ensureVisible(long double x, long double y);
  /// True when the physical point (x, y) lies inside the view.
  [[nodiscard]] bool shows(long double x, long double y) const noexcept;
  /// The view history, oldest first, and the index of the view shown (session files keep them).
  [[nodiscard]] const std::vector<Viewport>& history() const noexcept { return history_; }
  [[nodiscard]] std::size_t historyIndex() const noexcept { return historyIndex_; }
  /// Restores a history (e.g. from a session file) and shows views[current].  An empty list or an index past
  /// its end is refused (returns false, nothing changes).
  bool restoreHistory(std::vector<Viewport> views, std::size_t current);
  [[nodiscard]] bool canGoBack() const noexcept { return historyIndex_ > 0; }
  [[nodiscard]] bool canGoForward() const noexcept { return historyIndex_ + 1 < history_.size(); }
  /// Equal aspect ratio (the default): a unit of x is as long on screen as a unit of y, whatever the view.
  void setEqualAspect(bool on);
  [[nodiscard]] bool equalAspect() const noexcept;

  // --- Rendering ---------------------------------------------------------------------------------------
  void setMode(PortraitMode mode);
  [[nodiscard]] PortraitMode mode() const noexcept;
  /// A chaos-indicator map instead of the mode's raster (nothing: the mode's raster).
  void setIndicator(std::optional<IndicatorKind> kind);
  [[nodiscard]] std::optional<IndicatorKind> indicator() const noexcept;
  void setColourMap(ColourMapName colours);
  [[nodiscard]] ColourMapName colourMap() const noexcept;
  /// The points budget of a view: the render accumulates until it has done this many map steps.
  void setPointBudget(std::uint64_t points);
  [[nodiscard]] std::uint64_t pointBudget() const noexcept;
  /// Stops accumulating; the portrait so far stays.
  void stopRendering();
  /// Pauses the render in progress (it keeps its orbits and goes on from there on resume), e.g. while the
  /// portrait is hidden or a run should have the cores (issue 25, finding 15).
  void setRenderPaused(bool paused);

  // --- Launched orbits -----------------------------------------------------------------------------------
  /// Launches an orbit of N from the physical point (x, y), `steps` long, drawn in its own colour as soon as it
  /// is traced (off the GUI thread), then measured (rotation number, digits, chain).  Returns its id, or 0 when
  /// refused: kMaxLaunchedOrbits are shown already (statusMessage says so).  `number`: the number (and so the
  /// colour) to give it, as a session or Undo Clear brings an orbit back (issue 53, finding 2); 0, or a number
  /// another orbit shown has: the next.
  quint64 launchOrbit(long double x, long double y, std::uint64_t steps = kLaunchedOrbitSteps, bool backward = false,
                      quint64 number = 0);
  /// Launches a line or a grid of orbits at once (issue 37, finding 15; core's orbitFamilyStarts), each like
  /// launchOrbit().  Returns how many were launched: 0 when core refuses the family (statusMessage gives its
  /// words: a count of 0, or more than the portrait keeps with those launched already).
  int launchOrbitFamily(const OrbitFamily& family, std::uint64_t steps = kLaunchedOrbitSteps, bool backward = false);
  /// What a click on the portrait launches (issue 37, finding 15): `steps` steps (1 … 10⁸) of N, or of N⁻¹.
  void setClickOrbit(std::uint64_t steps, bool backward);
  [[nodiscard]] std::uint64_t clickSteps() const noexcept { return clickSteps_; }
  [[nodiscard]] bool clickBackward() const noexcept { return clickBackward_; }
  /// Writes one launched orbit as CSV (core's writeOrbitCsv: `archipelago-cli orbit --x X --y Y --steps N
  /// [--backward]` writes the same bytes).  False with the reason when there is no such orbit or the file fails.
  bool exportOrbitCsv(quint64 id, const QString& path, QString* error = nullptr) const;
  [[nodiscard]] int orbitCount() const noexcept { return static_cast<int>(orbits_.size()); }
  [[nodiscard]] const std::vector<LaunchedOrbit>& launchedOrbits() const noexcept { return orbits_; }
  /// The physical start points of the launched orbits, in launch order.
  [[nodiscard]] std::vector<PhysicalPoint> launchedOrbitStarts() const;
  /// Removes one orbit; the last one launched (Ctrl+Z), or, right after Clear Orbits, brings the cleared orbits
  /// back (issue 37, finding 20).  False when there is nothing to undo.
  bool removeOrbit(quint64 id);
  bool undoLastOrbit();
  /// True when Ctrl+Z would bring back the orbits Clear Orbits removed.
  [[nodiscard]] bool canUndoClear() const noexcept { return !cleared_.empty(); }
  /// Highlights one orbit (0: none): drawn wider, the others dimmed, its chain's elliptic orbit drawn.
  void highlightOrbit(quint64 id);
  [[nodiscard]] quint64 highlightedOrbit() const noexcept { return highlighted_; }
  /// True when every launched orbit is traced and measured (tests; sessions).
  [[nodiscard]] bool orbitsSettled() const;

  // --- Other layers ------------------------------------------------------------------------------------
  /// The selected long segment (null: none); its chain's centre orbit; the kept state shown.
  void showSegment(const SegmentReplayPtr& replay);
  void showSegmentChain(const ChainResultPtr& chain);
  void showSegmentStep(std::size_t index);
  /// A periodic orbit from the dialog (replacing the previous one).
  void showPeriodicOrbit(const PeriodicOrbit& orbit);
  /// The periodic orbit drawn as the overlay (the dialog's, a click's, an atlas island's chain), if any.
  [[nodiscard]] const std::optional<PeriodicOrbit>& shownPeriodicOrbit() const noexcept { return periodic_; }
  /// Removes the segment, its chain and its step (a new run: the periodic orbits of the same map stay, issue 25,
  /// finding 13).
  void clearSegment();
  /// Finds the periodic orbit at the physical point (issue 37, finding 16: a Shift+click, or any click while
  /// clickFindsPeriodicOrbit()): core's periodicOrbitAt off the GUI thread — the chain named as the rotation
  /// instrument names it, its elliptic orbit found as `archipelago-cli periodic --period n --near X,Y --stable`
  /// finds it — drawn as the periodic overlay; periodicOrbitFound() says what was found, or why nothing.
  void findPeriodicOrbitAt(long double x, long double y);
  /// A plain click finds the periodic orbit there instead of launching an orbit (Portrait ▸ Click Finds Periodic
  /// Orbits).
  void setClickFindsPeriodicOrbit(bool on) { clickFindsPeriodic_ = on; }
  [[nodiscard]] bool clickFindsPeriodicOrbit() const noexcept { return clickFindsPeriodic_; }
  /// The last orbit a click found (null: none yet, or the last search found nothing), and whether one is searched.
  [[nodiscard]] std::shared_ptr<const PeriodicOrbitAt> clickedPeriodicOrbit() const noexcept { return clickedPeriodic_; }
  [[nodiscard]] bool periodicSearchPending() const noexcept { return periodicRequest_ != 0; }
  /// The words of what a click found: "Period 6, elliptic (residue 0.36): 1/6 about the centre; …".
  [[nodiscard]] static QString periodicOrbitText(const PeriodicOrbitAt& found);
  /// Removes the periodic orbit of the dialog.
  void clearPeriodicOrbit();
  /// The rotation-profile line (none: hidden).
  void showProfileLine(std::optional<std::pair<PhysicalPoint, PhysicalPoint>> line);

  // --- Manifolds -----------------------------------------------------------------------------------------
  /// Shows the stable and unstable manifolds of the hyperbolic orbit (none: the fixed point (√K, 0)), refined in
  /// the visible view, and the turnstile's lobes with their areas.
  void setManifoldsShown(bool shown);
  [[nodiscard]] bool manifoldsShown() const noexcept { return manifoldsShown_; }
  /// The hyperbolic orbit whose manifolds are drawn (none: the fixed point).  Shows the layer.
  void setManifoldOrbit(std::optional<PeriodicOrbit> orbit);
  [[nodiscard]] const std::optional<PeriodicOrbit>& manifoldOrbit() const noexcept { return manifoldOrbit_; }
  [[nodiscard]] ManifoldsPtr manifolds() const noexcept { return manifolds_; }
  [[nodiscard]] FluxPtr flux() const noexcept { return flux_; }
  /// Nothing computing for the manifolds layer (tests).
  [[nodiscard]] bool manifoldsSettled() const;

  // --- The atlas (issue 38) -------------------------------------------------------------------------------
  /// Shows an island of an atlas of this map, in the background: zooms to it — the boundary circle of the island
  /// about node.centre (the orbit under Qⁿ of the point of node.boundaryPoint's orbit nearest that centre) framed with a margin of a quarter of its size on every side by core's
  /// dwellRegion and framedInBox, or `fallback` when it has no boundary circle — and draws its boundary circle (the
  /// orbit under Q, about 4000 points per island of the chain, in its own layer), its chain as the periodic-orbit
  /// overlay and its partner's manifolds (the fixed point (√K, 0)'s at the centre; the layer off when the chain has no
  /// partner).  An orbit the atlas keeps as one point (an atlas read from JSON) is found again by core's Newton.
  /// `label` names the island in the legend ("6 > 138").
  void showAtlasIsland(const AtlasNode& node, const QString& label, const SegmentRegion& fallback);
  /// Removes the boundary circle (the overlay and the manifolds stay).
  void clearAtlasIsland();
  /// What the last showAtlasIsland() drew (null: none yet, or cleared), and whether it is still computing (tests).
  [[nodiscard]] AtlasIslandPtr atlasIsland() const noexcept { return atlasIsland_; }
  [[nodiscard]] bool atlasIslandSettled() const noexcept { return atlasRequest_ == 0; }

  // --- Sessions (core/session) -------------------------------------------------------------------------
  /// The portrait's part of a session: the view history and its current entry, mode, colour map, points
  /// budget, the start points of launched orbits and the periodic-orbit overlay.
  [[nodiscard]] SessionPortrait sessionState() const;
  /// Shows `state` for this map: the map first (a new map clears), then the views, orbits and overlay.
  void restoreSession(const SessionPortrait& state, const MapParameters& map, double Xr);
  /// The map whose views and orbits a change of map kept (issue 37, finding 3): setting it again restores them.
  [[nodiscard]] std::optional<MapParameters> keptMap() const;

 public Q_SLOTS:
  void back();
  void forward();
  /// The whole box; when the view is already the whole box, renders it again.
  void resetView();
  /// Removes every launched orbit; Ctrl+Z (undoLastOrbit) brings them back until another orbit is launched.
  void clearOrbits();
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
  void show(bool record, const Viewport& view);
  void updateFixedPoints();
  void updateLegend();
  void traceOrbit(const LaunchedOrbit& orbit);
  /// Removes every launched orbit without an undo (a new map, a session).
  void discardOrbits();
  void onOrbitTraced(quint64 id, std::shared_ptr<const std::vector<QPointF>> points, const QString& error);
  void onOrbitMeasured(quint64 id, const OrbitMeasuresPtr& measures);
  void redrawOrbit(std::size_t index);
  void updateOrbitChain();
  LaunchedOrbit* findOrbit(quint64 id);
  void requestManifolds();
  void requestFlux();
  void drawManifolds();
  /// The views, launched orbits and periodic overlay of `state` (after a map change cleared them).
  void restoreWork(const SessionPortrait& state, const MapParameters& map);
  [[nodiscard]] bool hasWork() const;

  QPointer<PortraitView> view_;
  MapParameters map_;
  double Xr_ = 0.02;
  std::vector<Viewport> history_{Viewport()};
  std::size_t historyIndex_ = 0;
  std::vector<LaunchedOrbit> orbits_;
  std::vector<QwtPlotItem*> orbitItems_;            // orbitItems_[i] draws orbits_[i] (owned by the view), or null
  quint64 nextOrbitId_ = 0;
  quint64 highlighted_ = 0;
  std::vector<LaunchedOrbit> cleared_;              // what Clear Orbits removed (undoLastOrbit brings it back)
  std::uint64_t clickSteps_ = kLaunchedOrbitSteps;
  bool clickBackward_ = false;
  quint64 orbitGeneration_ = 0;                     // bumped by clear and by a new map: older results are dropped
  SegmentReplayPtr replay_;
  ChainResultPtr chain_;
  int periodicPeriod_ = 0;
  std::optional<PeriodicOrbit> periodic_;           // the overlay from the periodic-orbit dialog
  std::shared_ptr<const PeriodicOrbitAt> clickedPeriodic_;  // the last a click found
  quint64 periodicRequest_ = 0;
  bool clickFindsPeriodic_ = false;
  // The work of the last map left (views, orbits, overlay): a change of map keeps it, and setting that map again
  // brings it back (issue 37, finding 3: typing in K discarded it without a word).
  struct KeptWork {
    MapParameters map;
    SessionPortrait portrait;
  };
  std::optional<KeptWork> kept_;
  bool manifoldsShown_ = false;
  std::optional<PeriodicOrbit> manifoldOrbit_;
  ManifoldsPtr manifolds_;
  FluxPtr flux_;
  quint64 manifoldsRequest_ = 0;
  quint64 fluxRequest_ = 0;
  AtlasIslandPtr atlasIsland_;
  QString atlasLabel_;                              // the island whose boundary is drawn ("" : none)
  quint64 atlasRequest_ = 0;
  // Last members: destroyed first, they stop the jobs and join their threads while everything they use lives.
  std::unique_ptr<BackgroundJobs> jobs_;            // channels: kTraceChannel, kManifoldChannel, kFluxChannel,
                                                    // kAtlasChannel, kPeriodicChannel
  std::unique_ptr<BackgroundJobs> measureJobs_;     // niced: the measures of launched orbits, a queue
};

}  // namespace archipelago::ui
