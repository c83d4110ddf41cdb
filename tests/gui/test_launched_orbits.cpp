// Issue #23, finding 5: a session with many launched orbits froze the GUI — PortraitController::launchOrbit rebuilt
// every earlier orbit on each launch, on the GUI thread (1000 orbits: 34.6 s and 1.4 GB).  Now each orbit is traced
// once, off the GUI thread, and added as one item; their number (and so their points) is bounded by the session
// codec's own kMaxSessionOrbits, which the GUI shares.
#include <QElapsedTimer>
#include <QSignalSpy>
#include <QTimer>
#include <QVBoxLayout>
#include <QtTest>

#include <algorithm>

#include "GuiTestSupport.hpp"
#include "ui/portrait/LaunchedOrbits.hpp"
#include "ui/portrait/PortraitController.hpp"
#include "ui/portrait/PortraitView.hpp"

using archipelago::MapParameters;
using archipelago::SessionPortrait;
using archipelago::ui::kMaxLaunchedOrbits;
using archipelago::ui::PortraitController;
using archipelago::ui::PortraitLayer;
using archipelago::ui::PortraitView;

namespace {
struct Portrait {
  QWidget host;
  PortraitController* controller = nullptr;
  Portrait() {
    auto* layout = new QVBoxLayout(&host);
    controller = new PortraitController(&host);
    layout->addWidget(controller->view());
    controller->setPointBudget(1'000'000);
  }
};
}  // namespace

class TestLaunchedOrbits : public QObject {
  Q_OBJECT
 private Q_SLOTS:
  void finding5_aSessionFullOfOrbitsKeepsTheGuiResponsive() {
    static_assert(kMaxLaunchedOrbits == archipelago::kMaxSessionOrbits, "one bound for the GUI and the codec");
    QCOMPARE(kMaxLaunchedOrbits, std::size_t{500});
    Portrait p;
    p.host.resize(400, 400);
    p.host.show();
    QVERIFY(QTest::qWaitForWindowExposed(&p.host));
    SessionPortrait state;
    state.mode = archipelago::PortraitMode::Orbits;
    for (std::size_t i = 0; i < kMaxLaunchedOrbits; ++i)
      state.orbits.push_back({-0.55 + 0.5 * static_cast<double>(i) / kMaxLaunchedOrbits, 0.01});
    // The event loop's longest gap while the orbits arrive: a 10 ms timer measures it.
    QElapsedTimer clock;
    qint64 last = 0, longest = 0;
    QTimer tick;
    tick.setInterval(10);
    int ticks = 0;
    QObject::connect(&tick, &QTimer::timeout, [&] {
      const qint64 now = clock.elapsed();
      longest = std::max(longest, now - last);
      last = now;
      ++ticks;
    });
    clock.start();
    p.controller->restoreSession(state, MapParameters{0.1, -0.8, 0.5}, 0.02);
    // It only queues work: no orbit is traced inside the call on the GUI thread (results come back through queued
    // signals, so none can be drawn before the event loop runs).  Said without a clock: a bound in milliseconds fails
    // on a loaded machine (this one did, beside two busy loops, on main's build too).
    QCOMPARE(p.controller->view()->layerItems(PortraitLayer::launchedOrbits).size(), std::size_t{0});
    QCOMPARE(p.controller->orbitCount(), static_cast<int>(kMaxLaunchedOrbits));
    last = clock.elapsed();
    tick.start();
    QTRY_COMPARE_WITH_TIMEOUT(p.controller->view()->layerItems(PortraitLayer::launchedOrbits).size(), kMaxLaunchedOrbits,
                              900000);
    tick.stop();
    // Every delivery adds one item; redraws are coalesced.  The longest gap of the event loop is printed, not bounded:
    // a wall-clock bound (4 s until issue 53) fails on a busy machine; where the work runs is asserted above.
    qInfo("longest gap of the event loop %lld ms over %d ticks", static_cast<long long>(longest), ticks);
    for (const auto& o : p.controller->launchedOrbits()) {
      QVERIFY(o.points);
      QCOMPARE(o.points->size(), std::size_t{archipelago::ui::kLaunchedOrbitSteps + 1});
    }
  }

  void finding5_earlierOrbitsAreNotRecomputedAndTheCountIsBounded() {
    Portrait p;
    p.host.resize(300, 300);
    p.host.show();
    QVERIFY(QTest::qWaitForWindowExposed(&p.host));
    PortraitController& c = *p.controller;
    QVERIFY(c.launchOrbit(-0.3, 0.05) != 0);
    QTRY_COMPARE(c.view()->layerItems(PortraitLayer::launchedOrbits).size(), std::size_t{1});
    const auto firstPoints = c.launchedOrbits()[0].points;
    const auto* firstItem = c.view()->layerItems(PortraitLayer::launchedOrbits)[0];
    QVERIFY(c.launchOrbit(-0.25, 0.05) != 0);
    QTRY_COMPARE(c.view()->layerItems(PortraitLayer::launchedOrbits).size(), std::size_t{2});
    // The first orbit's points and item are the same objects: nothing of it was computed or drawn again.
    QCOMPARE(c.launchedOrbits()[0].points.get(), firstPoints.get());
    QCOMPARE(c.view()->layerItems(PortraitLayer::launchedOrbits)[0], firstItem);
    // At the bound a launch is refused with a message, never queued.
    c.clearOrbits();
    for (std::size_t i = 0; i < kMaxLaunchedOrbits; ++i) QVERIFY(c.launchOrbit(-0.3, 0.05, 10) != 0);
    QSignalSpy messages(&c, &PortraitController::statusMessage);
    QCOMPARE(c.launchOrbit(-0.3, 0.05, 10), quint64{0});
    QCOMPARE(c.orbitCount(), static_cast<int>(kMaxLaunchedOrbits));
    QVERIFY(messages.last().first().toString().contains(QString::number(kMaxLaunchedOrbits)));
    c.clearOrbits();  // the queued work goes with them
    QCOMPARE(c.orbitCount(), 0);
  }
};

ARCHIPELAGO_GUI_TEST_MAIN(TestLaunchedOrbits)
#include "test_launched_orbits.moc"
