#include "ui/ExportActions.hpp"

#include <QDir>
#include <QFileInfo>

#include <exception>

#include "core/export/StatisticsCsv.hpp"
#include "ui/plots/StatisticsPlot.hpp"

namespace archipelago::ui {

namespace {
QString noNumbers() { return QObject::tr("there are no numbers to export yet: start a run or open a run file"); }

QString fromPath(const std::filesystem::path& p) { return QString::fromStdString(p.string()); }
}  // namespace

ExportResult exportPlot(StatisticsPlot& plot, const RunSnapshotPtr& snapshot, const QString& path) {
  ExportResult result;
  const bool csv = QFileInfo(path).suffix().compare(QLatin1String("csv"), Qt::CaseInsensitive) == 0;
  if (!csv) {
    QString error;
    if (plot.exportImage(path, &error)) result.written << path;
    else result.error = error;
    return result;
  }
  if (!snapshot) {
    result.error = noNumbers();
    return result;
  }
  try {
    for (const auto& p : writeStatisticCsv(path.toStdString(), snapshot->state, snapshot->statistics,
                                           snapshot->theory, plot.statistic()))
      result.written << fromPath(p);
  } catch (const std::exception& e) {
    result.error = QString::fromStdString(e.what());
  }
  return result;
}

ExportResult exportAll(const QList<StatisticsPlot*>& plots, const RunSnapshotPtr& snapshot, const QString& folder) {
  ExportResult result;
  if (!QDir().mkpath(folder)) {
    result.error = QObject::tr("could not create the folder %1").arg(folder);
    return result;
  }
  const QDir dir(folder);
  for (StatisticsPlot* plot : plots) {
    for (const char* suffix : {"png", "svg", "pdf"}) {
      const ExportResult one =
          exportPlot(*plot, snapshot, dir.filePath(plot->fileName() + QLatin1Char('.') + QLatin1String(suffix)));
      result.written << one.written;
      if (!one.ok() && result.ok()) result.error = one.error;
    }
  }
  if (!snapshot) {
    if (result.ok()) result.error = noNumbers();
    return result;
  }
  try {
    for (const auto& p : writeStatisticsCsv(folder.toStdString(), snapshot->state, snapshot->statistics,
                                            snapshot->theory))
      result.written << fromPath(p);
  } catch (const std::exception& e) {
    if (result.ok()) result.error = QString::fromStdString(e.what());
  }
  return result;
}

}  // namespace archipelago::ui
