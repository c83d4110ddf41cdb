#pragma once
/// \file ExportActions.hpp
/// \brief Writing plots and their numbers to files: PNG, SVG, PDF (QwtPlotRenderer) and CSV.

#include <QList>
#include <QString>
#include <QStringList>

namespace archipelago::ui {

class StatisticsPlot;

/// The result of writing files: what was written, and the first error (empty when none).
struct ExportResult {
  QStringList written;
  QString error;
  [[nodiscard]] bool ok() const noexcept { return error.isEmpty(); }
};

/// Writes one plot to `path`: an image when the suffix is png, svg or pdf; its curves when it is csv.
[[nodiscard]] ExportResult exportPlot(StatisticsPlot& plot, const QString& path);

/// Writes every plot as <name>.png, .svg, .pdf and .csv into `folder` (created when missing).
[[nodiscard]] ExportResult exportAll(const QList<StatisticsPlot*>& plots, const QString& folder);

}  // namespace archipelago::ui
