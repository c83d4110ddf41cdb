// The main window: menus, presets, validation as you type, derived coefficients (offscreen platform).
#include <QComboBox>
#include <QAction>
#include <QLabel>
#include <QMenuBar>
#include <QTabWidget>

#include "GuiTestSupport.hpp"
#include "ui/window/StatisticsView.hpp"
#include "ui/plots/StatisticsPlot.hpp"

using archipelago::ui::MainWindow;

class TestMainWindow : public QObject {
  Q_OBJECT
 private Q_SLOTS:
  void opensWithMenusAndStatisticsTab() {
    MainWindow window;
    window.show();
    QVERIFY(QTest::qWaitForWindowExposed(&window));
    QStringList titles;
    const auto actions = window.menuBar()->actions();
    for (const QAction* a : actions) titles << a->text();
    QVERIFY(titles.contains(QStringLiteral("&File")));
    QVERIFY(titles.contains(QStringLiteral("&Run")));
    QVERIFY(titles.contains(QStringLiteral("&Help")));
    QCOMPARE(window.windowTitle(), QStringLiteral("Archipelago"));
    // The first screen is the phase portrait (issue 25, finding 5), with the run's f_t and C_τ beside it.
    QCOMPARE(window.tabs()->tabText(0), QStringLiteral("Phase portrait"));
    QCOMPARE(window.tabs()->currentIndex(), 0);
    QCOMPARE(window.tabs()->tabText(1), QStringLiteral("Statistics"));
    QCOMPARE(window.statisticsView()->plots().size(), 6);
    QCOMPARE(window.runAction()->shortcut(), QKeySequence(Qt::Key_F5));
    QVERIFY(window.runAction()->isEnabled());
    QVERIFY(!window.pauseAction()->isEnabled());
    QVERIFY(!window.resumeAction()->isEnabled());
    QVERIFY(!window.stopAction()->isEnabled());
  }

  void startsWithTheModestK01Preset() {
    MainWindow window;
    const auto p = window.parameterPanel()->parameters();
    QVERIFY(p.has_value());
    QCOMPARE(p->map.K, 0.1);
    QCOMPARE(p->map.xmin, -0.8);
    QCOMPARE(p->map.xmax, 0.5);
    QCOMPARE(p->Xr, 0.02);
  }

  void presetsReproduceThePaper() {
    MainWindow window;
    auto& panel = *window.parameterPanel();
    QVERIFY(panel.presetNames().size() >= 5);
    QVERIFY(panel.applyPreset(QStringLiteral("K = 0.1, paper's fig. 6 (long)")));
    auto p = panel.parameters();
    QVERIFY(p.has_value());
    QCOMPARE(p->M, std::uint64_t{1600});
    QCOMPARE(static_cast<double>(p->q) * static_cast<double>(p->T), 2e9);  // qT = 2×10⁹ (§5)
    for (const char* name : {"K = −10⁻⁴ (fig. 3a)", "K = 0 (fig. 3b)", "K = 10⁻⁴ (fig. 3c)"}) {
      QVERIFY2(panel.applyPreset(QString::fromUtf8(name)), name);
      p = panel.parameters();
      QVERIFY(p.has_value());
      QCOMPARE(p->q, 1u);
      QCOMPARE(p->map.xmax, -p->map.xmin);  // a box about the origin (fig. 3a's is wider: see its preset)
    }
    QCOMPARE(panel.parameters()->map.K, 1e-4);
    QVERIFY(!panel.applyPreset(QStringLiteral("no such preset")));
  }

  // Issue 13, finding 5: after a restart the preset box named the K = 0.1 preset while the fields held the
  // last session's K = 0 values.  The window now saves a run spec through core's codec and restores it whole.
  void restartRestoresTheLastSpecAndItsPreset() {
    {
      MainWindow window;
      window.show();
      QVERIFY(window.parameterPanel()->applyPreset(QStringLiteral("small-k-zero")));  // by the CLI's id
      window.close();  // saves the settings
    }
    {
      MainWindow window;
      const auto spec = window.parameterPanel()->spec();
      QVERIFY(spec.has_value());
      QCOMPARE(spec->parameters.map.K, 0.0);
      QCOMPARE(spec->parameters, archipelago::findPreset("small-k-zero")->spec.parameters);
      QCOMPARE(QString::fromStdString(spec->name), QStringLiteral("K = 0 (fig. 3b)"));
      auto* box = window.parameterPanel()->findChild<QComboBox*>(QStringLiteral("presets"));
      QCOMPARE(box->currentText(), QStringLiteral("K = 0 (fig. 3b)"));
      window.show();
      archipelago::test::typeInto(*window.parameterPanel(), QStringLiteral("M"), QStringLiteral("80"));
      window.close();
    }
    {
      MainWindow window;  // hand-edited parameters come back as Custom, with the edit kept
      const auto spec = window.parameterPanel()->spec();
      QVERIFY(spec.has_value());
      QCOMPARE(spec->parameters.M, std::uint64_t{80});
      QCOMPARE(spec->parameters.map.K, 0.0);
      QVERIFY(spec->name.empty());
      QCOMPARE(window.parameterPanel()->findChild<QComboBox*>(QStringLiteral("presets"))->currentIndex(), 0);
    }
    QSettings().setValue(QStringLiteral("run/spec"), QStringLiteral("{\"format\": \"archipelago-spec\", \"version\": 1, \"Kk\": 3}"));
    MainWindow window;  // an unreadable saved spec is ignored: the default preset, and a note
    QCOMPARE(window.parameterPanel()->spec()->parameters, archipelago::presets().front().spec.parameters);
    QSettings().remove(QStringLiteral("run/spec"));
  }

  void invalidInputDisablesRun() {
    MainWindow window;
    window.show();
    auto& panel = *window.parameterPanel();
    QVERIFY(window.runAction()->isEnabled());

    // xmin must be < −√K (appendix B): core's rule, shown with the field marked.
    archipelago::test::typeInto(panel, QStringLiteral("xmin"), QStringLiteral("0.2"));
    QVERIFY(!panel.isValid());
    QVERIFY(!window.runAction()->isEnabled());
    QCOMPARE(panel.invalidField(), QStringLiteral("xmin"));
    QVERIFY(panel.field(QStringLiteral("xmin"))->property("invalid").toBool());
    QVERIFY2(panel.validationMessage().contains(QStringLiteral("−√K")), qPrintable(panel.validationMessage()));
    auto* shown = panel.findChild<QLabel*>(QStringLiteral("validationMessage"));
    QVERIFY(shown);
    QCOMPARE(shown->text(), panel.validationMessage());
    QCOMPARE(panel.findChild<QLabel*>(QStringLiteral("derived_A"))->text(), QStringLiteral("—"));
    QVERIFY(!window.startRun());

    archipelago::test::typeInto(panel, QStringLiteral("xmin"), QStringLiteral("-0.8"));
    QVERIFY(panel.isValid());
    QVERIFY(window.runAction()->isEnabled());
    QVERIFY(!panel.field(QStringLiteral("xmin"))->property("invalid").toBool());

    // Not a number.
    archipelago::test::typeInto(panel, QStringLiteral("T"), QStringLiteral("lots"));
    QVERIFY(!window.runAction()->isEnabled());
    QCOMPARE(panel.invalidField(), QStringLiteral("T"));
    // Scientific notation is accepted for counts.
    archipelago::test::typeInto(panel, QStringLiteral("T"), QStringLiteral("2e7"));
    QVERIFY(panel.isValid());
    QCOMPARE(panel.parameters()->T, std::uint64_t{20'000'000});

    // More subsets than orbits.
    archipelago::test::typeInto(panel, QStringLiteral("M"), QStringLiteral("4"));
    QVERIFY(!window.runAction()->isEnabled());
    QCOMPARE(panel.invalidField(), QStringLiteral("subsets"));
    archipelago::test::typeInto(panel, QStringLiteral("M"), QStringLiteral("64"));
    QVERIFY(window.runAction()->isEnabled());

    // Xr outside [0, 1).
    archipelago::test::typeInto(panel, QStringLiteral("Xr"), QStringLiteral("1.5"));
    QCOMPARE(panel.invalidField(), QStringLiteral("Xr"));
    QVERIFY(!window.runAction()->isEnabled());
  }

  void derivedCoefficientsAreCores() {
    MainWindow window;
    auto& panel = *window.parameterPanel();
    const archipelago::TrappingParameters p = archipelago::test::shortRun();
    panel.setParameters(p, 1);
    const archipelago::MapCoefficients k = archipelago::computeCoefficients(p.map);
    QCOMPARE(panel.findChild<QLabel*>(QStringLiteral("derived_A"))->text(), QString::number(k.A));
    QCOMPARE(panel.findChild<QLabel*>(QStringLiteral("derived_B"))->text(), QString::number(k.B));
    QCOMPARE(panel.findChild<QLabel*>(QStringLiteral("derived_C"))->text(), QString::number(k.C));
    QCOMPARE(panel.findChild<QLabel*>(QStringLiteral("derived_m"))->text(), QString::number(k.m));
  }

  void parametersHaveTooltips() {
    MainWindow window;
    for (const char* name : {"K", "xmin", "xmax", "Xr", "q", "T", "M", "seed", "subsets", "threads"}) {
      QLineEdit* edit = window.parameterPanel()->field(QLatin1String(name));
      QVERIFY2(edit, name);
      QVERIFY2(edit->toolTip().size() > 30, name);
    }
  }
};

ARCHIPELAGO_GUI_TEST_MAIN(TestMainWindow)
#include "test_main_window.moc"
