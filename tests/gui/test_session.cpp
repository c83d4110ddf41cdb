// Session files (issue #13, deliverable 6): saving the window and opening it again restores it as it was —
// parameters, the run (embedded or referenced), the portrait's exact view and history, mode, colour map, budget,
// launched orbits, the periodic overlay, the selected segment and its replay position, plot zooms and the tab;
// a bad or foreign file changes nothing and says why; opening over unsaved work asks.
#include <QFile>
#include <QSignalSpy>
#include <QTabWidget>

#include "GuiTestSupport.hpp"
#include "core/runfile/RunFile.hpp"
#include "core/session/SessionFile.hpp"
#include "ui/run/RunController.hpp"
#include "ui/window/SessionController.hpp"
#include "ui/window/StatisticsView.hpp"
#include "ui/plots/StatisticsPlot.hpp"
#include "ui/portrait/PortraitController.hpp"
#include "ui/portrait/PortraitPanel.hpp"
#include "ui/portrait/PortraitView.hpp"
#include "ui/segments/LongSegmentsPanel.hpp"
#include "ui/segments/LongestSegmentsModel.hpp"

using archipelago::TrappingParameters;
using archipelago::ui::MainWindow;
using archipelago::ui::RunAnswer;
using archipelago::ui::RunQuestion;
using archipelago::ui::RunStatus;

using archipelago::test::waitForProgress;
using archipelago::test::waitForStatus;

namespace {


/// A finished short run with a zoomed portrait, an orbit, a periodic overlay, a segment at a replay position,
/// a zoomed plot and the portrait tab on top.
void arrange(MainWindow& w) {
  w.parameterPanel()->setParameters(archipelago::test::shortRun(), 2);
  QVERIFY(w.startRun());
  QVERIFY(waitForStatus(w, RunStatus::finished));
  w.refreshNow();
  QTRY_VERIFY(w.longSegments()->model()->rowCount() > 2);
  auto* portrait = w.portraitPanel()->controller();
  w.tabs()->setCurrentWidget(w.portraitPanel());
  portrait->setMode(archipelago::PortraitMode::Orbits);
  portrait->zoomAt(0.3, 0.7, 37.5);
  portrait->zoomAt(0.6, 0.2, 1000.25);  // deep: the centre's digits matter
  portrait->launchOrbit(-0.2, 0.05, 500);
  archipelago::PeriodicOrbit orbit;
  orbit.period = 3;
  orbit.points = {{-0.1L, 0.1L}, {0.2L, -0.1L}, {0.0L, 0.0L}};
  portrait->showPeriodicOrbit(orbit);
  w.longSegments()->selectRow(1);
  QTRY_VERIFY(w.longSegments()->currentReplay() != nullptr);
  w.longSegments()->setCurrentIndex(7);
  w.statisticsView()->plots().front()->setUserView(QRectF(2, 1e-6, 500, 0.5));
}

}  // namespace

class TestSession : public QObject {
  Q_OBJECT
 private Q_SLOTS:
  void savedWindowIsRestoredExactly() {
    QTemporaryDir dir;
    const QString path = dir.filePath(QStringLiteral("a.archipelago"));
    archipelago::Session saved;
    archipelago::TrappingState state;
    {
      MainWindow w;
      w.setConfirmations(false);
      w.show();
      arrange(w);
      QVERIFY(w.saveSession(path));
      saved = w.sessions()->capture(path);
      state = w.latestSnapshot()->state;
    }
    // Unsaved: the run is embedded.
    const archipelago::Session onDisk = archipelago::loadSession(path.toStdString());
    QVERIFY(onDisk.embeddedRun.has_value());
    QVERIFY(onDisk.portrait.history.size() >= 3);  // whole box, two zooms (and the segment's, if it zoomed)
    QCOMPARE(onDisk.segmentRank, 1);
    QCOMPARE(onDisk.segmentPosition, std::uint64_t{7});

    MainWindow w;
    w.setConfirmations(false);
    w.show();
    QSignalSpy restored(w.sessions(), &archipelago::ui::SessionController::restored);
    QString error;
    QVERIFY2(w.openSession(path, &error), qPrintable(error));
    QVERIFY(restored.wait(20000) || restored.count() > 0);
    QCOMPARE(w.runStatus(), RunStatus::finished);
    QCOMPARE(w.latestSnapshot()->state.blocksDone, state.blocksDone);
    QVERIFY(w.latestSnapshot()->state.subsets == state.subsets);
    QVERIFY(w.parameterPanel()->parameters() == archipelago::test::shortRun());
    QCOMPARE(w.tabs()->currentWidget(), static_cast<QWidget*>(w.portraitPanel()));
    auto* portrait = w.portraitPanel()->controller();
    QVERIFY(portrait->viewport() == saved.portrait.history.at(saved.portrait.current));  // to the bit
    QVERIFY(portrait->canGoBack());
    QVERIFY(portrait->mode() == archipelago::PortraitMode::Orbits);
    QCOMPARE(portrait->orbitCount(), 1);
    QCOMPARE(portrait->sessionState().periodic.size(), std::size_t{1});
    QTRY_COMPARE(w.longSegments()->selectedRow(), 1);
    QTRY_COMPARE(w.longSegments()->currentIndex(), std::size_t{7});
    const auto view = w.statisticsView()->plots().front()->userView();
    QVERIFY(view.has_value());
    QCOMPARE(*view, QRectF(2, 1e-6, 500, 0.5));
    // Saving the restored window gives the same document.
    QCOMPARE(archipelago::sessionText(w.sessions()->capture(path)), archipelago::sessionText(saved));
  }

  void aSavedRunIsReferencedNotEmbedded() {
    QTemporaryDir dir;
    MainWindow w;
    w.setConfirmations(false);
    w.parameterPanel()->setParameters(archipelago::test::shortRun(), 2);
    QVERIFY(w.startRun());
    QVERIFY(waitForStatus(w, RunStatus::finished));
    QVERIFY(w.saveRunFile(dir.filePath(QStringLiteral("run.json"))));
    QVERIFY(w.saveSession(dir.filePath(QStringLiteral("s.archipelago"))));
    const archipelago::Session s = archipelago::loadSession(dir.filePath(QStringLiteral("s.archipelago")).toStdString());
    QVERIFY(!s.embeddedRun);
    QVERIFY(s.runFile.has_value());
    QFile text(dir.filePath(QStringLiteral("s.archipelago")));
    QVERIFY(text.open(QIODevice::ReadOnly));
    QVERIFY(text.readAll().contains("\"file\": \"run.json\""));  // relative: the folder can move
  }

  void badOrForeignFilesChangeNothing() {
    QTemporaryDir dir;
    MainWindow w;
    w.setConfirmations(false);
    w.show();
    w.parameterPanel()->setParameters(archipelago::test::shortRun(), 2);
    QVERIFY(w.startRun());
    QVERIFY(waitForStatus(w, RunStatus::finished));
    const auto before = w.latestSnapshot();
    const auto params = w.parameterPanel()->parameters();
    const int tab = w.tabs()->currentIndex();

    const auto write = [&](const QString& name, const QByteArray& content) {
      QFile f(dir.filePath(name));
      if (!f.open(QIODevice::WriteOnly)) return QString();
      f.write(content);
      return dir.filePath(name);
    };
    archipelago::Session good;
    good.spec.parameters = archipelago::test::shortRun();
    good.tab = "Phase portrait";
    std::string unknownPlot = archipelago::sessionText(good);
    unknownPlot.replace(unknownPlot.find("\"plots\": []"), 11, R"("plots": [{"name": "g_t", "zoom": [1, 2, 1, 2]}])");
    std::string badTab = archipelago::sessionText(good);
    badTab.replace(badTab.find("Phase portrait"), 14, "Spectrum");
    const std::vector<std::pair<QString, QString>> cases = {
        {write(QStringLiteral("garbage.archipelago"), "\x00\x01garbage"), QString()},
        {write(QStringLiteral("spec.archipelago"), QByteArray::fromStdString(archipelago::runSpecJson(good.spec))),
         QStringLiteral("not an Archipelago session")},
        {write(QStringLiteral("plot.archipelago"), QByteArray::fromStdString(unknownPlot)), QStringLiteral("g_t")},
        {write(QStringLiteral("tab.archipelago"), QByteArray::fromStdString(badTab)), QStringLiteral("Spectrum")},
        {dir.filePath(QStringLiteral("missing.archipelago")), QString()},
    };
    for (const auto& [path, mention] : cases) {
      QString error;
      QVERIFY2(!w.openSession(path, &error), qPrintable(path));
      QVERIFY2(!error.isEmpty(), qPrintable(path));
      if (!mention.isEmpty()) QVERIFY2(error.contains(mention), qPrintable(error));
      QCOMPARE(w.latestSnapshot(), before);
      QVERIFY(w.parameterPanel()->parameters() == params);
      QCOMPARE(w.tabs()->currentIndex(), tab);
      QCOMPARE(w.runStatus(), RunStatus::finished);
    }
  }

  void openingOverUnsavedWorkAsks() {
    QTemporaryDir dir;
    MainWindow w;
    w.show();
    archipelago::Session other;
    other.spec.parameters = archipelago::test::shortRun();
    other.spec.parameters.seed = 99;
    const QString path = dir.filePath(QStringLiteral("other.archipelago"));
    archipelago::saveSession(path.toStdString(), other);
    w.parameterPanel()->setParameters(archipelago::test::shortRun(), 2);
    std::vector<RunQuestion::Kind> asked;
    w.runController()->setAsk([&](const RunQuestion& q) {
      asked.push_back(q.kind);
      return RunAnswer::cancel;
    });
    QVERIFY(w.startRun());
    QVERIFY(waitForStatus(w, RunStatus::finished));
    const auto before = w.latestSnapshot();
    QVERIFY(!w.openSession(path));
    QCOMPARE(asked.size(), std::size_t{1});
    QCOMPARE(w.latestSnapshot(), before);
    w.runController()->setAsk([](const RunQuestion&) { return RunAnswer::discard; });
    QVERIFY(w.openSession(path));
    QCOMPARE(w.runStatus(), RunStatus::idle);  // the session has no run
    QCOMPARE(w.parameterPanel()->parameters()->seed, std::uint64_t{99});
  }
};

ARCHIPELAGO_GUI_TEST_MAIN(TestSession)
#include "test_session.moc"
