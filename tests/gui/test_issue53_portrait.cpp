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
};

ARCHIPELAGO_GUI_TEST_MAIN(TestIssue53Portrait)
#include "test_issue53_portrait.moc"
