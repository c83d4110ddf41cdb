// Runs from the GUI: the plots show core's statistics; pause, resume and stop keep the exact state; closing
// mid-run leaves a loadable checkpoint (offscreen platform).  No assertion depends on timing: runs that must
// be caught mid-way are far too long to finish, and each state is compared with a headless run of core
// stopped at the same block.
#include <QAction>
#include <QFileInfo>

#include <cmath>

#include "GuiTestSupport.hpp"
#include "ui/window/StatisticsView.hpp"
#include "ui/plots/StatisticsPlot.hpp"
#include "core/runfile/RunFile.hpp"
#include "core/stats/RunStatistics.hpp"
#include "core/stats/StatisticsTable.hpp"

using archipelago::TrappingParameters;
using archipelago::TrappingState;
using archipelago::ui::MainWindow;
using archipelago::Statistic;
using archipelago::ui::RunStatus;

using archipelago::test::waitForProgress;
using archipelago::test::waitForStatus;

namespace {

/// The same run, headless, straight through core, for its first `blocks` blocks (all of them by default).
/// Orbits do not depend on T, so a run of T = blocks is the run of T' > blocks stopped at `blocks`.
TrappingState headless(TrappingParameters p, std::uint64_t blocks = 0) {
  if (blocks) p.T = blocks;
  return archipelago::runTrapping(archipelago::startTrapping(p), archipelago::TrappingRunOptions{});
}

/// The state of the run is exactly core's after as many blocks.
bool sameAsHeadless(const TrappingState& got) {
  const TrappingState want = headless(got.params, got.blocksDone);
  return got.blocksDone == want.blocksDone && got.orbits == want.orbits && got.subsets == want.subsets &&
         got.longest == want.longest;
}



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
    QVERIFY(snapshot->state.subsets == expectedState.subsets);  // threads, chunks and kernel do not matter
    const auto expected = archipelago::statisticsOf(expectedState);
    QVERIFY(expected.f.x.size() > 10);
    for (archipelago::ui::StatisticsPlot* plot : window.statisticsView()->plots()) {
      const archipelago::Series& want = archipelago::seriesOf(expected, plot->statistic());
      const archipelago::Series& got = plot->data();
      QCOMPARE(got.x, want.x);
      QCOMPARE(got.value, want.value);
      QCOMPARE(got.error, want.error);
      // What is drawn: every point a log axis can show, and nothing else.
      const bool logY = plot->statistic() != Statistic::localExponent;
      QVector<QPointF> drawable;
      for (std::size_t i = 0; i < want.x.size(); ++i)
        if (std::isfinite(want.x[i]) && std::isfinite(want.value[i]) && want.x[i] > 0 && (!logY || want.value[i] > 0))
          drawable.append(QPointF(want.x[i], want.value[i]));
      QCOMPARE(plot->plottedPoints(), drawable);
    }
    QVERIFY(!window.statisticsView()->plot(Statistic::f)->plottedPoints().isEmpty());
    QVERIFY(window.statisticsView()->summaryText().contains(QStringLiteral("segments")));
  }

  void smallKRunsCarryTheTheory() {
    MainWindow window;
    window.setConfirmations(false);
    QVERIFY(window.parameterPanel()->applyPreset(QStringLiteral("K = 0 (fig. 3b)")));
    auto p = *window.parameterPanel()->parameters();
    p.T = 200'000;  // enough segments for f_t out to t ~ 100
    window.parameterPanel()->setParameters(p, 2);
    QVERIFY(window.startRun());
    QVERIFY(waitForStatus(window, RunStatus::finished));
    QTRY_VERIFY(window.statisticsView()->refreshCount() > 0);
    // t^-7 over f_t (§4); nothing over P_t; nothing at all for K = 0.1 (the first test).
    QVERIFY(window.statisticsView()->plot(Statistic::f)->theoryCurveCount() >= 1);
    QCOMPARE(window.statisticsView()->plot(Statistic::P)->theoryCurveCount(), 0);
  }

  void pauseResumeAndStopKeepTheExactState() {
    MainWindow window;
    window.setConfirmations(false);
    window.show();
    const TrappingParameters p = archipelago::test::endlessRun();
    window.parameterPanel()->setParameters(p, 2);
    QVERIFY(window.startRun());
    QVERIFY(waitForProgress(window, 0));
    QVERIFY(window.parameterPanel()->field(QStringLiteral("K"))->isReadOnly());  // no edits under a run

    QVERIFY(window.pauseAction()->isEnabled());
    QVERIFY(window.pauseRun());
    QVERIFY(waitForStatus(window, RunStatus::paused));
    const auto paused = window.latestSnapshot();
    QVERIFY(paused);
    QVERIFY(paused->state.blocksDone > 0);
    QVERIFY(sameAsHeadless(paused->state));
    QVERIFY(window.resumeAction()->isEnabled());
    QVERIFY(window.runAction()->isEnabled());
    QVERIFY(!window.pauseAction()->isEnabled());
    QVERIFY(window.parameterPanel()->field(QStringLiteral("K"))->isReadOnly());  // the paused run's parameters

    QVERIFY(window.resumeRun());
    QCOMPARE(window.runStatus(), RunStatus::running);
    QVERIFY(!window.resumeAction()->isEnabled());
    QVERIFY(waitForProgress(window, paused->state.blocksDone));
    QVERIFY(window.stopRun());
    QVERIFY(waitForStatus(window, RunStatus::stopped));
    const auto stopped = window.latestSnapshot();
    QVERIFY(stopped->state.blocksDone > paused->state.blocksDone);
    QVERIFY(sameAsHeadless(stopped->state));  // resumed where it paused, bit for bit
    QVERIFY(!window.resumeAction()->isEnabled());  // Stop is final; Pause is the way to continue later
    QVERIFY(!window.stopAction()->isEnabled());
  }

  void closingMidRunKeepsALoadableCheckpoint() {
    QFile::remove(MainWindow::checkpointPath());
    const TrappingParameters p = archipelago::test::endlessRun();
    {
      MainWindow window;
      window.setConfirmations(false);
      window.show();
      window.parameterPanel()->setParameters(p, 2);
      QVERIFY(window.startRun());
      QVERIFY(waitForProgress(window, 0));
      QVERIFY(!window.close());  // it stops at the next chunk boundary first
      QTRY_VERIFY_WITH_TIMEOUT(!window.isVisible(), 900000);
      QCOMPARE(window.runStatus(), RunStatus::stopped);
    }
    QVERIFY(QFileInfo::exists(MainWindow::checkpointPath()));
    const TrappingState kept = archipelago::loadRunFile(MainWindow::checkpointPath().toStdString());
    QVERIFY(kept.params == p);
    QVERIFY(kept.blocksDone > 0);
    QVERIFY(sameAsHeadless(kept));

    // The next start offers it; opening and resuming it continues the same run.
    MainWindow next;
    next.setConfirmations(false);
    auto* banner = next.findChild<QWidget*>(QStringLiteral("checkpointBanner"));
    QVERIFY(banner);
    QVERIFY(!banner->isHidden());
    QVERIFY(next.openRunFile(MainWindow::checkpointPath()));
    QVERIFY(waitForStatus(next, RunStatus::paused));
    QCOMPARE(next.latestSnapshot()->state.blocksDone, kept.blocksDone);
    QVERIFY(next.resumeRun());
    QVERIFY(waitForProgress(next, kept.blocksDone));
    QVERIFY(next.stopRun());
    QVERIFY(waitForStatus(next, RunStatus::stopped));
    QVERIFY(sameAsHeadless(next.latestSnapshot()->state));
  }
};

ARCHIPELAGO_GUI_TEST_MAIN(TestRunControl)
#include "test_run_control.moc"
