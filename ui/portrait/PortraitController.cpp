#include "ui/portrait/PortraitController.hpp"

#include <QBrush>
#include <QElapsedTimer>
#include <QLocale>
#include <QPen>
#include <QWidget>
#include <qwt_plot_marker.h>
#include <qwt_symbol.h>
#include <qwt_text.h>

#include <algorithm>
#include <cmath>
#include <exception>
#include <limits>
#include <sstream>
#include <utility>

#include "core/io/NumberText.hpp"
#include "core/io/AtomicFile.hpp"
#include "core/kernels/KernelDispatch.hpp"
#include "core/limits/Limits.hpp"
#include "core/manifolds/HyperbolicOrbit.hpp"
#include "core/manifolds/ManifoldViewPlan.hpp"
#include "core/map/FixedPointMap.hpp"
#include "core/measures/OrbitMeasures.hpp"
#include "core/periodic/PeriodicOrbitFinder.hpp"
#include "core/periodic/SegmentAnalysis.hpp"
#include "core/portrait/MapOverlays.hpp"
#include "ui/jobs/BackgroundJobs.hpp"
#include "ui/portrait/PortraitLayers.hpp"
#include "ui/portrait/PortraitView.hpp"
#include "ui/portrait/SegmentOverlay.hpp"

namespace archipelago::ui {

namespace {
// Channels of jobs_ (normal priority: interactive work the user waits for).
constexpr int kTraceChannel = 0;     // a queue: each launched orbit once, in launch order
constexpr int kManifoldChannel = 1;  // latest wins: the manifolds of the view shown
constexpr int kFluxChannel = 2;      // latest wins: the flux of the orbit shown
constexpr int kAtlasChannel = 3;     // latest wins: the atlas island selected
constexpr int kPeriodicChannel = 4;  // latest wins: the periodic orbit at the last click

/// Points drawn of an atlas island's boundary circle, per island of its chain, and in all.
constexpr std::uint64_t kAtlasPointsPerIsland = 4000;
constexpr std::uint64_t kMaxAtlasBoundaryPoints = 2'000'000;
/// The margin about an atlas island's boundary circle in its view, in parts of its size on each side.
constexpr double kAtlasViewMargin = 0.25;

/// The smallest view aspect (and its inverse the largest) a rectangle zoom gives with equal aspect.
constexpr double kMinCropAspect = 0.25;

std::vector<QPointF> toQt(const std::vector<PhysicalPoint>& points) {
  std::vector<QPointF> out;
  out.reserve(points.size());
  for (const PhysicalPoint& p : points) out.emplace_back(static_cast<double>(p.x), static_cast<double>(p.y));
  return out;
}

QColor launchedColour(quint64 id) {
  const Rgb c = launchedOrbitColour(static_cast<std::uint32_t>(id));  // apart from the portrait's orbits
  return QColor(c.r, c.g, c.b);
}

QString areaText(long double a) { return QString::number(static_cast<double>(a), 'g', 6); }
}  // namespace

PortraitController::PortraitController(QWidget* viewParent) : QObject(viewParent) {
  qRegisterMetaType<OrbitMeasuresPtr>();
  view_ = new PortraitView(viewParent);
  PortraitView* v = view_;
  connect(v, &PortraitView::zoomRequested, this, &PortraitController::zoomAt);
  connect(v, &PortraitView::panRequested, this, &PortraitController::panBy);
  connect(v, &PortraitView::cropRequested, this, &PortraitController::crop);
  // A click launches an orbit and ends the selection: the new orbit is drawn in full, as are the others (issue 37,
  // finding 8: orbits clicked while one was selected were drawn dimmed, nearly invisible).
  connect(v, &PortraitView::periodicOrbitRequested, this, &PortraitController::findPeriodicOrbitAt);
  connect(v, &PortraitView::clicked, this, [this](long double x, long double y) {
    if (clickFindsPeriodic_) return findPeriodicOrbitAt(x, y);
    highlightOrbit(0);
    launchOrbit(x, y, clickSteps_, clickBackward_);
  });
  connect(v, &PortraitView::backRequested, this, &PortraitController::back);
  connect(v, &PortraitView::forwardRequested, this, &PortraitController::forward);
  connect(v, &PortraitView::resetRequested, this, &PortraitController::resetView);
  connect(v, &PortraitView::statusMessage, this, &PortraitController::statusMessage);
  jobs_ = std::make_unique<BackgroundJobs>(this, 5);
  measureJobs_ = std::make_unique<BackgroundJobs>(this, 1, JobPriority::background);
  updateFixedPoints();
  view_->display(map_, viewport());
}

PortraitController::~PortraitController() {
  // Stop the jobs and join their threads before the view and the lists they report to go.
  measureJobs_.reset();
  jobs_.reset();
}

bool PortraitController::setMap(const MapParameters& map, double Xr) {
  if (auto e = validationError(map)) {
    Q_EMIT statusMessage(tr("Invalid parameters: %1").arg(QString::fromStdString(*e)));
    return false;
  }
  if (map == map_) {
    Xr_ = Xr;  // the portrait does not depend on Xr (only the b₂ dialog does)
    return true;
  }
  // Returning to the map left last brings its work back; leaving a map with work keeps it (one map deep).
  std::optional<KeptWork> back;
  if (kept_ && kept_->map == map) back = std::exchange(kept_, std::nullopt);
  if (hasWork()) {
    const int orbits = orbitCount();
    kept_ = KeptWork{map_, sessionState()};
    if (!back)
      Q_EMIT statusMessage(tr("A new map: the %1 launched orbits and %2 views of K = %3 are kept; set K = %3 again "
                              "to have them back")
                               .arg(orbits)
                               .arg(history_.size())
                               .arg(QString::fromStdString(io::shortestText(static_cast<double>(map_.K)))));
  }
  map_ = map;
  Xr_ = Xr;
  history_.assign(1, Viewport());
  historyIndex_ = 0;
  discardOrbits();
  cleared_.clear();
  clearSegment();
  clearPeriodicOrbit();
  clearAtlasIsland();
  showProfileLine(std::nullopt);
  manifoldOrbit_.reset();  // an orbit of another K
  flux_.reset();
  manifolds_.reset();
  updateFixedPoints();
  if (view_) view_->display(map_, viewport());
  if (manifoldsShown_) {
    requestFlux();
    requestManifolds();
  }
  Q_EMIT manifoldsChanged();
  Q_EMIT mapChanged();
  if (back) {
    restoreWork(back->portrait, map_);
    Q_EMIT statusMessage(tr("K = %1 again: its %2 launched orbits and %3 views are back")
                             .arg(QString::fromStdString(io::shortestText(static_cast<double>(map_.K))))
                             .arg(back->portrait.orbits.size())
                             .arg(back->portrait.history.size()));
  }
  Q_EMIT viewportChanged();
  return true;
}

bool PortraitController::hasWork() const { return !orbits_.empty() || history_.size() > 1 || periodic_.has_value(); }

std::optional<MapParameters> PortraitController::keptMap() const {
  return kept_ ? std::optional<MapParameters>(kept_->map) : std::nullopt;
}

void PortraitController::setViewport(const Viewport& view) { show(true, view); }

void PortraitController::zoomAt(double fx, double fy, double factor) {
  show(true, viewport().zoomedAboutFraction(fx, fy, factor));
}

void PortraitController::panBy(double fx, double fy) {
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

void PortraitController::crop(double fx0, double fx1, double fy0, double fy1) {
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

bool PortraitController::zoomToRegion(const SegmentRegion& region) {
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

bool PortraitController::goTo(long double x, long double y, long double width, QString* error) {
  QString why;
  if (const auto e = viewWidthError(width, map_)) why = QString::fromStdString(*e);
  else if (const auto f = boxPointError("the centre", map_, {x, y})) why = QString::fromStdString(*f);
  else if (!zoomToRegion(SegmentRegion{x - width / 2, x + width / 2, y, y, 0})) why = tr("the view does not fit the box");
  if (why.isEmpty()) return true;
  if (error) *error = why;
  return false;
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
    if (view_) {
      view_->display(map_, viewport());  // axes back to the box, whatever moved them
      view_->rerender();                 // Reset always draws anew (e.g. after a render at a smaller size)
    }
    return;
  }
  show(true, Viewport());
}

void PortraitController::show(bool record, const Viewport& view) {
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
  if (manifoldsShown_) requestManifolds();  // refined anew in the visible view
  Q_EMIT viewportChanged();
}

void PortraitController::setEqualAspect(bool on) {
  if (!view_ || view_->equalAspect() == on) return;
  view_->setEqualAspect(on);
  Q_EMIT settingsChanged();
}

bool PortraitController::equalAspect() const noexcept { return view_ && view_->equalAspect(); }

void PortraitController::setMode(PortraitMode mode) {
  if (!view_ || (view_->mode() == mode && !view_->indicator())) return;
  view_->setMode(mode, std::nullopt);
  Q_EMIT settingsChanged();
}

PortraitMode PortraitController::mode() const noexcept { return view_ ? view_->mode() : PortraitMode::Orbits; }

void PortraitController::setIndicator(std::optional<IndicatorKind> kind) {
  if (!view_ || view_->indicator() == kind) return;
  view_->setMode(view_->mode(), kind);
  Q_EMIT settingsChanged();
}

std::optional<IndicatorKind> PortraitController::indicator() const noexcept {
  return view_ ? view_->indicator() : std::nullopt;
}

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

std::uint64_t PortraitController::pointBudget() const noexcept { return view_ ? view_->pointBudget() : 0; }

void PortraitController::stopRendering() {
  if (view_) view_->stopRender();
}

void PortraitController::setRenderPaused(bool paused) {
  if (view_) view_->setRenderPaused(paused);
}

// ------------------------------------------------------------------------------------------ launched orbits

std::vector<PhysicalPoint> PortraitController::launchedOrbitStarts() const {
  std::vector<PhysicalPoint> starts;
  starts.reserve(orbits_.size());
  for (const LaunchedOrbit& orbit : orbits_) starts.push_back({orbit.x, orbit.y});
  return starts;
}

void PortraitController::setClickOrbit(std::uint64_t steps, bool backward) {
  clickSteps_ = std::clamp<std::uint64_t>(steps, 1, limits::kOrbitLength);
  clickBackward_ = backward;
}

bool PortraitController::exportOrbitCsv(quint64 id, const QString& path, QString* error) const {
  const auto it = std::find_if(orbits_.begin(), orbits_.end(), [id](const LaunchedOrbit& o) { return o.id == id; });
  if (it == orbits_.end()) {
    if (error) *error = tr("there is no orbit %1").arg(id);
    return false;
  }
  try {
    std::ostringstream csv;
    writeOrbitCsv(csv, map_, it->x, it->y, it->steps, it->backward);
    const std::string text = csv.str();
    io::writeFileAtomically(path.toStdString(), text);
  } catch (const std::exception& e) {
    if (error) *error = QString::fromStdString(e.what());
    return false;
  }
  return true;
}

quint64 PortraitController::launchOrbit(long double x, long double y, std::uint64_t steps, bool backward, quint64 number) {
  if (orbits_.size() >= kMaxLaunchedOrbits) {
    Q_EMIT statusMessage(tr("%1 orbits are launched already, the most the portrait keeps: remove some (Ctrl+Z, "
                            "Clear orbits) first")
                             .arg(kMaxLaunchedOrbits));
    return 0;
  }
  LaunchedOrbit orbit;
  const bool taken = number == 0 || findOrbit(number) != nullptr;
  orbit.id = taken ? ++nextOrbitId_ : number;
  nextOrbitId_ = std::max(nextOrbitId_, orbit.id);
  orbit.x = x;
  orbit.y = y;
  orbit.steps = std::clamp<std::uint64_t>(steps, 1, limits::kOrbitLength);  // core's one table
  orbit.backward = backward;
  orbit.colour = launchedColour(orbit.id);
  cleared_.clear();  // a new orbit: Ctrl+Z now removes it, no longer undoes a Clear
  orbits_.push_back(orbit);
  orbitItems_.push_back(nullptr);
  traceOrbit(orbits_.back());
  Q_EMIT statusMessage(tr("Orbit %1 from (%2, %3): %4 steps%5; measuring its rotation number and chain…")
                           .arg(orbit.id)
                           .arg(QString::fromStdString(io::shortestText(x)))  // every digit given, no noise (issue 53, finding 18)
                           .arg(QString::fromStdString(io::shortestText(y)))
                           .arg(orbit.steps)
                           .arg(backward ? tr(" backward (N⁻¹)") : QString()));
  Q_EMIT orbitsChanged();
  return orbit.id;
}

int PortraitController::launchOrbitFamily(const OrbitFamily& family, std::uint64_t steps, bool backward) {
  std::vector<PhysicalPoint> starts;
  try {
    starts = orbitFamilyStarts(family, orbits_.size());
  } catch (const std::invalid_argument& e) {
    Q_EMIT statusMessage(QString::fromStdString(e.what()));
    return 0;
  }
  int launched = 0;
  for (const PhysicalPoint& p : starts) launched += launchOrbit(p.x, p.y, steps, backward) != 0;
  Q_EMIT statusMessage(tr("%1 orbits launched (%2 × %3), %4 steps each%5; measuring their rotation numbers and chains…")
                           .arg(launched)
                           .arg(family.columns)
                           .arg(family.rows)
                           .arg(std::clamp<std::uint64_t>(steps, 1, limits::kOrbitLength))
                           .arg(backward ? tr(" backward (N⁻¹)") : QString()));
  return launched;
}

void PortraitController::traceOrbit(const LaunchedOrbit& orbit) {
  // Each orbit once: traced on a queue (its points), then measured on the niced queue.  Nothing of the earlier
  // orbits is recomputed; the GUI thread only adds one plot item per orbit.
  const MapParameters map = map_;
  const quint64 id = orbit.id, generation = orbitGeneration_;
  const long double x = orbit.x, y = orbit.y;
  const std::uint64_t steps = orbit.steps;
  const bool backward = orbit.backward;
  Job<std::shared_ptr<const std::vector<QPointF>>> trace;
  trace.channel = kTraceChannel;
  trace.order = JobOrder::queued;
  trace.work = [map, x, y, steps, backward](JobContext<NoProgress>&) -> std::optional<std::shared_ptr<const std::vector<QPointF>>> {
    return std::make_shared<const std::vector<QPointF>>(toQt(archipelago::traceOrbit(map, x, y, steps, backward)));
  };
  trace.done = [this, id, generation](JobResult<std::shared_ptr<const std::vector<QPointF>>> r) {
    if (generation != orbitGeneration_) return;
    onOrbitTraced(id, r.value.value_or(nullptr), r.error);
  };
  jobs_->submit(std::move(trace));

  Job<OrbitMeasuresPtr> measure;
  measure.order = JobOrder::queued;
  measure.work = [map, x, y](JobContext<NoProgress>& context) -> std::optional<OrbitMeasuresPtr> {
    QElapsedTimer clock;
    clock.start();
    auto result = std::make_shared<OrbitMeasuresResult>();
    // As `archipelago-cli rotation` does (the same request for the same start): the measure's rules, then the
    // start's, then core's identification.
    ChainRequest& r = result->request;
    r.map = map;
    try {
      r = chainRequestAt(r, {x, y});  // core's recipe and messages, as the CLI's `rotation`
      result->chain = identifyChain(r, context.stopToken());
    } catch (const std::exception& e) {
      result->error = QString::fromUtf8(e.what());
    }
    if (context.stopRequested()) return std::nullopt;
    result->seconds = static_cast<double>(clock.nsecsElapsed()) * 1e-9;
    return result;
  };
  measure.done = [this, id, generation](JobResult<OrbitMeasuresPtr> r) {
    if (generation != orbitGeneration_) return;
    if (r.ok()) {
      onOrbitMeasured(id, *r.value);
    } else {
      auto failed = std::make_shared<OrbitMeasuresResult>();
      failed->error = r.error;
      onOrbitMeasured(id, failed);
    }
  };
  measureJobs_->submit(std::move(measure));
}

LaunchedOrbit* PortraitController::findOrbit(quint64 id) {
  for (LaunchedOrbit& o : orbits_)
    if (o.id == id) return &o;
  return nullptr;
}

void PortraitController::onOrbitTraced(quint64 id, std::shared_ptr<const std::vector<QPointF>> points,
                                       const QString& error) {
  LaunchedOrbit* orbit = findOrbit(id);
  if (!orbit) return;  // removed meanwhile
  orbit->points = std::move(points);
  orbit->error = error;
  if (!error.isEmpty()) Q_EMIT statusMessage(tr("Orbit %1: %2").arg(id).arg(error));
  redrawOrbit(static_cast<std::size_t>(orbit - orbits_.data()));
  Q_EMIT orbitsChanged();
}

void PortraitController::onOrbitMeasured(quint64 id, const OrbitMeasuresPtr& measures) {
  LaunchedOrbit* orbit = findOrbit(id);
  if (!orbit) return;
  orbit->measures = measures;
  Q_EMIT statusMessage(measures->error.isEmpty()
                           ? tr("Orbit %1: rotation %2; %3").arg(id).arg(rotationText(*measures), chainText(*measures))
                           : tr("Orbit %1: no measures (%2)").arg(id).arg(measures->error));
  if (highlighted_ == id) updateOrbitChain();
  Q_EMIT orbitsChanged();
}

void PortraitController::redrawOrbit(std::size_t index) {
  if (!view_ || index >= orbits_.size()) return;
  const LaunchedOrbit& orbit = orbits_[index];
  if (orbitItems_[index]) {
    view_->removeLayerItem(PortraitLayer::launchedOrbits, orbitItems_[index]);
    orbitItems_[index] = nullptr;
  }
  if (!orbit.points) return;
  QColor colour = orbit.colour;
  double width = 2;
  if (highlighted_ != 0 && orbit.id != highlighted_) colour.setAlpha(70);  // the highlighted one stands out
  if (orbit.id == highlighted_) width = 3.5;
  auto* item = new PointsItem(PointsItem::Style::dots, *orbit.points, colour);
  item->setPenWidth(width);
  item->setStartMarker(true);
  item->setZ(orbit.id == highlighted_ ? 22 : 20);
  item->setTitle(tr("orbit %1").arg(orbit.id));
  orbitItems_[index] = item;
  view_->addLayerItem(PortraitLayer::launchedOrbits, item);
}

bool PortraitController::removeOrbit(quint64 id) {
  const auto it = std::find_if(orbits_.begin(), orbits_.end(), [id](const LaunchedOrbit& o) { return o.id == id; });
  if (it == orbits_.end()) return false;
  const auto index = static_cast<std::size_t>(it - orbits_.begin());
  if (view_ && orbitItems_[index]) view_->removeLayerItem(PortraitLayer::launchedOrbits, orbitItems_[index]);
  orbits_.erase(it);
  orbitItems_.erase(orbitItems_.begin() + static_cast<std::ptrdiff_t>(index));
  if (highlighted_ == id) highlightOrbit(0);  // its jobs' results find no orbit and are dropped
  Q_EMIT orbitsChanged();
  return true;
}

bool PortraitController::undoLastOrbit() {
  if (orbits_.empty() && !cleared_.empty()) {
    // Undo Clear Orbits: the same starts, steps, directions and numbers (so colours), traced and measured again.
    const std::vector<LaunchedOrbit> back = std::exchange(cleared_, {});
    for (const LaunchedOrbit& o : back) launchOrbit(o.x, o.y, o.steps, o.backward, o.id);
    Q_EMIT statusMessage(tr("%1 cleared orbits are back").arg(back.size()));
    return true;
  }
  if (orbits_.empty()) {
    Q_EMIT statusMessage(tr("No launched orbit to remove"));
    return false;
  }
  const quint64 id = orbits_.back().id;
  removeOrbit(id);
  Q_EMIT statusMessage(tr("Orbit %1 removed (%2 left)").arg(id).arg(orbits_.size()));
  return true;
}

void PortraitController::clearOrbits() {
  if (orbits_.empty()) return;
  cleared_ = orbits_;  // before the lists' refresh (orbitsChanged): their Undo offers to bring them back
  for (LaunchedOrbit& o : cleared_) o.points.reset(), o.measures.reset();  // traced again if they come back
  discardOrbits();
  Q_EMIT statusMessage(tr("%1 orbits cleared; Ctrl+Z brings them back").arg(cleared_.size()));
}

void PortraitController::discardOrbits() {
  ++orbitGeneration_;
  if (jobs_) jobs_->cancel(kTraceChannel);
  if (measureJobs_) measureJobs_->cancel();
  orbits_.clear();
  orbitItems_.clear();
  highlighted_ = 0;
  if (view_) {
    view_->setLayer(PortraitLayer::launchedOrbits, {});
    view_->setLayer(PortraitLayer::orbitChain, {});
  }
  Q_EMIT orbitsChanged();
}

void PortraitController::highlightOrbit(quint64 id) {
  if (id != 0 && !findOrbit(id)) id = 0;
  if (id == highlighted_) return;
  highlighted_ = id;
  for (std::size_t i = 0; i < orbits_.size(); ++i) redrawOrbit(i);
  updateOrbitChain();
  Q_EMIT orbitsChanged();
}

void PortraitController::updateOrbitChain() {
  if (!view_) return;
  const LaunchedOrbit* orbit = highlighted_ ? findOrbit(highlighted_) : nullptr;
  std::vector<QwtPlotItem*> items;
  if (orbit && orbit->measures) {
    // The elliptic orbit of the deepest chain level: the island chain the orbit belongs to (issue #27).
    const auto& levels = orbit->measures->chain.levels;
    for (auto it = levels.rbegin(); it != levels.rend(); ++it)
      if (it->orbit) {
        auto* item = new PointsItem(PointsItem::Style::discs, toQt(it->orbit->points), orbit->colour.lighter(130));
        item->setTitle(tr("elliptic orbit of period %1").arg(it->orbit->period));
        items.push_back(item);
        break;
      }
  }
  view_->setLayer(PortraitLayer::orbitChain, std::move(items));
}

bool PortraitController::orbitsSettled() const {
  for (const LaunchedOrbit& o : orbits_)
    if ((!o.points && o.error.isEmpty()) || !o.measures) return false;
  return true;
}

// ------------------------------------------------------------------------------------------------ segment

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
  if (clickedPeriodic_ && &orbit != &clickedPeriodic_->orbit) clickedPeriodic_.reset();  // another's overlay
  periodicPeriod_ = orbit.period;
  periodic_ = orbit;
  if (!view_) return;
  view_->setLayer(PortraitLayer::periodicOrbits, SegmentOverlay::periodicItems(orbit));
  updateLegend();
}

void PortraitController::clearSegment() {
  replay_.reset();
  chain_.reset();
  if (!view_) return;
  for (PortraitLayer layer : {PortraitLayer::segment, PortraitLayer::segmentChain, PortraitLayer::segmentStep})
    view_->setLayer(layer, {});
  updateLegend();
}

QString PortraitController::periodicOrbitText(const PeriodicOrbitAt& found) {
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

void PortraitController::findPeriodicOrbitAt(long double x, long double y) {
  const MapParameters map = map_;
  Job<std::shared_ptr<const PeriodicOrbitAt>> job;
  job.channel = kPeriodicChannel;  // latest wins: another click replaces this search
  job.order = JobOrder::latest;
  job.work = [map, x, y](JobContext<NoProgress>& context) -> std::optional<std::shared_ptr<const PeriodicOrbitAt>> {
    ChainRequest request;
    request.map = map;
    request = chainRequestAt(request, {x, y});  // the rotation instrument's request for this start
    return std::make_shared<const PeriodicOrbitAt>(periodicOrbitAt(request, context.stopToken()));
  };
  job.done = [this, x, y](JobResult<std::shared_ptr<const PeriodicOrbitAt>> r) {
    periodicRequest_ = 0;
    if (!r.ok()) {
      clickedPeriodic_.reset();
      const QString text = tr("No periodic orbit found at (%1, %2): %3")
                               .arg(static_cast<double>(x), 0, 'g', 10)
                               .arg(static_cast<double>(y), 0, 'g', 10)
                               .arg(r.error);
      Q_EMIT statusMessage(text);
      Q_EMIT periodicOrbitFound(text);
      return;
    }
    clickedPeriodic_ = *r.value;
    showPeriodicOrbit(clickedPeriodic_->orbit);
    const QString text = periodicOrbitText(*clickedPeriodic_);
    Q_EMIT statusMessage(text);
    Q_EMIT periodicOrbitFound(text);
  };
  Q_EMIT statusMessage(tr("Finding the periodic orbit at (%1, %2): naming its chain, then Newton…")
                           .arg(static_cast<double>(x), 0, 'g', 10)
                           .arg(static_cast<double>(y), 0, 'g', 10));
  periodicRequest_ = jobs_->submit(std::move(job));
}

void PortraitController::clearPeriodicOrbit() {
  periodicPeriod_ = 0;
  clickedPeriodic_.reset();
  periodic_.reset();
  if (view_) view_->setLayer(PortraitLayer::periodicOrbits, {});
  updateLegend();
}

void PortraitController::showProfileLine(std::optional<std::pair<PhysicalPoint, PhysicalPoint>> line) {
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

void PortraitController::updateLegend() {
  QStringList lines = SegmentOverlay::legendLines(replay_, chain_, periodicPeriod_);
  if (clickedPeriodic_) {  // the chain a click named (issue 37, finding 16), its phrases one per line
    lines << tr("&nbsp;&nbsp;&nbsp;%1, residue %2, found at a click in the chain:")
                 .arg(QString::fromLatin1(toString(clickedPeriodic_->orbit.classification().stability)))
                 .arg(static_cast<double>(clickedPeriodic_->orbit.residue), 0, 'g', 6);
    // Each phrase on a line of its own, a long one cut (the legend is not wrapped; the status bar has it whole).
    for (QString phrase : QString::fromStdString(clickedPeriodic_->chain.summary).split(QStringLiteral("; "))) {
      if (phrase.size() > 52) phrase = phrase.left(51) + QStringLiteral("…");
      lines << QStringLiteral("&nbsp;&nbsp;&nbsp;") + phrase.toHtmlEscaped();
    }
  }
  if (!atlasLabel_.isEmpty())
    lines << tr("<span style='color:#78ff50'>●</span> boundary circle of the atlas island %1").arg(atlasLabel_.toHtmlEscaped());
  if (manifoldsShown_ && manifolds_)
    lines << tr("<span style='color:#ff5050'>━</span> unstable, <span style='color:#50a0ff'>━</span> stable manifold "
                "of %1")
                 .arg(manifoldOrbit_ ? tr("the period-%1 orbit").arg(manifoldOrbit_->period)
                                     : tr("the hyperbolic fixed point"));
  if (view_) view_->setLegend(lines.join(QStringLiteral("<br>")));
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

// -------------------------------------------------------------------------------------------------- manifolds

void PortraitController::setManifoldsShown(bool shown) {
  if (shown == manifoldsShown_) return;
  manifoldsShown_ = shown;
  if (shown) {
    requestFlux();
    requestManifolds();
  } else {
    jobs_->cancel(kManifoldChannel);
    jobs_->cancel(kFluxChannel);
    manifoldsRequest_ = fluxRequest_ = 0;
    if (view_) {
      view_->setLayer(PortraitLayer::manifolds, {});
      view_->setLayer(PortraitLayer::lobes, {});
    }
  }
  updateLegend();
  Q_EMIT manifoldsChanged();
}

void PortraitController::setManifoldOrbit(std::optional<PeriodicOrbit> orbit) {
  manifoldOrbit_ = std::move(orbit);
  manifolds_.reset();
  flux_.reset();
  if (!manifoldsShown_) {
    setManifoldsShown(true);
    return;
  }
  requestFlux();
  requestManifolds();
  Q_EMIT manifoldsChanged();
}

bool PortraitController::manifoldsSettled() const {
  return !manifoldsShown_ || (manifoldsRequest_ == 0 && fluxRequest_ == 0);
}

void PortraitController::requestManifolds() {
  if (!manifoldsShown_) return;
  const PhysicalRect view = viewport().physical(map_);
  const MapParameters box = map_;
  const std::optional<PeriodicOrbit> orbit = manifoldOrbit_;
  Job<ManifoldsPtr> job;
  job.channel = kManifoldChannel;  // latest wins: a new view replaces the refinement of the old one
  job.work = [view, box, orbit](JobContext<NoProgress>& context) -> std::optional<ManifoldsPtr> {
    QElapsedTimer clock;
    clock.start();
    auto result = std::make_shared<ManifoldsResult>();
    for (const ManifoldCurveRequest& r : manifoldPlanForView(box, orbit, view)) {
      ManifoldCurve curve = computeManifoldCurve(r, {}, context.stopToken());
      (r.kind == ManifoldKind::Unstable ? result->unstable : result->stable).push_back(std::move(curve));
    }
    result->seconds = static_cast<double>(clock.nsecsElapsed()) * 1e-9;
    return result;
  };
  job.done = [this](JobResult<ManifoldsPtr> r) {
    manifoldsRequest_ = 0;
    if (!manifoldsShown_) return;
    if (!r.ok()) {
      Q_EMIT statusMessage(tr("Manifolds: %1").arg(r.error));
      return;
    }
    manifolds_ = *r.value;
    drawManifolds();
    updateLegend();
    Q_EMIT manifoldsChanged();
  };
  manifoldsRequest_ = jobs_->submit(std::move(job));
}

void PortraitController::requestFlux() {
  if (!manifoldsShown_) return;
  TurnstileRequest request;
  request.K = map_.K;
  request.orbit = manifoldOrbit_;
  request.side = defaultSide(!manifoldOrbit_);
  Job<FluxPtr> job;
  job.channel = kFluxChannel;
  job.work = [request](JobContext<NoProgress>& context) -> std::optional<FluxPtr> {
    QElapsedTimer clock;
    clock.start();
    auto result = std::make_shared<FluxResult>();
    result->request = request;
    try {
      if (auto e = manifoldKError(request.K)) throw std::invalid_argument(*e);
      result->flux = computeTurnstileFlux(request, {}, context.stopToken());
    } catch (const std::exception& e) {
      if (context.stopRequested()) return std::nullopt;
      result->error = QString::fromUtf8(e.what());
    }
    result->seconds = static_cast<double>(clock.nsecsElapsed()) * 1e-9;
    return result;
  };
  job.done = [this](JobResult<FluxPtr> r) {
    fluxRequest_ = 0;
    if (!manifoldsShown_) return;
    if (r.ok()) {
      flux_ = *r.value;
    } else {
      auto failed = std::make_shared<FluxResult>();
      failed->error = r.error;
      flux_ = failed;
    }
    drawManifolds();
    Q_EMIT manifoldsChanged();
  };
  fluxRequest_ = jobs_->submit(std::move(job));
}

void PortraitController::drawManifolds() {
  if (!view_) return;
  std::vector<QwtPlotItem*> curves;
  if (manifolds_) {
    const auto add = [&curves](const std::vector<ManifoldCurve>& list, const QColor& colour) {
      for (const ManifoldCurve& c : list)
        for (const ManifoldPiece& piece : c.pieces) {
          if (piece.points.size() < 2) continue;
          auto* item = new PointsItem(PointsItem::Style::polyline, toQt(piece.points), colour);
          item->setPenWidth(2);
          curves.push_back(item);
        }
    };
    add(manifolds_->stable, QColor(80, 160, 255));
    add(manifolds_->unstable, QColor(255, 80, 80));
  }
  view_->setLayer(PortraitLayer::manifolds, std::move(curves));
  std::vector<QwtPlotItem*> lobes;
  if (flux_ && flux_->flux) {
    const TurnstileFlux& f = *flux_->flux;
    // The turnstile: the lobe that leaves the zone in one step (orange) and the one that enters (green), each
    // of area the flux per step; labelled with it.
    const QString area = tr("lobe area %1").arg(areaText(f.lobeArea));
    if (f.exitLobe.size() > 2) {
      auto* exit = new PointsItem(PointsItem::Style::polygon, toQt(f.exitLobe), QColor(255, 170, 40));
      exit->setLabel(area);
      lobes.push_back(exit);
    }
    if (f.entryLobe.size() > 2)  // the same area: one label is enough
      lobes.push_back(new PointsItem(PointsItem::Style::polygon, toQt(f.entryLobe), QColor(60, 220, 120)));
  }
  view_->setLayer(PortraitLayer::lobes, std::move(lobes));
}

// ----------------------------------------------------------------------------------------------------- atlas

void PortraitController::showAtlasIsland(const AtlasNode& node, const QString& label, const SegmentRegion& fallback) {
  const MapParameters map = map_;
  const bool centre = node.parent < 0;
  Job<AtlasIslandPtr> job;
  job.channel = kAtlasChannel;  // latest wins: another island replaces this one
  job.work = [map, node](JobContext<NoProgress>&) -> std::optional<AtlasIslandPtr> {
    auto result = std::make_shared<AtlasIslandResult>();
    const long double K = static_cast<long double>(map.K);
    const int period = static_cast<int>(node.period);
    // An orbit the atlas keeps whole is drawn as it is; one kept as a point (read from JSON) is found again from it.
    const auto whole = [&](const PeriodicOrbit& orbit) -> std::optional<PeriodicOrbit> {
      if (static_cast<int>(orbit.points.size()) == orbit.period && orbit.period > 0) return orbit;
      if (orbit.points.empty()) return std::nullopt;
      return refinePeriodicOrbit(K, orbit.period, orbit.points.front());
    };
    QStringList missing;
    try {
      if (node.boundaryFound) {
        const std::uint64_t steps = std::clamp<std::uint64_t>(node.period * kAtlasPointsPerIsland, kLaunchedOrbitSteps,
                                                              std::min(kMaxAtlasBoundaryPoints, limits::kOrbitLength));
        const std::vector<PhysicalPoint> orbit =
            archipelago::traceOrbit(map, node.boundaryPoint.x, node.boundaryPoint.y, steps, false);
        // The circle of the island about node.centre: every n-th point (an orbit under Qⁿ) from the first n's point
        // nearest that centre (the boundary point may lie on another island of the chain: 6 > 138's at K = 0.1);
        // framed whole, elongated or not.
        const std::size_t n = std::max<std::size_t>(node.period, 1);
        std::size_t phase = 0;
        long double nearest = std::numeric_limits<long double>::infinity();
        for (std::size_t k = 0; k < std::min(n, orbit.size()); ++k) {
          const long double d = std::hypot(orbit[k].x - node.centre.x, orbit[k].y - node.centre.y);
          if (d < nearest) nearest = d, phase = k;
        }
        std::vector<PhysicalPoint> own;
        for (std::size_t k = phase; k < orbit.size(); k += n) own.push_back(orbit[k]);
        if (!own.empty()) result->island = dwellRegion(own, 1.0, 64, kAtlasViewMargin);
        result->boundary = toQt(orbit);
      }
    } catch (const std::exception& e) {
      missing << QObject::tr("the boundary circle (%1)").arg(QString::fromUtf8(e.what()));
    }
    result->chain = whole(node.orbit);
    if (!result->chain) missing << QObject::tr("the chain's orbit of period %1 (not found again)").arg(period);
    if (node.flux.partner) {
      result->partner = whole(*node.flux.partner);
      if (!result->partner) missing << QObject::tr("the hyperbolic partner (not found again)");
    }
    result->error = missing.join(QStringLiteral(", "));
    return result;
  };
  job.done = [this, label, centre, fallback](JobResult<AtlasIslandPtr> r) {
    atlasRequest_ = 0;
    if (!r.ok()) {
      zoomToRegion(fallback);
      Q_EMIT statusMessage(tr("Atlas island %1: %2").arg(label, r.error));
      return;
    }
    atlasIsland_ = *r.value;
    zoomToRegion(atlasIsland_->island.value_or(fallback));
    atlasLabel_ = atlasIsland_->boundary.empty() ? QString() : label;
    if (view_) {
      std::vector<QwtPlotItem*> items;
      if (!atlasIsland_->boundary.empty()) {
        auto* item = new PointsItem(PointsItem::Style::dots, atlasIsland_->boundary, QColor(120, 255, 80));
        item->setPenWidth(3);  // a solid ring, thicker than the portrait's orbits about it
        item->setTitle(tr("boundary circle of %1").arg(label));
        items.push_back(item);
      }
      view_->setLayer(PortraitLayer::atlasIsland, std::move(items));
    }
    if (atlasIsland_->chain) showPeriodicOrbit(*atlasIsland_->chain);
    // The barrier about the island's chain: the partner's manifolds (at the centre, the fixed point's loop).
    if (centre) setManifoldOrbit(std::nullopt);
    else if (atlasIsland_->partner) setManifoldOrbit(atlasIsland_->partner);
    else setManifoldsShown(false);
    updateLegend();
    if (!atlasIsland_->error.isEmpty())
      Q_EMIT statusMessage(tr("Atlas island %1: not drawn: %2").arg(label, atlasIsland_->error));
    Q_EMIT atlasIslandShown();
  };
  atlasRequest_ = jobs_->submit(std::move(job));
}

void PortraitController::clearAtlasIsland() {
  if (jobs_) jobs_->cancel(kAtlasChannel);
  atlasRequest_ = 0;
  atlasIsland_.reset();
  atlasLabel_.clear();
  if (view_) view_->setLayer(PortraitLayer::atlasIsland, {});
  updateLegend();
}

// ------------------------------------------------------------------------------------------------- sessions

SessionPortrait PortraitController::sessionState() const {
  SessionPortrait state;
  state.history = history_;
  state.current = historyIndex_;
  state.mode = mode();
  state.colours = view_ ? view_->colourMap() : ColourMapName::Inferno;
  state.budget = pointBudget();
  for (const LaunchedOrbit& orbit : orbits_)
    state.orbits.push_back({{static_cast<double>(orbit.x), static_cast<double>(orbit.y)}, orbit.steps, orbit.backward, orbit.id});
  if (periodic_ && periodicPeriod_ > 0) {
    SessionPeriodicOverlay overlay;
    overlay.label = "period " + std::to_string(periodic_->period);
    for (const PhysicalPoint& p : periodic_->points)
      overlay.points.push_back({static_cast<double>(p.x), static_cast<double>(p.y)});
    state.periodic.push_back(std::move(overlay));
  }
  state.manifolds = manifoldsShown_;
  if (manifoldsShown_ && manifoldOrbit_)
    for (const PhysicalPoint& p : manifoldOrbit_->points)
      state.manifoldOrbit.push_back({static_cast<double>(p.x), static_cast<double>(p.y)});
  return state;
}

void PortraitController::restoreSession(const SessionPortrait& state, const MapParameters& map, double Xr) {
  setMap(map, Xr);
  discardOrbits();
  cleared_.clear();
  clearSegment();
  clearPeriodicOrbit();
  clearAtlasIsland();
  setMode(state.mode);
  setColourMap(state.colours);
  if (state.budget > 0) setPointBudget(state.budget);
  restoreWork(state, map);
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
                               .arg(QString::fromStdString(io::shortestText(static_cast<double>(map.K)))));
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
}

}  // namespace archipelago::ui
