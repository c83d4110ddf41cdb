#pragma once
// Measures how responsive the GUI stays while a run computes (scripts/gui-latency.py drives it).
//
// Event latency: every 20 ms a separate thread (as the X server would, independent of the GUI's own timers)
// posts a timestamped event to the GUI thread, which measures how long its event loop took to deliver it: the
// delay a key press or a click would see.  Refresh rate: the
// number of plot redraws (StatisticsView::refreshCount) per second of the measurement.  Run rate: the run's steps
// per second over the measurement, and the points the phase portrait added meanwhile (scripts/gui-portrait-yield.py
// compares the rate with the portrait accumulating beside the run and with it hidden, issue 25, finding 15, and
// with the segment panel identifying chains or not, issue 41), and the fraction of the probe events that found
// the segment panel's jobs (its chain identifications) running.

#include <QElapsedTimer>
#include <QObject>
#include <QTimer>

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <thread>

#include <vector>

namespace archipelago::ui {
class MainWindow;
}

namespace archipelago::app {

class LatencyProbe : public QObject {
  Q_OBJECT
 public:
  LatencyProbe(ui::MainWindow& window, double seconds, QObject* parent = nullptr);
  ~LatencyProbe() override;
  void start();

 Q_SIGNALS:
  void done(const QString& json);

 protected:
  void customEvent(QEvent* event) override;

 private:
  void finish();

  ui::MainWindow& window_;
  double seconds_;
  std::thread poster_;
  std::atomic<bool> posting_{false};
  QElapsedTimer clock_;
  std::vector<double> latenciesMs_;
  quint64 refreshesAtStart_ = 0;
  double refreshSecondsAtStart_ = 0;
  qint64 measureStartNs_ = 0;
  double stepsAtStart_ = 0;             // the run's steps done when the measure starts
  std::uint64_t portraitAtStart_ = 0;   // the portrait's points so far then
  bool measuring_ = false;
  std::size_t segmentJobsBusy_ = 0;     // probe events that found the segment panel's jobs running (chains)
};

}  // namespace archipelago::app
