// The run controller's state machine, and what a new user hit (issue #13, findings 1, 5, 6, 15; deliverable 2):
// every transition of the table against an independent list, a run that finishes while the quit question is
// open, discarding unsaved work always asks, the panel shows (read-only) the parameters of a resumable run,
// Stop is final, a stale-plots note, a rate only while computing.  No assertion depends on timing: runs that
// must be caught mid-way are far too long to finish (GuiTestSupport's endlessRun()).
#include <QAction>
#include <QFileInfo>
#include <QLabel>
#include <QStatusBar>

#include <set>
#include <tuple>
#include <vector>

#include "GuiTestSupport.hpp"
#include "core/atlas/BoxIslandCheck.hpp"
#include "core/runfile/RunFile.hpp"
#include "core/run/TrappingRun.hpp"
#include "ui/run/RunController.hpp"
#include "ui/window/StatisticsView.hpp"
#include "ui/segments/LongSegmentsPanel.hpp"
#include "ui/segments/LongestSegmentsModel.hpp"

using archipelago::TrappingParameters;
using archipelago::ui::MainWindow;
using archipelago::ui::RunAnswer;
using archipelago::ui::RunEvent;
using archipelago::ui::RunQuestion;
using archipelago::ui::RunStatus;

using archipelago::test::waitForProgress;
using archipelago::test::waitForStatus;

namespace {



/// Answers the controller's questions from a script and records them.
struct ScriptedAnswers {
  std::vector<RunQuestion::Kind> asked;
  RunAnswer answer = RunAnswer::cancel;
  std::function<void()> beforeAnswer;  // e.g. wait for the run to end while "the dialog is open"
  void install(MainWindow& w) {
    w.runController()->setAsk([this](const RunQuestion& q) {
      asked.push_back(q.kind);
      if (beforeAnswer) beforeAnswer();
      return answer;
    });
  }
};

}  // namespace

class TestRunController : public QObject {
  Q_OBJECT
 private Q_SLOTS:
  void init() { QFile::remove(MainWindow::checkpointPath()); }

  /// The table, written out independently of runTransition(): every (state, event) pair not listed is refused.
  void everyTransitionOfTheTable() {
    using S = RunStatus;
    using E = RunEvent;
    const std::vector<std::tuple<S, E, S>> allowed = {
        {S::idle, E::start, S::running},        {S::paused, E::start, S::running},
        {S::stopped, E::start, S::running},     {S::finished, E::start, S::running},
        {S::failed, E::start, S::running},      {S::running, E::pause, S::pausing},
        {S::paused, E::resume, S::running},     {S::running, E::stop, S::stopping},
        {S::pausing, E::stop, S::stopping},     {S::paused, E::stop, S::stopped},
        {S::pausing, E::workerPaused, S::paused},  {S::running, E::workerPaused, S::paused},  // an analysed file
        {S::stopping, E::workerStopped, S::stopped},
        {S::running, E::workerFinished, S::finished}, {S::pausing, E::workerFinished, S::finished},
        {S::stopping, E::workerFinished, S::finished},
        {S::running, E::workerFailed, S::failed},  {S::pausing, E::workerFailed, S::failed},
        {S::stopping, E::workerFailed, S::failed},
        {S::idle, E::clear, S::idle},           {S::paused, E::clear, S::idle},
        {S::stopped, E::clear, S::idle},        {S::finished, E::clear, S::idle},
        {S::failed, E::clear, S::idle},
    };
    const std::vector<S> states = {S::idle, S::running, S::pausing, S::paused, S::stopping, S::stopped, S::finished, S::failed};
    const std::vector<E> events = {E::start, E::pause, E::resume, E::stop, E::workerPaused, E::workerStopped,
                                   E::workerFinished, E::workerFailed, E::clear};
    int checked = 0;
    for (S s : states)
      for (E e : events) {
        std::optional<S> want;
        for (const auto& [from, event, to] : allowed)
          if (from == s && event == e) want = to;
        const auto got = archipelago::ui::runTransition(s, e);
        QVERIFY2(got == want, qPrintable(QStringLiteral("state %1, event %2")
                                             .arg(archipelago::ui::statusName(s)).arg(static_cast<int>(e))));
        ++checked;
      }
    QCOMPARE(checked, 72);
  }

  /// Finding 1: the run finishes while "A run is in progress" is open; Yes must close the window (it used to
  /// wait forever for a stop that could not come) and keep the finished run as a checkpoint.
  void runFinishingWhileTheQuitQuestionIsOpenStillQuits() {
    MainWindow window;
    window.show();
    TrappingParameters p = archipelago::test::shortRun();
    p.T = 400'000;  // a few tenths of a second: still running when close() is called
    window.parameterPanel()->setParameters(p, 2);
    ScriptedAnswers script;
    script.answer = RunAnswer::discard;  // "Yes, stop and quit"
    script.beforeAnswer = [&] {
      QVERIFY2(waitForStatus(window, RunStatus::finished),
               qPrintable(QStringLiteral("status %1").arg(archipelago::ui::statusName(window.runStatus()))));
    };
    script.install(window);
    QVERIFY(window.startRun());
    QCOMPARE(window.runStatus(), RunStatus::running);
    window.close();
    QCOMPARE(script.asked.size(), std::size_t{1});
    QCOMPARE(script.asked.front(), RunQuestion::Kind::quitWhileLive);
    QTRY_VERIFY_WITH_TIMEOUT(!window.isVisible(), 900000);
    QVERIFY(QFileInfo::exists(MainWindow::checkpointPath()));
    QVERIFY(archipelago::loadRunFile(MainWindow::checkpointPath().toStdString()).finished());
  }

  /// Cancel keeps the run going; a second close request while stopping neither asks again nor hangs.
  void quitQuestionCancelKeepsRunning() {
    MainWindow window;
    window.show();
    window.parameterPanel()->setParameters(archipelago::test::endlessRun(), 2);
    ScriptedAnswers script;
    script.install(window);
    QVERIFY(window.startRun());
    QVERIFY(waitForProgress(window));
    script.answer = RunAnswer::cancel;
    QVERIFY(!window.close());
    QVERIFY(window.isVisible());
    QCOMPARE(window.runStatus(), RunStatus::running);
    script.answer = RunAnswer::discard;
    QVERIFY(!window.close());  // stops first
    QVERIFY(!window.close());  // Ctrl+Q again while stopping: no second question
    QCOMPARE(script.asked.size(), std::size_t{2});
    QTRY_VERIFY_WITH_TIMEOUT(!window.isVisible(), 900000);
    QCOMPARE(window.runStatus(), RunStatus::stopped);
    QVERIFY(QFileInfo::exists(MainWindow::checkpointPath()));
  }

  /// Finding 6: F5 and quit over an unsaved finished run ask; Cancel keeps it, Discard replaces it, Save writes it.
  void discardingAnUnsavedRunAlwaysAsks() {
    QTemporaryDir dir;
    MainWindow window;
    window.show();
    window.parameterPanel()->setParameters(archipelago::test::shortRun(), 2);
    ScriptedAnswers script;
    script.install(window);
    QVERIFY(window.startRun());
    QVERIFY(waitForStatus(window, RunStatus::finished));
    QVERIFY(window.runController()->unsaved());
    const auto finished = window.latestSnapshot();

    script.answer = RunAnswer::cancel;
    QVERIFY(!window.startRun());
    QCOMPARE(script.asked.back(), RunQuestion::Kind::discardUnsaved);
    QCOMPARE(window.latestSnapshot(), finished);
    QVERIFY(!window.close());
    QCOMPARE(script.asked.back(), RunQuestion::Kind::quitUnsaved);
    QVERIFY(window.isVisible());

    // Save: the handler writes the run, then the new run starts and a second F5 asks again.
    const QString path = dir.filePath(QStringLiteral("kept.json"));
    window.runController()->setSaveHandler([&] { return window.saveRunFile(path); });
    script.answer = RunAnswer::save;
    QVERIFY(window.startRun());
    QVERIFY(QFileInfo::exists(path));
    QCOMPARE(archipelago::loadRunFile(path.toStdString()).blocksDone, finished->state.blocksDone);
    QVERIFY(waitForStatus(window, RunStatus::finished));
    const std::size_t before = script.asked.size();
    script.answer = RunAnswer::discard;
    QVERIFY(window.startRun());
    QCOMPARE(script.asked.size(), before + 1);
    QVERIFY(waitForStatus(window, RunStatus::finished));

    // A saved run is not asked about.
    QVERIFY(window.saveRunFile(path));
    QVERIFY(!window.runController()->unsaved());
    const std::size_t saved = script.asked.size();
    QVERIFY(window.close());
    QCOMPARE(script.asked.size(), saved);
  }

  /// Findings 5 and 6: while paused the panel shows the run's parameters and cannot be edited; Stop applies to a
  /// paused run and is final (Resume no longer applies); the rate is shown only while computing.
  void pausedRunIsReadOnlyAndStopIsFinal() {
    MainWindow window;
    window.show();
    const TrappingParameters p = archipelago::test::endlessRun();
    window.parameterPanel()->setParameters(p, 2);
    QVERIFY(window.startRun());
    QVERIFY(waitForProgress(window));
    auto* rate = window.findChild<QLabel*>(QStringLiteral("rateLabel"));
    QVERIFY(rate);
    QTRY_VERIFY(!rate->text().isEmpty());
    QVERIFY(window.pauseRun());
    QVERIFY(waitForStatus(window, RunStatus::paused));
    QVERIFY(rate->text().isEmpty());
    QVERIFY(window.parameterPanel()->field(QStringLiteral("K"))->isReadOnly());
    QVERIFY(window.parameterPanel()->parameters() == p);
    QVERIFY(window.stopAction()->isEnabled());
    QVERIFY(window.resumeAction()->isEnabled());

    QVERIFY(window.stopRun());
    QCOMPARE(window.runStatus(), RunStatus::stopped);  // at once: nothing is computing
    QVERIFY(!window.resumeAction()->isEnabled());
    QVERIFY(!window.resumeRun());
    QVERIFY(!window.parameterPanel()->field(QStringLiteral("K"))->isReadOnly());
    QVERIFY(window.saveAction()->isEnabled());
  }

  /// Found by the soak: Stop (or Pause) pressed while an opened run file is being analysed used to leave the
  /// window in "stopping" for ever (the analysis ends as a pause, which the table does not take in stopping).
  void stopWhileAnOpenedFileIsAnalysedStops() {
    QTemporaryDir dir;
    const QString path = dir.filePath(QStringLiteral("unfinished.json"));
    TrappingParameters p = archipelago::test::endlessRun();
    p.T = 2000;
    // Orbits do not depend on T: a finished run of 2000 blocks is the run of 10⁶ blocks stopped at 2000.
    archipelago::TrappingState state = archipelago::runTrapping(archipelago::startTrapping(p), {});
    state.params.T = 1'000'000;
    archipelago::saveRunFile(path.toStdString(), state);
    for (const bool stop : {true, false}) {
      MainWindow window;
      window.setConfirmations(false);
      QVERIFY(window.openRunFile(path));
      QCOMPARE(window.runStatus(), RunStatus::running);  // the analysis is a worker session
      QVERIFY(stop ? window.stopRun() : window.pauseRun());
      QVERIFY(waitForStatus(window, stop ? RunStatus::stopped : RunStatus::paused, 20000));
    }
  }

  /// Finding 5: plots of a finished run whose parameters were then edited say so.
  void editedParametersMarkThePlotsAsTheOldRun() {
    MainWindow window;
    window.show();
    window.parameterPanel()->setParameters(archipelago::test::shortRun(), 2);
    QVERIFY(window.startRun());
    QVERIFY(waitForStatus(window, RunStatus::finished));
    QVERIFY(window.staleRunNote().isEmpty());
    archipelago::test::typeInto(*window.parameterPanel(), QStringLiteral("K"), QStringLiteral("0.2"));
    QVERIFY(window.staleRunNote().contains(QStringLiteral("K = 0.1")));
    archipelago::test::typeInto(*window.parameterPanel(), QStringLiteral("K"), QStringLiteral("0.1"));
    QVERIFY(window.staleRunNote().isEmpty());
  }

  /// Finding 5: after a restart the preset box names the preset the restored fields hold, and parameters set
  /// from anywhere (a run file, a session) never keep a preset's name they have left.
  void presetBoxNamesOnlyWhatTheFieldsHold() {
    const archipelago::Preset* zero = archipelago::findPreset("small-k-zero");
    QVERIFY(zero);
    {
      MainWindow w;
      w.setConfirmations(false);
      QVERIFY(w.parameterPanel()->applyPreset(QStringLiteral("small-k-zero")));
      QVERIFY(w.close());
    }
    MainWindow next;
    next.setConfirmations(false);
    QVERIFY(next.parameterPanel()->parameters() == zero->spec.parameters);
    QCOMPARE(next.parameterPanel()->spec()->name, zero->spec.name);
    next.parameterPanel()->setParameters(archipelago::test::shortRun(), 2);
    QVERIFY(next.parameterPanel()->spec()->name.empty());
    next.parameterPanel()->setParameters(zero->spec.parameters, 2);
    QCOMPARE(next.parameterPanel()->spec()->name, zero->spec.name);
  }

  /// Finding 7: the header's longest segment is the Long segments table's first row, exactly; D carries the
  /// error the data supports once the run has ended (issue #14: the subset error understates it).
  void headerLongestIsTheTablesFirstRowAndDIsJudged() {
    MainWindow window;
    window.show();
    window.parameterPanel()->setParameters(archipelago::test::shortRun(), 2);
    QVERIFY(window.startRun());
    QVERIFY(waitForStatus(window, RunStatus::finished));
    window.refreshNow();
    const auto& longest = window.latestSnapshot()->state.longest.items();
    QVERIFY(!longest.empty());
    const QString exact = QLocale::c().toString(static_cast<qulonglong>(longest.front().length * 4));
    const QString summary = window.statisticsView()->summaryText();
    QVERIFY2(summary.contains(QStringLiteral("longest: ") + exact + QStringLiteral(" steps")), qPrintable(summary));
    QVERIFY(window.latestSnapshot()->tail != nullptr);
    QVERIFY2(summary.contains(QStringLiteral("bootstrap")) || summary.contains(QStringLiteral("dominated")),
             qPrintable(summary));
  }

  /// Finding 6: a new run clears the previous run's long segments (and with them its overlay).
  void newRunClearsTheOldSegments() {
    MainWindow window;
    window.show();
    window.parameterPanel()->setParameters(archipelago::test::shortRun(), 2);
    QVERIFY(window.startRun());
    QVERIFY(waitForStatus(window, RunStatus::finished));
    QTRY_VERIFY(window.longSegments()->model()->rowCount() > 0);
    window.parameterPanel()->setParameters(archipelago::test::endlessRun(), 2);
    window.runController()->setAsk([](const RunQuestion&) { return RunAnswer::discard; });
    QVERIFY(window.startRun());
    QCOMPARE(window.longSegments()->model()->rowCount(), 0);
    QVERIFY(window.stopRun());
    QVERIFY(waitForStatus(window, RunStatus::stopped));
  }

  /// Finding 15: resuming a checkpoint ends running, and the status bar does not say "Paused".
  void resumedCheckpointSaysRunning() {
    const TrappingParameters p = archipelago::test::endlessRun();
    {
      MainWindow window;
      window.setConfirmations(false);
      window.show();
      window.parameterPanel()->setParameters(p, 2);
      QVERIFY(window.startRun());
      QVERIFY(waitForProgress(window));
      window.close();
      QTRY_VERIFY_WITH_TIMEOUT(!window.isVisible(), 900000);
    }
    QVERIFY(QFileInfo::exists(MainWindow::checkpointPath()));
    const std::uint64_t kept = archipelago::loadRunFile(MainWindow::checkpointPath().toStdString()).blocksDone;
    MainWindow next;
    next.setConfirmations(false);
    next.show();
    QMetaObject::invokeMethod(&next, [&] {
      for (QAction* a : next.findChildren<QAction*>())
        if (a->text() == QStringLiteral("Resume &Checkpoint")) a->trigger();
    });
    QVERIFY(waitForProgress(next, kept));  // computing beyond the checkpoint
    QCOMPARE(next.runStatus(), RunStatus::running);
    QVERIFY(!next.statusBar()->currentMessage().startsWith(QStringLiteral("Paused")));
    QVERIFY(next.stopRun());
    QVERIFY(waitForStatus(next, RunStatus::stopped));
  }

  /// Issue 39, deliverable 4: a run whose box cuts the central island (K = 0.3 in the paper's K = 0.1 box: the
  /// randomizing zone reaches into it) starts, and the status bar shows core's warning, word for word
  /// (checkBoxAgainstIsland); the same box at K = 0.1 shows none.
  void boxCuttingTheIslandWarns() {
    MainWindow window;
    window.setConfirmations(false);
    window.show();
    TrappingParameters p = archipelago::test::shortRun();
    p.map.K = 0.3;
    const std::string warning = archipelago::checkBoxAgainstIsland(p.map, p.Xr).warning;
    QVERIFY(!warning.empty());
    window.parameterPanel()->setParameters(p, 2);
    QVERIFY(window.startRun());
    QVERIFY2(window.statusBar()->currentMessage().contains(QString::fromStdString(warning)),
             qPrintable(window.statusBar()->currentMessage()));
    QVERIFY(waitForStatus(window, RunStatus::finished, 900000));
    window.parameterPanel()->setParameters(archipelago::test::shortRun(), 2);
    QVERIFY(window.startRun());
    QVERIFY2(!window.statusBar()->currentMessage().contains(QStringLiteral("central island")),
             qPrintable(window.statusBar()->currentMessage()));
    QVERIFY(waitForStatus(window, RunStatus::finished, 900000));
  }
};

ARCHIPELAGO_GUI_TEST_MAIN(TestRunController)
#include "test_run_controller.moc"
