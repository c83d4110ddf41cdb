// PortraitView on the offscreen platform: a render completes with content, zoom and history change the
// viewport, a click launches an orbit, and both exports write files.
#include <QDir>
#include <QFileInfo>
#include <QSignalSpy>
#include <QTemporaryDir>
#include <QtTest>
#include <qwt_plot.h>
#include <qwt_scale_div.h>

#include "ui/portrait/PortraitView.hpp"
#include "ui/portrait/PortraitWorker.hpp"

using archipelago::PortraitMode;
using archipelago::Viewport;
using archipelago::ui::PortraitView;

class TestPortraitView : public QObject {
  Q_OBJECT
 private Q_SLOTS:
  void rendersNonEmptyImage() {
    PortraitView view;
    view.resize(420, 360);
    view.setPointBudget(2'000'000);
    view.setMode(PortraitMode::Density);
    QSignalSpy finished(&view, &PortraitView::renderFinished);
    view.show();
    QVERIFY(QTest::qWaitForWindowExposed(&view));
    QVERIFY(finished.wait(60000));
    const auto* frame = view.currentFrame();
    QVERIFY(frame != nullptr);
    QVERIFY(frame->final);
    QVERIFY(!frame->image.isNull());
    QVERIFY(frame->raster->nonEmptyPixels() > frame->raster->pixelCount() / 2);  // the sea fills most of the box
    QVERIFY(frame->raster->nonEmptyPixels() < frame->raster->pixelCount());      // the islands stay empty
    // The image has both the sea's colours and the empty islands' colour.
    const QImage& image = frame->image;
    QSet<QRgb> colours;
    for (int y = 0; y < image.height(); y += 7)
      for (int x = 0; x < image.width(); x += 7) colours.insert(image.pixel(x, y));
    QVERIFY(colours.size() > 5);
    QVERIFY(!view.isRendering());
  }

  void zoomChangesTheViewportAndHistoryRestoresIt() {
    PortraitView view;
    view.resize(300, 300);
    view.setPointBudget(200'000);
    const Viewport whole = view.viewport();
    QSignalSpy changed(&view, &PortraitView::viewportChanged);
    view.zoomAt(0.25, 0.75, 4.0);
    QCOMPARE(changed.count(), 1);
    QCOMPARE(static_cast<double>(view.viewport().widthUnits()), static_cast<double>(whole.widthUnits() / 4));
    QVERIFY(!(view.viewport() == whole));
    const double x0 = view.plot()->axisScaleDiv(QwtPlot::xBottom).lowerBound();
    QVERIFY(x0 > -0.8 + 1e-9);  // the axes follow the viewport
    view.back();
    QVERIFY(view.viewport() == whole);
    QVERIFY(view.canGoForward());
    view.forward();
    QCOMPARE(static_cast<double>(view.viewport().widthUnits()), static_cast<double>(whole.widthUnits() / 4));
    view.resetView();
    QVERIFY(view.viewport() == whole);
    // The wheel zooms about the cursor.
    view.show();
    QVERIFY(QTest::qWaitForWindowExposed(&view));
    QWidget* canvas = view.plot()->canvas();
    const QPoint centre = canvas->rect().center();
    QWheelEvent wheel(QPointF(centre), QPointF(canvas->mapToGlobal(centre)), QPoint(), QPoint(0, 120), Qt::NoButton,
                      Qt::NoModifier, Qt::NoScrollPhase, false);
    QApplication::sendEvent(canvas, &wheel);
    QCOMPARE(static_cast<double>(view.viewport().widthUnits()), static_cast<double>(whole.widthUnits() / 1.25L));
  }

  void clickLaunchesAnOrbitAndExportsWrite() {
    PortraitView view;
    view.resize(400, 400);
    view.setPointBudget(300'000);
    QSignalSpy finished(&view, &PortraitView::renderFinished);
    view.show();
    QVERIFY(QTest::qWaitForWindowExposed(&view));
    QWidget* canvas = view.plot()->canvas();
    QCOMPARE(view.orbitCount(), 0);
    QTest::mouseClick(canvas, Qt::LeftButton, Qt::NoModifier, canvas->rect().center());
    QCOMPARE(view.orbitCount(), 1);
    QVERIFY(view.viewport() == Viewport());  // a click is not a zoom
    view.launchOrbit(-0.3, 0.05, 1000);
    QCOMPARE(view.orbitCount(), 2);
    view.clearOrbits();
    QCOMPARE(view.orbitCount(), 0);

    QVERIFY(finished.wait(60000));
    QTemporaryDir dir;
    const QString png = dir.filePath(QStringLiteral("portrait.png")), npy = dir.filePath(QStringLiteral("portrait.npy"));
    QVERIFY(view.exportPng(png, QSize(500, 400)));
    QImage written(png);
    QCOMPARE(written.size(), QSize(500, 400));
    QVERIFY(view.exportNpy(npy));
    QVERIFY(QFileInfo(npy).size() > 128);
    QVERIFY(QFileInfo::exists(dir.filePath(QStringLiteral("portrait.json"))));
  }
};

QTEST_MAIN(TestPortraitView)
#include "test_portrait_view.moc"
