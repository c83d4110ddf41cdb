// The desktop application's command line: `archipelago --help` and `--version` work without a display (issue 25,
// deliverable 7), and every number it reads goes through core's one reader, with one `ERROR:` line and a non-zero
// status for a bad one (issue #23, finding 9: --after nan|-5|1e12 never quit; --segment abc silently meant 0,
// -1 and 99999 were ignored); without a display it says so in one line (issue 36).  The options are read by one parse
// before any application object, beside Qt's own (-platform, -style …), which it skips (issue 51).
#include <QFile>
#include <QProcess>
#include <QProcessEnvironment>
#include <QTemporaryDir>
#include <QtTest>

#include "GuiTestSupport.hpp"
#include "core/run/TrappingRun.hpp"
#include "core/runfile/RunFile.hpp"

#ifndef ARCHIPELAGO_GUI
#error "ARCHIPELAGO_GUI must name the archipelago executable (tests/gui/CMakeLists.txt)"
#endif

namespace {
struct Outcome {
  int status = -1;
  QString out;
  QString err;
};

Outcome run(const QStringList& arguments, bool display, const QString& home, const QString& platform = {}) {
  QProcess p;
  QProcessEnvironment env = QProcessEnvironment::systemEnvironment();
  env.remove(QStringLiteral("DISPLAY"));
  env.remove(QStringLiteral("WAYLAND_DISPLAY"));
  env.remove(QStringLiteral("QT_QPA_PLATFORM"));
  if (display) env.insert(QStringLiteral("QT_QPA_PLATFORM"), QStringLiteral("offscreen"));
  else if (!platform.isEmpty()) env.insert(QStringLiteral("QT_QPA_PLATFORM"), platform);
  env.insert(QStringLiteral("XDG_CONFIG_HOME"), home + QStringLiteral("/config"));
  env.insert(QStringLiteral("XDG_DATA_HOME"), home + QStringLiteral("/data"));
  env.insert(QStringLiteral("XDG_RUNTIME_DIR"), home);  // a private folder: Qt says nothing about it
  p.setProcessEnvironment(env);
  p.start(QStringLiteral(ARCHIPELAGO_GUI), arguments);
  if (!p.waitForFinished(90000)) {
    p.kill();
    p.waitForFinished();
    return {};
  }
  return {p.exitStatus() == QProcess::NormalExit ? p.exitCode() : -1, QString::fromUtf8(p.readAllStandardOutput()),
          QString::fromUtf8(p.readAllStandardError())};
}

/// Exactly one line on stderr, an ERROR line (Qt's own warnings about a missing display must not appear: the
/// numbers are checked before any window).
bool oneErrorLine(const QString& err) {
  const QStringList lines = err.split(QLatin1Char('\n'), Qt::SkipEmptyParts);
  return lines.size() == 1 && lines.front().startsWith(QStringLiteral("ERROR: "));
}
}  // namespace

class TestCommandLine : public QObject {
  Q_OBJECT
 private Q_SLOTS:
  void deliverable7_helpAndVersionWithoutADisplay() {
    QTemporaryDir home;
    const Outcome help = run({QStringLiteral("--help")}, false, home.path());
    QCOMPARE(help.status, 0);
    QVERIFY(help.out.contains(QStringLiteral("--segment")));
    const Outcome version = run({QStringLiteral("--version")}, false, home.path());
    QCOMPARE(version.status, 0);
    QVERIFY(version.out.startsWith(QStringLiteral("Archipelago ")));
  }

  void finding9_everyBadNumberIsOneErrorLine() {
    QTemporaryDir home;
    const QList<QStringList> cases = {
        {QStringLiteral("--after"), QStringLiteral("nan")},   {QStringLiteral("--after"), QStringLiteral("-5")},
        {QStringLiteral("--after"), QStringLiteral("1e12")},  {QStringLiteral("--after=abc")},
        {QStringLiteral("--measure"), QStringLiteral("inf")}, {QStringLiteral("--measure"), QStringLiteral("0")},
        {QStringLiteral("--segment"), QStringLiteral("abc"), QStringLiteral("run.json")},
        {QStringLiteral("--segment"), QStringLiteral("-1"), QStringLiteral("run.json")},
        {QStringLiteral("--segment"), QStringLiteral("1.5"), QStringLiteral("run.json")},
        {QStringLiteral("--threads"), QStringLiteral("99999")},
    };
    for (const QStringList& args : cases) {
      const Outcome o = run(args, false, home.path());  // no display: refused before any window
      QVERIFY2(o.status == 2 && oneErrorLine(o.err), qPrintable(args.join(QLatin1Char(' ')) + QStringLiteral(": ") + o.err));
    }
  }

  // Issue 36 class 8b: with QT_QPA_PLATFORM=xcb (or none: the default) and no DISPLAY, Qt's xcb plugin aborted the
  // process (SIGABRT, status -1 here) instead of saying what to do.
  void issue36_noDisplayIsOneErrorLine() {
    QTemporaryDir home;
    for (const QString& platform : {QStringLiteral("xcb"), QString(), QStringLiteral("wayland;xcb")}) {
      const Outcome o = run({}, false, home.path(), platform);
      QVERIFY2(o.status == 2 && oneErrorLine(o.err) && o.err.contains(QStringLiteral("no display")),
               qPrintable(platform + QStringLiteral(": status ") + QString::number(o.status) + QStringLiteral(", ") + o.err));
    }
  }

  void finding9_aSegmentBeyondTheRunIsAnError() {
    QTemporaryDir home;
    const QString file = home.filePath(QStringLiteral("run.json"));
    archipelago::TrappingParameters p = archipelago::test::shortRun();
    p.longestKept = 5;
    archipelago::saveRunFile(file.toStdString(),
                             archipelago::runTrapping(archipelago::startTrapping(p), archipelago::TrappingRunOptions{}));
    const Outcome beyond = run({QStringLiteral("--segment"), QStringLiteral("99999"), file}, true, home.path());
    QVERIFY2(beyond.status == 2, qPrintable(beyond.err));
    QVERIFY2(beyond.err.contains(QStringLiteral("ERROR: --segment = 99999")), qPrintable(beyond.err));
    const Outcome none = run({QStringLiteral("--segment"), QStringLiteral("0")}, true, home.path());
    QVERIFY2(none.status == 2 && oneErrorLine(none.err), qPrintable(none.err));
  }

  // Issue 51: one parse, before any application object, skips Qt's own options (which QApplication takes out of argv
  // only when it is made).  A bad number beside -platform is still one ERROR line without a display, and a screenshot
  // asked beside it is still written.  --help and --version beside a Qt option failed with the two-pass code (its
  // QCoreApplication left -platform to the parser: "Unknown options: p, l, a, t, f, o, r, m.", status 1), and
  // --periodic's bad value was reported as --orbit's.
  void issue51_qtOptionsBesideOurs() {
    QTemporaryDir home;
    const Outcome bad = run({QStringLiteral("-platform"), QStringLiteral("offscreen"), QStringLiteral("--after"),
                             QStringLiteral("nan")}, false, home.path());
    QVERIFY2(bad.status == 2 && oneErrorLine(bad.err) && bad.err.contains(QStringLiteral("--after")), qPrintable(bad.err));
    const Outcome periodic = run({QStringLiteral("--periodic"), QStringLiteral("abc")}, false, home.path());
    QVERIFY2(periodic.status == 2 && periodic.err.startsWith(QStringLiteral("ERROR: --periodic 'abc'")),
             qPrintable(periodic.err));
    const QList<QStringList> information = {
        {QStringLiteral("--help"), QStringLiteral("-platform"), QStringLiteral("offscreen")},
        {QStringLiteral("-style"), QStringLiteral("fusion"), QStringLiteral("--reverse"), QStringLiteral("--version")},
    };
    for (const QStringList& args : information) {
      const Outcome o = run(args, false, home.path());
      QVERIFY2(o.status == 0 && o.err.isEmpty(), qPrintable(args.join(QLatin1Char(' ')) + QStringLiteral(": ") + o.err));
    }
    // An option's missing value is the parser's one line (status 1): the two-pass code's scan for --help read past
    // argv's end there and crashed (SIGSEGV).
    for (const QString& option : {QStringLiteral("--after"), QStringLiteral("--preset")}) {
      const Outcome o = run({option}, false, home.path());
      QVERIFY2(o.status == 1 && o.err == QStringLiteral("Archipelago: Missing value after '") + option + QStringLiteral("'.\n"),
               qPrintable(option + QStringLiteral(": status ") + QString::number(o.status) + QStringLiteral(", ") + o.err));
    }
    const QString shot = home.filePath(QStringLiteral("shot.png"));
    const Outcome o = run({QStringLiteral("--after"), QStringLiteral("1"), QStringLiteral("-platform"),
                           QStringLiteral("offscreen"), QStringLiteral("--screenshot"), shot}, false, home.path());
    QVERIFY2(o.status == 0 && o.out.contains(QStringLiteral("wrote ") + shot) && QFile::exists(shot),
             qPrintable(QString::number(o.status) + QStringLiteral(" ") + o.out + o.err));
  }
};

ARCHIPELAGO_GUI_TEST_MAIN(TestCommandLine)
#include "test_command_line.moc"
