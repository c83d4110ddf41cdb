#include "ui/window/ExportActions.hpp"

#include <QDir>
#include <QFileInfo>
#include <QSettings>

#include <exception>

#include "core/export/StatisticsCsv.hpp"
#include "core/io/AtomicFile.hpp"
#include "core/runspec/RunSpec.hpp"
#include "ui/plots/StatisticsPlot.hpp"
#include "core/portrait/PortraitExport.hpp"
#include "ui/portrait/PortraitView.hpp"
#include "ui/window/StatisticsView.hpp"

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
    // The run shown, recorded in the picture: its provenance in the PNG's text, its parameters drawn under the plot.
    const bool run = snapshot != nullptr;
    if (plot.exportImage(path, &error, run ? runProvenance(snapshot->state) : Provenance{},
                         run ? QString::fromStdString(runParametersLine(snapshot->state)) : QString()))
      result.written << path;
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

ExportResult exportAll(const QList<StatisticsPlot*>& plots, const RunSnapshotPtr& snapshot, const QString& folder,
                       PortraitView* portrait, const std::optional<RunSpec>& spec) {
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
  const auto fail = [&result](const QString& error) {
    if (result.ok()) result.error = error;
  };
  if (portrait) {
    const QString png = dir.filePath(QLatin1String(kPortraitPngName));
    if (portrait->exportPng(png)) result.written << png;
    else fail(QObject::tr("could not write the phase portrait to %1").arg(png));
    if (portrait->currentFrame()) {
      const QString npy = dir.filePath(QLatin1String(kPortraitNpyName));
      // The .npy and its JSON sidecar: both counted ("Wrote N files" says how many are in the folder).
      if (portrait->exportNpy(npy)) result.written << npy << QString::fromStdString(sidecarPath(npy.toStdString()));
      else fail(QObject::tr("could not write the portrait's raster to %1").arg(npy));
    }
  }
  if (!snapshot) {
    fail(noNumbers());
    return result;
  }
  try {
    for (const auto& p : writeStatisticsCsv(folder.toStdString(), snapshot->state, snapshot->statistics,
                                            snapshot->theory, StatisticsView::summaryOf(*snapshot)))
      result.written << fromPath(p);
    RunSpec written;
    if (spec && spec->parameters == snapshot->state.params) written = *spec;
    else written.parameters = snapshot->state.params;
    const std::filesystem::path specPath = dir.filePath(QLatin1String(kRunSpecJsonName)).toStdString();
    io::writeFileAtomically(specPath, runSpecJson(written));
    result.written << fromPath(specPath);
  } catch (const std::exception& e) {
    fail(QString::fromStdString(e.what()));
  }
  return result;
}

}  // namespace archipelago::ui
