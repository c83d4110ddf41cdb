// Issue 25: what a new user hit at 1280×800, and the portrait as the first thing a user sees.  One test per
// finding (named after it), and one per item of the "Missing" list, on Qt's offscreen platform.  What only a
// picture can judge (the first screen, the legend's look, the deep zoom) is in scripts/gui-screenshots.sh too.
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
#include <qwt_abstract_legend.h>
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

/// True when `action` can be reached on the portrait's tool bar: a visible button, or an entry of the » menu.
bool reachable(OverflowToolBar* bar, QAction* action) {
  for (QToolButton* b : bar->findChildren<QToolButton*>())
    if (b->defaultAction() == action && b->isVisible()) return true;
  for (QAction* a : bar->overflowActions())
    if (a == action) return true;
  return false;
}

/// Every action of a menu, submenus included.
void collect(const QMenu* menu, std::set<const QAction*>& into) {
  for (QAction* a : menu->actions()) {
    into.insert(a);
    if (a->menu()) collect(a->menu(), into);
  }
}

Series fallingSeries(std::size_t n) {
  Series s;
  for (std::size_t i = 0; i < n; ++i) {
    const double t = std::pow(10.0, 0.05 * static_cast<double>(i));
    s.x.push_back(t);
    s.value.push_back(std::pow(t, -1.5));
    s.error.push_back(0.01 * std::pow(t, -1.5));
  }
  return s;
}
}  // namespace

class TestIssue25 : public QObject {
  Q_OBJECT
 private Q_SLOTS:
  // Finding 1: the tool bar's » did nothing, so Export PNG…, Export .npy… and b₂… could not be reached; at
  // 1024×700 neither could Reset, +, − or Clear orbits.  Now » opens a menu of what does not fit, and the Portrait
  // menu holds every action.
  void finding1_everyPortraitActionIsReachable() {
    for (const QSize size : {QSize(1200, 760), QSize(1024, 700)}) {
      MainWindow w;
      w.setConfirmations(false);
      w.resize(size);
      w.show();
      QVERIFY(QTest::qWaitForWindowExposed(&w));
      PortraitPanel& p = *w.portraitPanel();
      OverflowToolBar* bar = p.toolBar();
      QTRY_VERIFY(bar->width() > 0);
      for (QAction* a : {p.exportPngAction(), p.exportNpyAction(), p.stochasticAreaAction(), p.resetAction(),
                         p.clearOrbitsAction(), p.undoOrbitAction(), p.manifoldsAction(), p.profileToolAction()})
        QVERIFY2(reachable(bar, a), qPrintable(a->text()));
      // The » button is there when something is hidden, and its menu offers exactly the hidden actions.
      QVERIFY(!bar->overflowActions().empty());
      QVERIFY(bar->overflowButton()->isVisible());
      QMenu* menu = bar->overflowButton()->menu();
      QVERIFY(menu);
      menu->popup(bar->mapToGlobal(QPoint(0, 0)));
      QTRY_VERIFY(menu->isVisible());
      const auto hidden = bar->overflowActions();
      for (QAction* a : hidden) QVERIFY2(menu->actions().contains(a), qPrintable(a->text()));
      menu->close();
      // The bar never sets the window's minimum width.
      QVERIFY(bar->minimumSizeHint().width() < 80);
      // The Portrait menu holds every action of the bar.
      std::set<const QAction*> inMenu;
      collect(p.menu(), inMenu);
      for (QAction* a : {p.exportPngAction(), p.exportNpyAction(), p.stochasticAreaAction(), p.resetAction(),
                         p.clearOrbitsAction(), p.undoOrbitAction(), p.raiseBudgetAction(), p.equalAspectAction()})
        QVERIFY2(inMenu.count(a), qPrintable(a->text()));
    }
  }

  // Finding 2: a middle-drag at the full view moved the axes outside the box (QwtPlotPanner moved them while the
  // view stayed clamped); Home, Reset and the arrows then did nothing.  Now the axes only ever show the view.
  void finding2_middleDragAtTheFullViewKeepsTheAxesOnTheBox() {
    MainWindow w;
    w.setConfirmations(false);
    w.resize(1200, 760);
    w.show();
    QVERIFY(QTest::qWaitForWindowExposed(&w));
    PortraitPanel& p = *w.portraitPanel();
    PortraitController& c = *p.controller();
    QWidget* canvas = p.view()->canvas();
    QTRY_VERIFY(canvas->width() > 100);
    const auto drag = [&](QPoint by) {
      const QPoint from = canvas->rect().center();
      QTest::mousePress(canvas, Qt::MiddleButton, Qt::NoModifier, from);
      QTest::mouseMove(canvas, from + by / 2);
      QTest::mouseMove(canvas, from + by);
      QTest::mouseRelease(canvas, Qt::MiddleButton, Qt::NoModifier, from + by);
      QCoreApplication::processEvents();
    };
    QSignalSpy messages(&c, &PortraitController::statusMessage);
    drag(QPoint(120, 60));
    QVERIFY(c.viewport() == Viewport());
    const auto [x0, x1] = p.view()->xAxisRange();
    QCOMPARE(x0, -0.8);
    QCOMPARE(x1, 0.5);
    QVERIFY(!messages.isEmpty());  // says why nothing moved
    // Zoomed in at the box's corner, a drag past the edge stops at the edge: the axes stay in the box.
    c.zoomAt(0.02, 0.98, 8);
    drag(QPoint(300, 300));
    const auto [a0, a1] = p.view()->xAxisRange();
    const auto [b0, b1] = p.view()->yAxisRange();
    QVERIFY2(a0 >= -0.8 - 1e-12 && a1 <= 0.5 + 1e-12, qPrintable(QStringLiteral("%1 … %2").arg(a0).arg(a1)));
    QVERIFY(b0 >= -0.65 - 1e-12 && b1 <= 0.65 + 1e-12);
    // Home (Reset) works at once.
    p.resetAction()->trigger();
    QVERIFY(c.viewport() == Viewport());
    QCOMPARE(p.view()->xAxisRange().first, -0.8);
  }

  // Finding 6: P_t's legend ran past the plot frame and the four reference slopes shared one grey swatch.
  void finding6_pLegendInsideTheFrameWithDistinctReferenceSwatches() {
    StatisticsPlot plot(Statistic::P);
    plot.resize(330, 260);
    plot.show();
    QVERIFY(QTest::qWaitForWindowExposed(&plot));
    plot.setData(fallingSeries(80), {});
    plot.refresh();
    const auto refs = plot.referenceCurves();
    QCOMPARE(refs.size(), std::size_t{4});
    std::set<QRgb> colours;
    for (const QwtPlotCurve* c : refs) {
      colours.insert(c->pen().color().rgb());
      QVERIFY(c->title().text().contains(QStringLiteral("asymptotic (literature)")));
    }
    QCOMPARE(colours.size(), std::size_t{4});
    // Since issue 37 (finding 5) the legend is below the plot, not over the canvas: never past the frame
    // (gui.issue37 checks that every entry is whole).
    QVERIFY(plot.legendShown());
    QVERIFY(plot.legendRect().isEmpty());
    QVERIFY(plot.legend() && !plot.legend()->geometry().intersects(plot.canvas()->geometry()));
  }

  // Finding 7: −d log C/d log τ autoscaled to 0–16 on its last noisy points.
  void finding7_localExponentOnTheRangeOfInterest() {
    StatisticsPlot plot(Statistic::localExponent);
    Series s;
    for (int i = 0; i < 120; ++i) {
      s.x.push_back(std::pow(10.0, 0.03 * i));
      s.value.push_back(i < 110 ? 0.25 + 0.001 * i : 16.0);  // the last few: the tail's noise
      s.error.push_back(i < 110 ? 0.03 : 0.4);
    }
    plot.setData(s, {});
    plot.refresh();
    QCOMPARE(plot.axisInterval(QwtPlot::yLeft).minValue(), 0.0);
    QCOMPARE(plot.axisInterval(QwtPlot::yLeft).maxValue(), 2.0);
    // A zoom elsewhere, then Reset Zoom comes back to it.
    plot.setUserView(QRectF(1, 0, 100, 16));
    QVERIFY(plot.userView().has_value());
    plot.resetZoom();
    QCOMPARE(plot.axisInterval(QwtPlot::yLeft).maxValue(), 2.0);
  }

  // Finding 8: below a width of ~10⁻⁷ the budget left sparse dust, nothing suggested raising it, and the
  // readout was cut off.  Now a sparse view says so (in a readout on its own line) and Ctrl+B raises the budget.
  void finding8_aSparseDeepViewSuggestsTheBudget() {
    PortraitPanel panel;
    panel.resize(900, 600);
    PortraitController& c = *panel.controller();
    c.setPointBudget(3'000'000);
    c.setViewport(Viewport::fromPhysical(kPaper, {-0.10L, -0.10L + 1e-7L, 0.05L, 0.05L + 1e-7L}));
    QSignalSpy finished(panel.view(), &PortraitView::renderFinished);  // before show: the render may end in the wait
    panel.show();
    QVERIFY(QTest::qWaitForWindowExposed(&panel));
    QVERIFY(!finished.isEmpty() || finished.wait(900000));
    QVERIFY(panel.view()->sparse());
    QVERIFY2(panel.readoutText().contains(QStringLiteral("sparse")) && panel.readoutText().contains(QStringLiteral("Ctrl+B")),
             qPrintable(panel.readoutText()));
    QVERIFY(panel.raiseBudgetAction()->isEnabled());
    panel.raiseBudgetAction()->trigger();
    QCOMPARE(c.pointBudget(), std::uint64_t{30'000'000});
    QVERIFY(panel.view()->isRendering());
    // The readout has a line of its own, as wide as the portrait's column.
    auto* readout = panel.findChild<QLabel*>(QStringLiteral("portraitReadout"));
    QVERIFY(readout);
    QVERIFY(readout->width() >= panel.view()->width() - 8);
  }

  // Finding 9: an exported PNG was the 700×546 screen image stretched to 1200×1000.  Now its raster is rendered
  // anew at the size the canvas has in the image.
  void finding9_exportsAreRenderedAtTheExportSize() {
    PortraitPanel panel;
    panel.resize(520, 420);
    panel.controller()->setPointBudget(1'000'000);
    QSignalSpy finished(panel.view(), &PortraitView::renderFinished);  // before show: the render may end in the wait
    panel.show();
    QVERIFY(QTest::qWaitForWindowExposed(&panel));
    QVERIFY(!finished.isEmpty() || finished.wait(900000));
    const int screen = panel.view()->currentFrame()->request.width;
    QTemporaryDir dir;
    const QString png = dir.filePath(QStringLiteral("p.png"));
    QVERIFY(panel.view()->exportPng(png, QSize(1200, 1000)));
    const QSize raster = panel.view()->lastExportRasterSize();
    QVERIFY2(raster.width() > 2 * screen, qPrintable(QStringLiteral("%1 vs %2").arg(raster.width()).arg(screen)));
    QVERIFY(raster.height() > 800);
    const QImage image(png);
    QCOMPARE(image.height(), 1000);
    QVERIFY(image.width() > raster.width() && image.width() <= 1200);
  }

  // Finding 10: the periodic-orbit dialog said nothing about coordinates (the paper's x + √K = 0.352 is x = 0.036).
  void finding10_thePeriodicDialogNamesItsCoordinates() {
    archipelago::ui::PeriodicOrbitDialog dialog;
    QVERIFY(dialog.coordinatesNote().contains(QStringLiteral("x + √K")));
    QVERIFY(dialog.coordinatesNote().contains(QStringLiteral("0.036")));
  }

  // Finding 11: a clicked orbit was only a status line: not told apart from the seed orbits, no undo, no legend.
  void finding11_launchedOrbitsAreListedHighlightedAndUndone() {
    MainWindow w;
    w.setConfirmations(false);
    w.resize(1200, 760);
    w.show();
    QVERIFY(QTest::qWaitForWindowExposed(&w));
    PortraitPanel& p = *w.portraitPanel();
    PortraitController& c = *p.controller();
    QWidget* canvas = p.view()->canvas();
    QTRY_VERIFY(canvas->width() > 100);
    QTest::mouseClick(canvas, Qt::LeftButton, Qt::NoModifier, canvas->rect().center() + QPoint(-30, 10));
    QTest::mouseClick(canvas, Qt::LeftButton, Qt::NoModifier, canvas->rect().center() + QPoint(-60, 0));
    QCOMPARE(c.orbitCount(), 2);
    QTreeWidget* list = p.orbitList()->list();
    QTRY_COMPARE(list->topLevelItemCount(), 2);
    // Hang bounds, not speed bounds (issue 36, class 10): the measurement's row is filled by a queued signal after
    // the orbits settle, so it is waited for too (it was read at once, and a busy machine still showed "measuring…").
    QTRY_VERIFY_WITH_TIMEOUT(c.orbitsSettled(), 600000);
    const QTreeWidgetItem* row = list->topLevelItem(0);
    QVERIFY(!row->icon(0).isNull());                      // its colour
    QVERIFY(row->text(1).contains(QLatin1Char(',')));     // its start
    QCOMPARE(row->text(2), QLocale().toString(20000));   // its steps
    QTRY_VERIFY_WITH_TIMEOUT(!row->text(3).isEmpty() && row->text(3) != QStringLiteral("measuring…"), 600000);
    // Drawn with a marked start, and highlighted on selection (the others dimmed).
    QTRY_COMPARE(p.view()->layerItems(PortraitLayer::launchedOrbits).size(), std::size_t{2});
    list->setCurrentItem(list->topLevelItem(1));
    QCOMPARE(c.highlightedOrbit(), c.launchedOrbits()[1].id);
    QTRY_VERIFY(p.orbitList()->detailsText().contains(QStringLiteral("Orbit %1").arg(c.launchedOrbits()[1].id)));
    // Ctrl+Z removes the last one, then the first; Clear empties.
    canvas->setFocus();
    QTest::keyClick(canvas, Qt::Key_Z, Qt::ControlModifier);
    QCOMPARE(c.orbitCount(), 1);
    QTRY_COMPARE(list->topLevelItemCount(), 1);
    QCOMPARE(p.view()->layerItems(PortraitLayer::launchedOrbits).size(), std::size_t{1});
    c.launchOrbit(-0.3, 0.05);
    p.clearOrbitsAction()->trigger();
    QCOMPARE(c.orbitCount(), 0);
    QTRY_COMPARE(list->topLevelItemCount(), 0);
    // The legend of ○ and ×.
    bool legend = false;
    for (QLabel* l : p.findChildren<QLabel*>())
      legend = legend || (l->toolTip().contains(QStringLiteral("○ elliptic")) && l->toolTip().contains(QStringLiteral("× hyperbolic")));
    QVERIFY(legend);
  }

  // Finding 12: the arrows did nothing at the full view, without feedback, and needed focus on the portrait.
  void finding12_arrowsAtTheFullViewSayWhy() {
    MainWindow w;
    w.setConfirmations(false);
    w.resize(1200, 760);
    w.show();
    QVERIFY(QTest::qWaitForWindowExposed(&w));
    PortraitPanel& p = *w.portraitPanel();
    QWidget* canvas = p.view()->canvas();
    QVERIFY(canvas->focusPolicy() & Qt::WheelFocus);
    canvas->setFocus();
    QSignalSpy messages(p.controller(), &PortraitController::statusMessage);
    QTest::keyClick(canvas, Qt::Key_Left);
    QVERIFY(p.controller()->viewport() == Viewport());
    QVERIFY(!messages.isEmpty());
    QVERIFY(messages.last().first().toString().contains(QStringLiteral("zoom in")));
    // Zoomed in, the same key pans.
    QTest::keyClick(canvas, Qt::Key_Plus);
    const Viewport zoomed = p.controller()->viewport();
    QVERIFY(!(zoomed == Viewport()));
    QTest::keyClick(canvas, Qt::Key_Left);
    QVERIFY(!(p.controller()->viewport() == zoomed));
  }

  // Finding 15: the portrait accumulated on a hidden tab beside a run, sharing the cores with no priority.  Now
  // it pauses while hidden (keeping its orbits) and goes on when shown.  (The rates: scripts/gui-portrait-yield.py.)
  void finding15_aHiddenPortraitPauses() {
    MainWindow w;
    w.setConfirmations(false);
    w.resize(1200, 760);
    w.show();
    QVERIFY(QTest::qWaitForWindowExposed(&w));
    PortraitView* view = w.portraitPanel()->view();
    w.portraitPanel()->controller()->setPointBudget(100'000'000'000);
    QTRY_VERIFY_WITH_TIMEOUT(view->pointsSoFar() > 0, 900000);
    w.tabs()->setCurrentIndex(1);
    QTRY_VERIFY(view->renderPaused());
    // The pass in flight ends and the worker waits at the gate (a fixed 300-ms wait failed in the ASan phase on busy
    // cores: a pass outlasted it); the frames it posted before waiting are delivered by the next event processing.
    QTRY_VERIFY_WITH_TIMEOUT(view->renderHeld(), 900000);
    QTest::qWait(50);
    const std::uint64_t paused = view->pointsSoFar();
    QTest::qWait(600);
    QCOMPARE(view->pointsSoFar(), paused);
    QCOMPARE(view->renderState(), RenderState::accumulating);  // paused, not restarted
    w.tabs()->setCurrentWidget(w.portraitPanel());
    QVERIFY(!view->renderPaused());
    QTRY_VERIFY_WITH_TIMEOUT(view->pointsSoFar() > paused, 900000);
  }

  // Missing: equal aspect ratio (a rectangle zoom stretched the portrait).
  void missing_equalAspectRatio() {
    PortraitPanel panel;
    panel.resize(900, 600);
    panel.show();
    QVERIFY(QTest::qWaitForWindowExposed(&panel));
    PortraitController& c = *panel.controller();
    QVERIFY(c.equalAspect());
    const auto aspectOk = [&] {
      const QWidget* canvas = panel.view()->canvas();
      const PhysicalRect r = c.viewport().physical(c.map());
      const double view = static_cast<double>((r.x1 - r.x0) / (r.y1 - r.y0));
      const double screen = static_cast<double>(canvas->width()) / canvas->height();
      return std::fabs(screen / view - 1) < 0.02;
    };
    QTRY_VERIFY(aspectOk());
    c.crop(0.1, 0.9, 0.4, 0.6);  // a 4:1 rectangle of a square view
    QTRY_VERIFY(aspectOk());
    c.crop(0.45, 0.55, 0.0, 1.0);  // a sliver: widened to 1:4
    const PhysicalRect r = c.viewport().physical(c.map());
    QVERIFY(static_cast<double>((r.x1 - r.x0) / (r.y1 - r.y0)) >= 0.25 - 1e-9);
    QTRY_VERIFY(aspectOk());
  }

  // Missing: Help ▸ Keyboard Shortcuts and a Portrait menu.
  void missing_keyboardShortcutsAndPortraitMenu() {
    MainWindow w;
    QStringList menus;
    for (const QAction* a : w.menuBar()->actions()) menus << a->text();
    QVERIFY(menus.contains(QStringLiteral("&Portrait")));
    const auto rows = w.keyboardShortcuts();
    bool undo = false, run = false, home = false;
    for (const auto& [action, keys] : rows) {
      undo = undo || (action.contains(QStringLiteral("Undo Last Orbit")) && keys.contains(QStringLiteral("Ctrl+Z")));
      run = run || (action.startsWith(QStringLiteral("Run ▸")) && keys.contains(QStringLiteral("F5")));
      home = home || (action.contains(QStringLiteral("Reset View")) && keys.contains(QStringLiteral("Home")));
    }
    QVERIFY(undo && run && home);
    w.showKeyboardShortcuts();
    QTRY_VERIFY(w.findChild<QDialog*>(QStringLiteral("keyboardShortcutsDialog")) != nullptr);
  }
};

ARCHIPELAGO_GUI_TEST_MAIN(TestIssue25)
#include "test_issue25.moc"
