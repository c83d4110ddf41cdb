#pragma once
/// \file DurationText.hpp
/// \brief How long a background task has run or still needs, as text: the ETA and elapsed time that the run
/// (ui/run), the main window's status bar and the K scan (ui/scan) show.  One format for every long task, so
/// it lives beside the job mechanism they all use.

#include <QString>

namespace archipelago::ui {

/// A duration in seconds as h:mm:ss (an hour or more) or m:ss, rounded to the second; "—" when unknown
/// (negative, NaN) or beyond 10⁹ s (an ETA that means "not in this lifetime").
[[nodiscard]] QString formatDuration(double seconds);

}  // namespace archipelago::ui
