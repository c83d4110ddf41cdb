#pragma once
// The thread that renders portraits for a PortraitView (Qt's threaded-Mandelbrot pattern).
//
// One worker owns the computation.  The GUI hands it a request under a mutex and wakes it; a new request
// stops the render in progress at once (std::stop_source, checked by core at every chunk).  The worker copies
// the request and calls archipelago::renderPortrait() without holding the lock; each refinement pass comes
// back as an immutable PortraitFrame through a queued signal, tagged with the id of its request, so that the
// view can drop stale frames.  The destructor stops the render and waits for the thread.  No maths here.
//
// Accumulation: a request with a large budget (passPoints set, core's setProgressiveSchedule) keeps adding
// passes into the same raster until its budget is reached, a new request replaces it or cancel() stops it;
// every pass is a frame with the points so far.  A Density frame whose view core declares free of sea
// (viewHoldsNoSea) is the last one: the worker stops that render itself.

#include <QImage>
#include <QMutex>
#include <QString>
#include <QThread>
#include <QWaitCondition>

#include <cstdint>
#include <memory>
#include <optional>
#include <stop_token>

#include "core/portrait/ColourMap.hpp"
#include "core/portrait/PortraitRenderer.hpp"

namespace archipelago::ui {

/// One refinement pass of one request: an immutable snapshot, safe to pass between threads.
struct PortraitFrame {
  quint64 requestId = 0;
  PortraitRequest request;
  std::shared_ptr<const PortraitRaster> raster;
  QImage image;                 ///< colourized raster, row 0 on top (Format_RGB888)
  double scaleMin = 0;          ///< colour-bar range (RasterImage::scaleMin/Max), in `quantity`
  double scaleMax = 0;
  QString quantity;
  std::uint64_t pointsDone = 0;
  std::uint64_t pointsTotal = 0;
  std::uint32_t passesDone = 0;
  std::uint32_t passes = 0;
  bool final = false;           ///< the budget is reached: nothing more will come
  bool noSea = false;           ///< core's viewHoldsNoSea(): the render stopped here, nothing more will come
  bool cancelled = false;
  double seconds = 0;           ///< wall time since the request started
};

class PortraitWorker : public QThread {
  Q_OBJECT
 public:
  explicit PortraitWorker(QObject* parent = nullptr);
  ~PortraitWorker() override;

  /// Starts rendering `request` with colour map `colours`, stopping any render in progress; returns its id.
  quint64 render(const PortraitRequest& request, ColourMapName colours);
  /// Stops the render in progress (if any); no further frame of it is emitted.
  void cancel();

 Q_SIGNALS:
  /// A refinement pass finished (queued to the receiver's thread).
  void frameReady(const archipelago::ui::PortraitFrame& frame);
  /// Progress of the render `requestId`, at most every 100 ms.
  void progress(quint64 requestId, quint64 pointsDone, quint64 pointsTotal);
  /// The request failed (e.g. an invalid request): a one-line message.
  void failed(quint64 requestId, const QString& message);

 protected:
  void run() override;

 private:
  QMutex mutex_;
  QWaitCondition wake_;
  std::optional<PortraitRequest> pending_;   // guarded by mutex_
  ColourMapName pendingColours_ = ColourMapName::Inferno;
  quint64 pendingId_ = 0;
  quint64 nextId_ = 0;
  std::stop_source current_;                 // guarded by mutex_: stops the render in progress
  bool quitting_ = false;                    // guarded by mutex_
};

}  // namespace archipelago::ui

Q_DECLARE_METATYPE(archipelago::ui::PortraitFrame)
