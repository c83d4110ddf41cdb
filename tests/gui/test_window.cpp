// The window on a laptop screen and the keys a user expects (issue #13, findings 2, 3 and 15; deliverable 8):
// its minimum width fits a 1280 × 800 screen with room to spare (≤ 1024 px), zooms do not widen it, a restored
// geometry is clamped to the screen, Alt+Left goes back through the portrait's history (arrows pan), and the
// portrait's progress is shown only while its tab is.
#include <QGuiApplication>
#include <QScreen>
#include <QStatusBar>
#include <QTabWidget>

#include "GuiTestSupport.hpp"
#include "ui/settings/SettingsController.hpp"
#include "ui/window/StatisticsView.hpp"
#include "ui/portrait/PortraitController.hpp"
#include "ui/portrait/PortraitPanel.hpp"
#include "ui/portrait/PortraitView.hpp"

using archipelago::ui::MainWindow;
using archipelago::ui::SettingsController;

class TestWindow : public QObject {
  Q_OBJECT
 private Q_SLOTS:
  void minimumWidthFitsALaptopScreen() {
    MainWindow w;
    w.setConfirmations(false);
    w.show();
    QVERIFY2(w.minimumSizeHint().width() <= 1024, qPrintable(QString::number(w.minimumSizeHint().width())));
    QVERIFY2(w.minimumSizeHint().height() <= 700, qPrintable(QString::number(w.minimumSizeHint().height())));
    // Every tab: the portrait's tool bar overflows instead of widening the window.
    const int before = w.minimumSizeHint().width();
    w.tabs()->setCurrentWidget(w.portraitPanel());
    auto* portrait = w.portraitPanel()->controller();
    for (int i = 0; i < 6; ++i) portrait->zoomAt(0.37, 0.61, 7.0);
    QCoreApplication::processEvents();
    QCOMPARE(w.minimumSizeHint().width(), before);
    w.resize(1024, 700);
    QCoreApplication::processEvents();
    QVERIFY(w.width() <= 1024);
  }

  void clampToScreenKeepsTheWindowOnIt() {
    const QRect screen(0, 0, 1280, 800);
    QCOMPARE(SettingsController::clampToScreen(QRect(100, 50, 1600, 1000), screen), QRect(0, 0, 1280, 800));
    QCOMPARE(SettingsController::clampToScreen(QRect(900, 600, 600, 400), screen), QRect(680, 400, 600, 400));
    QCOMPARE(SettingsController::clampToScreen(QRect(-300, -20, 500, 300), screen), QRect(0, 0, 500, 300));
    QCOMPARE(SettingsController::clampToScreen(QRect(10, 10, 500, 300), screen), QRect(10, 10, 500, 300));
    const QRect second(1280, 0, 1920, 1080);  // a second monitor to the right
    QCOMPARE(SettingsController::clampToScreen(QRect(1300, 100, 2400, 1200), second), second);
  }

  void aRestoredGeometryLargerThanTheScreenIsClamped() {
    {
      MainWindow big;
      big.setConfirmations(false);
      big.show();
      big.setGeometry(40, 40, 4000, 3000);
      QVERIFY(big.close());  // saves the geometry
    }
    MainWindow w;
    w.setConfirmations(false);
    w.show();
    const QRect available = w.screen()->availableGeometry();
    QVERIFY2(w.width() <= std::max(available.width(), w.minimumSizeHint().width()),
             qPrintable(QStringLiteral("%1 > %2").arg(w.width()).arg(available.width())));
    QVERIFY(w.height() <= std::max(available.height(), w.minimumSizeHint().height()));
  }

  void altLeftGoesBackArrowsPan() {
    MainWindow w;
    w.setConfirmations(false);
    w.show();
    w.tabs()->setCurrentWidget(w.portraitPanel());
    auto* portrait = w.portraitPanel()->controller();
    const archipelago::Viewport whole = portrait->viewport();
    portrait->zoomAt(0.5, 0.5, 4.0);
    const archipelago::Viewport zoomed = portrait->viewport();
    QVERIFY(!(zoomed == whole));
    QWidget* view = w.portraitPanel()->view();
    QTest::keyClick(view, Qt::Key_Left, Qt::AltModifier);
    QVERIFY(portrait->viewport() == whole);
    QTest::keyClick(view, Qt::Key_Right, Qt::AltModifier);
    QVERIFY(portrait->viewport() == zoomed);
    QTest::keyClick(view, Qt::Key_Left);  // a pan: a new view, not the previous one
    QVERIFY(!(portrait->viewport() == whole));
    QVERIFY(!(portrait->viewport() == zoomed));
  }

  void portraitProgressOnlyOnItsTab() {
    MainWindow w;
    w.setConfirmations(false);
    w.show();
    w.tabs()->setCurrentWidget(w.statisticsView());
    w.statusBar()->clearMessage();
    Q_EMIT w.portraitPanel()->statusMessage(QStringLiteral("Rendering orbits: 100%"));
    QVERIFY(!w.statusBar()->currentMessage().contains(QStringLiteral("Rendering")));
    w.tabs()->setCurrentWidget(w.portraitPanel());
    Q_EMIT w.portraitPanel()->statusMessage(QStringLiteral("Rendering orbits: 100%"));
    QVERIFY(w.statusBar()->currentMessage().contains(QStringLiteral("Rendering")));
  }
};

ARCHIPELAGO_GUI_TEST_MAIN(TestWindow)
#include "test_window.moc"
