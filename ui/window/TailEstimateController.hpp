#pragma once
/// \file TailEstimateController.hpp
/// \brief File ▸ Open Tail Estimate (issue #29): P_t of a tail file (`archipelago-cli tail --out …`, core/tail)
/// drawn on the P_t plot beside the run's own P_t, at its reliable levels.
///
/// The file is read and its levels computed off the GUI thread (a background job, ui/jobs) against the run's
/// immutable snapshot; core decides whether the file's process is the run's (tailRunMismatch) and which levels are
/// reliable (reliableSurvivalIn).  A second file opened before the first is drawn replaces it (latest wins); a new
/// run forgets the file.

#include <QObject>
#include <QString>

#include <memory>

namespace archipelago::ui {

class BackgroundJobs;
class RunController;
class StatisticsPlot;

class TailEstimateController : public QObject {
  Q_OBJECT
 public:
  /// The estimates of `run`'s run, drawn on `plot` (the P_t plot).
  TailEstimateController(RunController* run, StatisticsPlot* plot, QObject* parent);
  ~TailEstimateController() override;

  /// Starts reading `path`: true when that started, and finished() says how it ended; false at once, with the
  /// reason (in `error` and refused()), without a run.  Refused, with the reason, when the file's process is not the
  /// run's (map, box, Xr, q: core's tailRunMismatch), the file cannot be read, or it has no reliable level.
  bool open(const QString& path, QString* error = nullptr);
  /// A tail file is being read or its levels computed.
  [[nodiscard]] bool pending() const noexcept { return request_ != 0; }
  /// The tail file whose estimate P_t shows (absolute; empty: none, or the run it was drawn for was replaced).
  [[nodiscard]] QString file() const { return file_; }

 Q_SIGNALS:
  /// open()'s end: error is empty when the estimate is drawn, else the reason it was refused (also refused()).
  void finished(const QString& path, const QString& error);
  /// The estimate of `path` is on the plot (before finished()): what is set against the tail may be redrawn.
  void shown(const QString& path);
  /// The file cannot be drawn: `reason`, for a dialog titled `title`.
  void refused(const QString& title, const QString& path, const QString& reason);
  /// A file is being read (true) or no longer (false).
  void pendingChanged(bool pending);
  void statusMessage(const QString& text, int timeoutMs);

 private:
  struct Estimate;
  /// The job's end: the estimate drawn, or the reason it is not.
  void finish(const QString& path, const std::shared_ptr<const Estimate>& estimate, const QString& error);
  /// Why the estimate found cannot be drawn on the run shown now (empty: it can).
  [[nodiscard]] QString refusalNow(const Estimate& estimate) const;
  void show(const QString& path, const Estimate& estimate);

  RunController* run_;
  StatisticsPlot* plot_;
  quint64 request_ = 0;  // open()'s job in flight (0: none)
  QString file_;         // the tail file drawn on P_t (sessions keep it)
  // Last: destroyed first, so that no job outlives what its handlers use (BackgroundJobs.hpp, "Lifetime").
  std::unique_ptr<BackgroundJobs> jobs_;
};

}  // namespace archipelago::ui
