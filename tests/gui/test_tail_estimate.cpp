// Issue #29, deliverable 3: the GUI's P_t plot draws the tail sampler's estimate beyond the run's data, in a style
// of its own with its ±1σ bars, from a tail file (File ▸ Open Tail Estimate…); a file of another process, or no
// run, is refused with the reason (offscreen platform).  The file is read and its levels computed by a background
// job: the call returns before anything is drawn, and the result arrives by the window's signal.
#include <QSignalSpy>
#include <QTemporaryDir>
#include <QtTest/QtTest>

#include "GuiTestSupport.hpp"
#include "core/run/TrappingRun.hpp"
#include "core/runfile/RunFile.hpp"
#include "core/tail/TailFile.hpp"
#include "core/tail/TailResult.hpp"
#include "ui/plots/StatisticsPlot.hpp"
#include "ui/run/RunController.hpp"
#include "ui/window/MainWindow.hpp"
#include "ui/window/StatisticsView.hpp"
#include "ui/window/TailEstimateController.hpp"

using namespace archipelago;
using namespace archipelago::ui;

namespace {

// The K = 0.1 process of the default spec (fig. 6's box), small: a run of 3.3·10⁷ steps and a sampler to 10⁵.
TrappingParameters process() {
  TrappingParameters p;
  p.M = 32;
  p.T = 64'000;
  return p;
}

TailState sampled(const TrappingParameters& run) {
  TailRequest r;
  r.run = run;
  r.population = 100;
  r.replicas = 4;
  r.firstSteps = 100;
  r.maxSteps = 100'000;
  r.minAncestors = 4;
  TailRunOptions o;
  o.threads = 2;
  return runTail(startTail(r), o);
}

// Opens `path` and waits for the job's end (the signal; the event loop runs meanwhile): the reason it was
// refused, or empty when drawn.  A refusal before any work (no run) is returned at once, with no signal.
QString openAndWait(MainWindow& window, const QString& path) {
  QSignalSpy finished(window.tailEstimates(), &TailEstimateController::finished);
  QString error;
  if (!window.tailEstimates()->open(path, &error)) {
    if (error.isEmpty()) return QStringLiteral("(refused without a reason)");
    return error;
  }
  // Nothing is read on the GUI thread: the call returned with the job in flight, its result not drawn yet.
  if (!window.tailEstimates()->pending()) return QStringLiteral("(no job in flight after the call)");
  if (!finished.wait(900000) && finished.isEmpty()) return QStringLiteral("(no finished signal)");
  if (window.tailEstimates()->pending()) return QStringLiteral("(still pending after its signal)");
  const QList<QVariant> args = finished.takeFirst();
  if (args.at(0).toString() != path) return QStringLiteral("(the signal names another file)");
  return args.at(1).toString();
}

}  // namespace

class TestTailEstimate : public QObject {
  Q_OBJECT
 private:
  QTemporaryDir dir_;

 private Q_SLOTS:
  void drawsTheReliableLevelsBesideTheRunsPt() {
    const QString runFile = dir_.filePath(QStringLiteral("run.json"));
    saveRunFile(runFile.toStdString(), runTrapping(startTrapping(process()), TrappingRunOptions{}));
    const TailState tail = sampled(process());
    const QString tailFile = dir_.filePath(QStringLiteral("tail.json"));
    saveTailFile(tailFile.toStdString(), tail);
    const Series expected = reliableSurvival(tailResult(tail));
    QVERIFY(expected.x.size() >= 3);

    MainWindow window;
    window.setConfirmations(false);
    QString error;
    // No run yet: refused, with the reason.
    {
      QSignalSpy finished(window.tailEstimates(), &TailEstimateController::finished);
      QVERIFY(!window.tailEstimates()->open(tailFile, &error));
      QVERIFY2(error.contains(QStringLiteral("no run")), qPrintable(error));
      QVERIFY(!window.tailEstimates()->pending());
      QCoreApplication::processEvents();
      QCOMPARE(finished.count(), 0);
    }

    QVERIFY2(window.openRunFile(runFile, &error), qPrintable(error));
    QVERIFY(QTest::qWaitFor([&] { return window.runStatus() == RunStatus::finished; }, 20000));
    StatisticsPlot* P = window.statisticsView()->plot(Statistic::P);
    QVERIFY(P);
    QVERIFY(P->estimatePoints().isEmpty());
    {
      QSignalSpy finished(window.tailEstimates(), &TailEstimateController::finished);
      QVERIFY2(window.tailEstimates()->open(tailFile, &error), qPrintable(error));
      QVERIFY(window.tailEstimates()->pending());
      QVERIFY(P->estimatePoints().isEmpty());  // not drawn by the call: the job's result comes by the event loop
      QTRY_COMPARE_WITH_TIMEOUT(finished.count(), 1, 60000);
      QVERIFY2(finished.at(0).at(1).toString().isEmpty(), qPrintable(finished.at(0).at(1).toString()));
      QVERIFY(!window.tailEstimates()->pending());
    }
    const QVector<QPointF> drawn = P->estimatePoints();
    QCOMPARE(static_cast<std::size_t>(drawn.size()), expected.x.size());
    for (int i = 0; i < drawn.size(); ++i) {
      QCOMPARE(drawn[i].x(), expected.x[static_cast<std::size_t>(i)]);
      QCOMPARE(drawn[i].y(), expected.value[static_cast<std::size_t>(i)]);
    }
    // It reaches beyond the run's data: the largest level lies past the run's last P_t point with segments.
    QVERIFY(drawn.back().x() > P->data().x.front());

    // Another process (K = 0.2): refused, naming what differs; the drawn estimate stays.
    TrappingParameters other = process();
    other.map.K = 0.2;
    const QString otherFile = dir_.filePath(QStringLiteral("other.json"));
    TailRequest r = tail.request;
    r.run = other;
    r.maxSteps = 1000;
    r.firstSteps = 100;
    saveTailFile(otherFile.toStdString(), runTail(startTail(r), TailRunOptions{}));
    error = openAndWait(window, otherFile);
    QVERIFY2(error.contains(QStringLiteral("another process")) && error.contains(QStringLiteral("K")), qPrintable(error));
    QCOMPARE(P->estimatePoints().size(), drawn.size());

    // A damaged file: refused, the reason core's.
    const QString broken = dir_.filePath(QStringLiteral("broken.json"));
    QFile f(broken);
    QVERIFY(f.open(QIODevice::WriteOnly));
    f.write("{\"format\": \"archipelago-tail\", ");
    f.close();
    error = openAndWait(window, broken);
    QVERIFY(!error.isEmpty() && !error.startsWith(QLatin1Char('(')));
    QCOMPARE(P->estimatePoints().size(), drawn.size());

    // Clearing the run clears its estimate.
    QVERIFY(window.runController()->clear());
    QVERIFY(P->estimatePoints().isEmpty());
  }
};

QTEST_MAIN(TestTailEstimate)
#include "test_tail_estimate.moc"
