// GUI soak (issue #13, deliverable 9): random keys, clicks, wheel zooms, drags, runs, pauses, stops, exports,
// run files and sessions saved and opened, for a given time, in the real application window; modal dialogs that
// come up are answered at random.  Not a timed test: scripts/gui-soak.sh runs it (under Xvfb) and reports.
//
// It fails (exit 1) on a hang — a watchdog thread sees the GUI thread's heartbeat stop for 20 s, prints the last
// action and aborts —, on a run stuck in pausing or stopping for a minute (its first run found one), and reports resident memory every minute and at the end (growth after the first minute is
// the number that matters: the first minute loads fonts, Qwt, caches).  A crash ends the process: the script
// sees its exit status.
//
//   gui_soak [--minutes M] [--seed S] [--log FILE]
#include <QAbstractButton>
#include <QAction>
#include <QLineEdit>
#include <QApplication>
#include <QCommandLineParser>
#include <QDialog>
#include <QDir>
#include <QElapsedTimer>
#include <QMenu>
#include <QMessageBox>
#include <QTabWidget>
#include <QTemporaryDir>
#include <QTimer>
#include <QWheelEvent>
#include <QtTest>

#include <atomic>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <malloc.h>
#include <mutex>
#include <random>
#include <string>
#include <thread>

#include "ui/window/MainWindow.hpp"
#include "ui/window/ParameterPanel.hpp"
#include "ui/window/Resources.hpp"
#include "ui/run/RunController.hpp"
#include "ui/portrait/PortraitPanel.hpp"
#include "ui/portrait/PortraitController.hpp"
#include "ui/portrait/PortraitView.hpp"
#include "ui/segments/LongSegmentsPanel.hpp"

namespace {

std::atomic<std::int64_t> heartbeat{0};
std::mutex lastActionMutex;
std::string lastAction = "start";

void setAction(const std::string& a) {
  const std::lock_guard lock(lastActionMutex);
  lastAction = a;
}

double residentMiB() {
  std::ifstream status("/proc/self/status");
  std::string key;
  while (status >> key) {
    if (key == "VmRSS:") {
      double kb = 0;
      status >> kb;
      return kb / 1024;
    }
    std::getline(status, key);
  }
  return -1;
}

/// Bytes malloc has handed out and not got back, over every arena (glibc's mallinfo2): the live heap.  RSS also
/// counts pages that free() kept in the per-thread arenas for reuse, which is not a leak; the live heap is.
double heapInUseMiB() {
  const struct mallinfo2 m = mallinfo2();
  return static_cast<double>(m.uordblks + m.hblkhd) / (1024.0 * 1024.0);
}

std::int64_t nowMs() {
  return std::chrono::duration_cast<std::chrono::milliseconds>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

}  // namespace

int main(int argc, char** argv) {
  archipelago::ui::configureProcessMemory();  // as the application's main() does
  QApplication app(argc, argv);
  QTemporaryDir home;
  qputenv("XDG_CONFIG_HOME", home.filePath(QStringLiteral("config")).toUtf8());
  qputenv("XDG_DATA_HOME", home.filePath(QStringLiteral("data")).toUtf8());
  QApplication::setOrganizationName(QStringLiteral("ArchipelagoSoak"));
  QApplication::setApplicationName(QStringLiteral("ArchipelagoSoak"));

  QCommandLineParser parser;
  const QCommandLineOption minutesOpt(QStringLiteral("minutes"), QStringLiteral("How long."), QStringLiteral("M"), QStringLiteral("30"));
  const QCommandLineOption seedOpt(QStringLiteral("seed"), QStringLiteral("Random seed."), QStringLiteral("S"), QStringLiteral("1"));
  parser.addOptions({minutesOpt, seedOpt});
  parser.process(app);
  const double minutes = parser.value(minutesOpt).toDouble();
  std::mt19937_64 rng(parser.value(seedOpt).toULongLong());
  auto pick = [&](int n) { return static_cast<int>(rng() % static_cast<unsigned>(n)); };
  auto unit = [&] { return std::uniform_real_distribution<double>(0, 1)(rng); };

  archipelago::ui::MainWindow window;
  window.resize(1280, 760);
  window.show();
  const QDir work(home.path());

  // The watchdog: the GUI thread beats every 100 ms (also inside nested dialog loops).
  heartbeat = nowMs();
  std::atomic<bool> done{false};
  std::thread watchdog([&] {
    while (!done) {
      std::this_thread::sleep_for(std::chrono::seconds(1));
      if (nowMs() - heartbeat.load() > 20000) {
        const std::lock_guard lock(lastActionMutex);
        std::fprintf(stderr, "SOAK HANG: the GUI thread has not run for 20 s; last action: %s\n", lastAction.c_str());
        std::fflush(stderr);
        std::abort();
      }
    }
  });
  QTimer beat;
  QObject::connect(&beat, &QTimer::timeout, [] { heartbeat = nowMs(); });
  beat.start(100);

  // Modal dialogs (questions, file dialogs, the periodic-orbit dialog is modeless) get a random answer.
  QTimer answer;
  QObject::connect(&answer, &QTimer::timeout, [&] {
    QWidget* modal = QApplication::activeModalWidget();
    if (!modal) return;
    if (auto* box = qobject_cast<QMessageBox*>(modal)) {
      const auto buttons = box->buttons();
      if (!buttons.isEmpty()) {
        setAction("answer " + box->windowTitle().toStdString());
        buttons.at(pick(static_cast<int>(buttons.size())))->click();
        return;
      }
    }
    if (auto* dialog = qobject_cast<QDialog*>(modal)) {
      setAction("reject " + dialog->windowTitle().toStdString());
      dialog->reject();
    }
  });
  answer.start(300);

  // Short runs so that runs finish, pause, resume and stop often.
  auto shortParameters = [&] {
    archipelago::TrappingParameters p;
    p.q = 4;
    p.T = 20'000 + static_cast<std::uint64_t>(pick(2'000'000));
    p.M = 16;
    p.subsets = 8;
    p.seed = 1 + static_cast<std::uint64_t>(pick(1000));
    return p;
  };

  std::uint64_t actions = 0;
  const double startMiB = residentMiB();
  double minuteOneMiB = -1;
  double minuteOneHeapMiB = -1;
  QElapsedTimer clock;
  clock.start();
  QElapsedTimer transitional;  // since the run entered pausing or stopping
  std::printf("soak: %.1f min, seed %s, RSS at start %.1f MiB\n", minutes, qPrintable(parser.value(seedOpt)), startMiB);
  std::fflush(stdout);
  int lastReport = 0;

  QTimer step;
  QObject::connect(&step, &QTimer::timeout, [&] {
    if (QApplication::activeModalWidget()) return;  // the answer timer handles it
    ++actions;
    const int kind = pick(26);
    auto* portrait = window.portraitPanel()->controller();
    auto* view = window.portraitPanel()->view();
    switch (kind) {
      case 0: {
        setAction("new short run");
        window.parameterPanel()->setParameters(shortParameters(), 2);
        window.startRun();
        break;
      }
      case 1: setAction("F5"); QTest::keyClick(&window, Qt::Key_F5); break;
      case 2: setAction("F6 pause"); QTest::keyClick(&window, Qt::Key_F6); break;
      case 3: setAction("F7 resume"); QTest::keyClick(&window, Qt::Key_F7); break;
      case 4: setAction("Shift+F5 stop"); QTest::keyClick(&window, Qt::Key_F5, Qt::ShiftModifier); break;
      case 5: {
        setAction("switch tab");
        window.tabs()->setCurrentIndex(pick(window.tabs()->count()));
        break;
      }
      case 6: {
        setAction("wheel on portrait");
        window.tabs()->setCurrentWidget(window.portraitPanel());
        QWidget* canvas = view->canvas() ? view->canvas() : view;
        const QPointF at(unit() * canvas->width(), unit() * canvas->height());
        QWheelEvent wheel(at, canvas->mapToGlobal(at), QPoint(), QPoint(0, pick(2) ? 120 : -120), Qt::NoButton,
                          Qt::NoModifier, Qt::NoScrollPhase, false);
        QApplication::sendEvent(canvas, &wheel);
        break;
      }
      case 7: {
        setAction("drag on portrait");
        QWidget* canvas = view->canvas() ? view->canvas() : view;
        const QPoint a(pick(std::max(1, canvas->width())), pick(std::max(1, canvas->height())));
        const QPoint b(pick(std::max(1, canvas->width())), pick(std::max(1, canvas->height())));
        QTest::mousePress(canvas, Qt::LeftButton, Qt::NoModifier, a);
        QTest::mouseMove(canvas, b);
        QTest::mouseRelease(canvas, Qt::LeftButton, Qt::NoModifier, b);
        break;
      }
      case 8: setAction("portrait back"); portrait->back(); break;
      case 9: setAction("portrait reset"); portrait->resetView(); break;
      case 10: {
        setAction("click somewhere");
        const QPoint at(pick(window.width()), pick(window.height()));
        QWidget* target = window.childAt(at);
        if (target && !qobject_cast<QMenu*>(target)) {
          const QPoint local = target->mapFrom(&window, at);
          QTest::mouseClick(target, Qt::LeftButton, Qt::NoModifier, local);
        }
        break;
      }
      case 11: {
        setAction("export all");
        window.exportAllTo(work.filePath(QStringLiteral("export-%1").arg(pick(3))));
        break;
      }
      case 12: {
        setAction("save run file");
        window.saveRunFile(work.filePath(QStringLiteral("run-%1.json").arg(pick(3))));
        break;
      }
      case 13: {
        setAction("open run file");
        window.openRunFile(work.filePath(QStringLiteral("run-%1.json").arg(pick(3))));
        break;
      }
      case 14: {
        setAction("select long segment");
        if (window.longSegments()->model()->rowCount() > 0)
          window.longSegments()->selectRow(pick(window.longSegments()->model()->rowCount()));
        break;
      }
      case 15: {
        setAction("launch orbit");
        portrait->launchOrbit(-0.8 + 1.3 * unit(), -0.8 + 1.3 * unit(), 2000);
        break;
      }
      case 16: {
        setAction("type into a field");
        static const char* names[] = {"K", "T", "M", "seed", "xmin", "threads"};
        static const char* values[] = {"0.1", "nan", "-1", "1e30", "0.2", "inf", "", "3", "0.6", "999"};
        if (auto* field = window.parameterPanel()->field(QString::fromLatin1(names[pick(6)]))) {
          if (!field->isReadOnly()) {
            field->selectAll();
            QTest::keyClicks(field, QString::fromLatin1(values[pick(10)]));
          }
        }
        break;
      }
      case 17: {
        setAction("preset");
        const QStringList presets = window.parameterPanel()->presetNames();
        if (!presets.isEmpty()) window.parameterPanel()->applyPreset(presets.at(pick(static_cast<int>(presets.size()))));
        window.parameterPanel()->setParameters(shortParameters(), 2);
        break;
      }
      case 18: {
        setAction("periodic orbit dialog");
        window.showPeriodicOrbitDialog();
        break;
      }
      case 19: {
        setAction("resize");
        window.resize(900 + pick(1100), 600 + pick(500));
        break;
      }
      case 20: {
        setAction("save session");
        window.saveSession(work.filePath(QStringLiteral("session-%1.archipelago").arg(pick(3))));
        break;
      }
      case 21: {
        setAction("open session");
        window.openSession(work.filePath(QStringLiteral("session-%1.archipelago").arg(pick(3))));
        break;
      }
      case 22: {
        setAction("portrait mode");  // the three modes and the five indicator maps (issue 25, #27)
        const auto displays = archipelago::ui::PortraitPanel::displays();
        window.portraitPanel()->setDisplay(displays[static_cast<std::size_t>(pick(static_cast<int>(displays.size())))]);
        break;
      }
      case 23: setAction("manifolds"); window.portraitPanel()->manifoldsAction()->trigger(); break;
      case 24: setAction("undo orbit (Ctrl+Z)"); QTest::keyClick(&window, Qt::Key_Z, Qt::ControlModifier); break;
      case 25: {
        setAction("rotation profile");
        window.portraitPanel()->profileToolAction()->trigger();
        QWidget* canvas = view->canvas();
        const QPoint a(pick(std::max(1, canvas->width())), pick(std::max(1, canvas->height())));
        const QPoint b(pick(std::max(1, canvas->width())), pick(std::max(1, canvas->height())));
        QTest::mousePress(canvas, Qt::LeftButton, Qt::NoModifier, a);
        QTest::mouseMove(canvas, b);
        QTest::mouseRelease(canvas, Qt::LeftButton, Qt::NoModifier, b);
        break;
      }
    }
    // A pause or stop ends at the next chunk boundary (0.1 s): one that lasts a minute is a stuck state machine.
    const auto status = window.runStatus();
    if (status == archipelago::ui::RunStatus::pausing || status == archipelago::ui::RunStatus::stopping) {
      if (!transitional.isValid()) transitional.start();
      if (transitional.elapsed() > 60000) {
        std::fprintf(stderr, "SOAK STUCK: the run has been %s for 60 s; last action: %s\n",
                     qPrintable(archipelago::ui::statusName(status)), lastAction.c_str());
        std::fflush(stderr);
        std::abort();
      }
    } else {
      transitional.invalidate();
    }
    const int minute = static_cast<int>(clock.elapsed() / 60000);
    if (minute > lastReport) {
      lastReport = minute;
      const double mib = residentMiB();
      const double heap = heapInUseMiB();
      if (minute == 1) minuteOneMiB = mib, minuteOneHeapMiB = heap;
      std::printf("soak: minute %d, %llu actions, RSS %.1f MiB, heap in use %.1f MiB, launched orbits %d, status %s\n",
                  minute, static_cast<unsigned long long>(actions), mib, heap,
                  window.portraitPanel()->controller()->orbitCount(),
                  qPrintable(archipelago::ui::statusName(window.runStatus())));
      std::fflush(stdout);
    }
    if (static_cast<double>(clock.elapsed()) > minutes * 60000) {
      setAction("finish");
      step.stop();
      window.setConfirmations(false);
      window.stopRun();
      QTimer::singleShot(2000, [&] {
        const double endMiB = residentMiB();
        const double endHeapMiB = heapInUseMiB();
        std::printf("soak: done: %llu actions in %.1f min; RSS start %.1f MiB, after minute 1 %.1f MiB, end %.1f MiB, "
                    "growth after minute 1 %.1f MiB; heap in use after minute 1 %.1f MiB, end %.1f MiB, "
                    "heap growth after minute 1 %.1f MiB\n",
                    static_cast<unsigned long long>(actions), static_cast<double>(clock.elapsed()) / 60000.0, startMiB,
                    minuteOneMiB, endMiB, minuteOneMiB > 0 ? endMiB - minuteOneMiB : endMiB - startMiB,
                    minuteOneHeapMiB, endHeapMiB, endHeapMiB - minuteOneHeapMiB);
        std::fflush(stdout);
        QApplication::exit(0);
      });
    }
  });
  step.start(150);
  const int rc = QApplication::exec();
  done = true;
  watchdog.join();
  return rc;
}
