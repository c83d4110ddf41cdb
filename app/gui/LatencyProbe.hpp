#pragma once
// Measures how responsive the GUI stays while a run computes (scripts/gui-latency.py drives it).
//
// Event latency: every 20 ms the probe posts a timestamped event to the window's thread and measures how
// long the event loop takes to deliver it, the delay a key press or click would see.  Refresh rate: the
// number of plot redraws (StatisticsView::refreshCount) per second of the measurement.

#include <QElapsedTimer>
#include <QObject>
#include <QTimer>

#include <vector>

namespace archipelago::ui {
class MainWindow;
}

namespace archipelago::app {

class LatencyProbe : public QObject {
  Q_OBJECT
 public:
  LatencyProbe(ui::MainWindow& window, double seconds, QObject* parent = nullptr);
  void start();

 Q_SIGNALS:
  void done(const QString& json);

 protected:
  void customEvent(QEvent* event) override;

 private:
  void post();
  void finish();

  ui::MainWindow& window_;
  double seconds_;
  QTimer postTimer_;
  QElapsedTimer clock_;
  std::vector<double> latenciesMs_;
  quint64 refreshesAtStart_ = 0;
  qint64 measureStartNs_ = 0;
  bool measuring_ = false;
};

}  // namespace archipelago::app
