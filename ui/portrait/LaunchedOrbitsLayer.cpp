#include "ui/portrait/LaunchedOrbitsLayer.hpp"

#include <QElapsedTimer>

#include <algorithm>
#include <exception>
#include <sstream>
#include <utility>

#include "core/colour/ColourMap.hpp"
#include "core/io/AtomicFile.hpp"
#include "core/io/NumberText.hpp"
#include "core/limits/Limits.hpp"
#include "core/portrait/MapOverlays.hpp"
#include "ui/jobs/BackgroundJobs.hpp"
#include "ui/portrait/PortraitLayers.hpp"
#include "ui/portrait/PortraitView.hpp"
#include "ui/portrait/ViewLayer.hpp"

namespace archipelago::ui {

namespace {
QColor launchedColour(quint64 id) {
  const Rgb c = launchedOrbitColour(static_cast<std::uint32_t>(id));  // apart from the portrait's orbits
  return QColor(c.r, c.g, c.b);
}

using TracePtr = std::shared_ptr<const std::vector<QPointF>>;
}  // namespace

LaunchedOrbitsLayer::LaunchedOrbitsLayer(const ViewLayer& view) : viewLayer_(view), view_(view.view()) {
  qRegisterMetaType<OrbitMeasuresPtr>();
  traceJobs_ = std::make_unique<BackgroundJobs>(this, 1);
  measureJobs_ = std::make_unique<BackgroundJobs>(this, 1, JobPriority::background);
}

LaunchedOrbitsLayer::~LaunchedOrbitsLayer() {
  // Stop the jobs and join their threads before the lists they report to go.
  measureJobs_.reset();
  traceJobs_.reset();
}

std::vector<PhysicalPoint> LaunchedOrbitsLayer::launchedOrbitStarts() const {
  std::vector<PhysicalPoint> starts;
  starts.reserve(orbits_.size());
  for (const LaunchedOrbit& orbit : orbits_) starts.push_back({orbit.x, orbit.y});
  return starts;
}

void LaunchedOrbitsLayer::setClickOrbit(std::uint64_t steps, bool backward) {
  clickSteps_ = std::clamp<std::uint64_t>(steps, 1, limits::kOrbitLength);
  clickBackward_ = backward;
}

bool LaunchedOrbitsLayer::exportOrbitCsv(quint64 id, const QString& path, QString* error) const {
  const auto it = std::find_if(orbits_.begin(), orbits_.end(), [id](const LaunchedOrbit& o) { return o.id == id; });
  if (it == orbits_.end()) {
    if (error) *error = tr("there is no orbit %1").arg(id);
    return false;
  }
  try {
    std::ostringstream csv;
    writeOrbitCsv(csv, viewLayer_.map(), it->x, it->y, it->steps, it->backward);
    const std::string text = csv.str();
    io::writeFileAtomically(path.toStdString(), text);
  } catch (const std::exception& e) {
    if (error) *error = QString::fromStdString(e.what());
    return false;
  }
  return true;
}

quint64 LaunchedOrbitsLayer::launchOrbit(long double x, long double y, std::uint64_t steps, bool backward,
                                         quint64 number) {
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
  measureOrbit(orbits_.back());
  Q_EMIT statusMessage(tr("Orbit %1 from (%2, %3): %4 steps%5; measuring its rotation number and chain…")
                           .arg(orbit.id)
                           .arg(QString::fromStdString(io::shortestText(x)))  // every digit given, no noise (issue 53, finding 18)
                           .arg(QString::fromStdString(io::shortestText(y)))
                           .arg(orbit.steps)
                           .arg(backward ? tr(" backward (N⁻¹)") : QString()));
  Q_EMIT orbitsChanged();
  return orbit.id;
}

int LaunchedOrbitsLayer::launchOrbitFamily(const OrbitFamily& family, std::uint64_t steps, bool backward) {
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

void LaunchedOrbitsLayer::traceOrbit(const LaunchedOrbit& orbit) {
  // Each orbit once, on a queue (its points); nothing of the earlier orbits is recomputed, the GUI thread only adds
  // one plot item per orbit.
  const MapParameters map = viewLayer_.map();
  const quint64 id = orbit.id, generation = generation_;
  const long double x = orbit.x, y = orbit.y;
  const std::uint64_t steps = orbit.steps;
  const bool backward = orbit.backward;
  Job<TracePtr> trace;
  trace.order = JobOrder::queued;
  trace.work = [map, x, y, steps, backward](JobContext<NoProgress>&) -> std::optional<TracePtr> {
    return std::make_shared<const std::vector<QPointF>>(toQt(archipelago::traceOrbit(map, x, y, steps, backward)));
  };
  trace.done = [this, id, generation](JobResult<TracePtr> r) {
    if (generation != generation_) return;
    onOrbitTraced(id, r.value.value_or(nullptr), r.error);
  };
  traceJobs_->submit(std::move(trace));
}

void LaunchedOrbitsLayer::measureOrbit(const LaunchedOrbit& orbit) {
  const MapParameters map = viewLayer_.map();
  const quint64 id = orbit.id, generation = generation_;
  const long double x = orbit.x, y = orbit.y;
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
    if (generation != generation_) return;
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

LaunchedOrbit* LaunchedOrbitsLayer::findOrbit(quint64 id) {
  for (LaunchedOrbit& o : orbits_)
    if (o.id == id) return &o;
  return nullptr;
}

void LaunchedOrbitsLayer::onOrbitTraced(quint64 id, std::shared_ptr<const std::vector<QPointF>> points,
                                        const QString& error) {
  LaunchedOrbit* orbit = findOrbit(id);
  if (!orbit) return;  // removed meanwhile
  orbit->points = std::move(points);
  orbit->error = error;
  if (!error.isEmpty()) Q_EMIT statusMessage(tr("Orbit %1: %2").arg(id).arg(error));
  redrawOrbit(static_cast<std::size_t>(orbit - orbits_.data()));
  Q_EMIT orbitsChanged();
}

void LaunchedOrbitsLayer::onOrbitMeasured(quint64 id, const OrbitMeasuresPtr& measures) {
  LaunchedOrbit* orbit = findOrbit(id);
  if (!orbit) return;
  orbit->measures = measures;
  Q_EMIT statusMessage(measures->error.isEmpty()
                           ? tr("Orbit %1: rotation %2; %3").arg(id).arg(rotationText(*measures), chainText(*measures))
                           : tr("Orbit %1: no measures (%2)").arg(id).arg(measures->error));
  if (highlighted_ == id) updateOrbitChain();
  Q_EMIT orbitsChanged();
}

void LaunchedOrbitsLayer::redrawOrbit(std::size_t index) {
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

bool LaunchedOrbitsLayer::removeOrbit(quint64 id) {
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

bool LaunchedOrbitsLayer::undoLastOrbit() {
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

void LaunchedOrbitsLayer::clearOrbits() {
  if (orbits_.empty()) return;
  cleared_ = orbits_;  // before the lists' refresh (orbitsChanged): their Undo offers to bring them back
  for (LaunchedOrbit& o : cleared_) o.points.reset(), o.measures.reset();  // traced again if they come back
  dropOrbits();
  Q_EMIT statusMessage(tr("%1 orbits cleared; Ctrl+Z brings them back").arg(cleared_.size()));
}

void LaunchedOrbitsLayer::discardOrbits() {
  dropOrbits();
  cleared_.clear();
}

void LaunchedOrbitsLayer::dropOrbits() {
  ++generation_;
  if (traceJobs_) traceJobs_->cancel(0);
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

void LaunchedOrbitsLayer::highlightOrbit(quint64 id) {
  if (id != 0 && !findOrbit(id)) id = 0;
  if (id == highlighted_) return;
  highlighted_ = id;
  for (std::size_t i = 0; i < orbits_.size(); ++i) redrawOrbit(i);
  updateOrbitChain();
  Q_EMIT orbitsChanged();
}

void LaunchedOrbitsLayer::updateOrbitChain() {
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

bool LaunchedOrbitsLayer::orbitsSettled() const {
  for (const LaunchedOrbit& o : orbits_)
    if ((!o.points && o.error.isEmpty()) || !o.measures) return false;
  return true;
}

}  // namespace archipelago::ui
