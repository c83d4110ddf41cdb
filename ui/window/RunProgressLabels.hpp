#pragma once
/// \file RunProgressLabels.hpp
/// \brief The run's progress in the status bar's permanent part: steps per second, the time left, the progress bar
/// (blocks done / T, or the q = 1 companion's part once the run is done) and the block kernel.

#include <QObject>

class QLabel;
class QProgressBar;
class QStatusBar;

namespace archipelago::ui {

struct RunSnapshot;

class RunProgressLabels : public QObject {
  Q_OBJECT
 public:
  /// Adds the labels and the bar to `bar`'s permanent part.
  explicit RunProgressLabels(QStatusBar* bar);

  /// The progress of `snapshot`; the rate and the time left only while the run computes (`live`).
  void show(const RunSnapshot& snapshot, bool live);
  /// The run no longer computes: no rate, no time left.
  void clearRate();

 private:
  void showCompanion(const RunSnapshot& snapshot);
  void showKernel(const RunSnapshot& snapshot);

  QProgressBar* progress_ = nullptr;
  QLabel* rate_ = nullptr;
  QLabel* eta_ = nullptr;
  QLabel* kernel_ = nullptr;
};

}  // namespace archipelago::ui
