#include "ExportActions.hpp"

#include <QDir>
#include <QFileInfo>

#include "plots/StatisticsPlot.hpp"

namespace archipelago::ui {

ExportResult exportPlot(StatisticsPlot& plot, const QString& path) {
  ExportResult result;
  const bool csv = QFileInfo(path).suffix().compare(QLatin1String("csv"), Qt::CaseInsensitive) == 0;
  QString error;
  const bool ok = csv ? plot.exportCsv(path, &error) : plot.exportImage(path, &error);
  if (ok) result.written << path;
  else result.error = error;
  return result;
}

ExportResult exportAll(const QList<StatisticsPlot*>& plots, const QString& folder) {
  ExportResult result;
  if (!QDir().mkpath(folder)) {
    result.error = QObject::tr("could not create the folder %1").arg(folder);
    return result;
  }
  const QDir dir(folder);
  for (StatisticsPlot* plot : plots) {
    for (const char* suffix : {"png", "svg", "pdf", "csv"}) {
      const ExportResult one = exportPlot(*plot, dir.filePath(plot->fileName() + QLatin1Char('.') + QLatin1String(suffix)));
      result.written << one.written;
      if (!one.ok() && result.ok()) result.error = one.error;
    }
  }
  return result;
}

}  // namespace archipelago::ui
