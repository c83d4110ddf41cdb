// The tail scan's figure γ(t, K) in the K-scan dialog (issue 55, deliverable 3): "Open tail scan…" on a folder made
// by core's runTailScan (two K, 10 to 10⁴ steps, small enough for a test, large enough that one K reaches every
// window and the other none) draws in the "Tail scan" tab the summary's γ in every cell of the heat map (no data where
// the K does not reach the window), its γ per window one point per K, the K-average, and the literature's 1.57 and
// 1.44 as lines; a folder with a truncated file, or without tail files, gives a one-line message and shows nothing
// new, the dialog alive; the folder chooser starts at the tail scan last opened.

#include <QFile>
#include <QFileDialog>
#include <QPushButton>
#include <QTimer>
#include <QSignalSpy>
#include <QTabWidget>
#include <QTemporaryDir>
#include <QtTest>
#include <qwt_plot.h>
#include <qwt_plot_curve.h>
#include <qwt_text.h>

#include <cmath>
#include <filesystem>
#include <map>

#include "GuiTestSupport.hpp"
#include "core/job/Ranks.hpp"
#include "core/scan/ScanBox.hpp"
#include "core/tail/TailFile.hpp"
#include "core/tail/TailScan.hpp"
#include "ui/scan/KScanDialog.hpp"
#include "ui/scan/TailScanPlots.hpp"

using archipelago::RunSpec;
using archipelago::TailScanSummary;
using archipelago::ui::KScanDialog;
using archipelago::ui::TailScanPlots;

namespace {

/// The points of the curve titled `title` in `plot`, by t (x); empty when there is no such curve.
std::map<double, double> curvePoints(QwtPlot* plot, const QString& title) {
  std::map<double, double> points;
  for (QwtPlotItem* item : plot->itemList(QwtPlotItem::Rtti_PlotCurve)) {
    if (item->title().text() != title) continue;
    const auto* curve = static_cast<QwtPlotCurve*>(item);
    for (size_t i = 0; i < curve->dataSize(); ++i)
      points[curve->sample(static_cast<int>(i)).x()] = curve->sample(static_cast<int>(i)).y();
  }
  return points;
}

/// Waits for the dialog's tail scan to be shown or refused; whether it was shown.
bool opened(KScanDialog& d, const QString& dir) {
  QSignalSpy spy(&d, &KScanDialog::tailScanOpened);
  d.openTailScan(dir);
  if (!spy.wait(900000)) return false;
  return spy.takeFirst().at(0).toBool();
}

}  // namespace

class TailScanFigureTest : public QObject {
  Q_OBJECT

 private:
  QTemporaryDir tmp_;
  QString scan_;
  TailScanSummary summary_;

 private Q_SLOTS:
  void initTestCase() {
    archipelago::TailScanRequest r;
    r.K = "0.1,0.15";
    r.base.threads = 2;
    r.request.population = 200;
    r.request.replicas = 2;
    r.request.minAncestors = 4;
    r.request.firstSteps = 10;
    r.request.maxSteps = 10000;
    scan_ = tmp_.filePath(QStringLiteral("scan"));
    r.dir = scan_.toStdString();
    archipelago::OneProcess one;
    const archipelago::TailScanOutcome outcome = archipelago::runTailScan(r, {}, one);
    QVERIFY(outcome.end == archipelago::TailScanOutcome::End::finished);
    summary_ = outcome.summary;
  }

  void opensAFolderAndDrawsItsSummary() {
    KScanDialog d{RunSpec{}};
    QVERIFY2(opened(d, scan_), qPrintable(d.message()));
    QVERIFY2(d.message().contains(QStringLiteral("2 K (0.1 to 0.15), 3 windows")), qPrintable(d.message()));
    QCOMPARE(d.findChild<QTabWidget*>(QStringLiteral("resultTabs"))->currentWidget(), d.tailPlots());
    // The heat map: every cell the summary's γ of its K and window; no data where the K does not reach it.
    const TailScanSummary& s = summary_;
    QCOMPARE(s.windows.size(), std::size_t{3});
    int reached = 0, notReached = 0;
    for (std::size_t k = 0; k < s.K.size(); ++k)
      for (std::size_t w = 0; w < s.windows.size(); ++w) {
        const double expected = s.gamma[k][w].gamma, drawn = d.tailPlots()->heatMapValue(s.K[k], s.average[w].t);
        QVERIFY2(std::isnan(expected) ? std::isnan(drawn) : drawn == expected,
                 qPrintable(QStringLiteral("K %1, window %2: drawn %3, summary %4").arg(s.K[k]).arg(w).arg(drawn).arg(expected)));
        (std::isnan(expected) ? notReached : reached) += 1;
      }
    QVERIFY2(reached > 0 && notReached > 0, "the scan has cells of both kinds");
    QVERIFY(std::isnan(d.tailPlots()->heatMapValue(0.1, 1e6)));  // above the last window: no cell
    // γ per window: a point per K and window reached, the K-average, the two reference lines.
    QwtPlot* windows = d.tailPlots()->plot(QStringLiteral("tailGammaWindows"));
    QVERIFY(windows);
    for (std::size_t k = 0; k < s.K.size(); ++k) {
      std::map<double, double> expected;
      for (const archipelago::TailExponent& e : s.gamma[k])
        if (std::isfinite(e.gamma)) expected[e.t] = e.gamma;
      QCOMPARE(curvePoints(windows, k == 0 ? QStringLiteral("K = 0.1") : QStringLiteral("K = 0.15")), expected);
    }
    std::map<double, double> mean;
    for (const archipelago::TailScanWindow& a : s.average)
      if (std::isfinite(a.mean)) mean[a.t] = a.mean;
    QCOMPARE(curvePoints(windows, QStringLiteral("K-average")), mean);
    int references = 0;
    for (QwtPlotItem* item : windows->itemList(QwtPlotItem::Rtti_PlotCurve)) {
      const QString title = item->title().text();
      const double gamma = title.startsWith(QStringLiteral("1.57: ")) ? 1.57
                           : title.startsWith(QStringLiteral("1.44: ")) ? 1.44 : 0;
      if (gamma == 0) continue;
      ++references;
      const auto* line = static_cast<QwtPlotCurve*>(item);
      QCOMPARE(line->sample(0).y(), gamma);
      QCOMPARE(line->sample(1).y(), gamma);
      QCOMPARE(line->sample(0).x(), s.windows.front().from);
      QCOMPARE(line->sample(1).x(), s.windows.back().to);
    }
    QCOMPARE(references, 2);
  }

  // A K whose first level is out of reach (its pilot's counts, as tail-scan keeps them) is named in the message and
  // drawn nowhere; the finished K are drawn as before.
  void aKOutOfReachIsNamedAndNotDrawn() {
    const QString folder = tmp_.filePath(QStringLiteral("reach"));
    std::filesystem::create_directories(folder.toStdString());
    std::filesystem::copy(archipelago::tailScanFile(scan_.toStdString(), 0.1),
                          archipelago::tailScanFile(folder.toStdString(), 0.1));
    archipelago::TailRequest request = summary_.states.front().request;
    request.run.map = archipelago::scanBox(1.3);
    archipelago::TailState refused = archipelago::startTail(request);
    refused.pilotTrials = archipelago::kPilotTrials;
    refused.pilotOrbits = 64;
    QVERIFY(archipelago::tailFirstLevelRefusal(refused));
    archipelago::saveTailFile(archipelago::tailScanFile(folder.toStdString(), 1.3), refused);
    KScanDialog d{RunSpec{}};
    QVERIFY2(opened(d, folder), qPrintable(d.message()));
    QVERIFY2(d.message().contains(QStringLiteral("1 K (0.1 to 0.1)")) &&
                 d.message().contains(QStringLiteral("First level out of reach (no tail there), not shown: K = 1.3.")),
             qPrintable(d.message()));
    QCOMPARE(d.tailPlots()->heatMapValue(summary_.K[0], summary_.average[0].t), summary_.gamma[0][0].gamma);
    // Its column is drawn empty: K = 0.1's cells do not stretch over K = 1.3.
    for (const archipelago::TailScanWindow& w : summary_.average)
      QVERIFY(std::isnan(d.tailPlots()->heatMapValue(1.3, w.t)));
  }

  void aTruncatedFileOrAnEmptyFolderIsAMessage() {
    KScanDialog d{RunSpec{}};
    QVERIFY(opened(d, scan_));
    const QString truncated = tmp_.filePath(QStringLiteral("truncated"));
    std::filesystem::copy(scan_.toStdString(), truncated.toStdString());
    QFile file(QDir(truncated).filePath(QStringLiteral("tail-K0.15.json")));
    QVERIFY(file.open(QIODevice::ReadWrite));
    QVERIFY(file.resize(5000));
    file.close();
    QVERIFY(!opened(d, truncated));
    QVERIFY2(d.message().startsWith(QStringLiteral("Tail scan not shown: ")) &&
                 d.message().contains(QStringLiteral("tail-K0.15.json")) && !d.message().contains(u'\n'),
             qPrintable(d.message()));
    // The figure shown before stays.
    QCOMPARE(d.tailPlots()->heatMapValue(summary_.K[0], summary_.average[0].t), summary_.gamma[0][0].gamma);
    const QString empty = tmp_.filePath(QStringLiteral("empty"));
    QVERIFY(QDir().mkpath(empty));
    QVERIFY(!opened(d, empty));
    QVERIFY2(d.message().contains(QStringLiteral("holds no tail file")), qPrintable(d.message()));
    QVERIFY(!opened(d, tmp_.filePath(QStringLiteral("no-such-folder"))));
    QVERIFY2(d.message().contains(QStringLiteral("is not a folder")), qPrintable(d.message()));
  }

  // "Open tail scan…" starts where the last tail scan was opened, not in the K scan's folder ("scan").
  void theFolderChooserStartsAtTheLastTailScan() {
    KScanDialog d{RunSpec{}};
    QPushButton* open = nullptr;
    for (QPushButton* b : d.findChildren<QPushButton*>())
      if (b->text().remove(u'&') == QStringLiteral("Open tail scan…")) open = b;
    QVERIFY(open);
    const auto startsIn = [&] {
      QString seen;
      QTimer::singleShot(0, [&] {
        auto* chooser = qobject_cast<QFileDialog*>(QApplication::activeModalWidget());
        if (chooser) {
          seen = chooser->directory().absolutePath();
          chooser->reject();
        }
      });
      open->click();
      return seen;
    };
    QVERIFY(startsIn() != QDir(scan_).absolutePath());
    QVERIFY(opened(d, scan_));
    QCOMPARE(startsIn(), QDir(scan_).absolutePath());
  }
};

int main(int argc, char** argv) {
  archipelago::test::isolatedHome();
  QApplication app(argc, argv);
  TailScanFigureTest test;
  return QTest::qExec(&test, argc, argv);
}

#include "test_tail_scan_figure.moc"
