// The K-scan dialog (ui/scan/KScanDialog): a tiny scan runs to the end and its summaries equal, byte for byte,
// those of `archipelago-cli scan` with the same parameters (both call core's runKScan); a scan stopped mid-way
// and started again resumes and gives the identical summaries; bad inputs are refused with a clear message and
// start nothing; Enter starts, Esc closes when idle.  What the dialog draws (its KScanPlots) is what the CLI
// wrote: every cell of the heat map equals scan_local_exponent.csv's (empty cells: no data), the b₂ (area,
// fraction), longest segment and long-segment fraction points equal scan_summary.csv's columns.  A KScanPlots
// of its own fed the finished summaries (as the report draws its K-scan figures) shows the same.  The heat map
// has one colour scale: cells, colour bar and no-data grey all come from KScanPlots::heatMapColour.
//
// With ARCHIPELAGO_SCREENSHOT_DIR set (run under xvfb-run with QT_QPA_PLATFORM=xcb), `screenshots` runs a
// 12-K scan and saves the dialog at 1280 × 800 and 1920 × 1080 there (the README's docs/images/k-scan-dialog*.png).

#include <QDir>
#include <QFile>
#include <QLabel>
#include <QLineEdit>
#include <QProcess>
#include <QSignalSpy>
#include <QTabWidget>
#include <QTemporaryDir>
#include <QtTest>
#include <qwt_plot.h>
#include <qwt_color_map.h>
#include <qwt_plot_curve.h>
#include <qwt_plot_spectrogram.h>
#include <qwt_scale_widget.h>
#include <qwt_text.h>

#include <cmath>
#include <map>

#include "GuiTestSupport.hpp"
#include "core/runfile/RunFile.hpp"
#include "ui/scan/KScanDialog.hpp"
#include "ui/scan/KScanPlots.hpp"

#ifndef ARCHIPELAGO_CLI
#error "ARCHIPELAGO_CLI must name the archipelago-cli executable (tests/gui/CMakeLists.txt)"
#endif

using archipelago::RunSpec;
using archipelago::ui::KScanDialog;
using archipelago::ui::KScanPlots;

namespace {

// Two K; 64 orbits of 10⁵ blocks of 16 steps each: about 10⁸ steps per K, long enough that a stop asked for
// at the scan's first progress report lands inside its first K, short enough for a test.
const QString kKs = QStringLiteral("0.1, 0.3");
const QString kM = QStringLiteral("64"), kT = QStringLiteral("100000"), kQ = QStringLiteral("16"),
              kSeed = QStringLiteral("3"), kThreads = QStringLiteral("2");
// b₂ of each box with 10⁶ steps: a coarse area, but every cell and column of the comparison is exercised.
const QString kB2 = QStringLiteral("1000000");

void fill(KScanDialog& d, const QString& folder) {
  d.kField()->setText(kKs);
  d.field(QStringLiteral("M"))->setText(kM);
  d.field(QStringLiteral("T"))->setText(kT);
  d.field(QStringLiteral("q"))->setText(kQ);
  d.field(QStringLiteral("seed"))->setText(kSeed);
  d.field(QStringLiteral("threads"))->setText(kThreads);
  d.field(QStringLiteral("b2Iterations"))->setText(kB2);
  d.folderField()->setText(folder);
}

QByteArray contents(const QString& path) {
  QFile f(path);
  return f.open(QIODevice::ReadOnly) ? f.readAll() : QByteArray("<missing " + path.toUtf8() + ">");
}

const char* const kSummaries[] = {"scan_summary.csv", "scan_f_t.csv", "scan_local_exponent.csv"};

/// A CSV file's rows (without the "# " lines), each a list of cells; the header first.
QList<QList<QByteArray>> csvRows(const QString& path) {
  QList<QList<QByteArray>> rows;
  for (const QByteArray& line : contents(path).split('\n'))
    if (!line.isEmpty() && !line.startsWith('#')) rows.append(line.split(','));
  return rows;
}

/// A cell's number; NaN for an empty cell (undefined).
double cell(const QByteArray& text) {
  if (text.isEmpty()) return std::nan("");
  bool ok = false;
  const double v = text.toDouble(&ok);
  return ok ? v : -12345.678;  // never equal to a plotted value
}

/// The points of the curve titled `title` in `plot`, by K (x).
std::map<double, double> curvePoints(QwtPlot* plot, const QString& title) {
  std::map<double, double> points;
  if (!plot) return points;
  for (QwtPlotItem* item : plot->itemList(QwtPlotItem::Rtti_PlotCurve)) {
    if (item->title().text() != title) continue;
    const auto* curve = static_cast<QwtPlotCurve*>(item);
    for (size_t i = 0; i < curve->dataSize(); ++i) points[curve->sample(static_cast<int>(i)).x()] = curve->sample(static_cast<int>(i)).y();
  }
  return points;
}

}  // namespace

class ScanDialogTest : public QObject {
  Q_OBJECT

 private:
  QTemporaryDir tmp_;
  QString cliDir_;

  /// The same scan by the CLI, once: the reference of the scans below (`T` blocks; the folder's name says it).
  void runCli(const QString& T = kT) {
    const QString dir = tmp_.filePath(QStringLiteral("cli-T") + T);
    if (cliDir_ == dir) return;
    cliDir_ = dir;
    if (QDir(dir).exists()) return;
    QProcess cli;
    cli.start(QStringLiteral(ARCHIPELAGO_CLI),
              {QStringLiteral("scan"), QStringLiteral("--K"), QStringLiteral("0.1,0.3"), QStringLiteral("--M"), kM,
               QStringLiteral("--T"), T, QStringLiteral("--q"), kQ, QStringLiteral("--seed"), kSeed,
               QStringLiteral("--threads"), kThreads, QStringLiteral("--b2-iterations"), kB2, QStringLiteral("--dir"),
               cliDir_, QStringLiteral("--quiet")});
    QVERIFY(cli.waitForFinished(300000));
    QVERIFY2(cli.exitStatus() == QProcess::NormalExit && cli.exitCode() == 0, cli.readAllStandardError().constData());
  }

  /// The plots' heat map, cell by cell, against the CLI's scan_local_exponent.csv; their b₂, longest-segment
  /// and long-fraction points against the CLI's scan_summary.csv.
  void comparePlotsWithCli(const KScanPlots& d) {
    runCli();
    const QList<QList<QByteArray>> map = csvRows(QDir(cliDir_).filePath(QStringLiteral("scan_local_exponent.csv")));
    QVERIFY(map.size() > 40);  // the local exponent's log grid (10 a decade, issue #26) over five decades of τ
    QCOMPARE(map[0].size(), 3);  // tau, 0.1, 0.3
    int defined = 0, undefined = 0;
    for (int r = 1; r < map.size(); ++r) {
      QCOMPARE(map[r].size(), 3);
      const double tau = cell(map[r][0]);
      for (int c = 1; c < 3; ++c) {
        const double K = cell(map[0][c]);
        const double expected = cell(map[r][c]);
        const double drawn = d.heatMapValue(K, tau);
        if (std::isnan(expected)) {
          QVERIFY2(std::isnan(drawn), qPrintable(QStringLiteral("K %1 tau %2: %3").arg(K).arg(tau).arg(drawn)));
          ++undefined;
        } else {
          QVERIFY2(drawn == expected,
                   qPrintable(QStringLiteral("K %1 tau %2: %3 != %4").arg(K).arg(tau).arg(drawn).arg(expected)));
          ++defined;
        }
      }
    }
    QVERIFY(defined > 60);  // two K on the log grid (10 a decade, issue #26) over up to five decades
    QVERIFY(undefined > 0);  // the long-τ cells of K = 0.3, whose segments stay short, have no data
    QVERIFY(std::isnan(d.heatMapValue(0.1, 0.5)));  // below the τ grid: no cell
    QVERIFY(std::isnan(d.heatMapValue(1.0, 2.0)));  // far from every K: no cell
    // A cell without data is drawn transparent over the grey canvas; a defined one opaque; a colour bar with a
    // title beside it.
    QwtPlot* heat = d.plot(QStringLiteral("heatMap"));
    QVERIFY(heat);
    const QwtPlotItemList spectrograms = heat->itemList(QwtPlotItem::Rtti_PlotSpectrogram);
    QCOMPARE(spectrograms.size(), 1);
    const QwtColorMap* colours = static_cast<QwtPlotSpectrogram*>(spectrograms.front())->colorMap();
    QVERIFY(colours);
    QCOMPARE(qAlpha(colours->rgb(QwtInterval(0, 2), std::nan(""))), 0);
    QCOMPARE(qAlpha(colours->rgb(QwtInterval(0, 2), 1.0)), 255);
    const QColor canvas = heat->canvasBackground().color();
    QVERIFY(canvas.red() == canvas.green() && canvas.green() == canvas.blue() && canvas.red() < 240);  // grey
    QVERIFY(heat->axisWidget(QwtPlot::yRight)->isColorBarEnabled());
    QVERIFY(!heat->axisTitle(QwtPlot::yRight).text().isEmpty());
    QVERIFY(heat->footer().text().contains(QStringLiteral("grey: no data")));

    const QList<QList<QByteArray>> summary = csvRows(QDir(cliDir_).filePath(QStringLiteral("scan_summary.csv")));
    QCOMPARE(summary.size(), 3);
    const QList<QByteArray>& header = summary[0];
    const auto column = [&](const char* name) { return static_cast<int>(header.indexOf(QByteArray(name))); };
    const struct {
      const char* plot;
      QString curve;
      const char* column;
    } checks[] = {
        {"b2", QStringLiteral("b₂, area (left)"), "b2_area"},
        {"b2", QStringLiteral("b₂ / L², fraction of the box (right)"), "b2_fraction"},
        {"long", QStringLiteral("longest segment (left)"), "longest_steps"},
        {"long", QStringLiteral("steps in segments ≥ 10⁴, fraction (right)"), "time_fraction_ge_1e4"},
    };
    for (const auto& check : checks) {
      const std::map<double, double> points = curvePoints(d.plot(QLatin1String(check.plot)), check.curve);
      QVERIFY2(column(check.column) >= 0, check.column);
      QVERIFY2(points.size() == 2, check.column);
      for (int r = 1; r < summary.size(); ++r) {
        const double K = cell(summary[r][column("K")]);
        const double expected = cell(summary[r][column(check.column)]);
        QVERIFY2(std::isfinite(expected), check.column);
        QVERIFY2(points.count(K) == 1, check.column);
        QVERIFY2(points.at(K) == expected,
                 qPrintable(QStringLiteral("%1 at K %2: %3 != %4").arg(QLatin1String(check.column)).arg(K)
                                .arg(points.at(K)).arg(expected)));
      }
    }
  }

  void compareWithCli(const QString& dir, const QString& T = kT) {
    runCli(T);
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
    comparePlotsWithCli(*d.plots());
    // The report's way: plots of their own, fed the finished summaries.
    KScanPlots report;
    report.showRuns(d.results());
    comparePlotsWithCli(report);

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
    // Ten times the other scans' T: a K of 10⁹ steps takes about half a second with AVX-512, several progress
    // reports, so the stop lands inside a K on a fast machine too (at kT a K could finish between two reports).
    const QString bigT = QStringLiteral("1000000");
    d.field(QStringLiteral("T"))->setText(bigT);
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
    QCOMPARE(d.results()[0].point.blocksDone, static_cast<std::uint64_t>(1000000));
    compareWithCli(dir, bigT);

    // A third start reuses both finished K (nothing to run) and writes the same summaries again.
    QVERIFY(d.start());
    QVERIFY(ended.wait(300000));
    QCOMPARE(ended.takeFirst().at(0).toBool(), true);
    compareWithCli(dir, bigT);
  }

  void heatMapHasOneColourScale() {
    KScanPlots plots;
    QwtPlot* heat = plots.plot(QStringLiteral("heatMap"));
    QVERIFY(heat);
    const QwtPlotItemList spectrograms = heat->itemList(QwtPlotItem::Rtti_PlotSpectrogram);
    QCOMPARE(spectrograms.size(), 1);
    const QwtColorMap* cells = static_cast<QwtPlotSpectrogram*>(spectrograms.front())->colorMap();
    const QwtColorMap* bar = heat->axisWidget(QwtPlot::yRight)->colorMap();
    QVERIFY(cells && bar);
    const QwtInterval range(0, KScanPlots::kHeatMapTop);
    QCOMPARE(heat->axisWidget(QwtPlot::yRight)->colorBarInterval().maxValue(), KScanPlots::kHeatMapTop);
    // Below 0, every 1/64 of the range, and beyond its top: cells and bar alike, both heatMapColour.
    for (int i = -8; i <= 72; ++i) {
      const double v = KScanPlots::kHeatMapTop * i / 64;
      const QRgb expected = KScanPlots::heatMapColour(v).rgb();
      QVERIFY2(cells->rgb(range, v) == expected, qPrintable(QString::number(v)));
      QVERIFY2(bar->rgb(range, v) == expected, qPrintable(QString::number(v)));
    }
    // The ends of the scale are its end colours; distinct values inside are distinct colours (a scale, not a flat
    // colour); no data is the canvas's grey, which no value takes.
    QCOMPARE(KScanPlots::heatMapColour(-1), KScanPlots::heatMapColour(0));
    QCOMPARE(KScanPlots::heatMapColour(10), KScanPlots::heatMapColour(KScanPlots::kHeatMapTop));
    QVERIFY(KScanPlots::heatMapColour(0.5) != KScanPlots::heatMapColour(1.5));
    const QColor noData = KScanPlots::heatMapColour(std::nan(""));
    QCOMPARE(heat->canvasBackground().color(), noData);
    for (int i = 0; i <= 64; ++i)
      QVERIFY(KScanPlots::heatMapColour(KScanPlots::kHeatMapTop * i / 64) != noData);
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
        {QStringLiteral("M"), QStringLiteral("-64"), QStringLiteral("M = -64 must be a whole number")},
        {QStringLiteral("M"), QStringLiteral("nan"), QStringLiteral("M = nan must be a whole number")},
        {QStringLiteral("M"), QStringLiteral("0"), QStringLiteral("M")},
        {QStringLiteral("T"), QString(), QStringLiteral("T =  must be a whole number")},
        {QStringLiteral("q"), QStringLiteral("1.5"), QStringLiteral("q = 1.5 must be a whole number")},
        {QStringLiteral("threads"), QStringLiteral("-1"), QStringLiteral("threads")},
        {QStringLiteral("b2Iterations"), QStringLiteral("-5"), QStringLiteral("b₂ steps = -5 must be an integer in [0, ")},
        {QStringLiteral("b2Iterations"), QStringLiteral("2251799813685248"), QStringLiteral("b2 at K = 0.1")},
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

  void fitsA1280x800Screen() {
    KScanDialog d{RunSpec{}};
    // The window frame and a panel take some 40 pixels of 800, a few of 1280.
    QVERIFY2(d.minimumSizeHint().width() <= 1240 && d.minimumSizeHint().height() <= 740,
             qPrintable(QStringLiteral("%1 x %2").arg(d.minimumSizeHint().width()).arg(d.minimumSizeHint().height())));
    QVERIFY(d.width() <= 1240 && d.height() <= 760);
  }

  void screenshots() {
    const QString out = qEnvironmentVariable("ARCHIPELAGO_SCREENSHOT_DIR");
    if (out.isEmpty()) QSKIP("ARCHIPELAGO_SCREENSHOT_DIR not set");
    KScanDialog d{RunSpec{}};
    const QString dir = tmp_.filePath(QStringLiteral("shots"));
    fill(d, dir);
    d.kField()->setText(QStringLiteral("0.05:0.6:0.05"));
    d.field(QStringLiteral("T"))->setText(QStringLiteral("40000"));
    d.field(QStringLiteral("seed"))->setText(QStringLiteral("1"));
    d.field(QStringLiteral("b2Iterations"))->setText(QStringLiteral("67108864"));
    d.show();
    QVERIFY(QTest::qWaitForWindowExposed(&d));
    QSignalSpy ended(&d, &KScanDialog::scanEnded);
    QVERIFY2(d.start(), qPrintable(d.message()));
    QVERIFY(ended.wait(600000));
    QCOMPARE(ended.takeFirst().at(0).toBool(), true);
    auto* upper = d.findChild<QTabWidget*>(QStringLiteral("upperTabs"));
    auto* lower = d.findChild<QTabWidget*>(QStringLiteral("lowerTabs"));
    QVERIFY(upper && lower);
    for (const QSize size : {QSize(1200, 740), QSize(1840, 1000)}) {
      d.resize(size);
      const QString suffix = size.width() > 1280 ? QStringLiteral("-1920x1080") : QString();
      // f_t | D; heat map | b₂; curves | long segments; f_t | table
      const std::pair<int, int> tabs[] = {{0, 0}, {1, 2}, {2, 1}, {0, 3}};
      const QString names[] = {QString(), QStringLiteral("-heatmap"), QStringLiteral("-exponent"),
                               QStringLiteral("-table")};
      for (int i = 0; i < 4; ++i) {
        upper->setCurrentIndex(tabs[i].first);
        lower->setCurrentIndex(tabs[i].second);
        if (i == 1) {  // the value under the mouse, on the heat map
          QWidget* canvas = d.plots()->plot(QStringLiteral("heatMap"))->canvas();
          QTest::qWait(200);
          QTest::mouseMove(canvas, QPoint(canvas->width() * 3 / 10, canvas->height() / 2));
        }
        QTest::qWait(300);
        QVERIFY(d.grab().save(QDir(out).filePath(QStringLiteral("k-scan-dialog%1%2.png").arg(names[i], suffix))));
      }
    }
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
