#pragma once
// Renders portraits for a PortraitView in the background, through the GUI's one background-job mechanism
// (ui/jobs/BackgroundJobs: latest request wins, cancellable, values tagged with their request).
//
// Each render() is one job: a new request stops the render in progress at once (its stop token, checked by
// core at every chunk) and whatever the old one would still deliver is dropped.  The job copies the request
// and calls archipelago::renderPortrait() — or, for a chaos-indicator map, computeIndicatorMap() (core/measures);
// each refinement pass comes back as an immutable PortraitFrame, tagged with the id of its request, so that the
// view can also drop frames it has itself left behind.  The destructor stops the render and waits for the
// thread.  No maths here.
//
// Accumulation: a request with a large budget (passPoints set, core's setProgressiveSchedule) keeps adding
// passes into the same raster until its budget is reached, a new request replaces it or cancel() stops it;
// every pass is a frame with the points so far.  A Density frame whose view core declares free of sea
// (viewHoldsNoSea) is the last one: the job stops that render itself.  Between rounds the job waits while the
// view's PauseGate is closed (the portrait hidden): it keeps its orbits and goes on where it was.  The render
// threads are niced to the lowest priority (JobPriority::idle), so that a run beside the portrait keeps most of
// the cores (issue 25, finding 15); the first coarse pass is small enough to arrive at once all the same.
//
// Exports: renderForExport() renders the same view at another size (the PNG's own pixels, issue 25, finding 9)
// on its own channel and returns the frame when it is done.

#include <QImage>
#include <QObject>
#include <QString>

#include <cstdint>
#include <memory>
#include <optional>

#include "core/measures/IndicatorMap.hpp"
#include "core/colour/ColourMap.hpp"
#include "core/portrait/PortraitRenderer.hpp"
#include "ui/jobs/BackgroundJobs.hpp"

namespace archipelago::ui {

/// One refinement pass of one request: an immutable snapshot, safe to pass between threads.
struct PortraitFrame {
  quint64 requestId = 0;
  PortraitRequest request;                         ///< the view, map and size (also of an indicator map)
  std::shared_ptr<const PortraitRaster> raster;    ///< the portrait's raster (null for an indicator map)
  std::optional<IndicatorRequest> indicatorRequest;        ///< set for an indicator map
  std::shared_ptr<const IndicatorRaster> indicator;        ///< its raster so far
  QImage image;                 ///< colourized raster, row 0 on top (Format_RGB888)
  double scaleMin = 0;          ///< colour-bar range (RasterImage::scaleMin/Max), in `quantity`
  double scaleMax = 0;
  QString quantity;
  std::uint64_t pointsDone = 0;   ///< map steps (an indicator map: pixels) done so far
  std::uint64_t pointsTotal = 0;
  std::uint32_t passesDone = 0;
  std::uint32_t passes = 0;
  bool final = false;           ///< the budget is reached: nothing more will come
  bool noSea = false;           ///< core's viewHoldsNoSea(): the render stopped here, nothing more will come
  bool cancelled = false;
  double seconds = 0;           ///< wall time since the request started

  [[nodiscard]] std::uint64_t nonEmptyPixels() const;
  [[nodiscard]] std::uint64_t pixelCount() const;
};

class PortraitWorker : public QObject {
  Q_OBJECT
 public:
  explicit PortraitWorker(QObject* parent = nullptr);
  ~PortraitWorker() override;

  /// Starts rendering `request` with colour map `colours`, stopping any render in progress; returns its id.  The
  /// render waits at `gate` (may be null) while it is paused.
  quint64 render(const PortraitRequest& request, ColourMapName colours, std::shared_ptr<PauseGate> gate = {});
  /// The same for a chaos-indicator map.
  quint64 renderIndicator(const IndicatorRequest& request, ColourMapName colours, std::shared_ptr<PauseGate> gate = {});
  /// Stops the render in progress (if any); no further frame of it is emitted.
  void cancel();

  /// Renders `request` (or the indicator map) for an export on its own channel; exportReady() brings the frame.
  quint64 renderForExport(const PortraitRequest& request, const std::optional<IndicatorRequest>& indicator,
                          ColourMapName colours);
  void cancelExport();

 Q_SIGNALS:
  /// A refinement pass finished (emitted on the thread that owns this object).
  void frameReady(const archipelago::ui::PortraitFrame& frame);
  /// Progress of the render `requestId`, at most every 100 ms.
  void progress(quint64 requestId, quint64 pointsDone, quint64 pointsTotal);
  /// The request failed (e.g. an invalid request): a one-line message.
  void failed(quint64 requestId, const QString& message);
  /// renderForExport()'s result (null frame with a message when it failed), and its progress.
  void exportReady(quint64 requestId, std::shared_ptr<const archipelago::ui::PortraitFrame> frame, const QString& error);
  void exportProgress(quint64 requestId, double fraction);

 private:
  // Last members: destroyed first, they stop the renders and join their threads.
  BackgroundJobs jobs_{this, 1, JobPriority::idle};
  BackgroundJobs exports_{this, 1, JobPriority::normal};
};

}  // namespace archipelago::ui

Q_DECLARE_METATYPE(archipelago::ui::PortraitFrame)
