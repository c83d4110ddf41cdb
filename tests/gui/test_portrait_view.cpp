// The phase portrait on the offscreen platform: its controller (the one owner of map, view and layers), the
// render that accumulates until the budget or a stop, the hidden-then-shown render at the real size, and the
// panel's readout (issue 13, findings 3, 4 and 10).
#include <QComboBox>
#include <QDir>
#include <QFileInfo>
#include <QSignalSpy>
#include <QTabWidget>
#include <QTemporaryDir>
#include <QToolButton>
#include <QVBoxLayout>
#include <QtTest>

#include <cmath>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "GuiTestSupport.hpp"
#include "core/io/NumberText.hpp"
#include "core/io/Png.hpp"
#include "core/portrait/MapOverlays.hpp"
#include "ui/portrait/PortraitController.hpp"
#include "ui/portrait/PortraitPanel.hpp"
#include "ui/portrait/PortraitView.hpp"
#include "ui/portrait/PortraitWorker.hpp"

using archipelago::MapParameters;
using archipelago::PhysicalRect;
using archipelago::PortraitMode;
using archipelago::Viewport;
using archipelago::ui::PortraitController;
using archipelago::ui::PortraitLayer;
using archipelago::ui::PortraitPanel;
using archipelago::ui::PortraitView;
using archipelago::ui::RenderState;

namespace {
const MapParameters kPaper{0.1, -0.8, 0.5};  // §5

/// A controller and its view in a plain host widget.
struct Portrait {
  QWidget host;
  PortraitController* controller = nullptr;
  PortraitView* view = nullptr;
  Portrait() {
    auto* layout = new QVBoxLayout(&host);
    layout->setContentsMargins(0, 0, 0, 0);
    controller = new PortraitController(&host);
    view = controller->view();
    layout->addWidget(view);
  }
};

/// The view's renders that end by themselves (budget or no sea), counted from this object's making.  Made before
/// the action that starts a render, so a render that ends while the test still processes events (in
/// qWaitForWindowExposed or a QTRY) is not missed: a spy made after them waited 900 s for a signal already sent
/// (the Qt 5 phase, on the deep zoom's render ended inside its QTRY).
class RenderEnd {
 public:
  explicit RenderEnd(PortraitView* view) : spy_(view, &PortraitView::renderFinished) {}
  // A hang bound (issue 36, class 10: 60 s was crossed by the 10⁸-point deep zoom beside two busy loops).
  bool wait(int ms = 900000) { return !spy_.isEmpty() || spy_.wait(ms); }

 private:
  QSignalSpy spy_;
};
}  // namespace

class TestPortraitView : public QObject {
  Q_OBJECT
 private Q_SLOTS:
  void rendersNonEmptyImage() {
    Portrait p;
    p.host.resize(420, 360);
    p.controller->setPointBudget(2'000'000);
    p.controller->setMode(PortraitMode::Density);
    QSignalSpy finished(p.view, &PortraitView::renderFinished);
    p.host.show();
    QVERIFY(QTest::qWaitForWindowExposed(&p.host));
    QVERIFY(finished.wait(900000));
    const auto* frame = p.view->currentFrame();
    QVERIFY(frame != nullptr);
    QVERIFY(frame->final);
    QCOMPARE(p.view->renderState(), RenderState::done);
    QVERIFY(p.view->pointsSoFar() >= 2'000'000);
    QVERIFY(!frame->image.isNull());
    QVERIFY(frame->raster->nonEmptyPixels() > frame->raster->pixelCount() / 2);  // the sea fills most of the box
    QVERIFY(frame->raster->nonEmptyPixels() < frame->raster->pixelCount());      // the islands stay empty
    const QImage& image = frame->image;
    QSet<QRgb> colours;
    for (int y = 0; y < image.height(); y += 7)
      for (int x = 0; x < image.width(); x += 7) colours.insert(image.pixel(x, y));
    QVERIFY(colours.size() > 5);
    QVERIFY(!p.view->isRendering());
  }

  void zoomChangesTheViewportAndHistoryRestoresIt() {
    Portrait p;
    p.host.resize(300, 300);
    p.controller->setPointBudget(200'000);
    PortraitController& c = *p.controller;
    const Viewport whole = c.viewport();
    QSignalSpy changed(&c, &PortraitController::viewportChanged);
    c.zoomAt(0.25, 0.75, 4.0);
    QCOMPARE(changed.count(), 1);
    QCOMPARE(static_cast<double>(c.viewport().widthUnits()), static_cast<double>(whole.widthUnits() / 4));
    QVERIFY(c.viewport() == p.view->viewport());  // the view shows what the controller holds
    QVERIFY(p.view->xAxisRange().first > -0.8 + 1e-9);  // the axes follow the viewport
    c.back();
    QVERIFY(c.viewport() == whole);
    QVERIFY(c.canGoForward());
    c.forward();
    QCOMPARE(static_cast<double>(c.viewport().widthUnits()), static_cast<double>(whole.widthUnits() / 4));
    c.resetView();
    QVERIFY(c.viewport() == whole);
    // The wheel zooms about the cursor: the view asks, the controller decides.
    p.host.show();
    QVERIFY(QTest::qWaitForWindowExposed(&p.host));
    QWidget* canvas = p.view->canvas();
    const QPoint centre = canvas->rect().center();
    QWheelEvent wheel(QPointF(centre), QPointF(canvas->mapToGlobal(centre)), QPoint(), QPoint(0, 120), Qt::NoButton,
                      Qt::NoModifier, Qt::NoScrollPhase, false);
    QApplication::sendEvent(canvas, &wheel);
    QCOMPARE(static_cast<double>(c.viewport().widthUnits()), static_cast<double>(whole.widthUnits() / 1.25L));
    QVERIFY(c.viewport() == p.view->viewport());
  }

  void theSameMapKeepsTheZoomAndANewMapResetsIt() {
    Portrait p;
    PortraitController& c = *p.controller;
    QSignalSpy maps(&c, &PortraitController::mapChanged);
    QVERIFY(c.setMap(kPaper, 0.02));
    QCOMPARE(maps.count(), 0);  // already shown
    c.zoomAt(0.5, 0.5, 8);
    QVERIFY(c.setMap(kPaper, 0.03));  // e.g. another T or Xr in the parameter panel
    QCOMPARE(maps.count(), 0);
    QVERIFY(!(c.viewport() == Viewport()));
    QCOMPARE(c.Xr(), 0.03);
    MapParameters other = kPaper;
    other.K = 0.2;
    QVERIFY(c.setMap(other, 0.02));
    QCOMPARE(maps.count(), 1);
    QVERIFY(c.viewport() == Viewport());
    QVERIFY(p.view->parameters() == other);
    QVERIFY(!c.canGoBack());
    // The fixed points layer follows the map; invalid parameters are refused and change nothing.
    QCOMPARE(p.view->layerItems(PortraitLayer::fixedPoints).size(), archipelago::fixedPoints(other).size());
    QSignalSpy messages(&c, &PortraitController::statusMessage);
    QVERIFY(!c.setMap(MapParameters{0.1, -0.2, 0.5}, 0.02));  // xmin > −√K
    QCOMPARE(messages.count(), 1);
    QVERIFY(c.map() == other);
  }

  // What a session file keeps: the history and the settings, restored through the controller; the panel's
  // boxes follow the controller.
  void historyAndSettingsRestoreThroughTheController() {
    PortraitPanel panel;
    PortraitController& c = *panel.controller();
    const Viewport whole;
    const Viewport a = whole.zoomedAboutFraction(0.3L, 0.6L, 4);
    const Viewport b = a.zoomedAboutFraction(0.5L, 0.5L, 8);
    QVERIFY(!c.restoreHistory({}, 0));
    QVERIFY(!c.restoreHistory({whole, a}, 2));
    QVERIFY(c.viewport() == whole);
    QVERIFY(c.restoreHistory({whole, a, b}, 1));
    QVERIFY(c.viewport() == a);
    QVERIFY(panel.view()->viewport() == a);
    QVERIFY(c.canGoBack() && c.canGoForward());
    QCOMPARE(c.history().size(), std::size_t{3});
    QCOMPARE(c.historyIndex(), std::size_t{1});
    c.forward();
    QVERIFY(c.viewport() == b);
    c.setMode(PortraitMode::Stickiness);
    c.setColourMap(archipelago::ColourMapName::Grey);
    c.setPointBudget(123'000'000);
    QVERIFY(panel.display() == (archipelago::ui::PortraitDisplay{PortraitMode::Stickiness, std::nullopt}));
    QCOMPARE(panel.modeBox()->currentText(), QStringLiteral("Stickiness (mean trapped length)"));
    QCOMPARE(panel.colourBox()->currentData().toInt(), static_cast<int>(archipelago::ColourMapName::Grey));
    QCOMPARE(panel.budgetBox()->currentData().toULongLong(), 123'000'000ULL);
    c.launchOrbit(-0.3, 0.05, 100);
    QCOMPARE(c.launchedOrbitStarts().size(), std::size_t{1});
    QVERIFY(std::fabs(static_cast<double>(c.launchedOrbitStarts()[0].x) + 0.3) < 1e-12);
  }

  void clickLaunchesAnOrbitAndExportsWrite() {
    Portrait p;
    p.host.resize(400, 400);
    p.controller->setPointBudget(300'000);
    QSignalSpy finished(p.view, &PortraitView::renderFinished);
    p.host.show();
    QVERIFY(QTest::qWaitForWindowExposed(&p.host));
    QWidget* canvas = p.view->canvas();
    QCOMPARE(p.controller->orbitCount(), 0);
    QTest::mouseClick(canvas, Qt::LeftButton, Qt::NoModifier, canvas->rect().center());
    QCOMPARE(p.controller->orbitCount(), 1);
    // Traced off the GUI thread, then drawn (issue #23, finding 5).
    QTRY_COMPARE(p.view->layerItems(PortraitLayer::launchedOrbits).size(), std::size_t{1});
    QVERIFY(p.controller->viewport() == Viewport());  // a click is not a zoom
    p.controller->launchOrbit(-0.3, 0.05, 1000);
    QCOMPARE(p.controller->orbitCount(), 2);
    p.controller->clearOrbits();
    QCOMPARE(p.controller->orbitCount(), 0);
    QVERIFY(p.view->layerItems(PortraitLayer::launchedOrbits).empty());

    QVERIFY(finished.wait(900000));
    QTemporaryDir dir;
    const QString png = dir.filePath(QStringLiteral("portrait.png")), npy = dir.filePath(QStringLiteral("portrait.npy"));
    QVERIFY(p.view->exportPng(png, QSize(500, 400)));
    QImage written(png);
    // At most the size asked, cut to the view's aspect (equal aspect: the whole box is square).
    QCOMPARE(written.height(), 400);
    QVERIFY(written.width() <= 500 && written.width() > 300);
    // Issue 42: the PNG says where it came from, in tEXt chunks (read from the file's bytes, not through Qt):
    // the program, its version and commit, K and the view exported.
    {
      QFile file(png);
      QVERIFY(file.open(QIODevice::ReadOnly));
      const QByteArray bytes = file.readAll();
      const auto text = archipelago::io::readPngText(std::vector<std::uint8_t>(bytes.begin(), bytes.end()));
      std::map<std::string, std::string> fields(text.begin(), text.end());
      QCOMPARE(QString::fromStdString(fields["Version"]), QStringLiteral(ARCHIPELAGO_VERSION));
      QCOMPARE(QString::fromStdString(fields["Software"]), QStringLiteral("archipelago " ARCHIPELAGO_VERSION));
      QVERIFY(!fields["Commit"].empty());
      QCOMPARE(QString::fromStdString(fields["K"]), QStringLiteral("0.1"));
      const PhysicalRect b = p.controller->viewport().physical(p.controller->map());
      QVERIFY(archipelago::io::parseLongDoubleC(fields["View x0"]) == b.x0);
      QVERIFY(archipelago::io::parseLongDoubleC(fields["View x1"]) == b.x1);
      QVERIFY(archipelago::io::parseLongDoubleC(fields["View y0"]) == b.y0);
      QVERIFY(archipelago::io::parseLongDoubleC(fields["View y1"]) == b.y1);
      QCOMPARE(QString::fromStdString(fields["Image"]), QStringLiteral("phase portrait, orbits"));  // the GUI's default
    }
    QVERIFY(p.view->exportNpy(npy));
    QVERIFY(QFileInfo(npy).size() > 128);
    QVERIFY(QFileInfo::exists(dir.filePath(QStringLiteral("portrait.json"))));
  }

  // Finding 4: the first portrait was rendered while its tab was hidden, at a tiny size, and stayed blocky.
  void aHiddenPortraitRendersAtItsRealSizeWhenShown() {
    QTabWidget tabs;
    tabs.resize(900, 700);
    tabs.addTab(new QWidget, QStringLiteral("Statistics"));
    auto* panel = new PortraitPanel;
    tabs.addTab(panel, QStringLiteral("Phase portrait"));
    PortraitController& c = *panel->controller();
    c.setPointBudget(1'000'000);
    QSignalSpy frames(panel->view(), &PortraitView::frameShown);
    tabs.show();
    QVERIFY(QTest::qWaitForWindowExposed(&tabs));
    MapParameters other = kPaper;
    other.K = 0.2;
    QVERIFY(c.setMap(other, 0.02));
    QTest::qWait(400);  // longer than the debounce: a render would have started
    QCOMPARE(frames.count(), 0);
    QVERIFY(panel->view()->currentFrame() == nullptr);
    QCOMPARE(panel->view()->renderState(), RenderState::pending);
    RenderEnd shown(panel->view());
    tabs.setCurrentWidget(panel);
    QVERIFY(shown.wait());
    const auto* frame = panel->view()->currentFrame();
    QVERIFY(frame != nullptr);
    const QWidget* canvas = panel->view()->canvas();
    const qreal ratio = canvas->devicePixelRatioF();
    QCOMPARE(frame->request.width, static_cast<int>(canvas->width() * ratio));
    QCOMPARE(frame->request.height, static_cast<int>(canvas->height() * ratio));
    QVERIFY(frame->request.width > 400);  // the tab's size, not a hidden widget's default
    QVERIFY(frame->request.map == other);
  }

  // The same in the main window: with the portrait's tab not shown, nothing renders until it is shown.
  void theMainWindowsPortraitRendersWhenItsTabIsShown() {
    archipelago::ui::MainWindow window;
    window.setConfirmations(false);
    window.resize(1500, 920);
    window.tabs()->setCurrentIndex(1);
    window.show();
    QVERIFY(QTest::qWaitForWindowExposed(&window));
    PortraitPanel& panel = *window.portraitPanel();
    panel.controller()->setPointBudget(1'000'000);
    QTest::qWait(300);
    QVERIFY(panel.view()->currentFrame() == nullptr);
    QVERIFY(!panel.isVisible());
    RenderEnd shown(panel.view());
    window.tabs()->setCurrentWidget(&panel);
    QVERIFY(shown.wait());
    const QWidget* canvas = panel.view()->canvas();
    QCOMPARE(panel.view()->currentFrame()->request.width, static_cast<int>(canvas->width() * canvas->devicePixelRatioF()));
    QVERIFY(panel.view()->currentFrame()->request.width > 450);
    QVERIFY(panel.view()->currentFrame()->request.map == window.parameterPanel()->parameters()->map);
  }

  void resizeAndResetRenderAgain() {
    Portrait p;
    p.host.resize(300, 260);
    p.controller->setPointBudget(500'000);
    RenderEnd first(p.view);
    p.host.show();
    QVERIFY(QTest::qWaitForWindowExposed(&p.host));
    QVERIFY(first.wait());
    const int before = p.view->currentFrame()->request.width;
    RenderEnd resized(p.view);
    p.host.resize(520, 420);
    QVERIFY(resized.wait());
    QVERIFY(p.view->currentFrame()->request.width > before);
    QCOMPARE(p.view->currentFrame()->request.width, p.view->rasterSize().width());
    // Reset on the whole box draws anew.
    QSignalSpy frames(p.view, &PortraitView::frameShown);
    RenderEnd reset(p.view);
    p.controller->resetView();
    QVERIFY(p.view->isRendering());
    QVERIFY(reset.wait());
    QVERIFY(frames.count() >= 1);
  }

  // Finding 10: a 7·10⁻⁴-wide view in the sea was solid black after a fixed 1.2·10⁷ points.  Now the render
  // accumulates until its budget: the points so far grow from pass to pass, and the view gets points.
  void deepZoomAccumulatesUntilTheBudget() {
    PortraitPanel panel;
    panel.resize(700, 560);
    PortraitController& c = *panel.controller();
    c.setMode(PortraitMode::Density);
    const int index = panel.budgetBox()->findData(QVariant::fromValue<qulonglong>(100'000'000));
    QVERIFY(index >= 0);
    panel.budgetBox()->setCurrentIndex(index);
    QCOMPARE(c.pointBudget(), std::uint64_t{100'000'000});
    c.setViewport(Viewport::fromPhysical(kPaper, {0.44965L, 0.45035L, 0.29965L, 0.30035L}));
    std::vector<std::uint64_t> points;
    connect(panel.view(), &PortraitView::frameShown, &panel, [&] { points.push_back(panel.view()->pointsSoFar()); });
    RenderEnd end(panel.view());
    panel.show();
    QVERIFY(QTest::qWaitForWindowExposed(&panel));
    QTRY_VERIFY_WITH_TIMEOUT(panel.readoutText().contains(QStringLiteral("accumulating")) ||
                                 panel.view()->renderState() == RenderState::done,
                             900000);
    QVERIFY(end.wait());
    QCOMPARE(panel.view()->renderState(), RenderState::done);
    QVERIFY2(points.size() >= 3, qPrintable(QString::number(points.size())));
    for (std::size_t i = 1; i < points.size(); ++i) QVERIFY(points[i] > points[i - 1]);
    QVERIFY(points.back() >= 100'000'000);
    QVERIFY(panel.view()->currentFrame()->raster->nonEmptyPixels() > 0);
    QVERIFY(panel.readoutText().contains(QStringLiteral("done")));
  }

  void aViewInsideAnIslandSaysItHoldsNoChaoticPoints() {
    PortraitPanel panel;
    panel.resize(600, 500);
    PortraitController& c = *panel.controller();
    c.setMode(PortraitMode::Density);
    c.setPointBudget(100'000'000'000);  // 10^11: the verdict must come long before
    // A 0.01-wide view about the elliptic fixed point (−√K, 0): the central island.
    const long double x = -std::sqrt(0.1L);
    c.setViewport(Viewport::fromPhysical(kPaper, {x - 0.005L, x + 0.005L, -0.005L, 0.005L}));
    RenderEnd verdict(panel.view());
    panel.show();
    QVERIFY(QTest::qWaitForWindowExposed(&panel));
    QVERIFY(verdict.wait());
    QCOMPARE(panel.view()->renderState(), RenderState::noSea);
    QVERIFY(panel.view()->pointsSoFar() < 1'000'000'000);
    QVERIFY2(panel.readoutText().contains(QStringLiteral("No chaotic points in this view")),
             qPrintable(panel.readoutText()));
    QVERIFY(!panel.stopButton()->isEnabled());
  }

  void stopEndsTheRenderAndChangingTheViewRestartsIt() {
    PortraitPanel panel;
    panel.resize(600, 500);
    PortraitController& c = *panel.controller();
    c.setMode(PortraitMode::Orbits);  // the slow mode: 10^11 points take hours
    c.setPointBudget(100'000'000'000);
    QSignalSpy frames(panel.view(), &PortraitView::frameShown);
    // The points of every frame as it is shown: a spy's wait() may return after two queued frames were
    // delivered in one batch, so the count after a wait says nothing about which frame was first.
    std::vector<std::uint64_t> pointsOfFrame;
    connect(panel.view(), &PortraitView::frameShown, &panel,
            [&] { pointsOfFrame.push_back(panel.view()->pointsSoFar()); });
    panel.show();
    QVERIFY(QTest::qWaitForWindowExposed(&panel));
    QVERIFY(frames.wait(900000));
    QVERIFY(panel.view()->isRendering());
    QVERIFY(panel.stopButton()->isEnabled());
    panel.stopButton()->click();
    QCOMPARE(panel.view()->renderState(), RenderState::stopped);
    const std::uint64_t stoppedAt = panel.view()->pointsSoFar();
    const auto shown = frames.count();
    QTest::qWait(500);
    QCOMPARE(frames.count(), shown);  // nothing more arrives
    QCOMPARE(panel.view()->pointsSoFar(), stoppedAt);
    QVERIFY(panel.readoutText().contains(QStringLiteral("stopped")));
    QVERIFY(!panel.stopButton()->isEnabled());
    // A new view starts again from nothing, and its frames are of the new view.
    c.zoomIn();
    QVERIFY(panel.view()->isRendering());
    QCOMPARE(panel.view()->pointsSoFar(), std::uint64_t{0});
    QVERIFY(frames.wait(900000));
    QVERIFY(panel.view()->currentFrame()->request.view == c.viewport());
    // The new view's first frame holds the schedule's first pass, as the stopped view's first frame did
    // (the schedule depends on the budget alone): a render that went on from the stopped one holds more.
    QVERIFY(pointsOfFrame.size() > static_cast<std::size_t>(shown));
    QCOMPARE(pointsOfFrame[static_cast<std::size_t>(shown)], pointsOfFrame.front());
    QVERIFY(pointsOfFrame.front() > 0 && pointsOfFrame.front() <= stoppedAt);
    c.stopRendering();
  }

  // Finding 3: each zoom widened the window (the coordinate readout grew the minimum width).
  void zoomingDoesNotGrowTheMinimumWidth() {
    PortraitPanel panel;
    panel.resize(800, 600);
    panel.controller()->setPointBudget(10'000'000);
    panel.show();
    QVERIFY(QTest::qWaitForWindowExposed(&panel));
    const int minimum = panel.minimumSizeHint().width();
    QWidget* canvas = panel.view()->canvas();
    for (int i = 0; i < 12; ++i) {
      panel.controller()->zoomAt(0.37, 0.61, 16);  // down to widths of ~10⁻¹⁴ of the box
      QTest::mouseMove(canvas, QPoint(canvas->width() / 3 + i, canvas->height() / 2));
      QCoreApplication::processEvents();
      QCOMPARE(panel.minimumSizeHint().width(), minimum);
    }
    panel.controller()->stopRendering();
  }

  // In Orbits mode the colour map shades the sea: changing it changes the picture.
  void colourMapChangesTheOrbitsPortrait() {
    Portrait p;
    p.host.resize(300, 300);
    p.controller->setPointBudget(400'000);
    p.controller->setMode(PortraitMode::Orbits);
    RenderEnd first(p.view);
    p.host.show();
    QVERIFY(QTest::qWaitForWindowExposed(&p.host));
    QVERIFY(first.wait());
    const QImage inferno = p.view->currentFrame()->image;
    RenderEnd recoloured(p.view);
    p.controller->setColourMap(archipelago::ColourMapName::Viridis);
    QVERIFY(recoloured.wait());
    QVERIFY(p.view->currentFrame()->image != inferno);
  }
};

ARCHIPELAGO_GUI_TEST_MAIN(TestPortraitView)
#include "test_portrait_view.moc"
