#include "ui/window/SessionController.hpp"

#include <QDir>
#include <QFileInfo>
#include <QTabWidget>
#include <QTimer>

#include <exception>
#include <utility>

#include "ui/window/ParameterPanel.hpp"
#include "ui/run/RunController.hpp"
#include "ui/window/StatisticsView.hpp"
#include "ui/window/TailEstimateController.hpp"
#include "ui/plots/StatisticsPlot.hpp"
#include "ui/portrait/AtlasPanel.hpp"
#include "ui/portrait/MarkovTreePanel.hpp"
#include "ui/portrait/PortraitController.hpp"
#include "ui/portrait/PortraitPanel.hpp"
#include "ui/segments/LongSegmentsPanel.hpp"

namespace archipelago::ui {

namespace {
/// A file's path as a session refers to it: relative to the session's folder when it lies inside it.
std::filesystem::path pathFromSession(const QString& sessionPath, const QString& file) {
  const QDir folder = QFileInfo(sessionPath).absoluteDir();
  const QString relative = folder.relativeFilePath(QFileInfo(file).absoluteFilePath());
  return (relative.startsWith(QLatin1String("..")) ? QFileInfo(file).absoluteFilePath() : relative).toStdString();
}

/// A page's title without its mnemonic.
std::string pageName(const QTabWidget& tabs, int i) { return tabs.tabText(i).remove(QLatin1Char('&')).toStdString(); }

bool hasPage(const QTabWidget& tabs, const std::string& name) {
  for (int i = 0; i < tabs.count(); ++i)
    if (pageName(tabs, i) == name) return true;
  return false;
}

void selectPage(QTabWidget& tabs, const std::string& name) {
  for (int i = 0; i < tabs.count(); ++i)
    if (pageName(tabs, i) == name) tabs.setCurrentIndex(i);
}
}  // namespace

SessionController::SessionController(SessionParts parts, QObject* parent) : QObject(parent), parts_(std::move(parts)) {
  Q_ASSERT(parts_.parameters && parts_.run && parts_.statistics && parts_.portrait && parts_.segments &&
           parts_.tabs && parts_.tailEstimates && parts_.refreshNow && parts_.showSegment);
}

Session SessionController::capture(const QString& sessionPath) const {
  Session s;
  const ParameterPanel& panel = *parts_.parameters;
  if (const auto spec = panel.spec()) s.spec = *spec;
  else if (const auto& latest = parts_.run->latest()) s.spec.parameters = latest->state.params;

  const RunController& run = *parts_.run;
  if (const auto& latest = run.latest()) {
    const QString file = run.currentFile();
    if (!file.isEmpty() && !run.unsaved() && file != RunController::checkpointPath() && QFileInfo::exists(file)) {
      s.runFile = pathFromSession(sessionPath, file);
    } else {
      s.embeddedRun = latest->state;
    }
    s.runStopped = run.status() == RunStatus::stopped;
  }

  s.tab = pageName(*parts_.tabs, parts_.tabs->currentIndex());
  s.sidePage = pageName(*parts_.portrait->sidePages(), parts_.portrait->sidePages()->currentIndex());
  s.portrait = parts_.portrait->sessionState();
  // The Atlas page's atlas, when it is of the map the session opens with (core refuses another map's), with the inputs
  // of its Markov tree when one is drawn.
  const AtlasPanel& atlasPage = *parts_.portrait->atlasPanel();
  if (auto atlas = atlasPage.sessionAtlas()) {
    const MapParameters& map = s.embeddedRun ? s.embeddedRun->params.map : s.spec.parameters.map;
    if (atlas->request.map == map) s.atlas = std::move(atlas);
  }
  if (const auto model = atlasPage.markovTreePanel()->model(); model && s.atlas)
    s.markovTree = SessionMarkovTree{model->request.alpha, model->request.b2};
  if (const QString tail = parts_.tailEstimates->file(); !tail.isEmpty() && run.latest()) s.tailFile = pathFromSession(sessionPath, tail);

  const LongSegmentsPanel& segments = *parts_.segments;
  if (run.latest() && segments.selectedRow() >= 0) {
    s.segmentRank = segments.selectedRow();
    s.segmentPosition = segments.currentIndex();
  }
  for (const StatisticsPlot* plot : parts_.statistics->plots())
    if (const auto view = plot->userView())
      s.plots.push_back({plot->fileName().toStdString(), {view->left(), view->right(), view->top(), view->bottom()}});
  return s;
}

bool SessionController::save(const QString& path, QString* error) {
  try {
    const Session s = capture(path);
    saveSession(path.toStdString(), s);
    if (s.embeddedRun) parts_.run->markSavedInSession();  // the session holds it: quitting loses nothing
  } catch (const std::exception& e) {
    if (error) *error = QString::fromStdString(e.what());
    return false;
  }
  return true;
}

std::optional<QString> SessionController::windowError(const Session& s) const {
  if (!s.tab.empty() && !hasPage(*parts_.tabs, s.tab))
    return tr("tab \"%1\" is not a tab of this window").arg(QString::fromStdString(s.tab));
  if (!s.sidePage.empty() && !hasPage(*parts_.portrait->sidePages(), s.sidePage))
    return tr("page \"%1\" is not a page beside the portrait").arg(QString::fromStdString(s.sidePage));
  for (const SessionPlotZoom& z : s.plots) {
    bool found = false;
    for (const StatisticsPlot* plot : parts_.statistics->plots())
      found = found || plot->fileName().toStdString() == z.name;
    if (!found) return tr("plot \"%1\" is not a plot of this window").arg(QString::fromStdString(z.name));
    if (const StatisticsPlot* plot = [&]() -> const StatisticsPlot* {
          for (const StatisticsPlot* p : parts_.statistics->plots())
            if (p->fileName().toStdString() == z.name) return p;
          return nullptr;
        }();
        plot && plot->statistic() != Statistic::localExponent && (z.zoom.ymin <= 0 || z.zoom.xmin <= 0))
      return tr("plot \"%1\": a log axis cannot show a range reaching 0 or below").arg(QString::fromStdString(z.name));
  }
  return std::nullopt;
}

bool SessionController::open(const QString& path, QString* error) {
  Session s;
  try {
    s = loadSession(path.toStdString());
  } catch (const std::exception& e) {
    if (error) *error = QString::fromStdString(e.what());
    return false;
  }
  return apply(s, error);
}

bool SessionController::apply(const Session& s, QString* error) {
  if (const auto e = windowError(s)) {
    if (error) *error = *e;
    return false;
  }
  RunController& run = *parts_.run;
  if (isLive(run.status())) {
    if (error) *error = tr("Stop or pause the run before opening a session");
    return false;
  }
  // The run first: it asks before unsaved work is lost, and a refusal changes nothing.
  QString why;
  bool ok = true;
  if (s.runFile) ok = run.open(QString::fromStdString(s.runFile->string()), &why);
  else if (s.embeddedRun) ok = run.adopt(*s.embeddedRun, &why);
  else ok = run.clear() || (why = tr("Cancelled"), false);
  if (!ok) {
    if (error) *error = why;
    return false;
  }
  applyViews(s);
  if (isLive(run.status())) {
    // The analysis of the run comes back through the worker: the rest waits for it.
    pending_ = s;
    auto connection = std::make_shared<QMetaObject::Connection>();
    *connection = connect(&run, &RunController::statusChanged, this, [this, connection](RunStatus status) {
      if (isLive(status)) return;
      disconnect(*connection);
      if (!pending_) return;
      const Session session = std::move(*pending_);
      pending_.reset();
      if (status != RunStatus::failed) applyRunDependent(session);
      else Q_EMIT restored();
    });
  } else {
    applyRunDependent(s);
  }
  return true;
}

void SessionController::applyViews(const Session& s) {
  selectTab(s.tab);
  selectSidePage(s.sidePage);
  const TrappingParameters& p =
      s.embeddedRun ? s.embeddedRun->params : s.spec.parameters;
  parts_.portrait->restoreSessionState(s.portrait, p.map, p.Xr);
  parts_.portrait->atlasPanel()->restoreAtlas(s.atlas);  // read back by core, not recomputed; none clears the page
}

void SessionController::applyRunDependent(const Session& s) {
  // A run saved stopped comes back stopped (final), not resumable (issue 25, finding 13).
  if (s.runStopped && parts_.run->status() == RunStatus::paused) parts_.run->stop();
  // A resumable run shows its own parameters (read-only); otherwise the panel holds the session's.
  if (parts_.run->status() != RunStatus::paused) parts_.parameters->setSpec(s.spec);
  parts_.refreshNow();
  redrawModels(s);
  for (StatisticsPlot* plot : parts_.statistics->plots()) {
    plot->resetZoom();
    for (const SessionPlotZoom& z : s.plots)
      if (plot->fileName().toStdString() == z.name)
        plot->setUserView(QRectF(z.zoom.xmin, z.zoom.ymin, z.zoom.xmax - z.zoom.xmin, z.zoom.ymax - z.zoom.ymin));
  }
  if (s.segmentRank < 0) {
    Q_EMIT restored();
    return;
  }
  // The segment is replayed in the background; drawing it switches to the portrait and frames it.  Once it is
  // drawn, its replay position, the session's tab and its exact views are put back.
  auto connection = std::make_shared<QMetaObject::Connection>();
  *connection = connect(parts_.segments, &LongSegmentsPanel::replayReady, this,
                        [this, connection, s](const SegmentReplayPtr& replay) {
                          if (!replay) return;
                          disconnect(*connection);
                          QTimer::singleShot(0, this, [this, s] {
                            parts_.segments->setCurrentIndex(static_cast<std::size_t>(s.segmentPosition));
                            selectTab(s.tab);
                            selectSidePage(s.sidePage);
                            if (!s.portrait.history.empty())
                              parts_.portrait->controller()->restoreHistory(s.portrait.history, s.portrait.current);
                            Q_EMIT restored();
                          });
                        });
  parts_.showSegment(s.segmentRank);
}

void SessionController::redrawModels(const Session& s) {
  // Both are background jobs; each says how it ended as when asked from the menu (a tail file gone: its dialog).
  const QString tail = s.tailFile ? QString::fromStdString(s.tailFile->string()) : QString();
  if (s.markovTree) parts_.portrait->atlasPanel()->markovTreePanel()->compute(s.markovTree->alpha, s.markovTree->b2, nullptr, tail);
  if (s.tailFile) parts_.tailEstimates->open(tail);
}

void SessionController::selectTab(const std::string& tab) { selectPage(*parts_.tabs, tab); }

void SessionController::selectSidePage(const std::string& page) { selectPage(*parts_.portrait->sidePages(), page); }

}  // namespace archipelago::ui
