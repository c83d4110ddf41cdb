#pragma once
/// \file KScanDialog.hpp
/// \brief The K scan of §5 in the GUI: the K values (the paper's list by default), the sizes (M, T, q, seed,
/// threads) and a folder; the scan runs in the background (ui/jobs, latest wins) through core's runKScan
/// (core/scan/ScanRun.hpp), the very loop of `archipelago-cli scan`, so a folder is resumed the same way by
/// either: Stop leaves the K running checkpointed in its run file, Start again resumes it and reuses the
/// finished K.  Progress and ETA per K and for the whole scan.  As each K finishes, its results appear in the
/// dialog's KScanPlots (f_t per K, the local exponent's heat map and curves, D(K), the long segments, b₂, a
/// table).  The summaries (core/scan/ScanSummary.hpp) are written into the folder at the end and can be exported
/// elsewhere.  "Open tail scan…" shows the figure γ(t, K) of a folder written by `archipelago-cli tail-scan` (issue
/// 55) in the "Tail scan" tab (TailScanPlots), its files read in the background by core's loadTailScan; a K scan may
/// run meanwhile.  No maths here: every number comes from core.  The plots' two tab widgets in a splitter keep it
/// inside a 1280 × 800 screen.
///
/// Keys: Enter starts (the default button), Esc closes (asking first while a scan runs; closing stops it,
/// resumably).

#include <QDialog>
#include <QString>

#include <optional>
#include <vector>

#include "core/scan/ScanRun.hpp"
#include "core/tail/TailScan.hpp"
#include "ui/jobs/BackgroundJobs.hpp"

class QLabel;
class QLineEdit;
class QProgressBar;
class QPushButton;
class QTabWidget;

namespace archipelago::ui {

class KScanPlots;
class TailScanPlots;

class KScanDialog : public QDialog {
  Q_OBJECT
 public:
  /// `base`: the run settings the K share (Xr, subsets, longestKept, kernel; M, T, q, seed, threads as the
  /// fields' defaults).
  explicit KScanDialog(const RunSpec& base, QWidget* parent = nullptr);
  ~KScanDialog() override;  // stops the scan (resumably) and waits for it

  /// The request of the fields, or the first problem as one line (also shown in the dialog).
  [[nodiscard]] std::optional<KScanRequest> request(QString* error = nullptr) const;

  /// Starts (or resumes) the scan of the fields; false, with the reason shown, when an input is bad.
  bool start();
  /// Asks the running scan to stop at its next chunk (its K is saved in its run file).
  void stop();
  [[nodiscard]] bool running() const noexcept { return running_; }
  /// The summaries of the last scan that finished (empty before).
  [[nodiscard]] const std::vector<ScanRunSummary>& results() const noexcept { return finishedRuns_; }
  /// Writes the scan CSVs of the last finished scan into `dir`; false, with the reason shown, when it cannot.
  bool exportCsv(const QString& dir);
  /// Reads the tail scan of folder `dir` in the background (core's loadTailScan) and shows its figure in the "Tail
  /// scan" tab; tailScanOpened() tells how it ended, the message why.
  void openTailScan(const QString& dir);
  /// The last message shown (an error, or where the scan is).
  [[nodiscard]] QString message() const;

  // The fields, for tests.
  [[nodiscard]] QLineEdit* kField() const noexcept { return kValues_; }
  [[nodiscard]] QLineEdit* field(const QString& name) const;
  [[nodiscard]] QLineEdit* folderField() const noexcept { return folder_; }
  /// The results on screen: the plots and the table of the K finished so far.
  [[nodiscard]] KScanPlots* plots() const noexcept { return plots_; }
  /// The tail scan on screen (openTailScan's).
  [[nodiscard]] TailScanPlots* tailPlots() const noexcept { return tailPlots_; }

 Q_SIGNALS:
  /// The scan ended: finished (every K and the summaries written), stopped, or failed.
  void scanEnded(bool finished);
  /// The fraction of the whole scan done (steps), at each progress report.
  void progressed(double fractionScan);
  /// openTailScan() ended: shown, or refused (the message says why).
  void tailScanOpened(bool shown);

 public Q_SLOTS:
  void reject() override;  // Esc / Close: asks first while a scan runs

 private:
  struct Update {
    std::optional<KScanProgress> progress;
    std::optional<std::pair<std::size_t, ScanRunSummary>> finished;
    QString warning;
  };
  void createResults();  // plots_, tailPlots_ and the tabs holding them
  void setRunning(bool running);
  void showMessage(const QString& text, bool error);
  void showProgress(const KScanProgress& p);
  void addResult(std::size_t index, const ScanRunSummary& run);
  void clearResults();
  void browse();
  void exportInteractively();
  void openTailScanInteractively();
  void showTailScan(const QString& dir, const TailScanFolder& folder);

  RunSpec base_;
  QLineEdit* kValues_ = nullptr;
  QLineEdit* M_ = nullptr;
  QLineEdit* T_ = nullptr;
  QLineEdit* q_ = nullptr;
  QLineEdit* seed_ = nullptr;
  QLineEdit* threads_ = nullptr;
  QLineEdit* b2Iterations_ = nullptr;
  QLineEdit* folder_ = nullptr;
  QPushButton* startButton_ = nullptr;
  QPushButton* stopButton_ = nullptr;
  QPushButton* exportButton_ = nullptr;
  QPushButton* tailButton_ = nullptr;
  QProgressBar* kProgress_ = nullptr;
  QProgressBar* scanProgress_ = nullptr;
  QLabel* kEta_ = nullptr;
  QLabel* scanEta_ = nullptr;
  QLabel* message_ = nullptr;
  KScanPlots* plots_ = nullptr;
  TailScanPlots* tailPlots_ = nullptr;
  QTabWidget* results_ = nullptr;  // the K scan's plots, the tail scan's
  QString tailFolder_;  // the tail scan last opened: where "Open tail scan…" starts (else the K scan's folder)
  std::vector<std::optional<ScanRunSummary>> shown_;  // per K of the running scan, as they finish
  std::vector<ScanRunSummary> finishedRuns_;
  bool running_ = false;
  quint64 jobId_ = 0;
  // Channel 0 the scan, 1 the reading of a tail scan.  Last: destroyed first, it stops the scan and joins.
  BackgroundJobs jobs_{this, 2, JobPriority::background};
};

}  // namespace archipelago::ui
