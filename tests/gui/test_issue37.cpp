// Issue 37: what a new user hit with the new instruments (under Xvfb at 1280×800 and 1920×1080).  One test per
// finding, named after it, on Qt's offscreen platform; each failed before its fix.  What only a picture can judge
// (the deep-zoom axes, the P_t legend, the chain's rings) is in docs/images too (scripts/gui-screenshots.sh).
// Finding 10 (the spliced D's error label) is the run summary's (StatisticsView::dText, the lead's part).
#include <QAction>
#include <QComboBox>
#include <QFile>
#include <QFontMetrics>
#include <QJsonDocument>
#include <QJsonObject>
#include <QLabel>
#include <QCheckBox>
#include <QLineEdit>
#include <QPainter>
#include <QProcess>
#include <QProgressBar>
#include <QSpinBox>
#include <QSignalSpy>
#include <QTemporaryDir>
#include <QTextDocument>  // Qt::mightBeRichText (Qt 5 declares it only here)
#include <QToolButton>
#include <QtTest>
#include <qwt_legend.h>
#include <qwt_legend_label.h>
#include <qwt_plot.h>
#include <qwt_plot_curve.h>
#include <qwt_scale_div.h>
#include <qwt_scale_draw.h>
#include <qwt_scale_map.h>
#include <qwt_scale_widget.h>
#include <qwt_text.h>

#include <cmath>
#include <set>

#include "GuiTestSupport.hpp"
#include "core/manifolds/ManifoldExport.hpp"
#include "core/map/FixedPointMap.hpp"
#include "core/portrait/MapOverlays.hpp"
#include "core/periodic/HyperbolicPartner.hpp"
#include "core/periodic/PeriodicOrbitFinder.hpp"
#include "core/run/TrappingRun.hpp"
#include "core/session/SessionFile.hpp"
#include "core/runspec/RunSpec.hpp"
#include "ui/plots/StatisticsPlot.hpp"
#include "ui/portrait/ManifoldsPanel.hpp"
#include "ui/portrait/OrbitListPanel.hpp"
#include "ui/portrait/PortraitController.hpp"
#include "ui/portrait/PortraitLayers.hpp"
#include "ui/portrait/PortraitPanel.hpp"
#include "ui/portrait/PortraitView.hpp"
#include "ui/run/RunController.hpp"
#include "ui/scan/KScanDialog.hpp"
#include "ui/scan/KScanPlots.hpp"
#include "ui/segments/LongSegmentsPanel.hpp"
#include "ui/window/ExportActions.hpp"
#include "ui/window/RunGlanceView.hpp"
#include "ui/window/StatisticsView.hpp"

using namespace archipelago;
using namespace archipelago::ui;
using archipelago::test::typeInto;
using archipelago::test::waitForStatus;

namespace {

/// f_t of a run: t⁻¹·⁵ from t = 1 to `tMax`.
Series falling(double tMax, double slope = 1.5) {
  Series s;
  for (double t = 1; t <= tMax; t *= 1.2) {
    s.x.push_back(t);
    s.value.push_back(std::pow(t, -slope));
    s.error.push_back(0.01 * std::pow(t, -slope));
  }
  return s;
}

QAction* actionNamed(const QWidget& w, const QString& text) {
  for (QAction* a : w.findChildren<QAction*>())
    if (a->text() == text) return a;
  return nullptr;
}

/// A finished K = 0.1 run of 16 × 20000 blocks with one segment on an island of the six (tests/gui/test_segments).
const TrappingState& islandRun() {
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

SegmentRecord islandSegment(const TrappingState& state) {
  const FixedPointMap map(state.params.map);
  SegmentRecord inside;
  inside.orbit = 3;
  inside.length = 2000;
  inside.start = {map.toUnit(0.0609L, 0.0974L), state.params.T - inside.length, 0};
  return inside;
}

}  // namespace

class TestIssue37 : public QObject {
  Q_OBJECT
 private Q_SLOTS:
  // Finding 1: after File ▸ Open or F5 the Run page's f_t and C_τ kept the placeholder's axes (t 1…10⁴, f_t
  // 10⁻⁶…1), cutting the new run's data off; Ctrl+0 did not reset them.
  void finding1_runPagePlotsFollowANewRun() {
    StatisticsPlot plot(Statistic::f);
    plot.resize(400, 300);
    plot.show();
    QVERIFY(QTest::qWaitForWindowExposed(&plot));
    plot.setData(falling(1e3), {});
    plot.refresh();
    // A new run: the glance clears its plots (RunGlanceView::clear), then the new run's data arrive.
    plot.clearData();
    plot.refresh();
    plot.setData(falling(1e7, 1.0), {});
    plot.refresh();
    const QwtInterval x = plot.axisInterval(QwtPlot::xBottom), y = plot.axisInterval(QwtPlot::yLeft);
    QVERIFY2(x.maxValue() >= 1e7, qPrintable(QString::number(x.maxValue())));
    QVERIFY2(y.minValue() <= 1e-7, qPrintable(QString::number(y.minValue())));
    QVERIFY(!plot.userView());

    // Ctrl+0 (View ▸ Reset Zoom) resets the Run page's plots too.
    MainWindow w;
    w.setConfirmations(false);
    StatisticsPlot* f = w.runGlance()->fPlot();
    f->setData(falling(1e5), {});
    f->refresh();
    f->setUserView(QRectF(10, 1e-3, 10, 1e-2));
    QVERIFY(f->userView());
    QAction* reset = actionNamed(w, QStringLiteral("Reset &Zoom"));
    QVERIFY(reset);
    reset->trigger();
    QVERIFY(!f->userView());
    QVERIFY(f->axisInterval(QwtPlot::xBottom).maxValue() >= 1e5);
  }

  // Finding 2: Home, then + about 45 times: the labels of a view 3·10⁻⁷ wide about x = −0.15 ran together
  // ("-0.1500000015000000…").  Now the ticks are short offsets from the view's centre, which the title names.
  void finding2_deepZoomLabelsDoNotOverlap() {
    PortraitPanel panel;
    panel.resize(800, 600);
    panel.show();
    QVERIFY(QTest::qWaitForWindowExposed(&panel));
    PortraitController& c = *panel.controller();
    c.setPointBudget(10000);
    QwtPlot* plot = panel.view()->findChild<QwtPlot*>();
    QVERIFY(plot);
    const auto width = [&] {
      const PhysicalRect r = c.viewport().physical(c.map());
      return static_cast<double>(r.x1 - r.x0);
    };
    for (const double depth : {3e-7, 1e-11}) {
      for (int i = 0; i < 200 && width() > depth; ++i) c.zoomIn();
      plot->replot();
      const QwtInterval x = plot->axisInterval(QwtPlot::xBottom);
      QVERIFY2(x.width() <= depth, qPrintable(QString::number(x.width())));
      const QwtScaleDraw* draw = plot->axisScaleDraw(QwtPlot::xBottom);
      const QFontMetrics metrics(plot->axisWidget(QwtPlot::xBottom)->font());
      const QList<double> ticks = plot->axisScaleDiv(QwtPlot::xBottom).ticks(QwtScaleDiv::MajorTick);
      QVERIFY(ticks.size() >= 3);
      const QwtScaleMap map = plot->canvasMap(QwtPlot::xBottom);
      std::set<QString> texts;
      for (int i = 0; i + 1 < ticks.size(); ++i) {
        const QString a = draw->label(ticks[i]).text(), b = draw->label(ticks[i + 1]).text();
        texts.insert(a);
        texts.insert(b);
        const double gap = std::abs(map.transform(ticks[i + 1]) - map.transform(ticks[i]));
        const double need = 0.5 * (metrics.horizontalAdvance(a) + metrics.horizontalAdvance(b)) + 4;
        QVERIFY2(gap >= need,
                 qPrintable(QStringLiteral("\"%1\" and \"%2\": %3 px apart, %4 wide").arg(a, b).arg(gap).arg(need)));
        QVERIFY2(a.size() <= 6, qPrintable(a));
      }
      QCOMPARE(static_cast<int>(texts.size()), ticks.size());  // every label differs
      // The title names the reference the offsets are from.
      const QString title = plot->axisTitle(QwtPlot::xBottom).text();
      QVERIFY2(title.contains(QStringLiteral("−0.15")) && title.contains(QStringLiteral("×10")), qPrintable(title));
    }
    // At the whole box: plain labels.
    c.resetView();
    QCOMPARE(plot->axisTitle(QwtPlot::xBottom).text(), QStringLiteral("x"));
  }

  // Finding 3: typing "0.1,5" then "0.1" into K discarded the orbits, the view history and the segment overlay
  // without a word, and the preset box said "Custom" although every field held the preset.
  void finding3_editingAParameterKeepsTheWork() {
    MainWindow w;
    w.setConfirmations(false);
    ParameterPanel& panel = *w.parameterPanel();
    QVERIFY(panel.applyPreset(QStringLiteral("K = 0.1, under a minute")));
    auto* presets = panel.findChild<QComboBox*>(QStringLiteral("presets"));
    QVERIFY(presets);
    const QString preset = presets->currentText();
    QVERIFY(preset != QStringLiteral("Custom"));
    PortraitController& c = *w.portraitPanel()->controller();
    c.setPointBudget(10000);
    QVERIFY(c.launchOrbit(0.0609L, 0.0974L) != 0);
    QVERIFY(c.launchOrbit(-0.2L, 0.0L) != 0);
    c.zoomIn();
    const Viewport zoomed = c.viewport();
    QSignalSpy messages(&c, &PortraitController::statusMessage);
    typeInto(panel, QStringLiteral("K"), QStringLiteral("0.1,5"));
    typeInto(panel, QStringLiteral("K"), QStringLiteral("0.1"));
    QCOMPARE(c.map().K, 0.1);
    QCOMPARE(c.orbitCount(), 2);
    QVERIFY(c.viewport() == zoomed);
    QCOMPARE(presets->currentText(), preset);
    QVERIFY(panel.spec()->companion > 0);  // the preset's companion comes back with it
    // A change of map says that the work is kept, and how to have it back.
    bool said = false;
    for (const QList<QVariant>& m : messages) said = said || m.first().toString().contains(QStringLiteral("kept"));
    QVERIFY(said);
    QTRY_VERIFY_WITH_TIMEOUT(c.orbitsSettled(), 900000);
  }

  // Finding 4: a session saved with the period-6 manifolds opened with the manifolds off (no entry for them).
  void finding4_sessionsKeepTheManifolds() {
    PeriodicOrbitSearch search;
    search.period = 6;
    search.near = {0.0509L, 0.0974L};
    const auto partner = findHyperbolicPartner(findPeriodicOrbit(0.1L, search));
    QVERIFY(partner);
    QTemporaryDir dir;
    const QString path = dir.filePath(QStringLiteral("m.archipelago"));
    {
      MainWindow w;
      w.setConfirmations(false);
      w.portraitPanel()->controller()->setPointBudget(10000);
      w.portraitPanel()->controller()->setManifoldOrbit(*partner);
      QVERIFY(w.saveSession(path));
    }
    MainWindow w;
    w.setConfirmations(false);
    QString error;
    QVERIFY2(w.openSession(path, &error), qPrintable(error));
    PortraitController& c = *w.portraitPanel()->controller();
    QVERIFY(c.manifoldsShown());
    QVERIFY(c.manifoldOrbit());
    QCOMPARE(c.manifoldOrbit()->period, 6);
    QVERIFY(partner->distanceTo(c.manifoldOrbit()->points.front()) < 1e-12L);
    // The fixed point's manifolds: an entry without an orbit; none: off.
    c.setManifoldOrbit(std::nullopt);
    QVERIFY(w.saveSession(path));
    const Session fixed = loadSession(path.toStdString());
    QVERIFY(fixed.portrait.manifolds);
    QVERIFY(fixed.portrait.manifoldOrbit.empty());
    c.setManifoldsShown(false);
    QVERIFY(w.saveSession(path));
    QVERIFY(!loadSession(path.toStdString()).portrait.manifolds);
    QTRY_VERIFY_WITH_TIMEOUT(c.manifoldsSettled(), 900000);
  }

  // Finding 5: the P_t legend covered the 10⁴–10⁷ tail, the reference slopes and the tail estimate's levels, and
  // the estimate's own entry was cut off.
  void finding5_thePtLegendCoversNoData() {
    StatisticsPlot plot(Statistic::P);
    plot.resize(330, 260);  // one of the Statistics tab's six at 1280×800
    plot.show();
    QVERIFY(QTest::qWaitForWindowExposed(&plot));
    Series p = falling(1e5, 0.5);
    plot.setData(p, {});
    Series tail;
    for (double t = 1e4; t <= 1e7; t *= 2) {
      tail.x.push_back(t);
      tail.value.push_back(std::pow(t, -0.5) * 0.8);
      tail.error.push_back(0.1 * std::pow(t, -0.5));
    }
    plot.setEstimate(tail, QStringLiteral("P_t by splitting (tail)"));
    plot.refresh();
    // Its legend is below the canvas, every entry whole; nothing of it is over the data.
    QVERIFY(plot.legendShown());
    QVERIFY(plot.legendRect().isEmpty());
    auto* below = qobject_cast<QwtLegend*>(plot.legend());
    QVERIFY(below);
    QVERIFY(below->isVisible());
    QVERIFY(!below->geometry().intersects(plot.canvas()->geometry()));
    QVERIFY(below->geometry().top() >= plot.canvas()->geometry().bottom());
    const auto labels = below->findChildren<QwtLegendLabel*>();
    QVERIFY(labels.size() >= 6);  // the data, four reference slopes, the estimate
    bool estimate = false;
    for (const QwtLegendLabel* label : labels) {
      QVERIFY(label->isVisible());
      const QRect at(label->mapTo(below, QPoint(0, 0)), label->size());
      QVERIFY2(below->contentsRect().contains(at), qPrintable(label->data().title().text()));
      QVERIFY2(label->width() >= label->sizeHint().width(), qPrintable(label->data().title().text()));
      estimate = estimate || label->data().title().text() == QStringLiteral("P_t by splitting (tail)");
    }
    QVERIFY(estimate);
  }

  // Finding 6: two "Stop" buttons side by side (the portrait's render, the run), unlabelled as such.
  void finding6_theTwoStopsSayWhatTheyStop() {
    MainWindow w;
    w.setConfirmations(false);
    w.resize(1280, 770);
    w.show();
    QVERIFY(QTest::qWaitForWindowExposed(&w));
    QStringList stops;
    for (QToolButton* b : w.findChildren<QToolButton*>())
      if (b->isVisible() && b->text().contains(QStringLiteral("Stop"))) stops << b->text();
    QVERIFY(stops.size() >= 2);
    QCOMPARE(w.portraitPanel()->stopButton()->text(), QStringLiteral("Stop Drawing"));
    QVERIFY(w.stopAction()->text().contains(QStringLiteral("Run")));
    QVERIFY(!w.portraitPanel()->stopButton()->toolTip().isEmpty());
    for (const QString& s : stops) QVERIFY2(s == QStringLiteral("Stop") || s == QStringLiteral("Stop Drawing"), qPrintable(s));
  }

  // Finding 7: at 100 % and "ETA 0:00" the q = 1 companion ran unlabelled; α then jumped with no word why.
  void finding7_theCompanionRunIsNamed() {
    MainWindow w;
    w.setConfirmations(false);
    TrappingParameters p = archipelago::test::shortRun();
    p.T = 200'000;
    QStringList shown;
    auto* bar = w.findChild<QProgressBar*>();
    QVERIFY(bar);
    // Every snapshot of the companion's phase, as the window shows it (the controller takes it first: queued).
    connect(&w.worker(), &RunWorker::snapshotReady, &w, [&](const RunSnapshotPtr& s) {
      if (!s || !s->companionRunning) return;
      QTimer::singleShot(0, &w, [&] {
        w.refreshNow();
        shown << bar->text() + QStringLiteral(" | ") + bar->format();
      });
    });
    RunSettings settings;
    settings.threads = 1;
    settings.companion = 1.0;
    QString error;
    QVERIFY2(w.runController()->start(p, settings, &error), qPrintable(error));
    QVERIFY(waitForStatus(w, RunStatus::finished, 120000));
    QTRY_VERIFY_WITH_TIMEOUT(!shown.isEmpty(), 900000);
    QVERIFY2(shown.front().contains(QStringLiteral("companion")), qPrintable(shown.front()));
    w.refreshNow();
    const RunSnapshotPtr last = w.latestSnapshot();
    QVERIFY(last && !last->companionRunning);
    if (last->companion)
      QVERIFY2(w.statisticsView()->summaryText().contains(QStringLiteral("spliced")),
               qPrintable(w.statisticsView()->summaryText()));
    else
      QVERIFY(!w.statisticsView()->summaryText().contains(QStringLiteral("spliced")));
  }

  // Finding 8: selecting an orbit dimmed all the others, including orbits clicked afterwards (nearly invisible).
  void finding8_aClickAfterASelectionIsSeen() {
    PortraitPanel panel;
    panel.resize(800, 600);
    panel.show();
    QVERIFY(QTest::qWaitForWindowExposed(&panel));
    PortraitController& c = *panel.controller();
    c.setPointBudget(10000);
    const quint64 first = c.launchOrbit(0.0609L, 0.0974L);
    QTRY_VERIFY_WITH_TIMEOUT(c.orbitsSettled(), 900000);
    c.highlightOrbit(first);
    QCOMPARE(c.highlightedOrbit(), first);
    // A click on the portrait launches the next orbit.
    QWidget* canvas = panel.view()->canvas();
    QTest::mouseClick(canvas, Qt::LeftButton, Qt::NoModifier, canvas->rect().center() + QPoint(30, 20));
    QTRY_VERIFY_WITH_TIMEOUT(c.orbitCount() == 2 && c.orbitsSettled(), 900000);
    QCOMPARE(c.highlightedOrbit(), quint64{0});
    for (QwtPlotItem* item : panel.view()->layerItems(PortraitLayer::launchedOrbits)) {
      const auto* points = static_cast<const PointsItem*>(item);
      QCOMPARE(points->colour().alpha(), 255);
    }
  }

  // Finding 9: the discs marking a chain's centres had a fixed size and hid the six islands at the full view.
  void finding9_chainCentresLeaveTheIslandVisible() {
    const PointsItem item(PointsItem::Style::discs, {QPointF(50, 50)}, QColor(0, 230, 255));
    QImage image(100, 100, QImage::Format_ARGB32);
    image.fill(Qt::transparent);
    QwtScaleMap xMap, yMap;
    xMap.setPaintInterval(0, 100);
    xMap.setScaleInterval(0, 100);
    yMap.setPaintInterval(100, 0);
    yMap.setScaleInterval(0, 100);
    {
      QPainter painter(&image);
      item.draw(&painter, xMap, yMap, QRectF(0, 0, 100, 100));
    }
    // The ring is drawn; inside it, between the dot and the ring, the island shows through.
    int drawnAround = 0;
    for (int dx = -10; dx <= 10; ++dx)
      if (qAlpha(image.pixel(50 + dx, 50)) > 0) ++drawnAround;
    QVERIFY(drawnAround > 0);
    for (const QPoint& p : {QPoint(53, 50), QPoint(47, 50), QPoint(50, 53), QPoint(50, 47), QPoint(52, 52)})
      QVERIFY2(qAlpha(image.pixel(p)) == 0, qPrintable(QStringLiteral("(%1, %2)").arg(p.x()).arg(p.y())));
  }

  // Finding 11: Play on a segment threw a "Zoom to island" view away (it widened to the segment's region).
  void finding11_playKeepsTheIslandView() {
    const TrappingState& state = islandRun();
    PortraitPanel portrait;
    portrait.resize(600, 500);
    PortraitController& controller = *portrait.controller();
    controller.setPointBudget(20000);
    const SegmentRecord inside = islandSegment(state);
    LongestSegments longest = state.longest;
    longest.insert(inside);
    LongSegmentsPanel panel;
    panel.setAutoIdentifiedRows(0);
    panel.setPortraitController(&controller);
    panel.updateSegments(state.params, longest);
    QSignalSpy replays(&panel, &LongSegmentsPanel::replayReady);
    panel.selectRow(panel.model()->rowOf(SegmentKey::of(inside)));
    QVERIFY(replays.wait(900000));
    QTRY_VERIFY_WITH_TIMEOUT(panel.currentChain() != nullptr && panel.currentChain()->chain.has_value(), 900000);
    panel.zoomToIsland();
    const Viewport island = controller.viewport();
    QToolButton* play = nullptr;
    for (QToolButton* b : panel.findChildren<QToolButton*>())
      if (b->text() == QStringLiteral("Play")) play = b;
    QVERIFY(play);
    int checked = 0, outside = 0;
    const auto& points = panel.currentReplay()->trace.points;
    connect(&panel, &LongSegmentsPanel::currentIndexChanged, &panel, [&](std::size_t index) {
      ++checked;
      if (!controller.shows(points[index].x, points[index].y)) ++outside;
    });
    play->click();
    QTRY_VERIFY_WITH_TIMEOUT(checked >= 12, 900000);
    play->click();  // pause
    QCOMPARE(outside, 0);
    QVERIFY(controller.viewport() == island);
  }

  // Finding 12: the K-scan dialog's empty plots had axes from 10⁻¹⁵⁰ to 1.
  void finding12_emptyScanPlotsHaveSensibleAxes() {
    KScanDialog dialog(RunSpec{});
    dialog.show();
    QVERIFY(QTest::qWaitForWindowExposed(&dialog));
    auto* plots = dialog.findChild<KScanPlots*>();
    QVERIFY(plots);
    for (const QString& name : plots->plotNames()) {
      QwtPlot* plot = plots->plot(name);
      QVERIFY(plot);
      for (const int axis : {int(QwtPlot::xBottom), int(QwtPlot::yLeft)}) {
        const QwtInterval r = plot->axisInterval(axis);
        const bool sensible = r.minValue() > 0 ? r.maxValue() / r.minValue() <= 1e9 : r.maxValue() <= 1e7;
        QVERIFY2(sensible, qPrintable(QStringLiteral("%1, axis %2: %3 … %4").arg(name).arg(axis).arg(r.minValue()).arg(r.maxValue())));
      }
    }
  }

  // Finding 13: the window opened at 1200×760 with the portrait's legend line cut ("… cl…"); it fits 1280×800.
  void finding13_theFirstWindowShowsItsLegendWhole() {
    MainWindow w;
    w.setConfirmations(false);
    w.show();
    QVERIFY(QTest::qWaitForWindowExposed(&w));
    QVERIFY(w.width() <= 1280 && w.height() <= 800 - 30);  // a title bar above it
    QVERIFY(w.minimumSizeHint().width() <= 1280);
    auto* hint = w.findChild<QLabel*>(QStringLiteral("portraitHint"));
    QVERIFY(hint);
    QTRY_VERIFY(hint->width() > 0);
    QVERIFY(hint->isVisible());
    QVERIFY(hint->text().endsWith(QStringLiteral("pan")));
    QVERIFY2(hint->height() >= hint->heightForWidth(hint->width()),
             qPrintable(QStringLiteral("%1 px high, needs %2").arg(hint->height()).arg(hint->heightForWidth(hint->width()))));
  }

  // Finding 14: "&amp;" in the Manifolds help; a zero coordinate printed as 7.2e-35; the exported run_spec.json
  // dropped "companion".
  void finding14_cosmetics() {
    PortraitPanel panel;
    auto* help = panel.manifoldsPanel()->findChild<QLabel*>(QStringLiteral("fluxNumbers"));
    QVERIFY(help);
    QVERIFY2(!help->text().contains(QStringLiteral("&amp;")) || Qt::mightBeRichText(help->text()), qPrintable(help->text()));
    QVERIFY(help->text().contains(QStringLiteral("Meiss & Percival")));
    // A coordinate that is round-off of zero beside a coordinate of order 1 is "0"; a small true one stays.
    QCOMPARE(QString::fromStdString(quadCoordinateText(quad(7.2e-35), quad(0.3162), 12)), QStringLiteral("0"));
    QCOMPARE(quadCoordinateText(quad(0.3162), quad(7.2e-35), 4), quadText(quad(0.3162), 4));
    QVERIFY(QString::fromStdString(quadCoordinateText(quad(2.5e-9), quad(1e-8), 12)).startsWith(QStringLiteral("2.5")));
    // run_spec.json of Export All keeps the preset's companion.
    MainWindow w;
    w.setConfirmations(false);
    QVERIFY(w.parameterPanel()->applyPreset(QStringLiteral("K = 0.1, under a minute")));
    const RunSpec spec = *w.parameterPanel()->spec();
    QVERIFY(spec.companion > 0);
    auto snapshot = std::make_shared<RunSnapshot>();
    snapshot->state = startTrapping(spec.parameters);
    QTemporaryDir dir;
    const ExportResult r = exportAll({}, snapshot, dir.path(), nullptr, spec);
    QVERIFY2(r.ok() || !r.error.contains(QLatin1String(kRunSpecJsonName)), qPrintable(r.error));
    const RunSpec written = loadRunSpec(dir.filePath(QLatin1String(kRunSpecJsonName)).toStdString());
    QCOMPARE(written.companion, spec.companion);
    QVERIFY(written.parameters == spec.parameters);
  }

  // Finding 15: launched orbits had 20 000 steps, forward only, from a click only.  Now the Orbits page sets the
  // steps and N⁻¹ of what a click launches, and launches from a typed start (every digit kept).
  void finding15_stepsBackwardAndATypedStart() {
    PortraitPanel panel;
    panel.resize(900, 600);
    panel.show();
    QVERIFY(QTest::qWaitForWindowExposed(&panel));
    PortraitController& c = *panel.controller();
    c.setPointBudget(10000);
    OrbitListPanel& list = *panel.orbitList();
    list.stepsBox()->setValue(500);
    list.backwardBox()->setChecked(true);
    QWidget* canvas = panel.view()->canvas();
    QTest::mouseClick(canvas, Qt::LeftButton, Qt::NoModifier, canvas->rect().center() + QPoint(40, 25));
    QTRY_VERIFY_WITH_TIMEOUT(c.orbitCount() == 1 && c.launchedOrbits().front().points, 900000);
    const LaunchedOrbit& clicked = c.launchedOrbits().front();
    QCOMPARE(clicked.steps, std::uint64_t{500});
    QVERIFY(clicked.backward);
    QCOMPARE(clicked.points->size(), std::size_t{501});
    // N⁻¹ of core (independent of the GUI's drawing): the orbit's points are those of traceOrbit(…, backward).
    const auto past = traceOrbit(c.map(), clicked.x, clicked.y, 500, true);
    QCOMPARE(clicked.points->back().x(), static_cast<double>(past.back().x));
    QCOMPARE(clicked.points->back().y(), static_cast<double>(past.back().y));
    const auto future = traceOrbit(c.map(), clicked.x, clicked.y, 500, false);
    QVERIFY(clicked.points->back().x() != static_cast<double>(future.back().x));
    // A typed start: exactly the long double typed (a click gives the pixel's point).
    list.backwardBox()->setChecked(false);
    list.startXField()->setText(QStringLiteral("0.06090000000000000001"));
    list.startYField()->setText(QStringLiteral("0.0974"));
    QVERIFY(list.launchTyped());
    QCOMPARE(c.orbitCount(), 2);
    QVERIFY(c.launchedOrbits().back().x == 0.06090000000000000001L);
    QVERIFY(c.launchedOrbits().back().y == 0.0974L);
    QVERIFY(!c.launchedOrbits().back().backward);
    list.startXField()->setText(QStringLiteral("zero"));
    QVERIFY(!list.launchTyped());
    list.startXField()->setText(QStringLiteral("5"));  // outside the box
    QVERIFY(!list.launchTyped());
    QCOMPARE(c.orbitCount(), 2);
    QTRY_VERIFY_WITH_TIMEOUT(c.orbitsSettled(), 900000);
  }

  // Finding 18: at depth the axes name the view's centre once and label the ticks as offsets (finding 2), and a
  // view can be typed: its centre and width (Portrait ▸ Go to View…).
  void finding18_aTypedViewWithOffsetAxes() {
    PortraitPanel panel;
    panel.resize(800, 600);
    panel.show();
    QVERIFY(QTest::qWaitForWindowExposed(&panel));
    PortraitController& c = *panel.controller();
    c.setPointBudget(10000);
    QVERIFY(panel.goToAction());
    QVERIFY(panel.goTo(QStringLiteral("-0.15000000123"), QStringLiteral("0.001"), QStringLiteral("4e-9")));
    const PhysicalRect r = c.viewport().physical(c.map());
    QVERIFY(std::fabs((r.x0 + r.x1) / 2 + 0.15000000123L) < 1e-15L);
    QVERIFY(std::fabs((r.y0 + r.y1) / 2 - 0.001L) < 1e-15L);
    QVERIFY(std::fabs((r.x1 - r.x0) - 4e-9L) < 1e-14L);
    QwtPlot* plot = panel.view()->findChild<QwtPlot*>();
    QVERIFY(plot);
    const QString title = plot->axisTitle(QwtPlot::xBottom).text();
    QVERIFY2(title.contains(QStringLiteral("(−0.150000001)")) && title.contains(QStringLiteral("×10⁻⁹")), qPrintable(title));
    for (const double tick : plot->axisScaleDiv(QwtPlot::xBottom).ticks(QwtScaleDiv::MajorTick)) {
      const QString label = plot->axisScaleDraw(QwtPlot::xBottom)->label(tick).text();
      QVERIFY2(label.size() <= 4, qPrintable(label));
    }
    // What is not a view is refused with the reason, and the view stays.
    const Viewport before = c.viewport();
    QSignalSpy messages(&panel, &PortraitPanel::statusMessage);
    QVERIFY(!panel.goTo(QStringLiteral("x"), QStringLiteral("0"), QStringLiteral("0.1")));
    QVERIFY(!panel.goTo(QStringLiteral("5"), QStringLiteral("0"), QStringLiteral("0.1")));
    QVERIFY(!panel.goTo(QStringLiteral("0"), QStringLiteral("0"), QStringLiteral("0")));
    QCOMPARE(messages.count(), 3);
    QVERIFY(c.viewport() == before);
  }

  // Finding 20: no CSV of a single launched orbit, and no undo for Clear Orbits.
  void finding20_orbitCsvAndUndoClear() {
    PortraitPanel panel;
    PortraitController& c = *panel.controller();
    c.setPointBudget(10000);
    const quint64 id = c.launchOrbit(0.0609L, 0.0974L, 300, true);
    QVERIFY(id != 0);
    c.launchOrbit(-0.2L, 0.01L, 200);
    QTemporaryDir dir;
    const QString path = dir.filePath(QStringLiteral("orbit.csv"));
    QString error;
    QVERIFY2(c.exportOrbitCsv(id, path, &error), qPrintable(error));
    QFile file(path);
    QVERIFY(file.open(QIODevice::ReadOnly));
    const QByteArray gui = file.readAll();
    QProcess cli;
    cli.start(QStringLiteral(ARCHIPELAGO_CLI),
              {QStringLiteral("orbit"), QStringLiteral("--K"), QStringLiteral("0.1"), QStringLiteral("--x"),
               QStringLiteral("0.0609"), QStringLiteral("--y"), QStringLiteral("0.0974"), QStringLiteral("--steps"),
               QStringLiteral("300"), QStringLiteral("--backward")});
    QVERIFY(cli.waitForFinished(120000));
    QCOMPARE(cli.exitCode(), 0);
    QCOMPARE(gui, cli.readAllStandardOutput());
    QCOMPARE(gui.count('\n'), 302);  // the header, the start and 300 steps
    QVERIFY(!c.exportOrbitCsv(9999, path, &error));
    // Clear Orbits, then Ctrl+Z: the same starts, steps and directions come back.
    c.clearOrbits();
    QCOMPARE(c.orbitCount(), 0);
    QVERIFY(c.canUndoClear());
    QVERIFY(panel.undoOrbitAction()->isEnabled());
    QVERIFY(c.undoLastOrbit());
    QCOMPARE(c.orbitCount(), 2);
    QVERIFY(c.launchedOrbits().front().x == 0.0609L && c.launchedOrbits().front().backward);
    QCOMPARE(c.launchedOrbits().front().steps, std::uint64_t{300});
    QCOMPARE(c.launchedOrbits().back().steps, std::uint64_t{200});
    QVERIFY(!c.canUndoClear());
    // Once another orbit is launched, Ctrl+Z removes that one: the Clear is no longer the last thing done.
    c.clearOrbits();
    c.launchOrbit(-0.3L, 0.0L);
    QVERIFY(!c.canUndoClear());
    QTRY_VERIFY_WITH_TIMEOUT(c.orbitsSettled(), 900000);
  }
};

ARCHIPELAGO_GUI_TEST_MAIN(TestIssue37)
#include "test_issue37.moc"
