// The main window opens and carries its menus (offscreen platform).
#include <QMenuBar>
#include <QtTest>

#include "MainWindow.hpp"

class TestMainWindow : public QObject {
  Q_OBJECT
 private Q_SLOTS:
  void opensWithMenus() {
    archipelago::ui::MainWindow window;
    window.show();
    QVERIFY(QTest::qWaitForWindowExposed(&window));
    QStringList titles;
    const auto actions = window.menuBar()->actions();
    for (const QAction* a : actions) titles << a->text();
    QVERIFY(titles.contains(QStringLiteral("&File")));
    QVERIFY(titles.contains(QStringLiteral("&Help")));
    QCOMPARE(window.windowTitle(), QStringLiteral("Archipelago"));
  }
};

QTEST_MAIN(TestMainWindow)
#include "test_main_window.moc"
