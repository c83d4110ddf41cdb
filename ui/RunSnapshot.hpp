#pragma once
/// \file RunSnapshot.hpp
/// \brief What the run worker hands to the GUI: an immutable value, tagged with the run it belongs to.
///
/// A snapshot is made on the worker thread at a chunk boundary of core's runTrapping() (the state is then
/// consistent: every orbit has done the same number of blocks).  It carries the state itself (so the GUI can
/// save it or resume from it), the statistics core computed from it, the progress, and the theory curves.
/// The GUI receives it through a queued signal as a shared pointer to const: nobody can change it after it
/// has been emitted, so it may be read from any thread without locks.

#include <QMetaType>

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "stats/TrappingStatistics.hpp"
#include "trapping/TrappingRun.hpp"

namespace archipelago::ui {

/// Which statistics plot a curve belongs to.
enum class PlotKind { f, P, C, localExponent, S, Dt };
inline constexpr int kPlotKinds = 6;

/// A theory curve drawn over a plot (Karney 1983, §4): either sampled points or a vertical line at `at`.
struct TheoryCurve {
  PlotKind plot = PlotKind::f;
  std::string label;        ///< plain text for files, e.g. "t^-7"
  std::string legend;       ///< rich text for the legend, e.g. "t<sup>−7</sup>" (label when empty)
  Series curve;             ///< abscissa and value; empty for a vertical line
  double verticalAt = 0;    ///< > 0: a vertical line at this abscissa (e.g. t_max for K < 0)
};

/// Why a worker session ended.
enum class RunEnd { finished, paused, stopped, failed };

struct RunSnapshot {
  std::uint64_t runId = 0;          ///< the request it answers; the GUI drops snapshots of other runs
  TrappingState state;              ///< at a chunk boundary
  TrappingProgress progress;
  bool hasStatistics = false;       ///< false until a segment has been recorded
  TrappingStatistics statistics;    ///< core's statistics of `state` (with errors from the subsets)
  std::vector<TheoryCurve> theory;  ///< small-K theory where it applies
  std::string kernel;               ///< the kernel that computed the last chunk
};

using RunSnapshotPtr = std::shared_ptr<const RunSnapshot>;

/// The series of `statistics` shown in plot `kind`.
[[nodiscard]] const Series& seriesOf(const TrappingStatistics& statistics, PlotKind kind);

}  // namespace archipelago::ui

Q_DECLARE_METATYPE(archipelago::ui::RunSnapshotPtr)
Q_DECLARE_METATYPE(archipelago::ui::RunEnd)
