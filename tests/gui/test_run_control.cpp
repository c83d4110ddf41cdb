// Runs from the GUI: the plots show core's statistics; pause, resume and stop keep the exact state; closing
// mid-run leaves a loadable checkpoint (offscreen platform).
#include <QAction>
#include <QFileInfo>
#include <QSignalSpy>

#include <cmath>

#include "GuiTestSupport.hpp"
#include "StatisticsView.hpp"
#include "plots/StatisticsPlot.hpp"
#include "runfile/RunFile.hpp"
#include "stats/TrappingStatistics.hpp"

using archipelago::TrappingParameters;
using archipelago::TrappingState;
using archipelago::ui::MainWindow;
using archipelago::ui::PlotKind;
using archipelago::ui::RunStatus;

namespace {

/// The same run, headless, straight through core.
TrappingState headless(const TrappingParameters& p) {
  archipelago::TrappingRunOptions options;
  options.threads = 1;
  return archipelago::runTrapping(archipelago::startTrapping(p), options);
}

archipelago::TrappingStatistics statisticsOf(const TrappingState& s) {
  std::vector<std::uint64_t> orbitsPerSubset(s.params.subsets, 0);
  for (std::uint64_t i = 0; i < s.params.M; ++i) orbitsPerSubset[i % s.params.subsets] += 1;
  return archipelago::computeStatistics(s.subsets, orbitsPerSubset, s.blocksDone, s.params.q);
}

bool waitForStatus(const MainWindow& w, RunStatus s, int ms = 20000) { return QTest::qWaitFor([&] { return w.runStatus() == s; }, ms); }

}  // namespace

class TestRunControl : public QObject {
  Q_OBJECT
 private Q_SLOTS:
  void plotsShowCoresStatistics() {
    MainWindow window;
    window.setConfirmations(false);
    window.show();
    const TrappingParameters p = archipelago::test::shortRun();
    window.parameterPanel()->setParameters(p, 2);
    QVERIFY(window.startRun());
    QCOMPARE(window.runStatus(), RunStatus::running);
    QVERIFY(!window.runAction()->isEnabled());
    QVERIFY(waitForStatus(window, RunStatus::finished));
    QTRY_VERIFY(window.statisticsView()->refreshCount() > 0);

    const TrappingState expectedState = headless(p);
    const auto snapshot = window.latestSnapshot();
    QVERIFY(snapshot);
    QVERIFY(snapshot->state.finished());
    QVERIFY(snapshot->state.subsets == expectedState.subsets);  // threads and chunks do not matter
    const auto expected = statisticsOf(expectedState);
    QVERIFY(expected.f.x.size() > 10);
    for (archipelago::ui::StatisticsPlot* plot : window.statisticsView()->plots()) {
      const archipelago::Series& want = archipelago::ui::seriesOf(expected, plot->kind());
      const archipelago::Series& got = plot->data();
      QCOMPARE(got.x, want.x);
      QCOMPARE(got.value, want.value);
      QCOMPARE(got.error, want.error);
      // What is drawn: every point a log axis can show, and nothing else.
      const bool logY = plot->kind() != PlotKind::localExponent;
      QVector<QPointF> drawable;
      for (std::size_t i = 0; i < want.x.size(); ++i)
        if (std::isfinite(want.x[i]) && std::isfinite(want.value[i]) && want.x[i] > 0 && (!logY || want.value[i] > 0))
          drawable.append(QPointF(want.x[i], want.value[i]));
      QCOMPARE(plot->plottedPoints(), drawable);
    }
    QVERIFY(!window.statisticsView()->plot(PlotKind::f)->plottedPoints().isEmpty());
  }

  void pauseResumeAndStopKeepTheExactState() {
    MainWindow window;
    window.setConfirmations(false);
    window.show();
    const TrappingParameters p = archipelago::test::mediumRun();
    window.parameterPanel()->setParameters(p, 2);
    QVERIFY(window.startRun());
    QTRY_VERIFY_WITH_TIMEOUT(window.latestSnapshot() != nullptr, 10000);

    QVERIFY(window.pauseAction()->isEnabled());
    QVERIFY(window.pauseRun());
    QVERIFY(waitForStatus(window, RunStatus::paused));
    const auto paused = window.latestSnapshot();
    QVERIFY(paused);
    QVERIFY(paused->state.blocksDone > 0);
    QVERIFY(!paused->state.finished());
    QVERIFY(window.resumeAction()->isEnabled());
    QVERIFY(window.runAction()->isEnabled());
    // The parameters cannot change under a paused run's state... but they are editable again.
    QVERIFY(!window.parameterPanel()->field(QStringLiteral("K"))->isReadOnly());

    QVERIFY(window.resumeRun());
    QCOMPARE(window.runStatus(), RunStatus::running);
    QTRY_VERIFY_WITH_TIMEOUT(window.latestSnapshot() != nullptr, 10000);
    QVERIFY(window.stopRun());
    QVERIFY(waitForStatus(window, RunStatus::stopped));
    const auto stopped = window.latestSnapshot();
    QVERIFY(stopped->state.blocksDone >= paused->state.blocksDone);
    QVERIFY(window.resumeAction()->isEnabled());

    // Resume to the end: the result is bit-identical to one uninterrupted run.
    QVERIFY(window.resumeRun());
    QVERIFY(waitForStatus(window, RunStatus::finished, 25000));
    const TrappingState expected = headless(p);
    const TrappingState& got = window.latestSnapshot()->state;
    QVERIFY(got.subsets == expected.subsets);
    QVERIFY(got.orbits == expected.orbits);
    QVERIFY(got.longest == expected.longest);
    QVERIFY(!window.resumeAction()->isEnabled());
  }

  void closingMidRunKeepsALoadableCheckpoint() {
    QFile::remove(MainWindow::checkpointPath());
    const TrappingParameters p = archipelago::test::mediumRun();
    {
      MainWindow window;
      window.setConfirmations(false);
      window.show();
      window.parameterPanel()->setParameters(p, 2);
      QVERIFY(window.startRun());
      QTRY_VERIFY_WITH_TIMEOUT(window.latestSnapshot() != nullptr, 10000);
      QVERIFY(!window.close());  // it stops at the next chunk boundary first
      QTRY_VERIFY_WITH_TIMEOUT(!window.isVisible(), 10000);
      QCOMPARE(window.runStatus(), RunStatus::stopped);
    }
    QVERIFY(QFileInfo::exists(MainWindow::checkpointPath()));
    const TrappingState kept = archipelago::loadRunFile(MainWindow::checkpointPath().toStdString());
    QVERIFY(kept.params == p);
    QVERIFY(kept.blocksDone > 0);
    QVERIFY(!kept.finished());

    // The next start offers it, and resuming it finishes the same run.
    MainWindow next;
    next.setConfirmations(false);
    auto* banner = next.findChild<QWidget*>(QStringLiteral("checkpointBanner"));
    QVERIFY(banner);
    QVERIFY(!banner->isHidden());
    QVERIFY(next.openRunFile(MainWindow::checkpointPath()));
    QVERIFY(waitForStatus(next, RunStatus::paused));
    QCOMPARE(next.latestSnapshot()->state.blocksDone, kept.blocksDone);
    QVERIFY(next.resumeRun());
    QVERIFY(waitForStatus(next, RunStatus::finished, 25000));
    QVERIFY(next.latestSnapshot()->state.subsets == headless(p).subsets);
  }
};

ARCHIPELAGO_GUI_TEST_MAIN(TestRunControl)
#include "test_run_control.moc"
