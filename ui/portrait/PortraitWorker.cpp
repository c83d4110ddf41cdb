#include "ui/portrait/PortraitWorker.hpp"

#include <QElapsedTimer>

#include <optional>
#include <stop_token>
#include <variant>

#include "core/kernels/KernelDispatch.hpp"

namespace archipelago::ui {

namespace {
/// The points of a render so far, as the throttled progress sends them.
struct Counts {
  quint64 done = 0;
  quint64 total = 0;
};
using PortraitUpdate = std::variant<PortraitFrame, Counts>;
}  // namespace

PortraitWorker::PortraitWorker(QObject* parent) : QObject(parent) {
  qRegisterMetaType<archipelago::ui::PortraitFrame>("archipelago::ui::PortraitFrame");
}

PortraitWorker::~PortraitWorker() = default;  // jobs_ stops the render and joins its thread

quint64 PortraitWorker::render(const PortraitRequest& request, ColourMapName colours) {
  Job<bool, PortraitUpdate> job;
  job.work = [request = request, colours](JobContext<PortraitUpdate>& context) mutable -> std::optional<bool> {
    QElapsedTimer clock;
    clock.start();
    const std::stop_token& stop = context.stopToken();
    // The render stops on a new request or cancel() (stop), or by itself once core says the view holds no sea.
    std::stop_source local;
    const std::stop_callback forward(stop, [&local] { local.request_stop(); });
    auto makeFrame = [&](const PortraitRaster& raster, const PortraitProgress& p) {
      const RasterImage rgb = colourize(raster, colours);
      PortraitFrame frame;
      frame.requestId = context.id();
      frame.request = request;
      frame.raster = std::make_shared<const PortraitRaster>(raster);
      frame.image = QImage(rgb.rgb.data(), rgb.width, rgb.height, 3 * rgb.width, QImage::Format_RGB888).copy();
      frame.scaleMin = rgb.scaleMin;
      frame.scaleMax = rgb.scaleMax;
      frame.quantity = QString::fromStdString(rgb.quantity);
      frame.pointsDone = p.pointsDone;
      frame.pointsTotal = p.pointsTotal;
      frame.passesDone = p.pass + 1;
      frame.passes = p.passes;
      frame.final = p.final;
      frame.noSea = viewHoldsNoSea(request, raster);
      frame.seconds = static_cast<double>(clock.elapsed()) / 1000.0;
      return frame;
    };
    request.kernel = &selectKernel();  // the fastest path, or $ARCHIPELAGO_KERNEL (throws on a bad name)
    (void)renderPortrait(  // a stopped render delivers nothing more: a newer request replaces it
        request,
        [&](const PortraitProgress& p) {
          if (context.stopRequested()) return;  // replaced or cancelled: its deliveries would be dropped
          if (p.snapshot) {
            PortraitFrame frame = makeFrame(*p.snapshot, p);
            if (frame.noSea) local.request_stop();
            context.post(std::move(frame));
          }
          context.progress(Counts{p.pointsDone, p.pointsTotal});
        },
        local.get_token());
    return true;  // every pass was a frame: the result itself says nothing more
  };
  job.progress = [this](quint64 id, PortraitUpdate update) {
    if (auto* frame = std::get_if<PortraitFrame>(&update)) {
      Q_EMIT frameReady(*frame);
    } else {
      const Counts& counts = std::get<Counts>(update);
      Q_EMIT progress(id, counts.done, counts.total);
    }
  };
  job.done = [this](JobResult<bool> r) {
    if (!r.ok()) Q_EMIT failed(r.id, r.error);
  };
  return jobs_.submit(std::move(job));
}

void PortraitWorker::cancel() { jobs_.cancel(); }

}  // namespace archipelago::ui
