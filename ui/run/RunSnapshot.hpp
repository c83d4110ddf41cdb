#pragma once
/// \file RunSnapshot.hpp
/// \brief What the run worker hands to the GUI: an immutable value, tagged with the run it belongs to.
///
/// A snapshot is made on the worker thread at a chunk boundary of core's runTrapping() (the state is then
/// consistent: every orbit has done the same number of blocks).  It carries the state itself (so the GUI can
/// save it or resume from it), the statistics core computed from it, the progress, and core's theory curves for them.
/// The GUI receives it through a queued signal as a shared pointer to const: nobody can change it after it
/// has been emitted, so it may be read from any thread without locks.

#include <QMetaType>

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "core/stats/TailAnalysis.hpp"
#include "core/stats/TrappingStatistics.hpp"
#include "core/theory/TheoryCurves.hpp"
#include "core/run/TrappingRun.hpp"

namespace archipelago::ui {

/// Why a worker session ended.
enum class RunEnd { finished, paused, stopped, failed };

struct RunSnapshot {
  std::uint64_t runId = 0;          ///< the request it answers; the GUI drops snapshots of other runs
  TrappingState state;              ///< at a chunk boundary
  TrappingProgress progress;
  bool hasStatistics = false;       ///< false until a segment has been recorded
  TrappingStatistics statistics;    ///< core's statistics of `state` (with errors from the subsets)
  std::vector<TheoryCurve> theory;  ///< core's small-K theory curves for `statistics`, where they apply
  /// The run's finished q = 1 companion (issue #26), when it has one: `statistics` are then the spliced ones
  /// (splicedStatisticsOf), and saving the run writes it beside the run file (companionRunFile).
  std::shared_ptr<const TrappingState> companion;
  /// The run has finished and its q = 1 companion is running (issue 37, finding 7: at 100 % the window said
  /// nothing while it ran): `state` and `statistics` are the finished run's, companionFraction the companion's part
  /// done (0 … 1).
  bool companionRunning = false;
  double companionFraction = 0;
  std::string kernel;               ///< the kernel that computed the last chunk
  /// D's honest error and the tail's verdict (core/stats/TailAnalysis: a bootstrap over segments), computed
  /// when a session ends (finished, paused, stopped, an opened file) — not at every chunk: it takes a second.
  std::shared_ptr<const TailAnalysis> tail;
};

using RunSnapshotPtr = std::shared_ptr<const RunSnapshot>;

}  // namespace archipelago::ui

Q_DECLARE_METATYPE(archipelago::ui::RunSnapshotPtr)
Q_DECLARE_METATYPE(archipelago::ui::RunEnd)
