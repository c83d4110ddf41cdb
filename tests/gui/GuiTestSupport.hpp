#pragma once
// Shared helpers of the GUI tests: an isolated environment and small runs.

#include <QApplication>
#include <QLineEdit>
#include <QSettings>
#include <QStandardPaths>
#include <QTemporaryDir>
#include <QtTest>

// A wait for an event is bounded against a hang, never against speed (issue 36, class 10): QTRY_VERIFY's and
// QTRY_COMPARE's default of 5 s failed gui.jobs once on two cores beside a build (load 10).  Every GUI test waits
// up to 900 s, as its explicit waits do.
#undef QTRY_VERIFY
#define QTRY_VERIFY(expr) QTRY_VERIFY_WITH_TIMEOUT(expr, 900000)
#undef QTRY_VERIFY2
#define QTRY_VERIFY2(expr, message) QTRY_VERIFY2_WITH_TIMEOUT(expr, message, 900000)
#undef QTRY_COMPARE
#define QTRY_COMPARE(expr, expected) QTRY_COMPARE_WITH_TIMEOUT(expr, expected, 900000)

#include "ui/window/MainWindow.hpp"
#include "ui/window/ParameterPanel.hpp"

namespace archipelago::test {

/// Settings and data go to a fresh temporary folder: tests never see the user's files or each other's.
/// Must run before QApplication exists (QStandardPaths reads XDG_* once).
inline QTemporaryDir& isolatedHome() {
  static QTemporaryDir dir;
  qputenv("XDG_CONFIG_HOME", dir.filePath(QStringLiteral("config")).toUtf8());
  qputenv("XDG_DATA_HOME", dir.filePath(QStringLiteral("data")).toUtf8());
  qputenv("XDG_CACHE_HOME", dir.filePath(QStringLiteral("cache")).toUtf8());
  return dir;
}

/// Types into a field as a user would (textEdited fires, validation runs).
inline void typeInto(ui::ParameterPanel& panel, const QString& field, const QString& text) {
  QLineEdit* edit = panel.field(field);
  QVERIFY2(edit, qPrintable(field));
  edit->selectAll();
  QTest::keyClicks(edit, text);
}

/// Sets every field of the panel from `p` (as if typed), with `threads` worker threads.
inline void enter(ui::ParameterPanel& panel, const TrappingParameters& p, int threads) {
  panel.setParameters(p, threads);
}

/// A K = 0.1 run that never finishes within a test (10¹⁴ steps): pause, stop and close always catch it
/// mid-way, whatever the speed of the kernel.
inline TrappingParameters endlessRun() {
  TrappingParameters p;  // K = 0.1, xmin = −0.8, xmax = 0.5, Xr = 0.02 (paper §5)
  p.q = 4;
  p.T = 1'000'000'000'000;
  p.M = 16;
  p.subsets = 8;
  p.seed = 7;
  return p;
}

/// A K = 0.1 run that finishes in a fraction of a second.
inline TrappingParameters shortRun() {
  TrappingParameters p;
  p.q = 4;
  p.T = 40'000;
  p.M = 16;
  p.subsets = 8;
  p.seed = 3;
  return p;
}

/// Waits (processing events) until the window's run reaches `status`.
inline bool waitForStatus(const ui::MainWindow& w, ui::RunStatus status, int ms = 30000) {
  return QTest::qWaitFor([&] { return w.runStatus() == status; }, ms);
}

/// Waits for a snapshot beyond `blocks` blocks.
inline bool waitForProgress(const ui::MainWindow& w, std::uint64_t blocks = 0) {
  return QTest::qWaitFor([&] { return w.latestSnapshot() && w.latestSnapshot()->state.blocksDone > blocks; }, 20000);
}

}  // namespace archipelago::test

/// main() for a GUI test: isolated settings and data folders, then Qt Test.
#define ARCHIPELAGO_GUI_TEST_MAIN(TestClass)                                         \
  int main(int argc, char** argv) {                                                 \
    archipelago::test::isolatedHome();                                              \
    QApplication app(argc, argv);                                                   \
    QApplication::setOrganizationName(QStringLiteral("ArchipelagoTests"));          \
    QApplication::setApplicationName(QStringLiteral(#TestClass));                   \
    TestClass test;                                                                 \
    return QTest::qExec(&test, argc, argv);                                         \
  }
