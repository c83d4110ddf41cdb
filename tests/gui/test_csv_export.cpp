// Regression for issue #11 ("One definition of each fact"): for the same run, the CLI wrote D_t.csv with the
// header "t,f_t,error" and the GUI D.csv with "curve,x,value,error".  Now both write through core's one CSV
// writer: for the same run file, `archipelago-cli stats --csv DIR` and the GUI's "Export all" (and its
// per-plot CSV export) must write byte-identical files, theory curves included (offscreen platform).
#include <QDir>
#include <QFile>
#include <QFileInfo>
#include <QProcess>
#include <QTemporaryDir>

#include "ui/window/ExportActions.hpp"
#include "GuiTestSupport.hpp"
#include "ui/window/StatisticsView.hpp"
#include "ui/plots/StatisticsPlot.hpp"
#include "core/runfile/RunFile.hpp"
#include "core/run/TrappingRun.hpp"

#ifndef ARCHIPELAGO_CLI
#error "ARCHIPELAGO_CLI must name the archipelago-cli executable (tests/gui/CMakeLists.txt)"
#endif

using archipelago::TrappingParameters;
using archipelago::ui::MainWindow;
using archipelago::ui::RunStatus;

namespace {

QByteArray contents(const QString& path) {
  QFile f(path);
  if (!f.open(QIODevice::ReadOnly)) return QByteArray("<cannot read ") + path.toUtf8() + '>';
  return f.readAll();
}

QStringList csvFiles(const QString& folder) {
  return QDir(folder).entryList({QStringLiteral("*.csv")}, QDir::Files, QDir::Name);
}

/// A run made headless through core and saved as a run file, as a user of the CLI would have it.
QString makeRunFile(const QString& path, const TrappingParameters& p) {
  const archipelago::TrappingState state =
      archipelago::runTrapping(archipelago::startTrapping(p), archipelago::TrappingRunOptions{});
  archipelago::saveRunFile(path.toStdString(), state);
  return path;
}

/// K = −10⁻⁴ in the small-K box (§4): the theory applies, so theory files are written too.
TrappingParameters negativeK() {
  TrappingParameters p;
  p.map = {-1e-4, -0.05, 0.05};
  p.q = 1;
  p.T = 20'000;
  p.M = 16;
  p.subsets = 4;
  p.seed = 5;
  return p;
}

/// K = 0 (fig. 3b): t^−7 and τ^−5 over f_t and C_τ.
TrappingParameters zeroK() {
  TrappingParameters p = negativeK();
  p.map.K = 0;
  p.T = 40'000;
  return p;
}

}  // namespace

class TestCsvExport : public QObject {
  Q_OBJECT
 private:
  QTemporaryDir dir_;

  /// Opens `runFile` in a window, exports everything into gui/, runs the CLI into cli/, and compares.
  void compareGuiAndCli(const QString& runFile, const QString& name, const QStringList& theoryFiles) {
    const QString guiDir = dir_.filePath(name + QStringLiteral("/gui"));
    const QString cliDir = dir_.filePath(name + QStringLiteral("/cli"));

    MainWindow window;
    window.setConfirmations(false);
    QString error;
    QVERIFY2(window.openRunFile(runFile, &error), qPrintable(error));
    QVERIFY(QTest::qWaitFor([&] { return window.runStatus() == RunStatus::finished; }, 20000));
    QVERIFY2(window.exportAllTo(guiDir, &error), qPrintable(error));

    QProcess cli;
    cli.start(QStringLiteral(ARCHIPELAGO_CLI), {QStringLiteral("stats"), runFile, QStringLiteral("--csv"), cliDir});
    QVERIFY(cli.waitForFinished(60000));
    QVERIFY2(cli.exitStatus() == QProcess::NormalExit && cli.exitCode() == 0, cli.readAllStandardError().constData());

    const QStringList fromGui = csvFiles(guiDir), fromCli = csvFiles(cliDir);
    QCOMPARE(fromGui, fromCli);
    for (const char* expected : {"f_t.csv", "p_t_probability.csv", "P_t.csv", "C_tau.csv", "local_exponent.csv",
                                 "S_t.csv", "D_t.csv", "summary.csv"})
      QVERIFY2(fromCli.contains(QLatin1String(expected)), expected);
    QStringList theoryWritten = QDir(cliDir).entryList({QStringLiteral("*.theory.csv")}, QDir::Files);
    QStringList theoryExpected = theoryFiles;
    theoryWritten.sort();
    theoryExpected.sort();
    QCOMPARE(theoryWritten, theoryExpected);
    for (const QString& file : fromCli) {
      const QByteArray a = contents(QDir(guiDir).filePath(file)), b = contents(QDir(cliDir).filePath(file));
      QVERIFY2(a.size() > 0, qPrintable(file));
      QVERIFY2(a == b, qPrintable(file + QStringLiteral(" differs between the GUI and the CLI")));
    }

    // One plot's CSV, exported alone to a name of the user's choice: the same bytes, its theory beside it.
    for (archipelago::ui::StatisticsPlot* plot : window.statisticsView()->plots()) {
      const QString mine = dir_.filePath(name + QStringLiteral("/one-") + plot->fileName() + QStringLiteral(".csv"));
      const auto r = archipelago::ui::exportPlot(*plot, window.latestSnapshot(), mine);
      QVERIFY2(r.ok(), qPrintable(r.error));
      QCOMPARE(contents(mine), contents(QDir(cliDir).filePath(plot->fileName() + QStringLiteral(".csv"))));
      const QString theory = plot->fileName() + QStringLiteral(".theory.csv");
      const QString mineTheory = QString(mine).replace(QStringLiteral(".csv"), QStringLiteral(".theory.csv"));
      QCOMPARE(QFileInfo::exists(mineTheory), theoryFiles.contains(theory));
      if (theoryFiles.contains(theory)) QCOMPARE(contents(mineTheory), contents(QDir(cliDir).filePath(theory)));
    }
  }

 private Q_SLOTS:
  void initTestCase() { QVERIFY(dir_.isValid()); }

  void kPointOneGuiAndCliWriteTheSameBytes() {
    const QString run = makeRunFile(dir_.filePath(QStringLiteral("k01.json")), archipelago::test::shortRun());
    compareGuiAndCli(run, QStringLiteral("k01"), {});
  }

  void negativeKGuiAndCliWriteTheSameTheory() {
    const QString run = makeRunFile(dir_.filePath(QStringLiteral("kneg.json")), negativeK());
    compareGuiAndCli(run, QStringLiteral("kneg"),
                     {QStringLiteral("C_tau.theory.csv"), QStringLiteral("P_t.theory.csv"),
                      QStringLiteral("f_t.theory.csv")});
  }

  void zeroKGuiAndCliWriteTheSameTheory() {
    const QString run = makeRunFile(dir_.filePath(QStringLiteral("k0.json")), zeroK());
    compareGuiAndCli(run, QStringLiteral("k0"), {QStringLiteral("C_tau.theory.csv"), QStringLiteral("f_t.theory.csv")});
  }

  void nothingToExportBeforeARun() {
    MainWindow window;
    window.setConfirmations(false);
    QString error;
    QVERIFY(!window.exportAllTo(dir_.filePath(QStringLiteral("empty")), &error));
    QVERIFY(error.contains(QStringLiteral("no numbers")));
    QVERIFY(csvFiles(dir_.filePath(QStringLiteral("empty"))).isEmpty());
  }
};

ARCHIPELAGO_GUI_TEST_MAIN(TestCsvExport)
#include "test_csv_export.moc"
