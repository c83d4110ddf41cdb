#include "ui/portrait/PortraitWorker.hpp"

#include <QElapsedTimer>

#include <cmath>
#include <optional>
#include <stop_token>
#include <variant>

#include "core/kernels/KernelDispatch.hpp"
#include "core/measures/MeasureExport.hpp"
#include "core/portrait/PortraitColours.hpp"

namespace archipelago::ui {

namespace {
/// The points of a render so far, as the throttled progress sends them.
struct Counts {
  quint64 done = 0;
  quint64 total = 0;
};
using PortraitUpdate = std::variant<PortraitFrame, Counts>;

// A render's frames and counts as the worker's signals (the portrait's and the indicator maps' renders alike).
void forwardFrames(Job<bool, PortraitUpdate>& job, PortraitWorker* worker) {
  job.progress = [worker](quint64 id, PortraitUpdate update) {
    if (auto* frame = std::get_if<PortraitFrame>(&update)) {
      Q_EMIT worker->frameReady(*frame);
    } else {
      const Counts& counts = std::get<Counts>(update);
      Q_EMIT worker->progress(id, counts.done, counts.total);
    }
  };
  job.done = [worker](JobResult<bool> r) {
    if (!r.ok()) Q_EMIT worker->failed(r.id, r.error);
  };
}

QImage toImage(const RasterImage& rgb) {
  return QImage(rgb.rgb.data(), rgb.width, rgb.height, 3 * rgb.width, QImage::Format_RGB888).copy();
}

/// A frame of an indicator raster (its filled values: a coarse pass shows its big pixels).
PortraitFrame indicatorFrame(const IndicatorRequest& request, const IndicatorRaster& raster, ColourMapName colours) {
  const RasterImage rgb = colourizeIndicator(raster, colours);
  PortraitFrame frame;
  frame.request.map = request.measure.map;
  frame.request.view = request.view;
  frame.request.width = request.width;
  frame.request.height = request.height;
  frame.indicatorRequest = request;
  frame.indicator = std::make_shared<const IndicatorRaster>(raster);
  frame.image = toImage(rgb);
  frame.scaleMin = rgb.scaleMin;
  frame.scaleMax = rgb.scaleMax;
  frame.quantity = QString::fromStdString(rgb.quantity);
  frame.pointsDone = raster.pixelsDone;
  frame.pointsTotal = raster.pixelCount();
  return frame;
}

PortraitFrame portraitFrame(const PortraitRequest& request, const PortraitRaster& raster, ColourMapName colours) {
  const RasterImage rgb = colourize(raster, colours);
  PortraitFrame frame;
  frame.request = request;
  frame.raster = std::make_shared<const PortraitRaster>(raster);
  frame.image = toImage(rgb);
  frame.scaleMin = rgb.scaleMin;
  frame.scaleMax = rgb.scaleMax;
  frame.quantity = QString::fromStdString(rgb.quantity);
  return frame;
}
}  // namespace

std::uint64_t PortraitFrame::nonEmptyPixels() const {
  if (raster) return raster->nonEmptyPixels();
  if (indicator) return indicator->pixelsDone;
  return 0;
}

std::uint64_t PortraitFrame::pixelCount() const {
  if (raster) return raster->pixelCount();
  if (indicator) return indicator->pixelCount();
  return 0;
}

PortraitWorker::PortraitWorker(QObject* parent) : QObject(parent) {
  qRegisterMetaType<archipelago::ui::PortraitFrame>("archipelago::ui::PortraitFrame");
}

PortraitWorker::~PortraitWorker() = default;  // jobs_ and exports_ stop their renders and join their threads

quint64 PortraitWorker::render(const PortraitRequest& request, ColourMapName colours, std::shared_ptr<PauseGate> gate) {
  Job<bool, PortraitUpdate> job;
  job.work = [request = request, colours, gate](JobContext<PortraitUpdate>& context) mutable -> std::optional<bool> {
    QElapsedTimer clock;
    clock.start();
    const std::stop_token& stop = context.stopToken();
    // The render stops on a new request or cancel() (stop), or by itself once core says the view holds no sea.
    std::stop_source local;
    const std::stop_callback forward(stop, [&local] { local.request_stop(); });
    request.kernel = &selectKernel();  // the fastest path, or $ARCHIPELAGO_KERNEL (throws on a bad name)
    (void)renderPortrait(  // a stopped render delivers nothing more: a newer request replaces it
        request,
        [&](const PortraitProgress& p) {
          if (context.stopRequested()) return;  // replaced or cancelled: its deliveries would be dropped
          if (p.snapshot) {
            PortraitFrame frame = portraitFrame(request, *p.snapshot, colours);
            frame.requestId = context.id();
            frame.pointsDone = p.pointsDone;
            frame.pointsTotal = p.pointsTotal;
            frame.passesDone = p.pass + 1;
            frame.passes = p.passes;
            frame.final = p.final;
            frame.noSea = viewHoldsNoSea(request, *p.snapshot);
            frame.seconds = static_cast<double>(clock.elapsed()) / 1000.0;
            if (frame.noSea) local.request_stop();
            context.post(std::move(frame));
          }
          context.progress(Counts{p.pointsDone, p.pointsTotal});
          if (gate && !p.final) (void)gate->waitWhilePaused(stop);  // hidden: wait here, orbits kept
        },
        local.get_token());
    return true;  // every pass was a frame: the result itself says nothing more
  };
  forwardFrames(job, this);
  return jobs_.submit(std::move(job));
}

quint64 PortraitWorker::renderIndicator(const IndicatorRequest& request, ColourMapName colours,
                                        std::shared_ptr<PauseGate> gate) {
  Job<bool, PortraitUpdate> job;
  job.work = [request = request, colours, gate](JobContext<PortraitUpdate>& context) mutable -> std::optional<bool> {
    QElapsedTimer clock;
    clock.start();
    request.measure.kernel = &selectKernel();
    (void)computeIndicatorMap(
        request,
        [&](const IndicatorProgress& p) {
          if (context.stopRequested()) return;
          if (p.snapshot) {
            PortraitFrame frame = indicatorFrame(request, *p.snapshot, colours);
            frame.requestId = context.id();
            frame.passesDone = p.pass + 1;
            frame.passes = p.passes;
            frame.final = p.final;
            frame.seconds = static_cast<double>(clock.elapsed()) / 1000.0;
            context.post(std::move(frame));
          }
          context.progress(Counts{p.pixelsDone, p.pixelsTotal});
          if (gate && !p.final) (void)gate->waitWhilePaused(context.stopToken());
        },
        context.stopToken());
    return true;
  };
  forwardFrames(job, this);
  return jobs_.submit(std::move(job));
}

void PortraitWorker::cancel() { jobs_.cancel(); }

quint64 PortraitWorker::renderForExport(const PortraitRequest& request, const std::optional<IndicatorRequest>& indicator,
                                        ColourMapName colours) {
  using FramePtr = std::shared_ptr<const PortraitFrame>;
  Job<FramePtr, double> job;
  job.work = [request = request, indicator = indicator, colours](JobContext<double>& context) mutable -> std::optional<FramePtr> {
    if (indicator) {
      indicator->measure.kernel = &selectKernel();
      const IndicatorResult r = computeIndicatorMap(
          *indicator,
          [&](const IndicatorProgress& p) {
            context.progress(p.pixelsTotal ? static_cast<double>(p.pixelsDone) / static_cast<double>(p.pixelsTotal) : 0);
          },
          context.stopToken());
      if (r.cancelled) return std::nullopt;
      auto frame = std::make_shared<PortraitFrame>(indicatorFrame(*indicator, r.raster, colours));
      frame->final = true;
      return frame;
    }
    request.kernel = &selectKernel();
    const PortraitResult r = renderPortrait(
        request,
        [&](const PortraitProgress& p) {
          context.progress(p.pointsTotal ? static_cast<double>(p.pointsDone) / static_cast<double>(p.pointsTotal) : 0);
        },
        context.stopToken());
    if (r.cancelled) return std::nullopt;
    auto frame = std::make_shared<PortraitFrame>(portraitFrame(request, r.raster, colours));
    frame->pointsDone = frame->pointsTotal = r.raster.pointsIterated;
    frame->final = true;
    return frame;
  };
  job.progress = [this](quint64 id, double fraction) { Q_EMIT exportProgress(id, fraction); };
  job.done = [this](JobResult<FramePtr> r) { Q_EMIT exportReady(r.id, r.value.value_or(nullptr), r.error); };
  return exports_.submit(std::move(job));
}

void PortraitWorker::cancelExport() { exports_.cancel(); }

}  // namespace archipelago::ui
