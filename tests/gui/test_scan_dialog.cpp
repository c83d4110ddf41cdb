// The K-scan dialog (ui/scan/KScanDialog): a tiny scan runs to the end and its summaries equal, byte for byte,
// those of `archipelago-cli scan` with the same parameters (both call core's runKScan); a scan stopped mid-way
// and started again resumes and gives the identical summaries; bad inputs are refused with a clear message and
// start nothing; Enter starts, Esc closes when idle.

#include <QDir>
#include <QFile>
#include <QLabel>
#include <QLineEdit>
#include <QProcess>
#include <QSignalSpy>
#include <QTemporaryDir>
#include <QtTest>

#include "GuiTestSupport.hpp"
#include "core/runfile/RunFile.hpp"
#include "ui/scan/KScanDialog.hpp"

#ifndef ARCHIPELAGO_CLI
#error "ARCHIPELAGO_CLI must name the archipelago-cli executable (tests/gui/CMakeLists.txt)"
#endif

using archipelago::RunSpec;
using archipelago::ui::KScanDialog;

namespace {

// Two K; 64 orbits of 10⁵ blocks of 16 steps each: about 10⁸ steps per K, long enough that a stop asked for
// at the scan's first progress report lands inside its first K, short enough for a test.
const QString kKs = QStringLiteral("0.1, 0.3");
const QString kM = QStringLiteral("64"), kT = QStringLiteral("100000"), kQ = QStringLiteral("16"),
              kSeed = QStringLiteral("3"), kThreads = QStringLiteral("2");

void fill(KScanDialog& d, const QString& folder) {
  d.kField()->setText(kKs);
  d.field(QStringLiteral("M"))->setText(kM);
  d.field(QStringLiteral("T"))->setText(kT);
  d.field(QStringLiteral("q"))->setText(kQ);
  d.field(QStringLiteral("seed"))->setText(kSeed);
  d.field(QStringLiteral("threads"))->setText(kThreads);
  d.folderField()->setText(folder);
}

QByteArray contents(const QString& path) {
  QFile f(path);
  return f.open(QIODevice::ReadOnly) ? f.readAll() : QByteArray("<missing " + path.toUtf8() + ">");
}

const char* const kSummaries[] = {"scan_summary.csv", "scan_f_t.csv", "scan_local_exponent.csv"};

}  // namespace

class ScanDialogTest : public QObject {
  Q_OBJECT

 private:
  QTemporaryDir tmp_;
  QString cliDir_;

  /// The same scan by the CLI, once: the reference of both scans below.
  void runCli() {
    if (!cliDir_.isEmpty()) return;
    cliDir_ = tmp_.filePath(QStringLiteral("cli"));
    QProcess cli;
    cli.start(QStringLiteral(ARCHIPELAGO_CLI),
              {QStringLiteral("scan"), QStringLiteral("--K"), QStringLiteral("0.1,0.3"), QStringLiteral("--M"), kM,
               QStringLiteral("--T"), kT, QStringLiteral("--q"), kQ, QStringLiteral("--seed"), kSeed,
               QStringLiteral("--threads"), kThreads, QStringLiteral("--dir"), cliDir_, QStringLiteral("--quiet")});
    QVERIFY(cli.waitForFinished(300000));
    QVERIFY2(cli.exitStatus() == QProcess::NormalExit && cli.exitCode() == 0, cli.readAllStandardError().constData());
  }

  void compareWithCli(const QString& dir) {
    runCli();
    for (const char* name : kSummaries) {
      const QByteArray gui = contents(QDir(dir).filePath(QLatin1String(name)));
      const QByteArray cli = contents(QDir(cliDir_).filePath(QLatin1String(name)));
      QVERIFY2(gui.size() > 200, name);  // a header and rows, not an empty file
      QVERIFY2(gui == cli, name);
    }
  }

 private Q_SLOTS:
  void tinyScanEqualsTheCli() {
    KScanDialog d{RunSpec{}};
    const QString dir = tmp_.filePath(QStringLiteral("gui"));
    fill(d, dir);
    QSignalSpy ended(&d, &KScanDialog::scanEnded);
    QVERIFY2(d.start(), qPrintable(d.message()));
    QVERIFY(d.running());
    QVERIFY(ended.wait(300000));
    QCOMPARE(ended.takeFirst().at(0).toBool(), true);
    QVERIFY(!d.running());
    QCOMPARE(static_cast<int>(d.results().size()), 2);
    QCOMPARE(d.results()[0].point.K, 0.1);
    QCOMPARE(d.results()[1].point.K, 0.3);
    compareWithCli(dir);

    // Export elsewhere writes the same files.
    const QString exported = tmp_.filePath(QStringLiteral("exported"));
    QVERIFY(QDir().mkpath(exported));
    QVERIFY2(d.exportCsv(exported), qPrintable(d.message()));
    for (const char* name : kSummaries)
      QVERIFY2(contents(QDir(exported).filePath(QLatin1String(name))) == contents(QDir(dir).filePath(QLatin1String(name))),
               name);
  }

  void stopThenStartResumesToTheSameResult() {
    KScanDialog d{RunSpec{}};
    const QString dir = tmp_.filePath(QStringLiteral("resumed"));
    fill(d, dir);
    QSignalSpy ended(&d, &KScanDialog::scanEnded);
    // Stop once some blocks are done (the whole scan takes several progress reports).
    QSignalSpy progressed(&d, &KScanDialog::progressed);
    QVERIFY(d.start());
    QTRY_VERIFY_WITH_TIMEOUT(!progressed.isEmpty() && progressed.last().at(0).toDouble() > 0, 300000);
    d.stop();
    QVERIFY(ended.wait(300000));
    QCOMPARE(ended.takeFirst().at(0).toBool(), false);
    QVERIFY2(d.message().startsWith(QStringLiteral("Stopped")), qPrintable(d.message()));
    QVERIFY(d.results().empty());
    QVERIFY(!QFile::exists(QDir(dir).filePath(QStringLiteral("scan_summary.csv"))));
    // The K running was checkpointed mid-way: some blocks done, not all.
    std::uint64_t blocks = 0;
    bool unfinished = false;
    for (const QString& name : {QStringLiteral("K0.1.json"), QStringLiteral("K0.3.json")}) {
      const QString file = QDir(dir).filePath(name);
      if (!QFile::exists(file)) continue;
      const archipelago::TrappingState s = archipelago::loadRunFile(file.toStdString());
      blocks += s.blocksDone;
      unfinished = unfinished || !s.finished();
    }
    QVERIFY(blocks > 0);
    QVERIFY(unfinished);

    // Start again: resumed from the checkpoint, to the same summaries as an uninterrupted scan.
    QVERIFY2(d.start(), qPrintable(d.message()));
    QVERIFY(ended.wait(300000));
    QCOMPARE(ended.takeFirst().at(0).toBool(), true);
    QCOMPARE(static_cast<int>(d.results().size()), 2);
    QCOMPARE(d.results()[0].point.blocksDone, static_cast<std::uint64_t>(100000));
    compareWithCli(dir);

    // A third start reuses both finished K (nothing to run) and writes the same summaries again.
    QVERIFY(d.start());
    QVERIFY(ended.wait(300000));
    QCOMPARE(ended.takeFirst().at(0).toBool(), true);
    compareWithCli(dir);
  }

  void badInputsStartNothing() {
    KScanDialog d{RunSpec{}};
    const QString dir = tmp_.filePath(QStringLiteral("bad"));
    QFile plain(tmp_.filePath(QStringLiteral("a-file")));
    QVERIFY(plain.open(QIODevice::WriteOnly));
    plain.close();
    struct Case {
      QString field, text, expected;
    };
    const Case cases[] = {
        {QStringLiteral("K"), QString(), QStringLiteral("empty")},
        {QStringLiteral("K"), QStringLiteral("  "), QStringLiteral("empty")},
        {QStringLiteral("K"), QStringLiteral("0.1, nan"), QStringLiteral("not a finite number")},
        {QStringLiteral("K"), QStringLiteral("0.1, -0.2"), QStringLiteral("must lie in [0, 4]")},
        {QStringLiteral("K"), QStringLiteral("0.1, 0.1"), QStringLiteral("twice")},
        {QStringLiteral("K"), QStringLiteral("0.1:0.05:0.05"), QStringLiteral("upwards")},
        {QStringLiteral("K"), QStringLiteral("0.1, abc"), QStringLiteral("'abc'")},
        {QStringLiteral("M"), QStringLiteral("-64"), QStringLiteral("M = '-64' is not a whole number")},
        {QStringLiteral("M"), QStringLiteral("nan"), QStringLiteral("M = 'nan' is not a whole number")},
        {QStringLiteral("M"), QStringLiteral("0"), QStringLiteral("M")},
        {QStringLiteral("T"), QString(), QStringLiteral("T = '' is not a whole number")},
        {QStringLiteral("q"), QStringLiteral("1.5"), QStringLiteral("q = '1.5' is not a whole number")},
        {QStringLiteral("threads"), QStringLiteral("-1"), QStringLiteral("threads")},
        {QStringLiteral("folder"), QString(), QStringLiteral("empty")},
        {QStringLiteral("folder"), plain.fileName(), QStringLiteral("not a folder")},
        {QStringLiteral("folder"), plain.fileName() + QStringLiteral("/sub"), plain.fileName()},
        {QStringLiteral("folder"), QStringLiteral("/proc/archipelago-no-such/scan"), QStringLiteral("/proc")},
    };
    for (const Case& c : cases) {
      fill(d, dir);
      QLineEdit* edit = c.field == QStringLiteral("K") ? d.kField()
                        : c.field == QStringLiteral("folder") ? d.folderField()
                                                              : d.field(c.field);
      QVERIFY2(edit, qPrintable(c.field));
      edit->setText(c.text);
      QVERIFY2(!d.start(), qPrintable(c.field + u'=' + c.text));
      QVERIFY(!d.running());
      QVERIFY2(d.message().contains(c.expected), qPrintable(c.text + QStringLiteral(": ") + d.message()));
      QVERIFY2(!d.message().contains(u'\n'), qPrintable(d.message()));
    }
    QVERIFY(!QFileInfo::exists(dir));  // nothing started, nothing written
  }

  void enterStartsAndEscapeCloses() {
    KScanDialog d{RunSpec{}};
    d.show();
    QVERIFY(QTest::qWaitForWindowExposed(&d));
    fill(d, tmp_.filePath(QStringLiteral("keys")));
    d.kField()->setText(QString());
    d.kField()->setFocus();
    QTest::keyClick(d.kField(), Qt::Key_Return);  // the default button: Start, refused with the reason
    QVERIFY2(d.message().contains(QStringLiteral("empty")), qPrintable(d.message()));
    QVERIFY(d.isVisible());
    QTest::keyClick(&d, Qt::Key_Escape);  // idle: closes without asking
    QVERIFY(!d.isVisible());
  }
};

int main(int argc, char** argv) {
  archipelago::test::isolatedHome();
  QApplication app(argc, argv);
  ScanDialogTest test;
  return QTest::qExec(&test, argc, argv);
}

#include "test_scan_dialog.moc"
