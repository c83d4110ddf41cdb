// Issue 53: what a new user hit this time (Xvfb at 1280×800 and 1920×1080, a2e223a).  One test per finding, named
// after it, on Qt's offscreen platform — here with a 1920×1080 screen (main() below), the size of finding 20; each
// failed before its fix.  What only a picture can judge (the P_t export's legend, the shortcuts dialog) was looked
// at too (the closing note of the issue).
#include <QAbstractButton>
#include <QApplication>
#include <QDialog>
#include <QDialogButtonBox>
#include <QDockWidget>
#include <QFile>
#include <QFileInfo>
#include <QHeaderView>
#include <QImage>
#include <QLabel>
#include <QLineEdit>
#include <QMessageBox>
#include <QMenu>
#include <QProgressBar>
#include <QPushButton>
#include <QScreen>
#include <QSignalSpy>
#include <QSpinBox>
#include <QStatusBar>
#include <QTabWidget>
#include <QTableView>
#include <QTableWidget>
#include <QTemporaryDir>
#include <QTimer>
#include <QtTest>
#include <qwt_plot.h>
#include <qwt_scale_div.h>
#include <qwt_scale_draw.h>
#include <qwt_scale_widget.h>
#include <qwt_text.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <utility>
#include <vector>

#include "GuiTestSupport.hpp"
#include "core/atlas/AtlasExport.hpp"
#include "core/io/AtomicFile.hpp"
#include "core/io/NumberText.hpp"
#include "core/markovtree/MarkovTreeExport.hpp"
#include "core/colour/ColourMap.hpp"
#include "core/tail/TailFile.hpp"
#include "core/tail/TailSampler.hpp"
#include "core/run/TrappingRun.hpp"
#include "core/runfile/RunFile.hpp"
#include "core/stats/RunStatistics.hpp"
#include "ui/run/RunWorker.hpp"
#include "core/session/SessionFile.hpp"
#include "ui/plots/StatisticsPlot.hpp"
#include "ui/portrait/AtlasPanel.hpp"
#include "ui/portrait/ManifoldsPanel.hpp"
#include "ui/portrait/MarkovTreePanel.hpp"
#include "ui/portrait/OrbitListPanel.hpp"
#include "ui/portrait/PortraitController.hpp"
#include "ui/portrait/PortraitPanel.hpp"
#include "ui/portrait/PortraitView.hpp"
#include "ui/segments/LongSegmentsPanel.hpp"
#include "ui/window/MainWindow.hpp"
#include "ui/window/ParameterPanel.hpp"
#include "ui/window/StatisticsView.hpp"
#include "ui/window/TailEstimateController.hpp"

using namespace archipelago;
using namespace archipelago::ui;
using archipelago::test::typeInto;

namespace {

/// A finished K = 0.1 run of 16 × 20000 blocks: its long segments fill the table.
const TrappingState& finishedRun() {
  static const TrappingState state = [] {
    TrappingParameters p;
    p.M = 16;
    p.T = 20000;
    p.longestKept = 12;
    TrappingRunOptions o;
    o.threads = 1;
    return runTrapping(startTrapping(p), o);
  }();
  return state;
}

/// A depth-1 atlas of K = 0.1, periods ≤ 200, by core (test_markov_tree's), in `path`: computed once for each map (three
/// findings write it, ~17 CPU-s each time).
void writeSmallAtlas(const QString& path, const MapParameters& map) {
  static std::vector<std::pair<MapParameters, Atlas>> computed;
  auto it = std::find_if(computed.begin(), computed.end(), [&](const auto& c) { return c.first == map; });
  if (it == computed.end()) {
    AtlasRequest r;
    r.map = map;
    r.depth = 1;
    r.maxPeriod = 200;
    r.scanSteps = 0;
    it = computed.emplace(computed.end(), map, computeAtlas(r));
  }
  writeAtlasJson(path.toStdString(), it->second);
}

/// A tail file of finishedRun()'s process (test_tail_estimate's sampler, small), in `path`.
void writeSmallTail(const QString& path) {
  TailRequest r;
  r.run = finishedRun().params;
  r.population = 100;
  r.replicas = 4;
  r.firstSteps = 100;
  r.maxSteps = 100'000;
  r.minAncestors = 4;
  TailRunOptions o;
  o.threads = 2;
  saveTailFile(path.toStdString(), runTail(startTail(r), o));
}

/// The portrait's x-axis tick labels closer to a neighbour than a digit's width (run together), as "label | label"
/// (empty: none), and all its labels.
QStringList overlappingTicks(const QwtPlot& plot, QStringList* labels) {
  const QwtScaleDraw& draw = *plot.axisScaleDraw(QwtPlot::xBottom);
  const QFont font = plot.axisWidget(QwtPlot::xBottom)->font();
  QList<double> ticks = plot.axisScaleDiv(QwtPlot::xBottom).ticks(QwtScaleDiv::MajorTick);
  std::sort(ticks.begin(), ticks.end());
  QStringList overlaps;
  for (int i = 0; i < ticks.size(); ++i) {
    *labels << draw.label(ticks[i]).text();
    if (i == 0) continue;
    const double gap = plot.transform(QwtPlot::xBottom, ticks[i]) - plot.transform(QwtPlot::xBottom, ticks[i - 1]);
    const double room = (draw.labelSize(font, ticks[i]).width() + draw.labelSize(font, ticks[i - 1]).width()) / 2;
    if (gap < room + QFontMetrics(font).horizontalAdvance(QLatin1Char('0'))) overlaps << draw.label(ticks[i - 1]).text() + QStringLiteral(" | ") + draw.label(ticks[i]).text();
  }
  return overlaps;
}

/// True when `w` is `ancestor` or inside it.
bool inside(const QWidget* w, const QWidget* ancestor) {
  for (; w; w = w->parentWidget())
    if (w == ancestor) return true;
  return false;
}

/// Runs `act` on the next modal dialog once it is shown (Go to View… opens one with exec()).
void onModal(std::function<void(QDialog&)> act) {
  QTimer::singleShot(0, qApp, [act] {
    QTRY_VERIFY(qobject_cast<QDialog*>(QApplication::activeModalWidget()));
    act(*qobject_cast<QDialog*>(QApplication::activeModalWidget()));
  });
}

}  // namespace

class TestIssue53 : public QObject {
  Q_OBJECT
 private Q_SLOTS:
  // Finding 1: with a run that has segments and the Parameters tab in front, Tab from "threads" went into the hidden
  // Long segments table, and each further 7 Tabs replayed its next row (the status bar: "Replayed … steps bit for
  // bit", the portrait jumping there).
  void finding1_tabStaysOutOfTheHiddenSegmentsTable() {
    QTemporaryDir dir;
    const QString file = dir.filePath(QStringLiteral("run.json"));
    saveRunFile(file.toStdString(), finishedRun());
    MainWindow w;
    w.setConfirmations(false);
    w.portraitPanel()->controller()->setPointBudget(10000);
    w.resize(1280, 760);
    w.show();
    QVERIFY(QTest::qWaitForWindowExposed(&w));
    w.activateWindow();
    QVERIFY(QTest::qWaitForWindowActive(&w));
    LongSegmentsPanel& segments = *w.longSegments();
    segments.setAutoIdentifiedRows(0);
    QVERIFY(w.openRunFile(file));
    QTRY_VERIFY_WITH_TIMEOUT(segments.model()->rowCount() > 0, 900000);
    w.parametersDock()->raise();
    QTRY_VERIFY(w.parametersDock()->isVisible());
    QSignalSpy messages(&segments, &LongSegmentsPanel::statusMessage);
    QLineEdit* threads = w.parameterPanel()->field(QStringLiteral("threads"));
    QVERIFY(threads);
    threads->setFocus(Qt::MouseFocusReason);
    QTRY_VERIFY(threads->hasFocus());
    for (int i = 0; i < 40; ++i) {
      QWidget* focus = QApplication::focusWidget();
      QVERIFY(focus);
      QTest::keyClick(focus, Qt::Key_Tab);
      QCoreApplication::processEvents();
      focus = QApplication::focusWidget();
      QVERIFY2(!inside(focus, &segments), qPrintable(QStringLiteral("Tab %1 went into the hidden segments table (%2)")
                                                         .arg(i + 1)
                                                         .arg(focus ? focus->metaObject()->className() : "none")));
    }
    QVERIFY(segments.table()->selectionModel()->selectedRows().isEmpty());
    for (const QList<QVariant>& m : messages) QVERIFY2(!m.front().toString().startsWith(QStringLiteral("Replayed")), qPrintable(m.front().toString()));
    // Shown, the table is reached by Tab, and Tab leaves it again without moving from cell to cell (a replay).
    w.segmentsDock()->raise();
    QTRY_VERIFY(segments.isVisible());
    segments.table()->setFocus(Qt::TabFocusReason);
    QTRY_VERIFY(segments.table()->hasFocus());
    QTest::keyClick(segments.table(), Qt::Key_Tab);
    QVERIFY(!segments.table()->hasFocus());
    QVERIFY(segments.table()->selectionModel()->selectedRows().isEmpty());
  }

  // Finding 2: a session kept only each launched orbit's start: 100 000 steps backward came back as 20 000 forward,
  // renumbered and recoloured.
  void finding2_sessionsKeepStepsDirectionAndNumbers() {
    QTemporaryDir dir;
    const QString path = dir.filePath(QStringLiteral("orbits.archipelago"));
    std::vector<LaunchedOrbit> launched;
    {
      MainWindow w;
      w.setConfirmations(false);
      PortraitController& c = *w.portraitPanel()->controller();
      c.setPointBudget(10000);
      QVERIFY(c.launchOrbit(0.0L, 0.01L));
      QVERIFY(c.launchOrbit(0.06L, 0.0974L, 100000, true));
      QVERIFY(c.launchOrbit(-0.2L, 0.01L, 777));
      QVERIFY(c.removeOrbit(c.launchedOrbits().front().id));  // numbers 2 and 3 left
      launched = c.launchedOrbits();
      QString error;
      QVERIFY2(w.saveSession(path, &error), qPrintable(error));
      QTRY_VERIFY_WITH_TIMEOUT(c.orbitsSettled(), 900000);
    }
    MainWindow w;
    w.setConfirmations(false);
    QString error;
    QVERIFY2(w.openSession(path, &error), qPrintable(error));
    PortraitController& c = *w.portraitPanel()->controller();
    const std::vector<LaunchedOrbit>& back = c.launchedOrbits();
    QCOMPARE(back.size(), launched.size());
    for (std::size_t i = 0; i < back.size(); ++i) {
      QCOMPARE(back[i].id, launched[i].id);
      QCOMPARE(back[i].steps, launched[i].steps);
      QCOMPARE(back[i].backward, launched[i].backward);
      QCOMPARE(back[i].colour, launched[i].colour);
      QCOMPARE(static_cast<double>(back[i].x), static_cast<double>(launched[i].x));
      QCOMPARE(static_cast<double>(back[i].y), static_cast<double>(launched[i].y));
    }
    QCOMPARE(back[0].id, quint64{2});
    QCOMPARE(back[0].steps, std::uint64_t{100000});
    QVERIFY(back[0].backward);
    // A new orbit takes the next number, not one of theirs.
    QCOMPARE(c.launchOrbit(0.01L, 0.01L), quint64{4});
    QTRY_VERIFY_WITH_TIMEOUT(c.orbitsSettled(), 900000);
  }

  // Finding 3 and "sessions that keep the chosen side page" (the issue's Done-when: a session round trip keeps launched
  // orbits' steps and direction, the Markov model's inputs and curve, the tail estimate's file and the side page):
  // the model's P_t, the tail's estimate and the Atlas page's shares were lost, and the side page was the Run page.
  void finding3_sessionsKeepTheModelTheTailAndTheSidePage() {
    QTemporaryDir dir;
    const QString run = dir.filePath(QStringLiteral("run.json")), atlas = dir.filePath(QStringLiteral("atlas.json"));
    const QString tail = dir.filePath(QStringLiteral("tail.json")), path = dir.filePath(QStringLiteral("s.archipelago"));
    saveRunFile(run.toStdString(), finishedRun());
    writeSmallAtlas(atlas, finishedRun().params.map);
    writeSmallTail(tail);
    QVector<QPointF> model, estimate;
    int shareRows = 0, comparedRows = 0;
    {
      MainWindow w;
      w.setConfirmations(false);
      PortraitController& c = *w.portraitPanel()->controller();
      c.setPointBudget(10000);
      QVERIFY(w.openRunFile(run));
      QTRY_VERIFY_WITH_TIMEOUT(w.latestSnapshot() && w.latestSnapshot()->hasStatistics && !isLive(w.runStatus()), 900000);
      w.refreshNow();
      QVERIFY(w.openAtlasFile(atlas));
      QSignalSpy drawn(w.portraitPanel()->atlasPanel()->markovTreePanel(), &MarkovTreePanel::drawn),
        tailed(w.tailEstimates(), &TailEstimateController::finished);
      QVERIFY(w.portraitPanel()->atlasPanel()->markovTreePanel()->draw(18.9043, 1.362484));
      QVERIFY(w.tailEstimates()->open(tail));
      // The model is drawn twice: alone, then against the tail once it is read (wait for the second: its comparison).
      QTRY_VERIFY_WITH_TIMEOUT(drawn.count() >= 1 && tailed.count() == 1 &&
                                   !w.portraitPanel()->atlasPanel()->markovTreePanel()->pending() &&
                                   w.portraitPanel()->atlasPanel()->markovTreePanel()->comparisonTable()->rowCount() > 0, 900000);
      QCOMPARE(drawn.back().front().toString(), QString());
      QCOMPARE(tailed.front().at(1).toString(), QString());
      QVERIFY(c.launchOrbit(0.06L, 0.0974L, 100000, true));
      w.portraitPanel()->sidePages()->setCurrentWidget(w.portraitPanel()->atlasPanel());
      const StatisticsPlot& p = *w.statisticsView()->plot(Statistic::P);
      model = p.modelPoints();
      estimate = p.estimatePoints();
      shareRows = w.portraitPanel()->atlasPanel()->markovTreePanel()->sharesTable()->rowCount();
      comparedRows = w.portraitPanel()->atlasPanel()->markovTreePanel()->comparisonTable()->rowCount();
      QVERIFY(!model.isEmpty() && !estimate.isEmpty() && shareRows > 0 && comparedRows > 0);
      QString error;
      QVERIFY2(w.saveSession(path, &error), qPrintable(error));
      QTRY_VERIFY_WITH_TIMEOUT(c.orbitsSettled(), 900000);
    }
    MainWindow w;
    w.setConfirmations(false);
    w.portraitPanel()->controller()->setPointBudget(10000);
    QSignalSpy drawn(w.portraitPanel()->atlasPanel()->markovTreePanel(), &MarkovTreePanel::drawn),
        tailed(w.tailEstimates(), &TailEstimateController::finished);
    QString error;
    QVERIFY2(w.openSession(path, &error), qPrintable(error));
    QCOMPARE(w.portraitPanel()->sidePages()->currentWidget(), static_cast<QWidget*>(w.portraitPanel()->atlasPanel()));
    QTRY_VERIFY_WITH_TIMEOUT(drawn.count() >= 1 && tailed.count() == 1 &&
                                 !w.portraitPanel()->atlasPanel()->markovTreePanel()->pending() &&
                                 w.portraitPanel()->atlasPanel()->markovTreePanel()->comparisonTable()->rowCount() > 0, 900000);
    QCOMPARE(drawn.back().front().toString(), QString());
    QCOMPARE(tailed.front().at(1).toString(), QString());
    const StatisticsPlot& p = *w.statisticsView()->plot(Statistic::P);
    QCOMPARE(p.modelPoints(), model);
    QCOMPARE(p.estimatePoints(), estimate);
    const AtlasPanel& page = *w.portraitPanel()->atlasPanel();
    QVERIFY(page.markovTreePanel()->model());
    QCOMPARE(page.markovTreePanel()->model()->request.alpha, 18.9043);
    QCOMPARE(page.markovTreePanel()->model()->request.b2, 1.362484);
    QCOMPARE(page.markovTreePanel()->sharesTable()->rowCount(), shareRows);
    QCOMPARE(page.markovTreePanel()->comparisonTable()->rowCount(), comparedRows);
    QCOMPARE(QFileInfo(w.tailEstimates()->file()), QFileInfo(tail));
    const std::vector<LaunchedOrbit>& orbits = w.portraitPanel()->controller()->launchedOrbits();
    QCOMPARE(orbits.size(), std::size_t{1});
    QCOMPARE(orbits.front().steps, std::uint64_t{100000});
    QVERIFY(orbits.front().backward);
    QCOMPARE(w.portraitPanel()->sidePages()->currentWidget(), static_cast<QWidget*>(w.portraitPanel()->atlasPanel()));
    // The file holds the inputs, not the curves; the tail file beside the session by its name.
    const Session s = loadSession(path.toStdString());
    QVERIFY(s.markovTree && s.markovTree->alpha == 18.9043 && s.markovTree->b2 == 1.362484);
    QCOMPARE(s.sidePage, std::string("Atlas"));
    QFile text(path);
    QVERIFY(text.open(QIODevice::ReadOnly));
    QVERIFY(text.readAll().contains(R"("file": "tail.json")"));
    QTRY_VERIFY_WITH_TIMEOUT(w.portraitPanel()->controller()->orbitsSettled(), 900000);
  }

  // Finding 3: a session of before (no "markovTree", "tail" or "sidePage") still opens, as it did.
  void finding3_anOldSessionStillOpens() {
    Session old;
    old.tab = "Phase portrait";
    QString text = QString::fromStdString(sessionText(old));
    QVERIFY(!text.contains(QStringLiteral("sidePage")) && !text.contains(QStringLiteral("markovTree")) &&
            !text.contains(QStringLiteral("\"tail\"")));
    const Session back = parseSession(text.toStdString());
    QVERIFY(!back.markovTree && !back.tailFile && back.sidePage.empty());
    QTemporaryDir dir;
    const QString path = dir.filePath(QStringLiteral("old.archipelago"));
    saveSession(path.toStdString(), old);
    MainWindow w;
    w.setConfirmations(false);
    w.portraitPanel()->sidePages()->setCurrentWidget(w.portraitPanel()->manifoldsPanel());
    QString error;
    QVERIFY2(w.openSession(path, &error), qPrintable(error));
    QCOMPARE(w.portraitPanel()->sidePages()->currentWidget(), static_cast<QWidget*>(w.portraitPanel()->manifoldsPanel()));
    // A model needs its atlas: refused, naming the key.
    QString withModel = text;
    withModel.replace(QStringLiteral("\"tab\""), QStringLiteral("\"markovTree\": {\"alpha\": 18.9, \"b2\": 1.36}, \"tab\""));
    try {
      (void)parseSession(withModel.toStdString());
      QFAIL("a model without its atlas was read");
    } catch (const std::exception& e) {
      QVERIFY2(QString::fromUtf8(e.what()).contains(QStringLiteral("markovTree")), e.what());
    }
  }

  // Finding 4: the exported P_t.png (945×650) wrapped the three "asymptotic (literature)" entries onto two lines,
  // their exponents lost.
  void finding4_theExportedPtLegendIsWhole() {
    QTemporaryDir dir;
    const QString file = dir.filePath(QStringLiteral("run.json"));
    saveRunFile(file.toStdString(), finishedRun());
    MainWindow w;
    w.setConfirmations(false);
    w.portraitPanel()->controller()->setPointBudget(10000);
    w.resize(1280, 760);
    w.show();
    QVERIFY(QTest::qWaitForWindowExposed(&w));
    QVERIFY(w.openRunFile(file));
    QTRY_VERIFY_WITH_TIMEOUT(w.latestSnapshot(), 900000);
    w.refreshNow();
    QString error;
    const QString out = qEnvironmentVariable("ARCHIPELAGO_SCREENSHOT_DIR", dir.filePath(QStringLiteral("export")));
    QVERIFY2(w.exportAllTo(out, &error), qPrintable(error));
    const QImage png = QImage(out + QStringLiteral("/P_t.png")).convertToFormat(QImage::Format_RGB32);
    QVERIFY(!png.isNull());
    // Each reference slope's legend entry: its icon (a swatch of the line's colour, below the plot) and, beside it,
    // its text on one line, centred on the icon, so its middle row crosses the letters ("t⁻¹·⁵ a…").  Wrapped onto
    // two lines, the gap between them lay there (the lines cut to the entry's height, the exponent lost).
    const QColor colours[] = {QColor(140, 86, 75), QColor(148, 103, 189), QColor(23, 150, 170), QColor(110, 110, 110)};
    const int legendTop = png.height() * 3 / 4;  // below the axis title
    int entries = 0;
    for (const QColor& colour : colours) {
      QRect icon;
      for (int y = legendTop; y < png.height(); ++y)  // runs of 12 pixels of the colour: the swatch, not text
        for (int x = 0, run = 0; x < png.width(); ++x) {
          run = png.pixel(x, y) == colour.rgb() ? run + 1 : 0;
          if (run >= 12) icon |= QRect(x - run + 1, y, run, 1);
        }
      if (icon.isEmpty() || icon.width() < 10) continue;  // a slope the run's range leaves out
      ++entries;
      bool crossed = false;
      for (int y = icon.center().y() - 1; y <= icon.center().y() + 1; ++y)
        for (int x = icon.right() + 2; x < std::min(png.width(), icon.right() + 30); ++x)
          crossed = crossed || qGray(png.pixel(x, y)) < 110;
      QVERIFY2(crossed, qPrintable(QStringLiteral("the entry of colour %1 at (%2, %3) wraps in %4")
                                       .arg(colour.name()).arg(icon.x()).arg(icon.y()).arg(out)));
    }
    QVERIFY(entries >= 3);
  }

  // Finding 5: at 1280×800 the thin island 13 (2/13) of a depth-1 atlas was framed in a view 1:4 wide, whose x
  // ticks ran together ("-0.54542.5458 36").  No two tick labels come closer than a digit's width now.
  void finding5_theThinIslandsTicksDoNotOverlap() {
    QTemporaryDir dir;
    const QString atlas = dir.filePath(QStringLiteral("atlas.json"));
    MainWindow w;
    w.setConfirmations(false);
    w.portraitPanel()->controller()->setPointBudget(10000);
    writeSmallAtlas(atlas, w.portraitPanel()->controller()->map());
    w.resize(1200, 760);  // the window on a 1280×800 screen (Xvfb, no window manager)
    w.show();
    QVERIFY(QTest::qWaitForWindowExposed(&w));
    QVERIFY(w.openAtlasFile(atlas));
    AtlasPanel& panel = *w.portraitPanel()->atlasPanel();
    int thin = -1;
    for (int i = 0; panel.item(i); ++i)
      if (panel.item(i)->text(AtlasPanel::island) == QStringLiteral("13") &&
          panel.item(i)->text(AtlasPanel::rotation) == QStringLiteral("2/13"))
        thin = i;
    QVERIFY2(thin >= 0, "no island 13 2/13 in the atlas");
    PortraitController& c = *w.portraitPanel()->controller();
    QVERIFY(panel.showIsland(thin));
    QTRY_VERIFY_WITH_TIMEOUT(c.atlasIslandSettled() && c.atlasIsland(), 900000);
    QCoreApplication::processEvents();
    const QwtPlot* plot = w.portraitPanel()->view()->findChild<QwtPlot*>();
    QVERIFY(plot);
    QStringList labels;
    const QStringList overlaps = overlappingTicks(*plot, &labels);
    QVERIFY2(labels.size() >= 2, qPrintable(labels.join(QStringLiteral(", "))));
    QVERIFY2(overlaps.isEmpty(), qPrintable(QStringLiteral("%1 in %2 (canvas %3 px wide)")
                                                .arg(overlaps.join(QStringLiteral("; ")), labels.join(QStringLiteral(", ")))
                                                .arg(plot->canvas()->width())));
    if (const QString shots = qEnvironmentVariable("ARCHIPELAGO_SCREENSHOT_DIR"); !shots.isEmpty())
      QVERIFY(w.grab().save(shots + QStringLiteral("/thin-island-1280.png")));
    QTRY_VERIFY_WITH_TIMEOUT(c.orbitsSettled(), 900000);
  }

  // Finding 8: the Atlas page's "area ± error" was explained as "± the change with half the points" (the curve's
  // convergence), where the atlas's ± now covers the interval [areaLower, areaUpper]: the header and each cell say so.
  void finding8_theAreasErrorSaysWhatItCovers() {
    MainWindow w;
    w.setConfirmations(false);
    AtlasPanel& panel = *w.portraitPanel()->atlasPanel();
    archipelago::Atlas atlas;
    atlas.request = panel.request();
    AtlasNode centre;
    centre.period = 1;
    centre.boundaryFound = true;
    centre.area = centre.circleArea = 0.2392;
    centre.areaLower = 0.2391;
    centre.areaUpper = 0.2415;
    centre.areaError = 0.0023;
    centre.polygonError = 2e-9;
    atlas.nodes.push_back(centre);
    panel.restoreAtlas(atlas);
    const QString header = panel.tree()->headerItem()->toolTip(AtlasPanel::area);
    QVERIFY2(header.contains(QStringLiteral("covers")) && !header.contains(QStringLiteral("half the points")),
             qPrintable(header));
    const QString cell = panel.item(0)->toolTip(AtlasPanel::area);
    QVERIFY2(cell.contains(QStringLiteral("[0.2391, 0.2415]")) && cell.contains(QStringLiteral("± 0.0023 covers")) &&
                 cell.contains(QStringLiteral("convergence (2e-09)")),
             qPrintable(cell));
  }

  // Finding 12: after a spliced run "Model P_t…" offered the q = 1 companion's α (2.72), called only "the run's mean
  // segment length", where the tail and `markov-tree --alpha` want the q process's (18.9).
  void finding12_theModelsAlphaIsTheQProcesss() {
    QTemporaryDir dir;
    const std::string run = dir.filePath(QStringLiteral("run.json")).toStdString();
    TrappingRunOptions o;
    o.threads = 1;
    saveRunFile(run, finishedRun());
    saveRunFile(companionRunFile(run), runTrapping(startTrapping(companionParameters(finishedRun().params, 1.0)), o));
    MainWindow w;
    w.setConfirmations(false);
    w.portraitPanel()->controller()->setPointBudget(10000);
    QVERIFY(w.openRunFile(QString::fromStdString(run)));
    QTRY_VERIFY_WITH_TIMEOUT(w.latestSnapshot() && w.latestSnapshot()->hasStatistics && !isLive(w.runStatus()), 900000);
    QVERIFY2(w.latestSnapshot()->statistics.splicedAt > 0, "the run and its companion did not splice");
    const double q = statisticsOf(finishedRun()).alpha, spliced = w.latestSnapshot()->statistics.alpha;
    QVERIFY(q > 2 * spliced);
    const MarkovTreePanel::Entry e = w.portraitPanel()->atlasPanel()->markovTreePanel()->entry();
    QCOMPARE(e.alpha, q);
    QVERIFY2(e.alphaSource.contains(QStringLiteral("q = 16 process")) &&
                 e.alphaSource.contains(QStringLiteral("markov-tree --alpha %1").arg(QLocale::c().toString(q, 'g', 8))) &&
                 e.alphaSource.contains(QStringLiteral("q = 1 companion")),
             qPrintable(e.alphaSource));
  }

  // Finding 19 (in part): the Atlas table's notes were ~150 characters of 20-digit numbers; the cell cuts them to 4
  // digits, its tooltip keeps the whole.
  void finding19_theAtlasNotesAreShort() {
    MainWindow w;
    w.setConfirmations(false);
    AtlasPanel& panel = *w.portraitPanel()->atlasPanel();
    archipelago::Atlas atlas;
    atlas.request = panel.request();
    AtlasNode centre;
    centre.period = 1;
    centre.boundaryFailure = "no circle between r = 0.12345678901234567890 and r = -1.2345678901234567e-05";
    atlas.nodes.push_back(centre);
    panel.restoreAtlas(atlas);
    const QString cell = panel.item(0)->text(AtlasPanel::note);
    QCOMPARE(cell, QStringLiteral("no circle between r = 0.1235 and r = -1.235e-05"));
    QCOMPARE(panel.item(0)->toolTip(AtlasPanel::note), QString::fromStdString(centre.boundaryFailure));
  }

  // Finding 19 (in part): at 1280×800 the q = 1 companion's label was clipped in the progress bar ("q = 1 companion
  // run: 40 % · then t < 160 steps come from it" in at most 320 pixels).
  void finding19_theCompanionsLabelFitsTheBar() {
    MainWindow w;
    w.setConfirmations(false);
    w.resize(1200, 760);
    w.show();
    QVERIFY(QTest::qWaitForWindowExposed(&w));
    TrappingParameters p = finishedRun().params;
    p.T = 2000;
    auto* bar = w.findChild<QProgressBar*>();
    QVERIFY(bar);
    QStringList clipped, shown;
    connect(&w.worker(), &RunWorker::snapshotReady, &w, [&](const RunSnapshotPtr& s) {
      if (!s || !s->companionRunning) return;
      QTimer::singleShot(0, &w, [&] {
        w.refreshNow();
        shown << bar->text();
        if (bar->fontMetrics().horizontalAdvance(bar->text()) + 8 > bar->width())
          clipped << QStringLiteral("'%1' in %2 pixels").arg(bar->text()).arg(bar->width());
      });
    });
    RunSettings settings;
    settings.threads = 1;
    settings.companion = 1.0;
    QString error;
    QVERIFY2(w.runController()->start(p, settings, &error), qPrintable(error));
    QTRY_VERIFY_WITH_TIMEOUT(w.runStatus() == RunStatus::finished, 900000);
    QTRY_VERIFY_WITH_TIMEOUT(!shown.isEmpty(), 900000);
    QVERIFY2(shown.front().contains(QStringLiteral("companion")), qPrintable(shown.front()));
    QVERIFY2(clipped.isEmpty(), qPrintable(clipped.join(QStringLiteral("; "))));
    QVERIFY2(bar->toolTip().contains(QStringLiteral("t < 160 steps")) || !w.latestSnapshot()->companionRunning,
             qPrintable(bar->toolTip()));
  }

  // Finding 19 (in part) and "a way to enlarge one plot" (missing): P_t with a model and a tail had ~230×180 pixels
  // and its menu offered only Reset zoom.  Its menu enlarges it (a double click too) over the room of all six, and
  // Esc shows all six again; the menu exports it too.
  void finding19_aPlotEnlargesAndItsMenuOffersMore() {
    MainWindow w;
    w.setConfirmations(false);
    w.resize(1200, 760);
    w.show();
    QVERIFY(QTest::qWaitForWindowExposed(&w));
    w.tabs()->setCurrentWidget(w.statisticsView());
    StatisticsView& view = *w.statisticsView();
    StatisticsPlot& p = *view.plot(Statistic::P);
    QTRY_VERIFY(p.isVisible());
    const QSize small = p.size();
    std::unique_ptr<QMenu> menu(p.createContextMenu(&p));
    QStringList entries;
    for (QAction* a : menu->actions()) entries << a->text();
    QVERIFY2(entries.size() >= 3 && entries.contains(QStringLiteral("Export…")), qPrintable(entries.join(QStringLiteral(", "))));
    QAction* enlarge = menu->actions().at(1);
    QVERIFY2(enlarge->text().startsWith(QStringLiteral("Enlarge")), qPrintable(enlarge->text()));
    enlarge->trigger();
    QCOMPARE(view.enlargedPlot(), &p);
    QTRY_VERIFY(p.width() > 2 * small.width() && p.height() > 3 * small.height() / 2);
    const QSize big = p.size();
    for (StatisticsPlot* other : view.plots())
      if (other != &p) QVERIFY(!other->isVisible());
    menu.reset(p.createContextMenu(&p));
    QVERIFY2(menu->actions().at(1)->text().startsWith(QStringLiteral("Show All Plots")), qPrintable(menu->actions().at(1)->text()));
    p.canvas()->setFocus();
    QTest::keyClick(p.canvas(), Qt::Key_Escape);
    QCOMPARE(view.enlargedPlot(), static_cast<StatisticsPlot*>(nullptr));
    QTRY_VERIFY(2 * p.width() < big.width());
    for (StatisticsPlot* other : view.plots()) QVERIFY(other->isVisible());
    QTest::mouseDClick(p.canvas(), Qt::LeftButton, {}, p.canvas()->rect().center());
    QCOMPARE(view.enlargedPlot(), &p);
    QTest::mouseDClick(p.canvas(), Qt::LeftButton, {}, p.canvas()->rect().center());
    QCOMPARE(view.enlargedPlot(), static_cast<StatisticsPlot*>(nullptr));
  }

  // Missing: keyboard and menu access to the side pages (Run, Orbits, Manifolds, Profile, Atlas) and to the Atlas
  // page's Compute and Model P_t….
  void missing_theSidePagesAndTheAtlasByTheKeyboard() {
    MainWindow w;
    w.setConfirmations(false);
    w.portraitPanel()->controller()->setPointBudget(10000);
    w.show();
    QVERIFY(QTest::qWaitForWindowExposed(&w));
    w.activateWindow();
    QVERIFY(QTest::qWaitForWindowActive(&w));
    w.tabs()->setCurrentWidget(w.statisticsView());
    QTabWidget& side = *w.portraitPanel()->sidePages();
    const QStringList pages = {QStringLiteral("Run"), QStringLiteral("Orbits"), QStringLiteral("Manifolds"),
                               QStringLiteral("Profile"), QStringLiteral("Atlas")};
    for (int i = static_cast<int>(pages.size()) - 1; i >= 0; --i) {
      QTest::keyClick(&w, static_cast<Qt::Key>(Qt::Key_1 + i), Qt::ControlModifier);
      QCOMPARE(w.tabs()->currentWidget(), static_cast<QWidget*>(w.portraitPanel()));
      QCOMPARE(side.tabText(side.currentIndex()).remove(QLatin1Char('&')), pages[i]);
    }
    const auto keys = w.keyboardShortcuts();
    const auto listed = [&keys](const QString& action) {
      return std::any_of(keys.begin(), keys.end(), [&](const auto& row) { return row.first.endsWith(action); });
    };
    QVERIFY(listed(QStringLiteral("View ▸ Atlas Page")) && listed(QStringLiteral("Tools ▸ Compute Atlas")) &&
            listed(QStringLiteral("Tools ▸ Model P_t of the Atlas…")));
    // Model P_t… without an atlas: the page shown, and why not in the status bar.
    side.setCurrentIndex(0);
    QTest::keyClick(&w, Qt::Key_M, Qt::ControlModifier | Qt::ShiftModifier);
    AtlasPanel& atlas = *w.portraitPanel()->atlasPanel();
    QCOMPARE(side.currentWidget(), static_cast<QWidget*>(&atlas));
    QVERIFY2(w.statusBar()->currentMessage().contains(atlas.markovTreePanel()->button()->toolTip()),
             qPrintable(w.statusBar()->currentMessage()));
    // Compute: the page's request, started.
    atlas.depthBox()->setValue(1);
    QSignalSpy ended(&atlas, &AtlasPanel::computationEnded);
    QTest::keyClick(&w, Qt::Key_A, Qt::ControlModifier | Qt::ShiftModifier);
    QVERIFY(atlas.busy());
    atlas.stop();
    QTRY_COMPARE_WITH_TIMEOUT(ended.count(), 1, 900000);
    QTRY_VERIFY_WITH_TIMEOUT(w.portraitPanel()->controller()->orbitsSettled(), 900000);
  }

  // Missing: the model against the tail in the GUI (ratio per level, reach, the level holding the survivors, as
  // `markov-tree --tail` prints them): the page's table and line are core's comparison of the same atlas and tail.
  void missing_theModelAgainstTheTailIsShown() {
    QTemporaryDir dir;
    const QString run = dir.filePath(QStringLiteral("run.json")), atlas = dir.filePath(QStringLiteral("atlas.json"));
    const QString tail = dir.filePath(QStringLiteral("tail.json"));
    saveRunFile(run.toStdString(), finishedRun());
    writeSmallAtlas(atlas, finishedRun().params.map);
    writeSmallTail(tail);
    MainWindow w;
    w.setConfirmations(false);
    w.portraitPanel()->controller()->setPointBudget(10000);
    QVERIFY(w.openRunFile(run));
    QTRY_VERIFY_WITH_TIMEOUT(w.latestSnapshot() && w.latestSnapshot()->hasStatistics && !isLive(w.runStatus()), 900000);
    QVERIFY(w.openAtlasFile(atlas));
    AtlasPanel& page = *w.portraitPanel()->atlasPanel();
    QSignalSpy tailed(w.tailEstimates(), &TailEstimateController::finished);
    QVERIFY(w.tailEstimates()->open(tail));
    QTRY_COMPARE_WITH_TIMEOUT(tailed.count(), 1, 900000);
    QVERIFY(w.portraitPanel()->atlasPanel()->markovTreePanel()->draw(18.9043, 1.362484));
    QTRY_VERIFY_WITH_TIMEOUT(!page.markovTreePanel()->pending() && page.markovTreePanel()->model(), 900000);
    MarkovTreeRequest r;
    r.alpha = 18.9043;
    r.b2 = 1.362484;
    r.needsP = true;
    r.at = MarkovTreePanel::shareTimes();
    const TailState state = loadTailFile(tail.toStdString());
    const MarkovTreeResult expected = computeMarkovTree(atlasFromJson(io::readRegularFile(atlas.toStdString(), 1 << 26)), r, &state);
    QVERIFY(expected.comparison && !expected.comparison->levels.empty());
    const MarkovTreeComparison& c = *expected.comparison;
    const QTableWidget& table = *page.markovTreePanel()->comparisonTable();
    QVERIFY(table.isVisibleTo(&page));
    QCOMPARE(table.rowCount(), static_cast<int>(c.levels.size()));
    for (int row = 0; row < table.rowCount(); ++row) {
      const MarkovTreeLevelComparison& m = c.levels[static_cast<std::size_t>(row)];
      QCOMPARE(table.item(row, 0)->text(), QString::number(m.t, 'f', 0));
      QCOMPARE(table.item(row, 3)->data(Qt::UserRole).toDouble(), static_cast<double>(m.ratio));
      if (m.holdingLevel >= 0) QVERIFY(table.item(row, 4)->text().startsWith(QString::number(m.holdingLevel)));
    }
    const QString reach = c.reach > 0 ? QString::fromStdString(io::shortestText(c.reach)) : QStringLiteral("none");
    QVERIFY2(page.markovTreePanel()->text().contains(QStringLiteral("last at t = %1").arg(reach)), qPrintable(page.markovTreePanel()->text()));
  }

  // Finding 9: "Model P_t…" was greyed out on a stopped atlas with no reason: its tooltip and the page's progress line
  // give core's (markovTreeAtlasError).
  void finding9_modelPtSaysWhyAStoppedAtlasHasNone() {
    MainWindow w;
    w.setConfirmations(false);
    AtlasPanel& panel = *w.portraitPanel()->atlasPanel();
    archipelago::Atlas stopped;
    stopped.request = panel.request();
    stopped.nodes.emplace_back();  // the centre, known and not measured
    stopped.cancelled = true;
    stopped.stopReason = "stopped";
    panel.restoreAtlas(stopped);
    const QString why = QStringLiteral("the atlas was stopped before its end (stopped)");
    QVERIFY(!panel.markovTreePanel()->button()->isEnabled());
    QVERIFY2(panel.markovTreePanel()->button()->toolTip().contains(why), qPrintable(panel.markovTreePanel()->button()->toolTip()));
    QVERIFY2(panel.progressText().contains(QStringLiteral("Model P_t")) && panel.progressText().contains(why),
             qPrintable(panel.progressText()));
  }

  // Finding 10: Ctrl+Z right after the Orbits page's Clear did nothing (the focus fell into Steps, which took the
  // key), and Undo brought the orbits back renumbered and recoloured.
  void finding10_undoRightAfterClearBringsTheSameOrbitsBack() {
    MainWindow w;
    w.setConfirmations(false);
    w.resize(1280, 760);
    w.show();
    QVERIFY(QTest::qWaitForWindowExposed(&w));
    w.activateWindow();
    QVERIFY(QTest::qWaitForWindowActive(&w));
    PortraitPanel& portrait = *w.portraitPanel();
    PortraitController& c = *portrait.controller();
    c.setPointBudget(10000);
    QVERIFY(c.launchOrbit(0.0L, 0.01L));
    QVERIFY(c.launchOrbit(-0.2L, 0.01L, 300, true));
    const std::vector<LaunchedOrbit> before = c.launchedOrbits();
    portrait.sidePages()->setCurrentWidget(portrait.orbitList());
    QPushButton* clear = nullptr;
    for (QPushButton* b : portrait.orbitList()->findChildren<QPushButton*>())
      if (b->text() == QStringLiteral("Clear")) clear = b;
    QVERIFY(clear);
    QTRY_VERIFY(clear->isVisible() && clear->isEnabled());
    QTest::mouseClick(clear, Qt::LeftButton);
    QCOMPARE(c.orbitCount(), 0);
    QTest::qWait(100);  // the list's refresh (30 ms) disables Clear: where does the focus go?
    QWidget* focus = QApplication::focusWidget();
    QVERIFY(focus);
    QTest::keyClick(focus, Qt::Key_Z, Qt::ControlModifier);
    QCOMPARE(c.orbitCount(), 2);
    for (std::size_t i = 0; i < before.size(); ++i) {
      QCOMPARE(c.launchedOrbits()[i].id, before[i].id);
      QCOMPARE(c.launchedOrbits()[i].colour, before[i].colour);
      QCOMPARE(c.launchedOrbits()[i].steps, before[i].steps);
      QCOMPARE(c.launchedOrbits()[i].backward, before[i].backward);
    }
    QTRY_VERIFY_WITH_TIMEOUT(c.orbitsSettled(), 900000);
  }

  // Finding 11: File ▸ Open Atlas… replaced a computed atlas in no file and Quit asked nothing (runs get Save,
  // Discard, Cancel); the replaced atlas's boundary circle stayed drawn.
  void finding11_anUnsavedAtlasIsAskedForAndItsCircleGoes() {
    QTemporaryDir dir;
    MainWindow w;  // confirmations on: the questions are asked
    w.show();
    QVERIFY(QTest::qWaitForWindowExposed(&w));
    AtlasPanel& panel = *w.portraitPanel()->atlasPanel();
    PortraitController& c = *w.portraitPanel()->controller();
    QSignalSpy ended(&panel, &AtlasPanel::computationEnded);
    archipelago::AtlasRequest r = panel.request();
    r.depth = 1;
    QVERIFY(panel.compute(r));
    panel.stop();  // a stopped atlas is work too
    QTRY_COMPARE_WITH_TIMEOUT(ended.count(), 1, 900000);
    const std::shared_ptr<const archipelago::Atlas> computed = panel.atlas();
    QVERIFY(computed);
    QString asked;
    const auto cancel = [&asked](QDialog& d) {
      asked = d.windowTitle();
      auto* box = qobject_cast<QMessageBox*>(&d);
      if (box && box->button(QMessageBox::Cancel)) box->button(QMessageBox::Cancel)->click();
      else d.reject();
    };
    onModal(cancel);
    QVERIFY(!w.close());  // Quit: Cancel keeps the window and the atlas
    QCOMPARE(asked, QStringLiteral("Unsaved atlas"));
    QAction* open = nullptr;
    for (QAction* a : w.findChildren<QAction*>())
      if (a->text() == QStringLiteral("Open &Atlas…")) open = a;
    QVERIFY(open);
    asked.clear();
    onModal(cancel);
    open->trigger();  // File ▸ Open Atlas…: asked before the file dialog, Cancel keeps the atlas
    QCOMPARE(asked, QStringLiteral("Unsaved atlas"));
    QCOMPARE(panel.atlas(), computed);
    // An island's circle drawn, then the atlas exported (nothing left to ask) and another opened: the circle goes.
    archipelago::AtlasNode centre;
    centre.boundaryFound = true;
    centre.boundaryPoint = {0.0L, 0.01L};
    centre.centre = centre.boundaryPoint;
    c.showAtlasIsland(centre, QStringLiteral("centre"), {});
    QTRY_VERIFY_WITH_TIMEOUT(c.atlasIslandSettled() && c.atlasIsland(), 900000);
    const QString file = dir.filePath(QStringLiteral("atlas.json"));
    QVERIFY(panel.exportJson(file));
    QVERIFY(panel.openAtlasFile(file));
    QVERIFY(!c.atlasIsland());
    QVERIFY(w.close());  // the atlas is in a file: nothing asked
  }

  // Compute over an unsaved atlas replaced it without a question (File ▸ Open Atlas… and Open… asked): it asks the
  // same way now, and Cancel keeps the atlas.
  void computeOverAnUnsavedAtlasAsks() {
    MainWindow w;  // confirmations on: the question is asked
    w.show();
    QVERIFY(QTest::qWaitForWindowExposed(&w));
    w.portraitPanel()->controller()->setPointBudget(10000);
    AtlasPanel& panel = *w.portraitPanel()->atlasPanel();
    QSignalSpy ended(&panel, &AtlasPanel::computationEnded);
    archipelago::AtlasRequest r = panel.request();
    r.depth = 1;
    QVERIFY(panel.compute(r));
    panel.stop();
    QTRY_COMPARE_WITH_TIMEOUT(ended.count(), 1, 900000);
    const std::shared_ptr<const archipelago::Atlas> computed = panel.atlas();
    QVERIFY(computed && panel.unsavedWork());
    QString asked;
    onModal([&asked](QDialog& d) {
      asked = d.windowTitle();
      auto* box = qobject_cast<QMessageBox*>(&d);
      if (box && box->button(QMessageBox::Cancel)) box->button(QMessageBox::Cancel)->click();
      else d.reject();
    });
    panel.computeButton()->click();
    QCOMPARE(asked, QStringLiteral("Unsaved atlas"));
    QVERIFY(!panel.busy());
    QCOMPARE(panel.atlas(), computed);
    w.setConfirmations(false);  // the window closes without asking
    QTRY_VERIFY_WITH_TIMEOUT(w.portraitPanel()->controller()->orbitsSettled(), 900000);
  }

  // Finding 14: launched orbits took the portrait's palette (orbitColour(id): the id-th seed's orbit's colour in
  // Island-orbits mode), so a clicked curve could not be told apart.  Each launched orbit's colour is now 80 or more
  // away, in some channel, from the colour of every orbit of the seed grid.
  void finding14_launchedOrbitsStandApartFromThePortraitsColours() {
    PortraitPanel panel;
    PortraitController& c = *panel.controller();
    c.setPointBudget(10000);
    for (int k = 0; k < 12; ++k) QVERIFY(c.launchOrbit(-0.3L + 0.05L * k, 0.01L));
    for (const LaunchedOrbit& o : c.launchedOrbits())
      for (std::uint32_t label = 1; label <= 24 * 24; ++label) {
        const archipelago::Rgb p = archipelago::orbitColour(label);
        const int apart = std::max({std::abs(o.colour.red() - p.r), std::abs(o.colour.green() - p.g),
                                    std::abs(o.colour.blue() - p.b)});
        QVERIFY2(apart >= 80, qPrintable(QStringLiteral("orbit %1 (%2) and the portrait's label %3: %4 apart")
                                             .arg(o.id).arg(o.colour.name()).arg(label).arg(apart)));
      }
    QTRY_VERIFY_WITH_TIMEOUT(c.orbitsSettled(), 900000);
  }

  // Finding 17: K = 1e300 marked xmin red ("must be < −√K = -1e+150"), though no xmin can hold it: K is named.
  void finding17_aKNoBoxHoldsMarksK() {
    MainWindow w;
    w.setConfirmations(false);
    ParameterPanel& panel = *w.parameterPanel();
    typeInto(panel, QStringLiteral("K"), QStringLiteral("1e300"));
    QVERIFY(!panel.isValid());
    QVERIFY2(panel.fieldError(QStringLiteral("K")).contains(QStringLiteral("K = 1e+300 is too large")),
             qPrintable(panel.validationMessage()));
    QVERIFY2(panel.fieldError(QStringLiteral("xmin")).isEmpty(), qPrintable(panel.fieldError(QStringLiteral("xmin"))));
    typeInto(panel, QStringLiteral("K"), QStringLiteral("0.1"));
    QVERIFY(panel.isValid());
  }

  // Finding 18: noise in messages: "must lie in the box [-0.8, 0.5) x [-0.65000000000000002, 0.65000000000000002)";
  // an orbit typed at (0.06, 0.0974) announced as from (0.059999999999999998, …).
  void finding18_messagesPrintShortestNumbers() {
    PortraitPanel panel;
    PortraitController& c = *panel.controller();
    c.setPointBudget(10000);
    QString error;
    QVERIFY(!c.goTo(0.0L, 5.0L, 0.1L, &error));
    QVERIFY2(error.contains(QStringLiteral("the centre = (0, 5) must lie in the box [-0.8, 0.5) x [-0.65, 0.65)")),
             qPrintable(error));
    QSignalSpy messages(&c, &PortraitController::statusMessage);
    panel.orbitList()->startXField()->setText(QStringLiteral("0.06"));
    panel.orbitList()->startYField()->setText(QStringLiteral("0.0974"));
    QVERIFY(panel.orbitList()->launchTyped());
    bool announced = false;
    for (const QList<QVariant>& m : messages) {
      const QString text = m.front().toString();
      QVERIFY2(!text.contains(QStringLiteral("0000000")) && !text.contains(QStringLiteral("9999999")), qPrintable(text));
      announced = announced || text.contains(QStringLiteral("from (0.06, 0.0974)"));
    }
    QVERIFY(announced);
    QTRY_VERIFY_WITH_TIMEOUT(c.orbitsSettled(), 900000);
  }

  // Finding 20: at 1920×1080 the window opened at 1200×760 in the middle of the screen.
  void finding20_theFirstWindowTakesMostOfTheScreen() {
    const QRect available = QGuiApplication::primaryScreen()->availableGeometry();
    if (available.width() < 1600) QSKIP("a screen of 1920 × 1080 (main() gives the offscreen platform one)");
    MainWindow w;
    w.show();
    QVERIFY(QTest::qWaitForWindowExposed(&w));
    QVERIFY2(w.width() >= available.width() * 85 / 100 && w.height() >= available.height() * 85 / 100,
             qPrintable(QStringLiteral("%1 × %2").arg(w.width()).arg(w.height())));
    QVERIFY(available.contains(w.geometry()));
  }

  // Finding 21: Go to View with a NaN or negative width closed the dialog and lost the typed values; a width of 1e300
  // silently meant the whole box; Steps turned 999999999 into 99,999,999 without a word.
  void finding21_goToViewKeepsARefusedViewAndSaysWhy() {
    PortraitPanel panel;
    panel.resize(900, 600);
    panel.show();
    QVERIFY(QTest::qWaitForWindowExposed(&panel));
    PortraitController& c = *panel.controller();
    c.setPointBudget(10000);
    const std::size_t views = c.history().size();
    for (const QString& bad : {QStringLiteral("nan"), QStringLiteral("-0.1"), QStringLiteral("1e300")}) {
      bool stillOpen = false;
      QString reason;
      onModal([&](QDialog& dialog) {
        const auto fields = dialog.findChildren<QLineEdit*>();
        QCOMPARE(fields.size(), 3);
        fields[0]->setText(QStringLiteral("-0.15"));
        fields[1]->setText(QStringLiteral("0.001"));
        fields[2]->setText(bad);
        dialog.findChild<QDialogButtonBox*>()->button(QDialogButtonBox::Ok)->click();
        stillOpen = dialog.isVisible();
        if (auto* label = dialog.findChild<QLabel*>(QStringLiteral("goToViewError"))) reason = label->isVisible() ? label->text() : QString();
        QCOMPARE(fields[0]->text(), QStringLiteral("-0.15"));  // the typed values are kept
        QCOMPARE(fields[2]->text(), bad);
        dialog.reject();
      });
      panel.goToAction()->trigger();
      QVERIFY2(stillOpen, qPrintable(bad));
      QVERIFY2(reason.contains(QStringLiteral("the width = ")), qPrintable(bad + QStringLiteral(": ") + reason));
      QCOMPARE(c.history().size(), views);
    }
    QString error;
    QVERIFY(!c.goTo(-0.15L, 0.0L, 1e300L, &error));
    QVERIFY2(error.contains(QStringLiteral("must be at most the box's width L = xmax − xmin = 1.3")), qPrintable(error));
    QVERIFY(c.goTo(-0.15L, 0.0L, 1.3L, &error));  // the whole box's width is a view

    // Steps: 999999999 typed is the largest, 10⁸, with core's reason.
    QSpinBox* steps = panel.orbitList()->stepsBox();
    QSignalSpy messages(panel.orbitList(), &OrbitListPanel::statusMessage);
    steps->setFocus();
    steps->selectAll();
    QTest::keyClicks(steps, QStringLiteral("999999999"));
    QTest::keyClick(steps, Qt::Key_Return);
    QCOMPARE(steps->value(), 100'000'000);
    bool said = false;
    for (const QList<QVariant>& m : messages)
      said = said || m.front().toString().contains(QStringLiteral("steps = 999999999 must lie in [1, 100000000]"));
    QVERIFY(said);
  }

  // Finding 21 (the rest): the fields of a paused run looked editable and dropped the keys without a word; they look
  // read-only now (the window's background) and a note above them says why and how to edit.
  void finding21_aPausedRunsFieldsLookReadOnlyAndSayWhy() {
    MainWindow w;
    w.setConfirmations(false);
    w.portraitPanel()->controller()->setPointBudget(10000);
    w.show();
    QVERIFY(QTest::qWaitForWindowExposed(&w));
    ParameterPanel& panel = *w.parameterPanel();
    QLineEdit& K = *panel.field(QStringLiteral("K"));
    const QColor editable = K.palette().color(QPalette::Base);
    auto* note = panel.findChild<QLabel*>(QStringLiteral("parametersLocked"));
    QVERIFY2(!note || !note->isVisible(), "the note shows with editable fields");
    TrappingParameters p = finishedRun().params;
    p.T = 100'000'000;
    panel.setParameters(p, 1);
    QVERIFY(w.startRun());
    QVERIFY(w.pauseRun());
    QTRY_COMPARE_WITH_TIMEOUT(w.runStatus(), RunStatus::paused, 900000);
    QVERIFY(K.isReadOnly());
    QVERIFY2(note && note->isVisible() && note->text().contains(QStringLiteral("Read-only")) &&
                 note->text().contains(QStringLiteral("Shift+F5")),
             note ? qPrintable(note->text()) : "no note");
    QVERIFY2(K.palette().color(QPalette::Base) != editable, qPrintable(K.palette().color(QPalette::Base).name()));
    QVERIFY(w.stopRun());
    QTRY_COMPARE_WITH_TIMEOUT(w.runStatus(), RunStatus::stopped, 900000);
    QVERIFY(!K.isReadOnly());
    QVERIFY(!note->isVisible());
    QCOMPARE(K.palette().color(QPalette::Base), editable);
  }

  // Finding 22: a deep view in Island-orbits mode was black and the readout said "raise the budget": the seeds' orbits
  // leave such a view (here 10⁻⁶ wide about the hyperbolic fixed point), so an indicator mode is the advice.
  void finding22_aDeepOrbitsViewAdvisesAnIndicator() {
    PortraitPanel panel;
    PortraitController& c = *panel.controller();
    c.setMode(archipelago::PortraitMode::Orbits);
    c.setPointBudget(100000);
    QString error;
    QVERIFY2(c.goTo(0.316227766L, 0.0L, 1e-6L, &error), qPrintable(error));
    panel.resize(800, 600);
    panel.show();
    QVERIFY(QTest::qWaitForWindowExposed(&panel));
    const PortraitView& v = *c.view();
    QTRY_VERIFY_WITH_TIMEOUT(v.renderState() == RenderState::done, 900000);
    QVERIFY2(v.readout().contains(QStringLiteral("Fast Lyapunov indicator")) &&
                 !v.readout().contains(QStringLiteral("raise the budget")),
             qPrintable(v.readout()));
  }

  // Finding 23: Help ▸ Keyboard Shortcuts did not list Shift+click, and its Action column wrapped.
  void finding23_theShortcutsListShiftClickAndFit() {
    MainWindow w;
    w.show();
    QVERIFY(QTest::qWaitForWindowExposed(&w));
    bool shiftClick = false;
    for (const auto& row : w.keyboardShortcuts()) shiftClick = shiftClick || row.first.contains(QStringLiteral("Shift+click"));
    QVERIFY(shiftClick);
    w.showKeyboardShortcuts();
    auto* dialog = w.findChild<QDialog*>(QStringLiteral("keyboardShortcutsDialog"));
    QVERIFY(dialog);
    QVERIFY(QTest::qWaitForWindowExposed(dialog));
    auto* table = dialog->findChild<QTableWidget*>();
    QVERIFY(table);
    QCoreApplication::processEvents();
    const QFontMetrics metrics(table->font());
    for (int row = 0; row < table->rowCount(); ++row) {
      const QString action = table->item(row, 0)->text();
      QVERIFY2(table->columnWidth(0) >= metrics.horizontalAdvance(action), qPrintable(action));  // one line, whole
      const QString keys = table->item(row, 1)->text();
      const int room = std::max(1, table->columnWidth(1) - 12);  // the cell's margins
      const int lines = (metrics.horizontalAdvance(keys) + room - 1) / room;
      QVERIFY2(table->rowHeight(row) >= std::min(lines, 4) * metrics.lineSpacing(),
               qPrintable(QStringLiteral("%1: row %2 px, %3 lines of %4 px, columns %5 + %6, text %7 px")
                              .arg(keys).arg(table->rowHeight(row)).arg(lines).arg(metrics.lineSpacing())
                              .arg(table->columnWidth(0)).arg(table->columnWidth(1)).arg(metrics.horizontalAdvance(keys))));
    }
    QVERIFY2(table->columnWidth(0) + table->columnWidth(1) <= table->viewport()->width() + 1, "no horizontal scrolling");
    if (const QString shots = qEnvironmentVariable("ARCHIPELAGO_SCREENSHOT_DIR"); !shots.isEmpty())
    {
      QVERIFY(dialog->grab().save(shots + QStringLiteral("/keyboard-shortcuts.png")));
      table->scrollToBottom();  // the mouse's rows
      QCoreApplication::processEvents();
      QVERIFY(dialog->grab().save(shots + QStringLiteral("/keyboard-shortcuts-mouse.png")));
    }
    dialog->close();
  }
};

// A 1920×1080 screen (finding 20): Qt's offscreen platform reads its screens from a file.
int main(int argc, char** argv) {
  archipelago::test::isolatedHome();
  static QTemporaryDir screens;
  const QString config = screens.filePath(QStringLiteral("screens.json"));
  QFile file(config);
  if (!file.open(QIODevice::WriteOnly)) return 1;
  file.write(R"({"screens": [{"name": "1920x1080", "x": 0, "y": 0, "width": 1920, "height": 1080,
                 "logicalDpi": 96, "logicalBaseDpi": 96, "dpr": 1}]})");
  file.close();
  if (qEnvironmentVariable("QT_QPA_PLATFORM", QStringLiteral("offscreen")).startsWith(QStringLiteral("offscreen")))
    qputenv("QT_QPA_PLATFORM", ("offscreen:configfile=" + config).toUtf8());  // else (xcb under Xvfb) its screen
  QApplication app(argc, argv);
  QApplication::setOrganizationName(QStringLiteral("ArchipelagoTests"));
  QApplication::setApplicationName(QStringLiteral("TestIssue53"));
  TestIssue53 test;
  return QTest::qExec(&test, argc, argv);
}

#include "test_issue53.moc"
