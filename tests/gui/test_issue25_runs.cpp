// Issue 25, the findings whose tests need a run (the others: test_issue25.cpp): one test per finding, named
// after it, on Qt's offscreen platform.  What only a picture can judge is in scripts/gui-screenshots.sh.
#include <QAction>
#include <QDir>
#include <QDockWidget>
#include <QFileInfo>
#include <QLabel>
#include <QMenu>
#include <QMenuBar>
#include <QScrollArea>
#include <QScrollBar>
#include <QSignalSpy>
#include <QSlider>
#include <QComboBox>
#include <QSplitter>
#include <QStatusBar>
#include <QTabWidget>
#include <QTemporaryDir>
#include <QToolButton>
#include <QTreeWidget>
#include <QVBoxLayout>
#include <QtTest>
#include <qwt_plot_curve.h>
#include <qwt_text.h>

#include <cmath>
#include <set>

#include "GuiTestSupport.hpp"
#include "core/view/Viewport.hpp"
#include "ui/periodic/PeriodicOrbitDialog.hpp"
#include "ui/plots/StatisticsPlot.hpp"
#include "ui/portrait/OrbitListPanel.hpp"
#include "ui/portrait/OverflowToolBar.hpp"
#include "ui/portrait/PortraitController.hpp"
#include "ui/portrait/PortraitPanel.hpp"
#include "ui/portrait/PortraitView.hpp"
#include "ui/portrait/PortraitWorker.hpp"
#include "ui/segments/LongSegmentsPanel.hpp"
#include "ui/window/RunGlanceView.hpp"
#include "ui/window/SessionController.hpp"

using archipelago::MapParameters;
using archipelago::PhysicalRect;
using archipelago::PortraitMode;
using archipelago::Series;
using archipelago::Statistic;
using archipelago::Viewport;
using archipelago::ui::MainWindow;
using archipelago::ui::OverflowToolBar;
using archipelago::ui::PortraitController;
using archipelago::ui::PortraitLayer;
using archipelago::ui::PortraitPanel;
using archipelago::ui::PortraitView;
using archipelago::ui::RenderState;
using archipelago::ui::RunStatus;
using archipelago::ui::StatisticsPlot;
using archipelago::test::waitForStatus;

namespace {
const MapParameters kPaper{0.1, -0.8, 0.5};  // §5

/// A window at a laptop's size with a finished short run.
void finishedRun(MainWindow& w) {
  w.setConfirmations(false);
  w.parameterPanel()->setParameters(archipelago::test::shortRun(), 2);
  QVERIFY(w.startRun());
  QVERIFY(waitForStatus(w, RunStatus::finished));
  w.refreshNow();
}

}  // namespace

class TestIssue25Runs : public QObject {
  Q_OBJECT
 private Q_SLOTS:
  // Finding 3: after reopening a session, the replay slider was squeezed to a handle.  Finding 4: the left panel
  // widened by itself (300 → 380 at Run → 460 with a segment → 480 on Play).  Missing: a replay speed control.
  void finding3and4_replaySliderAndLeftPanelKeepTheirSize() {
    QTemporaryDir dir;
    const QString path = dir.filePath(QStringLiteral("s.archipelago"));
    int width = 0;
    {
      MainWindow w;
      w.resize(1200, 760);
      w.show();
      QVERIFY(QTest::qWaitForWindowExposed(&w));
      width = w.parametersDock()->width();
      finishedRun(w);
      QCOMPARE(w.parametersDock()->width(), width);
      w.showLongSegment(0, false);
      QTRY_VERIFY_WITH_TIMEOUT(w.longSegments()->currentReplay() != nullptr, 900000);
      QCoreApplication::processEvents();
      QCOMPARE(w.segmentsDock()->width(), width);
      // Play (and its "Pause" label) does not widen it either; the speed multiplies the pace.
      auto* panel = w.longSegments();
      QComboBox* speed = panel->speedBox();
      QVERIFY(speed->count() >= 5);
      speed->setCurrentIndex(speed->findText(QStringLiteral("64×")));
      panel->setCurrentIndex(0);
      QToolButton* play = nullptr;
      for (QToolButton* b : panel->findChildren<QToolButton*>())
        if (b->text() == QStringLiteral("Play")) play = b;
      QVERIFY(play);
      play->click();
      QTest::qWait(120);
      QCOMPARE(w.segmentsDock()->width(), width);
      const std::size_t states = panel->currentReplay()->trace.states.size();
      QTRY_VERIFY(panel->currentIndex() > std::min<std::size_t>(states - 1, 3 * 64 * states / 450 / 2));
      if (play->isChecked()) play->click();
      QVERIFY(w.saveSession(path));
    }
    MainWindow w;
    w.setConfirmations(false);
    w.resize(1200, 760);
    w.show();
    QVERIFY(QTest::qWaitForWindowExposed(&w));
    QSignalSpy restored(w.sessions(), &archipelago::ui::SessionController::restored);
    QVERIFY(w.openSession(path));
    QVERIFY(restored.wait(900000) || restored.count() > 0);
    w.segmentsDock()->raise();
    QTRY_VERIFY(w.longSegments()->isVisible());
    QCOMPARE(w.segmentsDock()->width(), width);
    QSlider* slider = w.longSegments()->slider();
    QVERIFY(slider->isEnabled());
    QVERIFY2(slider->width() >= width / 2, qPrintable(QStringLiteral("slider %1 of %2").arg(slider->width()).arg(width)));
  }

  // Finding 5: the first screen was six empty plots.  Now it is the portrait, accumulating, with f_t and C_τ of
  // the run beside it.
  void finding5_theFirstScreenIsThePortrait() {
    MainWindow w;
    w.setConfirmations(false);
    w.resize(1200, 760);
    w.show();
    QVERIFY(QTest::qWaitForWindowExposed(&w));
    QCOMPARE(w.tabs()->currentWidget(), static_cast<QWidget*>(w.portraitPanel()));
    PortraitView* view = w.portraitPanel()->view();
    QTRY_VERIFY_WITH_TIMEOUT(view->currentFrame() != nullptr, 900000);
    QVERIFY(view->currentFrame()->nonEmptyPixels() > 0);
    QCOMPARE(w.portraitPanel()->sidePages()->currentWidget(), static_cast<QWidget*>(w.runGlance()));
    QVERIFY(w.runGlance()->fPlot()->isVisible() && w.runGlance()->cPlot()->isVisible());
    // A run feeds them.
    w.parameterPanel()->setParameters(archipelago::test::shortRun(), 2);
    QVERIFY(w.startRun());
    QVERIFY(waitForStatus(w, RunStatus::finished));
    w.refreshNow();
    QVERIFY(!w.runGlance()->fPlot()->isEmpty());
    QVERIFY(!w.runGlance()->cPlot()->isEmpty());
  }

  // Finding 13: Ctrl+Q asked to save the run right after Save Session embedded it; a stopped run came back
  // resumable; a new run dropped the periodic overlays of the same map.
  void finding13_savingIsConsistent() {
    QTemporaryDir dir;
    const QString path = dir.filePath(QStringLiteral("stopped.archipelago"));
    {
      MainWindow w;
      w.setConfirmations(false);
      w.show();
      w.parameterPanel()->setParameters(archipelago::test::endlessRun(), 2);
      QVERIFY(w.startRun());
      QVERIFY(archipelago::test::waitForProgress(w));
      QVERIFY(w.stopRun());
      QVERIFY(waitForStatus(w, RunStatus::stopped));
      QVERIFY(w.runController()->unsaved());
      QVERIFY(w.saveSession(path));
      QVERIFY(!w.runController()->unsaved());  // the session holds it: quitting asks nothing
    }
    MainWindow w;
    w.setConfirmations(false);
    w.show();
    QSignalSpy restored(w.sessions(), &archipelago::ui::SessionController::restored);
    QVERIFY(w.openSession(path));
    QVERIFY(restored.wait(900000) || restored.count() > 0);
    QCOMPARE(w.runStatus(), RunStatus::stopped);
    QVERIFY(!w.resumeAction()->isEnabled());
    // A periodic orbit drawn from the dialog stays when a new run of the same map starts.
    archipelago::PeriodicOrbit orbit;
    orbit.K = 0.1;
    orbit.period = 2;
    orbit.points = {{-0.1L, 0.1L}, {0.2L, -0.1L}};
    w.portraitPanel()->controller()->showPeriodicOrbit(orbit);
    w.parameterPanel()->setParameters(archipelago::test::shortRun(), 2);
    QVERIFY(w.startRun());
    QVERIFY(waitForStatus(w, RunStatus::finished));
    QCOMPARE(w.portraitPanel()->view()->layerItems(PortraitLayer::periodicOrbits).size(), std::size_t{1});
  }

  // Finding 14 (minor): Save Run File As had no shortcut; the parameter panel showed both scroll bars; "Wrote 30
  // files" when 31 were in the folder.
  void finding14_minorOnes() {
    MainWindow w;
    w.setConfirmations(false);
    w.resize(1200, 760);
    w.show();
    QVERIFY(QTest::qWaitForWindowExposed(&w));
    QAction* saveAs = nullptr;
    for (QAction* a : w.findChildren<QAction*>())
      if (a->text() == QStringLiteral("Save Run File &As…")) saveAs = a;
    QVERIFY(saveAs);
    QVERIFY(!saveAs->shortcut().isEmpty());
    QScrollArea* scroll = nullptr;
    for (QScrollArea* s : w.findChildren<QScrollArea*>())
      if (s->widget() == static_cast<QWidget*>(w.parameterPanel())) scroll = s;
    QVERIFY(scroll);
    QVERIFY(!scroll->horizontalScrollBar()->isVisible());
    finishedRun(w);
    QSignalSpy finished(w.portraitPanel()->view(), &PortraitView::renderFinished);
    w.portraitPanel()->controller()->setPointBudget(1'000'000);
    QVERIFY(finished.wait(900000));
    QTemporaryDir dir;
    QVERIFY(w.exportAllTo(dir.path()));
    const int files = static_cast<int>(QDir(dir.path()).entryList(QDir::Files).size());
    QVERIFY(w.statusBar()->currentMessage().startsWith(QStringLiteral("Wrote %1 files").arg(files)));
  }

};

ARCHIPELAGO_GUI_TEST_MAIN(TestIssue25Runs)
#include "test_issue25_runs.moc"
