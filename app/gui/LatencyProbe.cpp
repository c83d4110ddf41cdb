#include "LatencyProbe.hpp"

#include <QCoreApplication>
#include <QEvent>
#include <QJsonArray>
#include <QJsonDocument>
#include <QJsonObject>
#include <QThread>

#include <algorithm>
#include <chrono>
#include <numeric>

#include "ui/portrait/PortraitPanel.hpp"
#include "ui/portrait/PortraitView.hpp"
#include "ui/segments/LongSegmentsPanel.hpp"
#include "ui/window/MainWindow.hpp"
#include "ui/window/StatisticsView.hpp"

namespace archipelago::app {

namespace {
const QEvent::Type kProbeEvent = static_cast<QEvent::Type>(QEvent::registerEventType());

class ProbeEvent : public QEvent {
 public:
  explicit ProbeEvent(qint64 atNs) : QEvent(kProbeEvent), postedNs(atNs) {}
  qint64 postedNs;
};

double percentile(std::vector<double> v, double p) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  const auto i = static_cast<std::size_t>(p * static_cast<double>(v.size() - 1) + 0.5);
  return v[std::min(i, v.size() - 1)];
}
}  // namespace

LatencyProbe::LatencyProbe(ui::MainWindow& window, double seconds, QObject* parent)
    : QObject(parent), window_(window), seconds_(seconds) {}

LatencyProbe::~LatencyProbe() {
  posting_ = false;
  if (poster_.joinable()) poster_.join();
}

void LatencyProbe::start() {
  clock_.start();
  // Measure once the run has started and its first snapshot is shown (the kernel then uses every core).
  QTimer::singleShot(1500, this, [this] {
    measuring_ = true;
    refreshesAtStart_ = window_.statisticsView()->refreshCount();
    refreshSecondsAtStart_ = window_.statisticsView()->refreshSeconds();
    measureStartNs_ = clock_.nsecsElapsed();
    if (const auto snapshot = window_.latestSnapshot()) stepsAtStart_ = snapshot->state.stepsDone();
    portraitAtStart_ = window_.portraitPanel()->view()->pointsSoFar();
    posting_ = true;
    poster_ = std::thread([this] {
      while (posting_) {
        QCoreApplication::postEvent(this, new ProbeEvent(clock_.nsecsElapsed()));  // thread-safe
        std::this_thread::sleep_for(std::chrono::milliseconds(20));
      }
    });
    QTimer::singleShot(static_cast<int>(1000 * seconds_), this, &LatencyProbe::finish);
  });
}

void LatencyProbe::customEvent(QEvent* event) {
  if (event->type() != kProbeEvent || !measuring_) return;
  const auto* probe = static_cast<ProbeEvent*>(event);
  latenciesMs_.push_back(static_cast<double>(clock_.nsecsElapsed() - probe->postedNs) / 1e6);
  if (!window_.longSegments()->idle()) ++segmentJobsBusy_;  // sampled every 20 ms
}

void LatencyProbe::finish() {
  measuring_ = false;
  posting_ = false;
  if (poster_.joinable()) poster_.join();
  const double elapsed = static_cast<double>(clock_.nsecsElapsed() - measureStartNs_) / 1e9;
  const quint64 refreshes = window_.statisticsView()->refreshCount() - refreshesAtStart_;
  QJsonObject o;
  const auto snapshot = window_.latestSnapshot();
  o[QStringLiteral("run_steps_per_second")] =
      snapshot && elapsed > 0 ? (snapshot->state.stepsDone() - stepsAtStart_) / elapsed : 0.0;
  const std::uint64_t portraitNow = window_.portraitPanel()->view()->pointsSoFar();
  o[QStringLiteral("portrait_points_added")] =
      static_cast<double>(portraitNow >= portraitAtStart_ ? portraitNow - portraitAtStart_ : portraitNow);
  o[QStringLiteral("segment_jobs_busy")] =
      latenciesMs_.empty() ? 0.0 : static_cast<double>(segmentJobsBusy_) / static_cast<double>(latenciesMs_.size());
  o[QStringLiteral("portrait_visible")] = window_.portraitPanel()->view()->isVisible();
  o[QStringLiteral("seconds")] = elapsed;
  o[QStringLiteral("events")] = static_cast<int>(latenciesMs_.size());
  o[QStringLiteral("latency_ms_median")] = percentile(latenciesMs_, 0.5);
  o[QStringLiteral("latency_ms_p99")] = percentile(latenciesMs_, 0.99);
  o[QStringLiteral("latency_ms_max")] = latenciesMs_.empty() ? 0 : *std::max_element(latenciesMs_.begin(), latenciesMs_.end());
  o[QStringLiteral("refreshes")] = static_cast<double>(refreshes);
  o[QStringLiteral("refresh_ms_mean")] =
      refreshes ? 1e3 * (window_.statisticsView()->refreshSeconds() - refreshSecondsAtStart_) / static_cast<double>(refreshes) : 0;
  o[QStringLiteral("refresh_hz")] = elapsed > 0 ? static_cast<double>(refreshes) / elapsed : 0;
  o[QStringLiteral("skipped_snapshots")] = static_cast<double>(window_.worker().skippedSnapshots());
  o[QStringLiteral("cores")] = QThread::idealThreadCount();
  o[QStringLiteral("status_running")] = window_.runStatus() == ui::RunStatus::running;
  Q_EMIT done(QString::fromUtf8(QJsonDocument(o).toJson(QJsonDocument::Compact)));
}

}  // namespace archipelago::app
