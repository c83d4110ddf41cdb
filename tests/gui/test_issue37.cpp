// Issue 37: what a new user hit with the new instruments (under Xvfb at 1280×800 and 1920×1080).  One test per
// finding, named after it, on Qt's offscreen platform; each failed before its fix.  What only a picture can judge
// (the deep-zoom axes, the P_t legend, the chain's rings) is in docs/images too (scripts/gui-screenshots.sh).
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
#include <QPushButton>
#include <QTreeWidget>
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
#include "core/session/OrbitFamily.hpp"
#include "core/session/SessionFile.hpp"
#include "core/measures/ChainIdentification.hpp"
#include "core/measures/PeriodicOrbitAt.hpp"
#include "core/measures/RotationProfile.hpp"
#include "core/runspec/RunSpec.hpp"
#include "core/runfile/RunFile.hpp"
#include "core/stats/RunSummary.hpp"
#include "core/trapping/TrappingParameters.hpp"
#include "ui/run/RunWorker.hpp"
#include "ui/plots/StatisticsPlot.hpp"
#include "ui/portrait/ManifoldsPanel.hpp"
#include "ui/portrait/OrbitListPanel.hpp"
#include "ui/portrait/PortraitController.hpp"
#include "ui/portrait/PortraitLayers.hpp"
#include "ui/portrait/PortraitPanel.hpp"
#include "ui/portrait/PortraitView.hpp"
#include "ui/portrait/RotationProfilePanel.hpp"
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

/// `archipelago-cli ARGS`' standard output (empty, with the failure in `error`, when it fails).
QString cliOutput(const QStringList& args, QString* error) {
  QProcess cli;
  cli.start(QStringLiteral(ARCHIPELAGO_CLI), args);
  if (!cli.waitForFinished(900000) || cli.exitStatus() != QProcess::NormalExit || cli.exitCode() != 0) {
    *error = QString::fromUtf8(cli.readAllStandardError());
    return {};
  }
  return QString::fromUtf8(cli.readAllStandardOutput());
}

/// printf's formatting of long doubles (QString::asprintf reads %Lg as a double: digits lost).
QString longText(const char* format, long double a, long double b) {
  char buffer[128];
  std::snprintf(buffer, sizeof buffer, format, a, b);
  return QString::fromLatin1(buffer);
}
QString longText(const char* format, long double a) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, format, a);
  return QString::fromLatin1(buffer);
}

/// The rest of `text`'s line that starts with `label` (`stats`' columns: "gamma_P     …"), trimmed; empty if none.
QString lineAfter(const QString& text, const QString& label) {
  for (const QString& line : text.split(QLatin1Char('\n')))
    if (line.startsWith(label)) return line.mid(label.size()).trimmed();
  return {};
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

  // Finding 15's rest: a line or a grid of orbits launched at once from the Orbits page (two points and a count, or
  // the rectangle they span and n × m), each measured and listed like a clicked one; an over-large count refused
  // with core's words (orbitFamilyStarts), nothing launched.
  void finding15_aLineAndAGridOfOrbits() {
    PortraitPanel panel;
    panel.resize(900, 600);
    panel.show();
    QVERIFY(QTest::qWaitForWindowExposed(&panel));
    PortraitController& c = *panel.controller();
    c.setPointBudget(10000);
    OrbitListPanel& list = *panel.orbitList();
    list.stepsBox()->setValue(2000);
    QPushButton* many = list.findChild<QPushButton*>(QStringLiteral("launchFamily"));
    QVERIFY(many);
    // A line of 5 from (−0.3, 0) to (−0.1, 0.04): the ends and three between, equally spaced.
    list.startXField()->setText(QStringLiteral("-0.3"));
    list.startYField()->setText(QStringLiteral("0"));
    list.endXField()->setText(QStringLiteral("-0.1"));
    list.endYField()->setText(QStringLiteral("0.04"));
    list.columnsBox()->setValue(5);
    list.rowsBox()->setValue(1);
    QTest::mouseClick(many, Qt::LeftButton);
    QCOMPARE(c.orbitCount(), 5);
    for (int i = 0; i < 5; ++i) {
      const LaunchedOrbit& o = c.launchedOrbits()[static_cast<std::size_t>(i)];
      QVERIFY2(std::fabs(o.x - (-0.3L + 0.05L * i)) < 1e-18L, qPrintable(QString::number(static_cast<double>(o.x))));
      QVERIFY(std::fabs(o.y - 0.01L * i) < 1e-18L);
      QCOMPARE(o.steps, std::uint64_t{2000});
    }
    // A grid of 3 × 2 over the rectangle (0.05, 0.09) … (0.07, 0.1): rows at y = 0.09 and 0.1, columns 0.05 … 0.07.
    list.startXField()->setText(QStringLiteral("0.05"));
    list.startYField()->setText(QStringLiteral("0.09"));
    list.endXField()->setText(QStringLiteral("0.07"));
    list.endYField()->setText(QStringLiteral("0.1"));
    list.columnsBox()->setValue(3);
    list.rowsBox()->setValue(2);
    QCOMPARE(list.launchFamily(), 6);
    QCOMPARE(c.orbitCount(), 11);
    const LaunchedOrbit& corner = c.launchedOrbits()[10];
    QVERIFY(corner.x == 0.07L && corner.y == 0.1L);
    QVERIFY(std::fabs(c.launchedOrbits()[6].x - 0.06L) < 1e-18L && c.launchedOrbits()[6].y == 0.09L);
    // Each measured and listed as a clicked orbit is (core's identifyChain for its start).
    QTRY_VERIFY_WITH_TIMEOUT(c.orbitsSettled(), 900000);
    QTRY_COMPARE_WITH_TIMEOUT(list.list()->topLevelItemCount(), 11, 900000);
    for (const LaunchedOrbit& o : c.launchedOrbits()) QVERIFY(o.measures && o.measures->error.isEmpty());
    ChainRequest request;
    request.map = c.map();
    const ChainIdentification expected = identifyChain(chainRequestAt(request, {corner.x, corner.y}));
    QCOMPARE(c.launchedOrbits()[10].measures->chain.summary, expected.summary);
    // The list refreshes once the event loop is free (a burst of measures, one refresh): wait for it.
    QTRY_COMPARE_WITH_TIMEOUT(list.list()->topLevelItem(10)->text(4), chainText(*c.launchedOrbits()[10].measures), 900000);
    // Over-large: refused with core's message, nothing launched; a count of 0 likewise.
    QSignalSpy messages(&c, &PortraitController::statusMessage);
    list.columnsBox()->setValue(500);
    list.rowsBox()->setValue(1);
    QCOMPARE(list.launchFamily(), 0);
    QCOMPARE(c.orbitCount(), 11);
    QString why;
    try {
      (void)orbitFamilyStarts({{0.05L, 0.09L}, {0.07L, 0.1L}, 500, 1}, 11);
    } catch (const std::invalid_argument& e) {
      why = QString::fromUtf8(e.what());
    }
    QVERIFY(!why.isEmpty());
    QVERIFY(!messages.isEmpty());
    QCOMPARE(messages.last().first().toString(), why);
    list.columnsBox()->setValue(0);
    QCOMPARE(list.launchFamily(), 0);
    QCOMPARE(c.orbitCount(), 11);
    list.columnsBox()->setValue(3);
    list.endXField()->setText(QStringLiteral("east"));
    QCOMPARE(list.launchFamily(), 0);
    QCOMPARE(c.orbitCount(), 11);
  }

  // Finding 16: a click could not find the periodic orbit there.  Shift+click (or a click in Portrait ▸ Click Finds
  // Periodic Orbits) names the chain as the rotation instrument does and finds its elliptic orbit as
  // `archipelago-cli periodic --period n --near X,Y --stable` does: the same residue and points, digit for digit.
  void finding16_aClickFindsThePeriodicOrbitThere() {
    PortraitPanel panel;
    panel.resize(900, 600);
    panel.show();
    QVERIFY(QTest::qWaitForWindowExposed(&panel));
    PortraitController& c = *panel.controller();
    c.setPointBudget(10000);
    QSignalSpy found(&c, &PortraitController::periodicOrbitFound);
    // The gesture: Shift+click on the canvas searches, it does not launch an orbit.
    QWidget* canvas = panel.view()->canvas();
    QTest::mouseClick(canvas, Qt::LeftButton, Qt::ShiftModifier, canvas->rect().center() + QPoint(40, 25));
    QTRY_VERIFY_WITH_TIMEOUT(found.count() == 1 && !c.periodicSearchPending(), 900000);
    QCOMPARE(c.orbitCount(), 0);
    // The mode: a plain click searches too.
    QVERIFY(panel.findPeriodicAction() && panel.findPeriodicAction()->isCheckable());
    panel.findPeriodicAction()->setChecked(true);
    QTest::mouseClick(canvas, Qt::LeftButton, Qt::NoModifier, canvas->rect().center() + QPoint(-30, 10));
    QTRY_VERIFY_WITH_TIMEOUT(found.count() == 2 && !c.periodicSearchPending(), 900000);
    QCOMPARE(c.orbitCount(), 0);
    panel.findPeriodicAction()->setChecked(false);

    // An exact point in one of the six islands (tests/gui/test_instruments): its chain and orbit against the CLI's.
    c.findPeriodicOrbitAt(0.06L, 0.0974L);
    QTRY_VERIFY_WITH_TIMEOUT(found.count() == 3 && !c.periodicSearchPending(), 900000);
    const auto at = c.clickedPeriodicOrbit();
    QVERIFY2(at, qPrintable(found.last().first().toString()));
    QVERIFY(!panel.view()->layerItems(PortraitLayer::periodicOrbits).empty());
    QVERIFY(found.last().first().toString().contains(QString::fromStdString(at->chain.summary)));
    QString error;
    const QString rotation = cliOutput({QStringLiteral("rotation"), QStringLiteral("--K"), QStringLiteral("0.1"),
                                        QStringLiteral("--x=0.06"), QStringLiteral("--y=0.0974"), QStringLiteral("--json")},
                                       &error);
    QVERIFY2(!rotation.isEmpty(), qPrintable(error));
    const QJsonObject chain = QJsonDocument::fromJson(rotation.toUtf8()).object()[QStringLiteral("chain")].toObject();
    QCOMPARE(QString::fromStdString(at->chain.summary), chain[QStringLiteral("summary")].toString());
    QCOMPARE(static_cast<qint64>(at->orbit.period), static_cast<qint64>(chain[QStringLiteral("period")].toDouble()));
    QCOMPARE(at->orbit.period, 6);  // the paper's six islands (fig. 8)
    const QString near = longText("--near=%.21Lg,%.21Lg", at->search.near.x, at->search.near.y);
    const QString periodic = cliOutput({QStringLiteral("periodic"), QStringLiteral("--K"), QStringLiteral("0.1"),
                                        QStringLiteral("--period"), QString::number(at->orbit.period), near,
                                        QStringLiteral("--stable")},
                                       &error);
    QVERIFY2(!periodic.isEmpty(), qPrintable(error));
    QCOMPARE(lineAfter(periodic, QStringLiteral("# residue:")), longText("%.18Lg", at->orbit.residue));
    QCOMPARE(lineAfter(periodic, QStringLiteral("# class:")), QString::fromLatin1(toString(at->orbit.classification().stability)));
    for (std::size_t k = 0; k < at->orbit.points.size(); ++k)
      QVERIFY2(periodic.contains(QStringLiteral("\n%1,").arg(k) + longText("%.21Lg,%.21Lg\n", at->orbit.points[k].x, at->orbit.points[k].y)),
               qPrintable(QString::number(k)));
    // In the sea (here an orbit that leaves the box) there is no chain to find an orbit of: said in the chain's words.
    c.findPeriodicOrbitAt(0.0079L, 0.081L);
    QTRY_VERIFY_WITH_TIMEOUT(found.count() == 4 && !c.periodicSearchPending(), 900000);
    QVERIFY2(!c.clickedPeriodicOrbit(), qPrintable(found.last().first().toString()));
    ChainRequest sea;
    sea.map = c.map();
    const ChainIdentification seaChain = identifyChain(chainRequestAt(sea, {0.0079L, 0.081L}));
    QVERIFY(seaChain.levels.front().rotation.verdict != OrbitVerdict::Regular);
    QVERIFY2(found.last().first().toString().contains(QString::fromStdString(seaChain.summary)),
             qPrintable(found.last().first().toString()));
  }

  // Finding 17: the rotation profile's plateaus had no p/q labels.  Core finds the plateaus (rotationPlateaus), the
  // plot names each; here they equal the runs of equal rationals read independently from `rotation --line --csv`.
  void finding17_theProfilesPlateausAreLabelled() {
    PortraitPanel panel;
    panel.resize(900, 600);
    panel.show();
    QVERIFY(QTest::qWaitForWindowExposed(&panel));
    panel.controller()->setPointBudget(10000);
    RotationProfilePanel& profile = *panel.profilePanel();
    QSignalSpy ready(&profile, &RotationProfilePanel::profileReady);
    profile.profile({-0.25L, 0.0L}, {0.06L, 0.0974L}, 120);
    QVERIFY(ready.wait(900000));
    QTemporaryDir dir;
    const QString csv = dir.filePath(QStringLiteral("cli.csv"));
    QString error;
    cliOutput({QStringLiteral("rotation"), QStringLiteral("--K"), QStringLiteral("0.1"),
               QStringLiteral("--line=-0.25,0:0.06,0.0974"), QStringLiteral("--points"), QStringLiteral("120"),
               QStringLiteral("--csv"), csv, QStringLiteral("--quiet")},
              &error);
    QFile file(csv);
    QVERIFY2(file.open(QIODevice::ReadOnly), qPrintable(error));
    QStringList rationals, verdicts;
    QList<double> rotations;
    for (const QByteArray& line : file.readAll().split('\n'))
      if (!line.startsWith('#') && !line.startsWith("index") && !line.isEmpty()) {
        const QList<QByteArray> f = line.split(',');  // index,x,y,rotation,digits,verdict,rational
        rotations << (f[3].isEmpty() ? std::nan("") : f[3].toDouble());
        verdicts << QString::fromUtf8(f[5]);
        rationals << QString::fromUtf8(f[6]);
      }
    QCOMPARE(rationals.size(), 120);
    // The plateaus read from the table: from a point naming p/q over the points that name it, or name nothing while
    // regular within 10⁻⁹ of p/q (the 6 islands' sub-island orbits: 13 digits, no rational named), at least 3.
    QStringList runs;
    for (int i = 0; i < rationals.size();) {
      if (rationals[i].isEmpty()) {
        ++i;
        continue;
      }
      const QStringList pq = rationals[i].split(QLatin1Char('/'));
      const double value = pq[0].toDouble() / pq[1].toDouble();
      int j = i;
      while (j < rationals.size() &&
             (rationals[j] == rationals[i] ||
              (rationals[j].isEmpty() && verdicts[j] == QStringLiteral("regular") && std::fabs(rotations[j] - value) <= 1e-9)))
        ++j;
      if (j - i >= 3) runs << rationals[i];
      i = j;
    }
    QVERIFY2(runs.contains(QStringLiteral("1/6")), qPrintable(runs.join(QLatin1Char(' '))));
    QVERIFY2(profile.plateauLabels() == runs,
             qPrintable(profile.plateauLabels().join(QLatin1Char(' ')) + QStringLiteral(" | ") + runs.join(QLatin1Char(' '))));

    // About an island's own centre: the period-6 orbit a click found, its member nearest the line.  Measuring about
    // the centre (−√K, 0) without an orbit drawn is the default; asking for an orbit before one is drawn is refused.
    PortraitController& c = *panel.controller();
    profile.aboutBox()->setCurrentIndex(1);
    QVERIFY(!profile.profile({0.05L, 0.0974L}, {0.07L, 0.0974L}, 40));
    QSignalSpy found(&c, &PortraitController::periodicOrbitFound);
    c.findPeriodicOrbitAt(0.06L, 0.0974L);
    QTRY_VERIFY_WITH_TIMEOUT(found.count() == 1 && !c.periodicSearchPending(), 900000);
    QVERIFY(c.clickedPeriodicOrbit());
    const PeriodicOrbit orbit = c.clickedPeriodicOrbit()->orbit;
    QCOMPARE(orbit.period, 6);
    const PhysicalPoint member = nearestMember(orbit, {0.06L, 0.0974L});
    const PhysicalPoint from{member.x - 0.004L, member.y}, to{member.x + 0.004L, member.y};
    QVERIFY(profile.profile(from, to, 40));
    QVERIFY(ready.wait(900000));
    QVERIFY(profile.lastRequest().about && profile.lastRequest().about->x == member.x &&
            profile.lastRequest().about->y == member.y);
    QCOMPARE(profile.lastRequest().power, std::uint64_t{6});
    // Independently: a regular start's rotation about the island is the one identifyChain measures at its level 1
    // (the rotation of Q⁶ about the chain's member), not the rotation about the centre (1/6 for the whole island).
    const RotationProfile* island = profile.currentProfile();
    QVERIFY(island && island->points.size() == 40);
    const RotationProfilePoint& p = island->points[25];
    QVERIFY(p.measure.verdict == OrbitVerdict::Regular);
    ChainRequest request;
    request.map = c.map();
    request.start = p.start;
    const ChainIdentification chain = identifyChain(request);
    QVERIFY2(chain.levels.size() >= 2, chain.summary.c_str());
    QVERIFY2(std::fabs(p.measure.value - chain.levels[1].rotation.rotation) < 1e-9,
             qPrintable(QStringLiteral("%1 vs %2").arg(p.measure.value, 0, 'g', 17).arg(chain.levels[1].rotation.rotation, 0, 'g', 17)));
    QVERIFY(std::fabs(p.measure.value - 1.0 / 6) > 1e-3);
    // And the CLI's `rotation --line … --about X,Y --period 6 --csv` writes the same rows.
    const QString gui = dir.filePath(QStringLiteral("gui-about.csv")), cliAbout = dir.filePath(QStringLiteral("cli-about.csv"));
    QVERIFY(profile.exportCsv(gui));
    const QString line = longText("--line=%.21Lg,%.21Lg", from.x, from.y) + longText(":%.21Lg,%.21Lg", to.x, to.y);
    cliOutput({QStringLiteral("rotation"), QStringLiteral("--K"), QStringLiteral("0.1"), line, QStringLiteral("--points"),
               QStringLiteral("40"), longText("--about=%.21Lg,%.21Lg", member.x, member.y),
               QStringLiteral("--period"), QStringLiteral("6"), QStringLiteral("--csv"), cliAbout, QStringLiteral("--quiet")},
              &error);
    const auto rows = [](const QString& path) {
      QFile f(path);
      f.open(QIODevice::ReadOnly);
      QStringList lines;
      for (const QByteArray& l : f.readAll().split('\n'))
        if ((!l.startsWith('#') || l.startsWith("# about") || l.startsWith("# period")) && !l.isEmpty())
          lines << QString::fromUtf8(l);
      return lines;
    };
    QCOMPARE(rows(gui).size(), 43);  // about, period, the header and 40 rows
    QCOMPARE(rows(gui), rows(cliAbout));
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

  // Finding 10: the spliced D's error was labelled by the GUI's own words ("bootstrap over segments", later
  // "spliced; subsets of orbits …") where `stats --short` names the subsets' error: both now print core's one
  // run summary's note (RunSummary::DErrorNote), for the spliced statistics and for the run alone.
  void finding10_theSplicedErrorIsNamedAsTheCliNamesIt() {
    QTemporaryDir dir;
    TrappingParameters p = archipelago::test::shortRun();
    p.T = 200'000;
    TrappingRunOptions o;
    o.threads = 1;
    const TrappingState run = runTrapping(startTrapping(p), o);
    const auto companion =
        std::make_shared<const TrappingState>(runTrapping(startTrapping(companionParameters(p, 1.0)), o));
    const RunSnapshotPtr spliced = makeSnapshot(1, run, {}, true, companion);
    QVERIFY2(spliced->companion, "the run and its companion did not splice");
    QVERIFY(spliced->tail);
    const RunSummary summary = summarizeRun(spliced->statistics, spliced->tail.get());
    QVERIFY(summary.spliced);
    StatisticsView view;
    view.showSnapshot(*spliced);
    QTextDocument shown;
    shown.setHtml(view.summaryText());
    const QString gui = shown.toPlainText();
    const QString note = QString::fromStdString(summary.DErrorNote);
    QVERIFY2(gui.contains(note), qPrintable(gui + QStringLiteral(" | ") + note));
    if (summary.errorSource == DErrorSource::subsets)
      QVERIFY2(!gui.contains(QStringLiteral("bootstrap")), qPrintable(gui));
    // The CLI's D line for the same two files says the same words.
    const std::string runFile = dir.filePath(QStringLiteral("run.json")).toStdString();
    saveRunFile(runFile, run);
    saveRunFile(companionRunFile(runFile), *companion);
    QString error;
    const QString out = cliOutput({QStringLiteral("stats"), QString::fromStdString(runFile), QStringLiteral("--short"),
                                   QString::fromStdString(companionRunFile(runFile).string())}, &error);
    QVERIFY2(!out.isEmpty(), qPrintable(error));
    const QString dLine = lineAfter(out, QStringLiteral("D           "));
    QVERIFY2(dLine.contains(note), qPrintable(dLine + QStringLiteral(" | ") + note));

    // The run alone: the bootstrap's words, the same in both.
    const RunSnapshotPtr alone = makeSnapshot(2, run, {}, true);
    const RunSummary own = summarizeRun(alone->statistics, alone->tail.get());
    view.showSnapshot(*alone);
    shown.setHtml(view.summaryText());
    QVERIFY2(shown.toPlainText().contains(QString::fromStdString(own.DErrorNote)), qPrintable(shown.toPlainText()));
  }

  // Finding 19: the Statistics page showed neither the fitted γ_P nor the tail's verdict, which `stats` prints.
  // The same run file, opened in the window and given to the CLI: the same words and digits (one core summary).
  void finding19_gammaPAndTheVerdictAsTheCliPrintsThem() {
    QTemporaryDir dir;
    TrappingParameters p = archipelago::test::shortRun();
    p.T = 200'000;
    TrappingRunOptions o;
    o.threads = 1;
    const QString runFile = dir.filePath(QStringLiteral("run.json"));
    saveRunFile(runFile.toStdString(), runTrapping(startTrapping(p), o));
    QString error;
    const QString out = cliOutput({QStringLiteral("stats"), runFile}, &error);
    QVERIFY2(!out.isEmpty(), qPrintable(error));
    QString gamma = lineAfter(out, QStringLiteral("gamma_P     "));
    QVERIFY2(!gamma.isEmpty(), qPrintable(out));  // this run has a tail fit
    gamma = gamma.left(gamma.indexOf(QStringLiteral(" (P_t")));
    const QString verdict = lineAfter(out, QStringLiteral("verdict     "));
    QVERIFY(!verdict.isEmpty());

    MainWindow w;
    w.setConfirmations(false);
    QVERIFY(w.statisticsView()->tailText().isEmpty());
    QVERIFY2(w.openRunFile(runFile, &error), qPrintable(error));
    QVERIFY(waitForStatus(w, RunStatus::finished, 900000));
    QTRY_VERIFY_WITH_TIMEOUT(w.latestSnapshot() && w.latestSnapshot()->tail, 900000);
    w.refreshNow();
    const QString tail = w.statisticsView()->tailText();
    QVERIFY2(tail.contains(QStringLiteral("γP")) || tail.contains(QStringLiteral("γ")), qPrintable(tail));
    QVERIFY2(tail.contains(gamma), qPrintable(tail + QStringLiteral(" | CLI: ") + gamma));
    QVERIFY2(tail.contains(verdict), qPrintable(tail + QStringLiteral(" | CLI: ") + verdict));
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
