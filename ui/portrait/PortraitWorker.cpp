#include "ui/portrait/PortraitWorker.hpp"

#include <QElapsedTimer>
#include <QMutexLocker>

#include <exception>

#include "core/kernels/KernelDispatch.hpp"

namespace archipelago::ui {

PortraitWorker::PortraitWorker(QObject* parent) : QThread(parent) {
  qRegisterMetaType<archipelago::ui::PortraitFrame>("archipelago::ui::PortraitFrame");
}

PortraitWorker::~PortraitWorker() {
  {
    QMutexLocker lock(&mutex_);
    quitting_ = true;
    current_.request_stop();
    wake_.wakeOne();
  }
  wait();
}

quint64 PortraitWorker::render(const PortraitRequest& request, ColourMapName colours) {
  QMutexLocker lock(&mutex_);
  pending_ = request;
  pendingColours_ = colours;
  pendingId_ = ++nextId_;
  current_.request_stop();  // the render in progress ends within one chunk
  if (!isRunning())
    start(QThread::LowPriority);
  else
    wake_.wakeOne();
  return pendingId_;
}

void PortraitWorker::cancel() {
  QMutexLocker lock(&mutex_);
  pending_.reset();
  current_.request_stop();
}

void PortraitWorker::run() {
  for (;;) {
    PortraitRequest request;
    ColourMapName colours;
    quint64 id;
    std::stop_token stop;
    {
      QMutexLocker lock(&mutex_);
      while (!pending_ && !quitting_) wake_.wait(&mutex_);
      if (quitting_) return;
      request = *pending_;
      colours = pendingColours_;
      id = pendingId_;
      pending_.reset();
      current_ = std::stop_source();
      stop = current_.get_token();
    }
    QElapsedTimer clock;
    clock.start();
    qint64 lastProgress = -1000;
    // The render stops on a new request or cancel() (stop), or by itself once core says the view holds no sea.
    std::stop_source local;
    const std::stop_callback forward(stop, [&local] { local.request_stop(); });
    auto makeFrame = [&](const PortraitRaster& raster, const PortraitProgress& p) {
      const RasterImage rgb = colourize(raster, colours);
      PortraitFrame frame;
      frame.requestId = id;
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
    try {
      request.kernel = &selectKernel();  // the fastest path, or $ARCHIPELAGO_KERNEL (throws on a bad name)
      const PortraitResult result = renderPortrait(
          request,
          [&](const PortraitProgress& p) {
            if (stop.stop_requested()) return;
            if (p.snapshot) {
              PortraitFrame frame = makeFrame(*p.snapshot, p);
              if (frame.noSea) local.request_stop();
              Q_EMIT frameReady(frame);
            }
            if (clock.elapsed() - lastProgress >= 100) {
              lastProgress = clock.elapsed();
              Q_EMIT progress(id, p.pointsDone, p.pointsTotal);
            }
          },
          local.get_token());
      (void)result;  // a cancelled render emits nothing more: a newer request replaces it
    } catch (const std::exception& e) {
      Q_EMIT failed(id, QString::fromUtf8(e.what()));
    }
  }
}

}  // namespace archipelago::ui
