#include "ui/window/FileController.hpp"

#include <QFileInfo>
#include <QMenu>
#include <QMessageBox>
#include <QTabWidget>

#include "ui/plots/StatisticsPlot.hpp"
#include "ui/portrait/AtlasPanel.hpp"
#include "ui/portrait/PortraitPanel.hpp"
#include "ui/settings/FileDialogs.hpp"
#include "ui/settings/SettingsController.hpp"
#include "ui/window/ExportActions.hpp"
#include "ui/window/ParameterPanel.hpp"
#include "ui/window/SessionController.hpp"
#include "ui/window/StatisticsView.hpp"

namespace archipelago::ui {

namespace {
constexpr int kMessageMs = 6000;

bool isRunFile(const QString& path) { return path.endsWith(QLatin1String(".json"), Qt::CaseInsensitive); }
bool isSession(const QString& path) { return path.endsWith(QLatin1String(".archipelago"), Qt::CaseInsensitive); }
}  // namespace

FileController::FileController(FileParts parts, QObject* parent) : QObject(parent), parts_(std::move(parts)) {
  Q_ASSERT(parts_.window && parts_.run && parts_.sessions && parts_.portrait && parts_.statistics &&
           parts_.parameters && parts_.tabs && parts_.refreshNow && parts_.runSettings);
}

bool FileController::opens(const QString& path) { return isRunFile(path) || path.endsWith(QLatin1String(".archipelago")); }

// ------------------------------------------------------------------------------------------- run files

bool FileController::openRunFile(const QString& path, QString* error) {
  QString why;
  if (!parts_.run->open(path, &why, false, parts_.runSettings())) {
    if (error) *error = why;
    if (why != tr("Cancelled")) showOpenError(tr("Cannot open run file"), path, why);
    return false;
  }
  return true;
}

bool FileController::saveRunFile(const QString& path, QString* error) { return parts_.run->save(path, error); }

void FileController::openRunDialog() {
  const QString path = askOpenFile(parts_.window, tr("Open Run File"), tr("Run files (*.json);;All files (*)"));
  if (!path.isEmpty()) openInteractively(path);
}

bool FileController::saveRunDialog() {
  QString path = askSaveFile(parts_.window, tr("Save Run File"), QStringLiteral("run.json"), tr("Run files (*.json)"));
  if (path.isEmpty()) return false;
  if (!isRunFile(path)) path += QStringLiteral(".json");
  QString error;
  if (saveRunFile(path, &error)) return true;
  QMessageBox::warning(parts_.window, tr("Cannot save the run file"), tr("%1\n\n%2").arg(path, error));
  return false;
}

void FileController::save() {
  const QString file = parts_.run->currentFile();
  if (file.isEmpty() || file == RunController::checkpointPath()) saveRunDialog();
  else saveRunFile(file);
}

// ---------------------------------------------------------------------------------------------- atlases

bool FileController::openAtlasFile(const QString& path, QString* error) {
  AtlasPanel* atlas = parts_.portrait->atlasPanel();
  if (!atlas->openAtlasFile(path, error)) return false;
  parts_.tabs->setCurrentWidget(parts_.portrait);
  parts_.portrait->sidePages()->setCurrentWidget(atlas);
  return true;
}

void FileController::openAtlasDialog() {
  if (!parts_.portrait->atlasPanel()->confirmDiscard(tr("opening another atlas"))) return;
  const QString path = askOpenFile(parts_.window, tr("Open Atlas"), tr("Atlas files (*.json);;All files (*)"));
  if (path.isEmpty()) return;
  QString error;
  if (!openAtlasFile(path, &error)) showOpenError(tr("Cannot open the atlas"), path, error);
}

// --------------------------------------------------------------------------------------------- sessions

bool FileController::saveSession(const QString& path, QString* error) {
  QString why;
  if (!parts_.sessions->save(path, &why)) {
    if (error) *error = why;
    Q_EMIT statusMessage(tr("Cannot save the session: %1").arg(why), 0);
    return false;
  }
  parts_.portrait->atlasPanel()->markSaved();  // the session holds the atlas
  Q_EMIT statusMessage(tr("Session saved to %1").arg(path), kMessageMs);
  return true;
}

bool FileController::openSession(const QString& path, QString* error) {
  QString why;
  if (!parts_.sessions->open(path, &why)) {
    if (error) *error = why;
    return false;
  }
  Q_EMIT statusMessage(tr("Session %1 opened").arg(path), kMessageMs);
  return true;
}

void FileController::openSessionDialog() {
  const QString path =
      askOpenFile(parts_.window, tr("Open Session"), tr("Archipelago sessions (*.archipelago);;All files (*)"));
  if (!path.isEmpty()) openInteractively(path);
}

bool FileController::saveSessionDialog() {
  QString path = askSaveFile(parts_.window, tr("Save Session"), QStringLiteral("session.archipelago"),
                             tr("Archipelago sessions (*.archipelago)"));
  if (path.isEmpty()) return false;
  if (!path.endsWith(QLatin1String(".archipelago"))) path += QStringLiteral(".archipelago");
  QString error;
  if (saveSession(path, &error)) return true;
  QMessageBox::warning(parts_.window, tr("Cannot save the session"), tr("%1\n\n%2").arg(path, error));
  return false;
}

void FileController::openInteractively(const QString& path) {
  if (isSession(path)) {
    if (!parts_.portrait->atlasPanel()->confirmDiscard(tr("opening the session"))) return;
    QString error;
    if (!openSession(path, &error) && error != tr("Cancelled"))
      showOpenError(tr("Cannot open session"), path, tr("%1\n\nNothing was changed.").arg(error));
    return;
  }
  openRunFile(path);  // a failure shows its reason
}

void FileController::showOpenError(const QString& title, const QString& path, const QString& reason) {
  // The status bar cuts long reasons off: the whole reason in a dialog (window-modal, not blocking).
  Q_EMIT statusMessage(tr("%1: %2").arg(title, reason), 0);
  auto* box = new QMessageBox(QMessageBox::Warning, title, tr("Cannot open %1").arg(QFileInfo(path).fileName()),
                              QMessageBox::Ok, parts_.window);
  box->setObjectName(QStringLiteral("openErrorDialog"));
  box->setInformativeText(reason);
  box->setAttribute(Qt::WA_DeleteOnClose);
  box->open();
}

void FileController::fillRecentMenu(QMenu* menu) {
  menu->clear();
  const QStringList files = SettingsController::recentFiles();
  for (const QString& f : files)
    menu->addAction(QFileInfo(f).fileName(), this, [this, f] { openInteractively(f); })->setToolTip(f);
  if (files.isEmpty()) menu->addAction(tr("(none)"))->setEnabled(false);
}

// ---------------------------------------------------------------------------------------------- exports

bool FileController::exportAllTo(const QString& folder, QString* error) {
  const RunSnapshotPtr shown = parts_.refreshNow();  // export what the newest snapshot holds
  const ExportResult r =
      exportAll(parts_.statistics->plots(), shown, folder, parts_.portrait->view(), parts_.parameters->spec());
  if (!r.ok()) {
    if (error) *error = r.error;
    Q_EMIT statusMessage(tr("Export failed: %1").arg(r.error), 0);
    return false;
  }
  Q_EMIT statusMessage(tr("Wrote %1 files to %2").arg(r.written.size()).arg(folder), kMessageMs);  // sidecars too
  return true;
}

void FileController::exportAllDialog() {
  const QString folder = askFolder(parts_.window, tr("Export All To"));
  if (!folder.isEmpty()) exportAllTo(folder);
}

void FileController::exportPlotDialog(StatisticsPlot* plot) {
  const QString path = askSaveFile(parts_.window, tr("Export %1").arg(plot->displayName()),
                                   plot->fileName() + QStringLiteral(".png"),
                                   tr("PNG image (*.png);;SVG drawing (*.svg);;PDF document (*.pdf);;CSV data (*.csv)"));
  if (path.isEmpty()) return;
  const ExportResult r = exportPlot(*plot, parts_.refreshNow(), path);
  Q_EMIT statusMessage(r.ok() ? tr("Wrote %1").arg(path) : tr("Export failed: %1").arg(r.error), kMessageMs);
}

}  // namespace archipelago::ui
