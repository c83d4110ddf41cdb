#include "ui/portrait/ManifoldsLayer.hpp"

#include <QColor>
#include <QElapsedTimer>

#include <exception>
#include <stdexcept>
#include <utility>

#include "core/manifolds/ManifoldViewPlan.hpp"
#include "ui/jobs/BackgroundJobs.hpp"
#include "ui/portrait/PortraitLayers.hpp"
#include "ui/portrait/PortraitView.hpp"
#include "ui/portrait/ViewLayer.hpp"

namespace archipelago::ui {

namespace {
constexpr int kManifoldChannel = 0;  // latest wins: the manifolds of the view shown
constexpr int kFluxChannel = 1;      // latest wins: the flux of the orbit shown

QString areaText(long double a) { return QString::number(static_cast<double>(a), 'g', 6); }
}  // namespace

ManifoldsLayer::ManifoldsLayer(const ViewLayer& view) : viewLayer_(view), view_(view.view()) {
  jobs_ = std::make_unique<BackgroundJobs>(this, 2);
}

ManifoldsLayer::~ManifoldsLayer() { jobs_.reset(); }

void ManifoldsLayer::setManifoldsShown(bool shown) {
  if (shown == shown_) return;
  shown_ = shown;
  if (shown) {
    recompute();
  } else {
    jobs_->cancel(kManifoldChannel);
    jobs_->cancel(kFluxChannel);
    manifoldsRequest_ = fluxRequest_ = 0;
    if (view_)
      for (PortraitLayer layer : {PortraitLayer::manifolds, PortraitLayer::lobes, PortraitLayer::lobeLabel})
        view_->setLayer(layer, {});
  }
  Q_EMIT legendChanged();
  Q_EMIT manifoldsChanged();
}

void ManifoldsLayer::setManifoldOrbit(std::optional<PeriodicOrbit> orbit) {
  orbit_ = std::move(orbit);
  manifolds_.reset();
  flux_.reset();
  if (!shown_) {
    setManifoldsShown(true);
    return;
  }
  recompute();
  Q_EMIT manifoldsChanged();
}

bool ManifoldsLayer::manifoldsSettled() const { return !shown_ || (manifoldsRequest_ == 0 && fluxRequest_ == 0); }

void ManifoldsLayer::forgetMap() {
  orbit_.reset();  // an orbit of another K
  flux_.reset();
  manifolds_.reset();
}

void ManifoldsLayer::recompute() {
  requestFlux();
  requestManifolds();
}

void ManifoldsLayer::followView() { requestManifolds(); }

std::vector<LegendLine> ManifoldsLayer::legendLines() const {
  if (!shown_ || !manifolds_) return {};
  return {{PortraitLayer::manifolds,
           tr("<span style='color:#ff5050'>━</span> unstable, <span style='color:#50a0ff'>━</span> stable manifold "
              "of %1")
               .arg(orbit_ ? tr("the period-%1 orbit").arg(orbit_->period) : tr("the hyperbolic fixed point"))}};
}

void ManifoldsLayer::requestManifolds() {
  if (!shown_) return;
  const PhysicalRect view = viewLayer_.viewport().physical(viewLayer_.map());
  const MapParameters box = viewLayer_.map();
  const std::optional<PeriodicOrbit> orbit = orbit_;
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
    if (!shown_) return;
    if (!r.ok()) {
      Q_EMIT statusMessage(tr("Manifolds: %1").arg(r.error));
      return;
    }
    manifolds_ = *r.value;
    drawManifolds();
    Q_EMIT legendChanged();
    Q_EMIT manifoldsChanged();
  };
  manifoldsRequest_ = jobs_->submit(std::move(job));
}

void ManifoldsLayer::requestFlux() {
  if (!shown_) return;
  TurnstileRequest request;
  request.K = viewLayer_.map().K;
  request.orbit = orbit_;
  request.side = defaultSide(!orbit_);
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
    if (!shown_) return;
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

void ManifoldsLayer::drawManifolds() {
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
  std::vector<QwtPlotItem*> lobes, label;
  if (flux_ && flux_->flux) {
    const TurnstileFlux& f = *flux_->flux;
    // The turnstile: the lobe that leaves the zone in one step (orange) and the one that enters (green), each
    // of area the flux per step; the exit lobe labelled with it, over every orbit (issue 53, finding 16).
    if (f.exitLobe.size() > 2) {
      lobes.push_back(new PointsItem(PointsItem::Style::polygon, toQt(f.exitLobe), QColor(255, 170, 40)));
      auto* area = new PointsItem(PointsItem::Style::label, toQt(f.exitLobe));
      area->setLabel(tr("lobe area %1").arg(areaText(f.lobeArea)));
      label.push_back(area);
    }
    if (f.entryLobe.size() > 2)  // the same area: one label is enough
      lobes.push_back(new PointsItem(PointsItem::Style::polygon, toQt(f.entryLobe), QColor(60, 220, 120)));
  }
  view_->setLayer(PortraitLayer::lobes, std::move(lobes));
  view_->setLayer(PortraitLayer::lobeLabel, std::move(label));
}

}  // namespace archipelago::ui
