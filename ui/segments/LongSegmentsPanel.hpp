#pragma once
/// \file LongSegmentsPanel.hpp
/// \brief The "Long segments" panel: the live table of the longest trapped segments, exact replay, stepping,
/// export, and (through the PortraitController) drawing the segment zoomed in with its chain's centre orbit.
///
/// Karney (1983), §7 and fig. 8: the longest segment at K = 0.1 sticks to a chain of 6 × 23 = 138 islands.
///
/// Threads (Qt's threaded-Mandelbrot pattern, STYLE.md): two channels of a BackgroundJobs (ui/jobs) do all
/// the work, calling core (periodic/SegmentAnalysis.hpp).  Selecting a row submits a replay tagged with a new
/// request id on the replay channel, where the latest request wins; results of any other id are dropped.
/// Chains are identified on the other channel (a queue), lazily: for the top `autoIdentifiedRows()` rows and,
/// first of all (urgent), the selected one.  The GUI thread only stores the values they return and draws.  The panel is fed by updateSegments() from the run's snapshots (the GUI's
/// refresh timer), so the table follows the run live; the selection is kept by segment, not by row.

#include <QPointer>
#include <QWidget>

#include <cstdint>
#include <memory>
#include <optional>

#include "ui/jobs/BackgroundJobs.hpp"
#include "ui/segments/LongestSegmentsModel.hpp"
#include "ui/portrait/SegmentResults.hpp"
#include "core/periodic/PeriodicOrbit.hpp"
#include "core/view/Viewport.hpp"
#include "core/trapping/LongestSegments.hpp"

class QComboBox;
class QLabel;
class QLayout;
class QPushButton;
class QSlider;
class QSpinBox;
class QTableView;
class QTimer;
class QToolButton;

namespace archipelago::ui {

class PortraitController;

class LongSegmentsPanel : public QWidget {
  Q_OBJECT
 public:
  explicit LongSegmentsPanel(QWidget* parent = nullptr);
  ~LongSegmentsPanel() override;
  /// Wide enough for every column of the table (the dock opens so); the minimum stays narrow (a scroll bar).
  [[nodiscard]] QSize sizeHint() const override;

  /// The segments of the run shown (from a snapshot or an opened run file).
  void updateSegments(const TrappingParameters& params, const LongestSegments& longest);
  /// Forgets the run (a new run with other parameters starts from an empty table).
  void clear();

  /// Draw replayed segments and their chains' centre orbits on this portrait (may be null): the panel asks
  /// the controller to show the run's map, the segment layer, and to zoom.
  void setPortraitController(PortraitController* portrait);

  /// Zoom the portrait to where the segment spent its time / to one island of its chain.
  void zoomToSegment();
  void zoomToIsland();

  /// Selects the segment of rank `row` (0: the longest), which replays it.
  void selectRow(int row);
  /// Selects the segment of rank `rank` as soon as the table lists it (now, or when updateSegments() brings it) and,
  /// when `island`, zooms to one island of its chain once the chain is known.  (Scripts, sessions, screenshots.)
  void selectWhenListed(int rank, bool island);
  [[nodiscard]] int selectedRow() const;

  /// The replay shown (null before the first one).
  [[nodiscard]] SegmentReplayPtr currentReplay() const noexcept { return replay_; }
  /// The chain of the segment shown (null while unknown).
  [[nodiscard]] ChainResultPtr currentChain() const noexcept { return chain_; }
  /// The index into currentReplay()->trace of the step shown.
  [[nodiscard]] std::size_t currentIndex() const noexcept { return index_; }
  void setCurrentIndex(std::size_t index);

  /// Most states a replay keeps for drawing and export (stride > 1 beyond that).
  void setMaxReplayPoints(std::uint64_t points) noexcept { maxReplayPoints_ = points; }
  /// Consecutive points used to identify a chain.
  void setChainPoints(std::uint64_t points) noexcept { chainPoints_ = points; }
  /// How many of the top rows get their chain identified without being selected.
  void setAutoIdentifiedRows(int rows) noexcept { autoRows_ = rows; }
  [[nodiscard]] int autoIdentifiedRows() const noexcept { return autoRows_; }

  /// Exports the replay shown.  False (with the reason in `error`) when there is none or writing failed.
  bool exportCsv(const QString& path, QString* error = nullptr);
  bool exportNpy(const QString& path, QString* error = nullptr);

  /// Nothing queued or running on either worker (tests).
  [[nodiscard]] bool idle() const { return jobs_->idle(); }

  [[nodiscard]] LongestSegmentsModel* model() const noexcept { return model_; }
  [[nodiscard]] QTableView* table() const noexcept { return table_; }
  /// The replay slider and speed (tests: the slider keeps its length, the speed multiplies the pace).
  [[nodiscard]] QSlider* slider() const noexcept { return slider_; }
  [[nodiscard]] QComboBox* speedBox() const noexcept { return speedBox_; }

 Q_SIGNALS:
  /// A replay is about to be drawn on the portrait (connect directly: the receiver can show the portrait's
  /// tab first; the panel then sets the run's map through the controller).
  void aboutToDraw(const archipelago::TrappingParameters& params);
  /// A replay arrived (after the stale ones were dropped).
  void replayReady(archipelago::ui::SegmentReplayPtr replay);
  /// The chain of the segment shown is known (or failed: then chain has an error).
  void chainReady(archipelago::ui::ChainResultPtr chain);
  void currentIndexChanged(std::size_t index);
  void statusMessage(const QString& text);

 private:
  /// The constructor's steps, in the order the widgets are made (the order of the Tab chain): the table; the hint
  /// and the segment's numbers; Play, the slider, the step and its label; Export CSV / .npy; the replay speed; the
  /// rows of the replay's controls (returned, for layOut); Zoom to segment / island; then the panel's layout.
  void createTable();
  void createInfoLabels();
  void createStepControls();
  void createExportButtons();
  void createSpeedBox();
  QLayout* layOutStepControls();
  void createZoomButtons();
  void layOut(QLayout* steps);
  void onSelectionChanged();
  /// updateSegments() less the pending selection (selectWhenListed).
  void showSegments(const TrappingParameters& params, const LongestSegments& longest);
  void selectPending();
  void requestReplay(const SegmentRecord& record);
  void requestChain(const SegmentRecord& record, bool urgent);
  void requestTopChains();
  void onReplay(quint64 requestId, const SegmentReplayPtr& replay, const QString& error);
  void onChain(quint64 generation, SegmentKey key, const ChainResultPtr& chain);
  void updateInfo();
  void updateStepControls();
  void togglePlay();
  void advancePlay();
  void exportDialog(bool npy);
  void showOnPortrait();
  void updateColumns();

  LongestSegmentsModel* model_ = nullptr;
  QTableView* table_ = nullptr;
  QLabel* hint_ = nullptr;   // what to do while the table is empty
  QLabel* info_ = nullptr;
  QSlider* slider_ = nullptr;
  QSpinBox* stepBox_ = nullptr;
  QLabel* stepLabel_ = nullptr;
  QToolButton* playButton_ = nullptr;
  QComboBox* speedBox_ = nullptr;
  QPushButton* csvButton_ = nullptr;
  QPushButton* npyButton_ = nullptr;
  QPushButton* zoomSegmentButton_ = nullptr;
  QPushButton* zoomIslandButton_ = nullptr;
  QTimer* playTimer_ = nullptr;
  std::unique_ptr<BackgroundJobs> jobs_;  // channels: kReplayChannel (latest wins), kChainChannel (a queue)
  QPointer<PortraitController> portrait_;

  quint64 replayRequest_ = 0;   // the request whose result is wanted; others are stale
  bool replayPending_ = false;
  SegmentKey wantedKey_{UINT64_MAX, UINT64_MAX};  // segment requested or shown
  SegmentReplayPtr replay_;
  ChainResultPtr chain_;
  std::size_t index_ = 0;
  // The view "Zoom to island" chose: while the portrait shows it, Play steps through the segment's visits to that
  // island and keeps the view (issue 37, finding 11: Play widened it at once).
  std::optional<Viewport> islandView_;
  std::uint64_t maxReplayPoints_ = 1'000'000;
  std::uint64_t chainPoints_ = kChainIdentificationPoints;
  int autoRows_ = 10;
  int pendingRow_ = -1;          // selectWhenListed(): the rank to select when the table has it
  bool pendingIsland_ = false;   // … and to zoom to one island of its chain once known
};

}  // namespace archipelago::ui
