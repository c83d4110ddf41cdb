// The parameter form (issue #13, finding 11): every invalid field is marked at once with its own reason, the
// reasons state the ranges of core's parameterRules() and kMaxThreads in the paper's notation, numbers are
// printed shortest round trip, and the fields do not move when the preset's description changes.
#include <QLabel>
#include <QLineEdit>

#include "GuiTestSupport.hpp"
#include "core/runspec/RunSpec.hpp"
#include "ui/periodic/PeriodicOrbitDialog.hpp"

using archipelago::ui::ParameterPanel;
using archipelago::test::typeInto;

class TestParameterPanel : public QObject {
  Q_OBJECT
 private Q_SLOTS:
  void init() {
    panel_ = new ParameterPanel;
    panel_->resize(420, 900);
    panel_->show();
    QVERIFY(panel_->applyPreset(QStringLiteral("k0.1-minute")));
    QVERIFY(panel_->isValid());
  }
  void cleanup() { delete panel_; }

  // Bug: one error was shown at a time; a second invalid field lost its mark.
  void everyInvalidFieldIsMarkedAtOnce() {
    typeInto(*panel_, QStringLiteral("K"), QStringLiteral("inf"));
    typeInto(*panel_, QStringLiteral("T"), QStringLiteral("1e30"));
    typeInto(*panel_, QStringLiteral("M"), QStringLiteral("0"));
    typeInto(*panel_, QStringLiteral("threads"), QStringLiteral("999"));
    QVERIFY(!panel_->isValid());
    QCOMPARE(panel_->invalidFields(),
             (QStringList{QStringLiteral("K"), QStringLiteral("T"), QStringLiteral("M"), QStringLiteral("threads")}));
    for (const QString& name : panel_->invalidFields())
      QVERIFY2(panel_->field(name)->property("invalid").toBool(), qPrintable(name));
    QVERIFY(!panel_->field(QStringLiteral("xmin"))->property("invalid").toBool());
    // Each field's own reason, with the real range (bugs: "K is not a number" for inf, "T must be a whole
    // number ≥ 0" for 1e30, "M … ≥ 0" although 0 is rejected, threads = 999 accepted).
    QCOMPARE(panel_->fieldError(QStringLiteral("K")), QStringLiteral("K = inf must be a finite number"));
    QCOMPARE(panel_->fieldError(QStringLiteral("T")), QStringLiteral("T = 1e30 must be a whole number in [1, 2⁶²], q·T ≤ 2⁶²"));
    QCOMPARE(panel_->fieldError(QStringLiteral("M")), QStringLiteral("M = 0 must lie in [1, 2³²] (and the memory they need)"));
    QCOMPARE(panel_->fieldError(QStringLiteral("threads")),
             QStringLiteral("threads = 999 must lie in [0, %1] (0: one per core)").arg(archipelago::kMaxThreads));
    const QStringList shown = panel_->findChild<QLabel*>(QStringLiteral("validationMessage"))->text().split(QLatin1Char('\n'));
    QCOMPARE(shown.size(), 4);
    QVERIFY(panel_->field(QStringLiteral("T"))->toolTip().contains(QStringLiteral("2⁶²")));

    typeInto(*panel_, QStringLiteral("K"), QStringLiteral("0.1"));
    QVERIFY(!panel_->field(QStringLiteral("K"))->property("invalid").toBool());
    QVERIFY(panel_->field(QStringLiteral("T"))->property("invalid").toBool());  // the others keep their marks
    typeInto(*panel_, QStringLiteral("T"), QStringLiteral("1000"));
    typeInto(*panel_, QStringLiteral("M"), QStringLiteral("64"));
    typeInto(*panel_, QStringLiteral("threads"), QString::number(archipelago::kMaxThreads));
    QVERIFY(panel_->isValid());
  }

  // Bug: xmin = 0.6 (> xmax) marked xmax, and the message printed -0.80000000000000004.
  void theWrongFieldIsMarkedWithShortestNumbers() {
    typeInto(*panel_, QStringLiteral("xmin"), QStringLiteral("0.6"));
    QVERIFY(panel_->field(QStringLiteral("xmin"))->property("invalid").toBool());
    QVERIFY2(panel_->fieldError(QStringLiteral("xmin")).contains(QStringLiteral("xmin = 0.6 must be < −√K = -0.31622776601683794")),
             qPrintable(panel_->fieldError(QStringLiteral("xmin"))));
    QVERIFY(panel_->fieldError(QStringLiteral("xmin")).contains(QStringLiteral("xmax = 0.5 must be > xmin = 0.6")));
    typeInto(*panel_, QStringLiteral("xmin"), QStringLiteral("-0.8"));
    typeInto(*panel_, QStringLiteral("xmax"), QStringLiteral("-0.8"));
    // Equal edges: the rule is about both, so both are marked with it.
    QVERIFY(panel_->field(QStringLiteral("xmax"))->property("invalid").toBool());
    QVERIFY(panel_->field(QStringLiteral("xmin"))->property("invalid").toBool());
    QVERIFY(panel_->validationMessage().contains(QStringLiteral("xmax = -0.8 must be > xmin = -0.8")));
    QVERIFY2(!panel_->validationMessage().contains(QStringLiteral("0000")), qPrintable(panel_->validationMessage()));
  }

  // Bug: user-facing text used ASCII maths ("sqrt", "2^62", "N^-1") and the paper's internal labels ("eq. qu").
  void textUsesThePapersNotation() {
    typeInto(*panel_, QStringLiteral("q"), QStringLiteral("0"));
    typeInto(*panel_, QStringLiteral("subsets"), QStringLiteral("2000"));
    QStringList texts{panel_->validationMessage()};
    for (QWidget* w : panel_->findChildren<QWidget*>()) texts << w->toolTip();
    for (QLabel* l : panel_->findChildren<QLabel*>()) texts << l->text();
    for (const QString& t : std::as_const(texts))
      for (const char* ascii : {"sqrt", "^", "<=", ">=", "eq. qu", "eq. gstar", "eq. fneg", "N^-", "*T"})
        QVERIFY2(!t.contains(QLatin1String(ascii)), qPrintable(QStringLiteral("'%1' in: %2").arg(QLatin1String(ascii), t)));
    QVERIFY(panel_->validationMessage().contains(QStringLiteral("q = 0 must lie in [1, 65536]")));
    QVERIFY(panel_->validationMessage().contains(QStringLiteral("subsets = 2000 must lie in [1, 1024], ≤ M")));
  }

  // Bug: the description disappeared when a field was edited and the fields jumped by about 57 px; it was
  // also drawn in the disabled colour.
  void fieldsDoNotMoveWhenTheDescriptionChanges() {
    auto* description = panel_->findChild<QLabel*>(QStringLiteral("presetDescription"));
    QVERIFY(description);
    QVERIFY(!description->text().isEmpty());
    QCOMPARE(description->palette().color(QPalette::WindowText), panel_->palette().color(QPalette::WindowText));
    QVERIFY(description->styleSheet().isEmpty());
    QApplication::processEvents();
    const int before = panel_->field(QStringLiteral("K"))->mapTo(panel_, QPoint(0, 0)).y();
    typeInto(*panel_, QStringLiteral("K"), QStringLiteral("0.12"));  // no longer the preset
    QApplication::processEvents();
    QCOMPARE(panel_->field(QStringLiteral("K"))->mapTo(panel_, QPoint(0, 0)).y(), before);
    QVERIFY(panel_->applyPreset(QStringLiteral("small-k-negative")));  // a longer description
    QApplication::processEvents();
    QCOMPARE(panel_->field(QStringLiteral("K"))->mapTo(panel_, QPoint(0, 0)).y(), before);
    // A description longer than its five lines scrolls instead of being cut mid-line (the k0.1 presets' were).
    QVERIFY(panel_->applyPreset(QStringLiteral("k0.1-minute")));
    QApplication::processEvents();
    QCOMPARE(panel_->field(QStringLiteral("K"))->mapTo(panel_, QPoint(0, 0)).y(), before);
    QVERIFY2(description->height() >= description->heightForWidth(description->width()),
             qPrintable(QStringLiteral("%1 < %2").arg(description->height()).arg(description->heightForWidth(description->width()))));
  }

  // Issue 13, finding 12: Find Periodic Orbit showed a literal "&Near (x, y):" and K = 0.10000000000000001.
  void periodicOrbitDialogText() {
    archipelago::ui::PeriodicOrbitDialog dialog;
    dialog.setK(0.1);
    dialog.setNear(0.0509, 0.0974);
    QStringList texts;
    for (const QLineEdit* edit : dialog.findChildren<QLineEdit*>()) texts << edit->text();
    QVERIFY2(texts.contains(QStringLiteral("0.1")) && texts.contains(QStringLiteral("0.0509")), qPrintable(texts.join(u' ')));
    for (const QString& t : std::as_const(texts)) QVERIFY2(!t.contains(QStringLiteral("0000000")), qPrintable(t));
    bool nearHasBuddy = false;
    for (const QLabel* label : dialog.findChildren<QLabel*>())
      if (label->text().contains(QStringLiteral("Near"))) nearHasBuddy = label->buddy() != nullptr;  // "&" is a mnemonic
    QVERIFY(nearHasBuddy);
  }

 private:
  ParameterPanel* panel_ = nullptr;
};

ARCHIPELAGO_GUI_TEST_MAIN(TestParameterPanel)
#include "test_parameter_panel.moc"
