#pragma once
/// \file ExportActions.hpp
/// \brief Writing plots and their numbers to files: PNG, SVG, PDF (QwtPlotRenderer) and CSV; the folder file
/// dialogs start in.
///
/// Numbers are written by core's one CSV writer (export/StatisticsCsv.hpp) from the snapshot's state,
/// statistics and theory curves, so the GUI writes exactly the files `archipelago-cli stats --csv` writes.

#include <QList>
#include <QString>
#include <QStringList>

#include <optional>

#include "core/runspec/RunSpec.hpp"
#include "ui/run/RunSnapshot.hpp"

namespace archipelago::ui {

class PortraitView;
class StatisticsPlot;

/// The result of writing files: what was written, and the first error (empty when none).
struct ExportResult {
  QStringList written;
  QString error;
  [[nodiscard]] bool ok() const noexcept { return error.isEmpty(); }
};

/// Writes one plot to `path`: an image when the suffix is png, svg or pdf; when it is csv, the numbers of its
/// statistic in `snapshot` (and, next to them, <name>.theory.csv when theory curves belong to it).
[[nodiscard]] ExportResult exportPlot(StatisticsPlot& plot, const RunSnapshotPtr& snapshot, const QString& path);

/// Writes every plot as <stem>.png, .svg and .pdf into `folder` (created when missing); every CSV file of
/// `snapshot` (each statistic, its theory curves, summary.csv) and its longest segments (longest_segments.csv)
/// as core's writer names them; the run's parameters as run_spec.json (core's spec codec: `archipelago-cli run
/// --spec` reads it back); and, when `portrait` is given, the phase portrait as portrait.png with, once it has
/// a raster, portrait.npy and its JSON sidecar (PortraitView's own exports).  The run spec is `spec` (the preset's
/// name, description, threads and q = 1 companion: issue 37, finding 14) when its parameters are the snapshot's,
/// else the snapshot's parameters alone.
[[nodiscard]] ExportResult exportAll(const QList<StatisticsPlot*>& plots, const RunSnapshotPtr& snapshot,
                                     const QString& folder, PortraitView* portrait = nullptr,
                                     const std::optional<RunSpec>& spec = std::nullopt);

/// The file names exportAll() gives the portrait, the segments table and the run spec.
inline constexpr const char* kPortraitPngName = "portrait.png";
inline constexpr const char* kPortraitNpyName = "portrait.npy";
inline constexpr const char* kRunSpecJsonName = "run_spec.json";

}  // namespace archipelago::ui
