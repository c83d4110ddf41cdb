// Issue 40, deliverable 4 (GUI): the Meiss–Ott Markov tree of an atlas (core/markovtree) drawn on the P_t plot and
// its levels' shares on the Atlas page.  A depth-1 atlas of K = 0.1 is computed by core and written by core's
// writeAtlasJson; the window opens it (File ▸ Open Atlas), draws the model with α and b₂ on a background job (the
// result arrives by the window's signal), and the curve's points and the page's shares are checked against the
// JSON that `archipelago-cli markov-tree` writes for the same file, α and b₂ (the CLI's own path: file, parser,
// JSON writer), not against the GUI's own numbers.
#include <QJsonArray>
#include <QJsonDocument>
#include <QJsonObject>
#include <QProcess>
#include <QPushButton>
#include <QSignalSpy>
#include <QTableWidget>
#include <QTemporaryDir>
#include <QtTest>

#include <cmath>
#include <memory>

#include "GuiTestSupport.hpp"
#include "core/atlas/AtlasExport.hpp"
#include "core/markovtree/MarkovTreeExport.hpp"
#include "ui/plots/StatisticsPlot.hpp"
#include "ui/portrait/AtlasPanel.hpp"
#include "ui/portrait/MarkovTreePanel.hpp"
#include "ui/portrait/PortraitController.hpp"
#include "ui/portrait/PortraitPanel.hpp"
#include "ui/window/MainWindow.hpp"
#include "ui/window/StatisticsView.hpp"

using archipelago::AtlasRequest;
using archipelago::ui::AtlasPanel;
using archipelago::ui::MainWindow;
using archipelago::ui::MarkovTreePanel;
using archipelago::ui::StatisticsPlot;

namespace {

/// The suite's hang bound for every wait (never a speed bound).
constexpr int kWait = 900000;

/// docs/markov-tree.md's entry at K = 0.1, typed from the docs (not from core's constants).
constexpr double kAlpha = 18.9043;
constexpr double kB2 = 1.362484;

/// Runs the CLI; its exit code and output.
int cli(const QStringList& args, QString* output) {
  QProcess p;
  p.start(QStringLiteral(ARCHIPELAGO_CLI), args);
  if (!p.waitForFinished(kWait)) return -1;
  *output = QString::fromUtf8(p.readAllStandardOutput() + p.readAllStandardError());
  return p.exitStatus() == QProcess::NormalExit ? p.exitCode() : -1;
}

bool near(double a, double b, double rel) { return std::fabs(a - b) <= rel * std::fabs(b); }

}  // namespace

class TestMarkovTree : public QObject {
  Q_OBJECT
 private:
  std::unique_ptr<MainWindow> w_;
  AtlasPanel* panel_ = nullptr;
  QTemporaryDir dir_;
  QString atlasFile_;
  QJsonObject cliJson_;

  /// The Atlas page's Markov tree.
  MarkovTreePanel* tree() const { return panel_->markovTreePanel(); }

  /// MarkovTreePanel::draw() and its signal: the reason it failed, or empty when drawn.
  QString drawAndWait(double alpha, double b2) {
    QSignalSpy drawn(tree(), &MarkovTreePanel::drawn);
    QString error;
    if (!tree()->draw(alpha, b2, &error)) return error.isEmpty() ? QStringLiteral("(refused, no reason)") : error;
    if (!tree()->pending()) return QStringLiteral("(no job in flight after the call)");
    if (!drawn.wait(kWait) && drawn.isEmpty()) return QStringLiteral("(no drawn signal)");
    if (tree()->pending()) return QStringLiteral("(still pending after its signal)");
    return drawn.takeFirst().at(0).toString();
  }

 private Q_SLOTS:
  void initTestCase() {
    QVERIFY(dir_.isValid());
    w_ = std::make_unique<MainWindow>();
    w_->setConfirmations(false);
    w_->resize(1280, 770);
    w_->show();
    QVERIFY(QTest::qWaitForWindowExposed(w_.get()));
    panel_ = w_->portraitPanel()->atlasPanel();
    QVERIFY(panel_);

    // The atlas: K = 0.1, depth 1, periods ≤ 200 (the core and GUI atlas tests' request), by core, to a file.
    AtlasRequest r;
    r.map = w_->portraitPanel()->controller()->map();
    QCOMPARE(r.map.K, 0.1);
    r.depth = 1;
    r.maxPeriod = 200;
    r.scanSteps = 0;
    const archipelago::Atlas atlas = archipelago::computeAtlas(r);
    QVERIFY(!atlas.cancelled);
    atlasFile_ = dir_.filePath(QStringLiteral("a.json"));
    archipelago::writeAtlasJson(atlasFile_.toStdString(), atlas);

    // The CLI's model of the same file with the same α, b₂ and times (its defaults: t ≤ 10⁹, 30 per decade).
    const QString json = dir_.filePath(QStringLiteral("model.json"));
    QString out;
    QCOMPARE(cli({QStringLiteral("markov-tree"), QStringLiteral("--atlas"), atlasFile_, QStringLiteral("--alpha"),
                  QStringLiteral("18.9043"), QStringLiteral("--b2"), QStringLiteral("1.362484"), QStringLiteral("--at"),
                  QStringLiteral("10000,100000,1000000"), QStringLiteral("--json"), json, QStringLiteral("--quiet")},
                 &out),
             0);
    QFile f(json);
    QVERIFY(f.open(QIODevice::ReadOnly));
    cliJson_ = QJsonDocument::fromJson(f.readAll()).object();
    QCOMPARE(cliJson_.value(QStringLiteral("format")).toString(), QStringLiteral("archipelago markov tree"));
  }

  // Without an atlas there is nothing to model: refused at once with the reason, nothing drawn.
  void refusedWithoutAnAtlas() {
    QString error;
    QVERIFY(!tree()->draw(kAlpha, kB2, &error));
    QVERIFY2(error.contains(QStringLiteral("no atlas")), qPrintable(error));
    QVERIFY(!tree()->button()->isEnabled());
    QVERIFY(w_->statisticsView()->plot(archipelago::Statistic::P)->modelPoints().isEmpty());
  }

  // Without a run, the dialog offers docs/markov-tree.md's α and b₂, saying so.
  void theEntryWithoutARunIsTheDocs() {
    const MarkovTreePanel::Entry e = tree()->entry();
    QCOMPARE(e.alpha, kAlpha);
    QCOMPARE(e.b2, kB2);
    QVERIFY2(e.alphaSource.contains(QStringLiteral("markov-tree.md")), qPrintable(e.alphaSource));
  }

  // File ▸ Open Atlas shows the file on the Atlas page.
  void opensTheAtlasFile() {
    QString error;
    QVERIFY2(w_->openAtlasFile(atlasFile_, &error), qPrintable(error));
    QVERIFY(panel_->atlas());
    QVERIFY(w_->portraitPanel()->sidePages()->currentWidget() == panel_);
    QVERIFY2(panel_->progressText().startsWith(QStringLiteral("From a.json")), qPrintable(panel_->progressText()));
    QVERIFY(tree()->button()->isEnabled());
    // A file that is not an atlas is refused with core's reason.
    const QString bad = dir_.filePath(QStringLiteral("bad.json"));
    QFile b(bad);
    QVERIFY(b.open(QIODevice::WriteOnly));
    b.write("{\"format\": \"something else\"}");
    b.close();
    QVERIFY(!panel_->openAtlasFile(bad, &error));
    QVERIFY(!error.isEmpty());
    QVERIFY(panel_->atlas());  // the one shown stays
  }

  // Bad α or b₂: refused at once with core's reason.
  void refusesCoresBadNumbers() {
    QString error;
    QVERIFY(!tree()->draw(0, kB2, &error));
    QVERIFY2(error.contains(QStringLiteral("alpha")), qPrintable(error));
    QVERIFY(!tree()->draw(kAlpha, -1, &error));
    QVERIFY2(error.contains(QStringLiteral("b2")), qPrintable(error));
    // Issue 53 finding 6, issue 54 item 2: α = β = 0 drew an empty "model", α below one step was taken; both are
    // refused at once with core's words.
    QVERIFY(!tree()->draw(0, 0, &error));
    QVERIFY2(error.contains(QStringLiteral("alpha = 0 must be finite and at least 1")), qPrintable(error));
    QVERIFY(!tree()->draw(1e-300, kB2, &error));
    QVERIFY2(error.contains(QStringLiteral("alpha = 1e-300")), qPrintable(error));
  }

  // Issue 53 finding 6: α = 1e300 gave w = 2.8e297 visits per segment and a vertical line on P_t.  A P_1 above 1 (and
  // a b₂ above the box's area) needs the atlas's tree: refused by the job with core's words, nothing drawn.
  void refusesAnImpossibleEntry() {
    const QString huge = drawAndWait(1e300, kB2);
    QVERIFY2(huge.contains(QStringLiteral("P_1 = w S(1)")) && huge.contains(QStringLiteral("cannot exceed 1")),
             qPrintable(huge));
    // The page says it too, whole (the status bar cuts a long reason off), and nothing is drawn.
    QVERIFY2(tree()->text().contains(QStringLiteral("cannot exceed 1")), qPrintable(tree()->text()));
    QVERIFY(!tree()->model());
    const QString box = drawAndWait(kAlpha, 100);
    QVERIFY2(box.contains(QStringLiteral("b2 = 100 must lie in (0, 1.69")), qPrintable(box));
  }

  // The curve: at every t of the CLI's grid where its P is a number, the plot has the point (t, P), the same double;
  // nothing else; the legend names the atlas's depth.
  void theCurveIsTheClisPt() {
    QCOMPARE(drawAndWait(kAlpha, kB2), QString());
    StatisticsPlot* p = w_->statisticsView()->plot(archipelago::Statistic::P);
    QCOMPARE(p->modelTitle(), QStringLiteral("Markov tree (atlas depth 1)"));
    const QVector<QPointF> points = p->modelPoints();
    const QJsonObject s = cliJson_.value(QStringLiteral("survival")).toObject();
    const QJsonArray t = s.value(QStringLiteral("t")).toArray(), P = s.value(QStringLiteral("P")).toArray();
    QCOMPARE(t.size(), P.size());
    int expected = 0;
    for (int i = 0; i < t.size(); ++i) {
      // t = 0, the exponential tail below the doubles (null) and P = 0: nothing a log axis shows.
      if (t.at(i).toDouble() == 0 || P.at(i).isNull() || P.at(i).toDouble() == 0) continue;
      QVERIFY2(expected < points.size(), qPrintable(QStringLiteral("fewer points than the CLI's: %1 at t = %2").arg(points.size()).arg(t.at(i).toDouble())));
      const QPointF q = points.at(expected++);
      QCOMPARE(q.x(), t.at(i).toDouble());
      QVERIFY2(near(q.y(), P.at(i).toDouble(), 1e-15),
               qPrintable(QStringLiteral("t = %1: plot %2, CLI %3").arg(q.x()).arg(q.y(), 0, 'g', 17).arg(P.at(i).toDouble(), 0, 'g', 17)));
    }
    QCOMPARE(points.size(), expected);
    QVERIFY(expected > 100);  // 30 per decade to where the exponential tail leaves the doubles
    // w = α Φ_centre / b₂ with the loop's flux in the file and the docs' α, b₂ (the CLI's entry weight).
    const double flux = cliJson_.value(QStringLiteral("entry_flux")).toDouble();
    QVERIFY(flux > 0);
    QVERIFY(near(static_cast<double>(tree()->model()->weight.value_or(0)), kAlpha * flux / kB2, 1e-12));
    QVERIFY(near(cliJson_.value(QStringLiteral("entry")).toObject().value(QStringLiteral("weight")).toDouble(),
                 kAlpha * flux / kB2, 1e-12));
  }

  // The Atlas page's shares: each level's part of S(t) / S(t) at 10⁴, 10⁵, 10⁶ as the CLI's JSON gives them, summing
  // to 1 in each column.
  void theSharesAreTheClisAndSumToOne() {
    QTableWidget* table = tree()->sharesTable();
    QVERIFY(table->isVisible());
    const QJsonObject s = cliJson_.value(QStringLiteral("survival")).toObject();
    const QJsonArray t = s.value(QStringLiteral("t")).toArray(), S = s.value(QStringLiteral("S")).toArray();
    const QJsonArray levels = s.value(QStringLiteral("levels")).toArray();
    QCOMPARE(table->rowCount(), static_cast<int>(levels.size()));
    QCOMPARE(table->rowCount(), 2);  // depth 1: the centre's level and the chains about it
    const std::vector<std::uint64_t> times = MarkovTreePanel::shareTimes();
    QCOMPARE(table->columnCount(), static_cast<int>(times.size()));
    for (int c = 0; c < table->columnCount(); ++c) {
      int i = -1;
      for (int k = 0; k < t.size(); ++k)
        if (static_cast<std::uint64_t>(t.at(k).toDouble()) == times[static_cast<std::size_t>(c)]) i = k;
      QVERIFY2(i >= 0, "the CLI's grid lacks a share time");
      double sum = 0;
      for (int l = 0; l < table->rowCount(); ++l) {
        QTableWidgetItem* cell = table->item(l, c);
        QVERIFY(cell);
        bool ok = false;
        const double share = cell->data(Qt::UserRole).toDouble(&ok);
        QVERIFY(ok);
        const double cliShare = levels.at(l).toArray().at(i).toDouble() / S.at(i).toDouble();
        QVERIFY2(near(share, cliShare, 1e-12),
                 qPrintable(QStringLiteral("level %1 at t = %2: page %3, CLI %4").arg(l).arg(times[static_cast<std::size_t>(c)])
                                .arg(share).arg(cliShare)));
        QCOMPARE(cell->text(), QStringLiteral("%1 %").arg(100 * share, 0, 'f', 1));
        sum += share;
      }
      QVERIFY2(std::fabs(sum - 1) < 1e-12, qPrintable(QString::number(sum, 'g', 17)));
    }
  }

  // Another atlas removes the model of the previous one from the page (its plot curve is redrawn by the next Model).
  void anotherAtlasRemovesTheShares() {
    QString error;
    QVERIFY2(w_->openAtlasFile(atlasFile_, &error), qPrintable(error));
    QVERIFY(!tree()->model());
    QVERIFY(!tree()->sharesTable()->isVisible());
  }

  // With a run shown, the entry's α is the run's mean segment length; a new run clears the curve with its other
  // plots, and Model P_t draws it again with that α: P is linear in α, so each point is the CLI's (α = 18.9043)
  // times α_run / 18.9043.
  void withARunTheEntryIsTheRunsAlpha() {
    w_->parameterPanel()->setParameters(archipelago::test::shortRun(), 2);
    QVERIFY(w_->startRun());
    QVERIFY(archipelago::test::waitForStatus(*w_, archipelago::ui::RunStatus::finished, kWait));
    w_->refreshNow();
    StatisticsPlot* p = w_->statisticsView()->plot(archipelago::Statistic::P);
    QVERIFY(p->modelPoints().isEmpty());
    const double runAlpha = w_->latestSnapshot()->statistics.alpha;
    QVERIFY(runAlpha > 1 && runAlpha != kAlpha);
    const MarkovTreePanel::Entry e = tree()->entry();
    QCOMPARE(e.alpha, runAlpha);
    QVERIFY2(e.alphaSource.contains(QStringLiteral("run")), qPrintable(e.alphaSource));
    QCOMPARE(e.b2, kB2);
    QCOMPARE(drawAndWait(e.alpha, e.b2), QString());
    w_->refreshNow();
    const QVector<QPointF> points = p->modelPoints();
    const QJsonObject s = cliJson_.value(QStringLiteral("survival")).toObject();
    const QJsonArray t = s.value(QStringLiteral("t")).toArray(), P = s.value(QStringLiteral("P")).toArray();
    QVERIFY(points.size() > 100);
    int checked = 0;
    for (const QPointF& q : points)
      for (int i = 0; i < t.size(); ++i)
        if (t.at(i).toDouble() == q.x() && !P.at(i).isNull() && P.at(i).toDouble() > 1e-300) {
          QVERIFY2(near(q.y(), P.at(i).toDouble() * runAlpha / kAlpha, 1e-13), qPrintable(QString::number(q.x())));
          ++checked;
        }
    QVERIFY(checked > 100);
    QCOMPARE(p->modelTitle(), QStringLiteral("Markov tree (atlas depth 1)"));
  }

  // A run of another map (K = 0.15) beside the K = 0.1 atlas: its α is not offered (it would size the model of
  // another map), the docs' is, saying why (core's markovTreeEntryOffer).
  void aRunOfAnotherMapIsNotTheEntry() {
    archipelago::TrappingParameters p = archipelago::test::shortRun();
    p.map.K = 0.15;
    w_->parameterPanel()->setParameters(p, 2);
    QVERIFY(w_->startRun());
    QVERIFY(archipelago::test::waitForStatus(*w_, archipelago::ui::RunStatus::finished, kWait));
    w_->refreshNow();
    const double runAlpha = w_->latestSnapshot()->statistics.alpha;
    QVERIFY(runAlpha > 1 && runAlpha != kAlpha);
    QVERIFY(panel_->atlas() && panel_->atlas()->request.map.K == 0.1);
    const MarkovTreePanel::Entry e = tree()->entry();
    QCOMPARE(e.alpha, kAlpha);
    QCOMPARE(e.b2, kB2);
    QVERIFY2(e.alphaSource.contains(QStringLiteral("another map: K = 0.15")), qPrintable(e.alphaSource));
  }

  void cleanupTestCase() { w_.reset(); }
};

ARCHIPELAGO_GUI_TEST_MAIN(TestMarkovTree)
#include "test_markov_tree.moc"

