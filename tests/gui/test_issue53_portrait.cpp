// Issue 53: the findings that live in the phase portrait (7, 13, 15, 16), fixed in the portrait's layers after its
// split by layer (issue 51).  One test per finding, named after it; each failed before its fix.  The zoom limit was
// also looked at in screenshots at 1280×800 and 1920×1080 (the closing note of the issue).
#include <QSignalSpy>
#include <QtTest>
#include <qwt_plot.h>
#include <qwt_scale_div.h>
#include <qwt_scale_draw.h>
#include <qwt_text.h>

#include <algorithm>
#include <cmath>

#include "GuiTestSupport.hpp"
#include "core/periodic/PeriodicOrbitFinder.hpp"
#include "core/view/DeepestZoom.hpp"
#include "ui/portrait/PortraitController.hpp"
#include "ui/portrait/PortraitPanel.hpp"
#include "ui/portrait/PortraitView.hpp"

using namespace archipelago;
using namespace archipelago::ui;

namespace {

/// The period-6 orbit of K = 0.1 about the centre's chain of six: elliptic or hyperbolic.
PeriodicOrbit sixChain(bool stable) {
  PeriodicOrbitSearch search;
  search.period = 6;
  search.near = {0.0509L, 0.0974L};
  search.searchRadius = 0.1L;
  for (const PeriodicOrbit& o : findSymmetricPeriodicOrbits(0.1L, search))
    if (o.classification().stable() == stable) return o;
  return {};
}

/// The labels of an axis's major ticks, as numbers, with the ticks.
struct AxisTicksShown {
  QList<double> ticks;
  std::vector<double> labels;
};
AxisTicksShown ticksOf(QwtPlot& plot, QwtPlot::Axis axis) {
  AxisTicksShown shown;
  shown.ticks = plot.axisScaleDiv(axis).ticks(QwtScaleDiv::MajorTick);
  for (const double t : shown.ticks) shown.labels.push_back(plot.axisScaleDraw(axis)->label(t).text().toDouble());
  return shown;
}

}  // namespace

class TestIssue53Portrait : public QObject {
  Q_OBJECT
 private Q_SLOTS:
  // Finding 7: at the deepest zoom (3·10⁻¹³ wide) the ticks were not round and unevenly spaced (−1.268, −0.7676, …,
  // the last interval 0.456), and further zoom clicks silently did nothing.
  void finding7_theDeepestZoomSaysSoAndHasRoundEvenTicks() {
    PortraitPanel panel;
    panel.resize(800, 600);
    panel.show();
    QVERIFY(QTest::qWaitForWindowExposed(&panel));
    PortraitController& c = *panel.controller();
    c.setPointBudget(10000);
    QSignalSpy messages(&c, &PortraitController::statusMessage);
    for (int i = 0; i < 80 && !atDeepestZoom(c.viewport()); ++i) c.zoomIn();
    QVERIFY(atDeepestZoom(c.viewport()));
    const Viewport deepest = c.viewport();
    messages.clear();
    c.zoomIn();  // a click that cannot zoom further
    QCOMPARE(c.viewport(), deepest);
    QVERIFY(!messages.isEmpty());
    const QString said = messages.last().first().toString();
    QVERIFY2(said.startsWith(QStringLiteral("Deepest zoom")) && said.contains(QStringLiteral("2^52")), qPrintable(said));
    QwtPlot* plot = panel.view()->findChild<QwtPlot*>();
    QVERIFY(plot);
    plot->replot();
    for (const QwtPlot::Axis axis : {QwtPlot::xBottom, QwtPlot::yLeft}) {
      const AxisTicksShown shown = ticksOf(*plot, axis);
      QVERIFY(shown.ticks.size() >= 3);
      const double step = shown.ticks[1] - shown.ticks[0], labelStep = shown.labels[1] - shown.labels[0];
      QVERIFY(labelStep > 0);
      for (int i = 0; i + 1 < shown.ticks.size(); ++i) {
        // Evenly spaced (to the round-off of a coordinate near 0.3: 10⁻³ of a step) and round labels: whole
        // multiples of their step, written with no noise digit.
        QVERIFY2(std::fabs(shown.ticks[i + 1] - shown.ticks[i] - step) < 1e-2 * step,
                 qPrintable(QStringLiteral("tick %1: %2 after a step of %3").arg(i).arg(shown.ticks[i + 1] - shown.ticks[i]).arg(step)));
        QCOMPARE(shown.labels[i + 1] - shown.labels[i], labelStep);
      }
      for (const double label : shown.labels) {
        const double k = label / labelStep;
        QVERIFY2(std::fabs(k - std::round(k)) < 1e-9, qPrintable(QString::number(label)));
      }
    }
  }

  // Finding 13: after K 0.1 → 0.15 → 0.1 the period-13 orbit came back, but its manifolds were the fixed point's.
  void finding13_aKRoundTripBringsBackTheManifoldsOrbit() {
    PortraitPanel panel;
    panel.resize(800, 600);
    panel.show();
    QVERIFY(QTest::qWaitForWindowExposed(&panel));
    PortraitController& c = *panel.controller();
    c.setPointBudget(10000);
    const PeriodicOrbit partner = sixChain(false);
    QCOMPARE(partner.period, 6);
    c.showPeriodicOrbit(partner);
    c.setManifoldOrbit(partner);
    const MapParameters first = c.map();
    MapParameters other = first;
    other.K = 0.15;
    QVERIFY(c.setMap(other, c.Xr()));
    QVERIFY(!c.manifoldOrbit());
    QVERIFY(c.setMap(first, c.Xr()));
    QVERIFY(c.shownPeriodicOrbit());
    QVERIFY(c.manifoldOrbit());
    QCOMPARE(c.manifoldOrbit()->period, 6);
    QVERIFY(c.manifoldsShown());
    QTRY_VERIFY_WITH_TIMEOUT(c.manifoldsSettled() && c.manifolds(), 900000);
  }

  // Finding 15: stale legend entries piled up (5 layers listed in an FLI view 7·10⁻⁸ wide containing none of them).
  void finding15_theLegendListsOnlyWhatTheViewShows() {
    PortraitPanel panel;
    panel.resize(800, 600);
    panel.show();
    QVERIFY(QTest::qWaitForWindowExposed(&panel));
    PortraitController& c = *panel.controller();
    c.setPointBudget(10000);
    c.showPeriodicOrbit(sixChain(true));
    c.setManifoldsShown(true);
    QTRY_VERIFY_WITH_TIMEOUT(c.manifoldsSettled() && c.manifolds(), 900000);
    const auto legend = [&] { return panel.view()->legendText(); };
    QVERIFY2(legend().contains(QStringLiteral("periodic orbit of period 6")), qPrintable(legend()));
    QVERIFY2(legend().contains(QStringLiteral("manifold")), qPrintable(legend()));
    // A view 7·10⁻⁸ wide at the elliptic fixed point: neither the six's points nor the manifolds are in it.
    QVERIFY(c.goTo(-std::sqrt(0.1L), 0, 7e-8L));
    QTRY_VERIFY_WITH_TIMEOUT(c.manifoldsSettled(), 900000);
    QVERIFY2(!legend().contains(QStringLiteral("periodic orbit")), qPrintable(legend()));
    QVERIFY2(!legend().contains(QStringLiteral("manifold")), qPrintable(legend()));
    c.back();  // the whole box again: both listed again
    QTRY_VERIFY_WITH_TIMEOUT(c.manifoldsSettled() && legend().contains(QStringLiteral("manifold")), 900000);
    QVERIFY2(legend().contains(QStringLiteral("periodic orbit of period 6")), qPrintable(legend()));
  }

  // Finding 16: the manifolds' "lobe area" label was drawn under the launched orbits (after a session reopen), cut
  // to "obe area …" in the exported PNG.
  void finding16_theLobeAreaIsOverTheOrbitsAndInsideTheCanvas() {
    PortraitPanel panel;
    panel.resize(800, 600);
    panel.show();
    QVERIFY(QTest::qWaitForWindowExposed(&panel));
    PortraitController& c = *panel.controller();
    c.setPointBudget(10000);
    c.setManifoldsShown(true);
    QVERIFY(c.launchOrbit(0.3L, -0.2L) != 0);  // an orbit of the sea, over the lobes
    QTRY_VERIFY_WITH_TIMEOUT(c.manifoldsSettled() && c.flux() && c.orbitsSettled(), 900000);
    QVERIFY2(c.flux()->flux.has_value(), qPrintable(c.flux()->error));
    const PointsItem* label = nullptr;
    for (const PortraitLayer layer : {PortraitLayer::lobes, PortraitLayer::lobeLabel})
      for (const QwtPlotItem* item : panel.view()->layerItems(layer))
        if (item->rtti() == PointsItem::kRtti && !static_cast<const PointsItem*>(item)->label().isEmpty())
          label = static_cast<const PointsItem*>(item);
    QVERIFY(label);
    QVERIFY(label->label().startsWith(QStringLiteral("lobe area ")));
    const auto& orbits = panel.view()->layerItems(PortraitLayer::launchedOrbits);
    QVERIFY(!orbits.empty());
    for (const QwtPlotItem* orbit : orbits) QVERIFY2(label->z() > orbit->z(), qPrintable(QString::number(label->z())));
    // Whole inside the canvas, wherever the lobe is: at the right edge it moves left, at the left edge right.
    const QRectF canvas(0, 0, 400, 300);
    const QSizeF size(120, 18);
    for (const QPointF anchor : {QPointF(395, 150), QPointF(-30, 150), QPointF(200, 299), QPointF(200, 2)}) {
      const QRectF at = PointsItem::labelRect(anchor, size, canvas);
      QVERIFY2(canvas.contains(at), qPrintable(QStringLiteral("%1,%2 %3×%4").arg(at.x()).arg(at.y()).arg(at.width()).arg(at.height())));
      QCOMPARE(at.size(), size);
    }
    QCOMPARE(PointsItem::labelRect({100, 150}, size, canvas).topLeft(), QPointF(108, 141));  // right of it, as before
  }
};

ARCHIPELAGO_GUI_TEST_MAIN(TestIssue53Portrait)
#include "test_issue53_portrait.moc"
