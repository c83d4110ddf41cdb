// Exports: every plot to PNG, SVG and PDF, every statistic to CSV; run files round-trip (offscreen platform).
#include <QDir>
#include <QDragEnterEvent>
#include <QDropEvent>
#include <QFileInfo>
#include <QMimeData>
#include <QUrl>
#include <QFile>
#include <QHash>
#include <QImage>
#include <QSvgRenderer>
#include <QTemporaryDir>

#include "GuiTestSupport.hpp"
#include "ui/settings/SettingsController.hpp"
#include "ui/window/StatisticsView.hpp"
#include "ui/plots/StatisticsPlot.hpp"
#include "core/runfile/RunFile.hpp"
#include "core/runspec/RunSpec.hpp"
#include "ui/window/ExportActions.hpp"

#include <QMessageBox>

using archipelago::ui::MainWindow;
using archipelago::ui::RunStatus;

// The columns of each plot's CSV file, by file name (issue #11: descriptive names, never a generic "x").
const QHash<QString, QString> kColumns = {
    {QStringLiteral("f_t"), QStringLiteral("t,f_t,f_t_error,blocks_affected")},
    {QStringLiteral("P_t"), QStringLiteral("t,P_t,P_t_error,blocks_affected")},
    {QStringLiteral("C_tau"), QStringLiteral("tau,C_tau,C_tau_error,blocks_affected")},
    {QStringLiteral("local_exponent"), QStringLiteral("tau,local_exponent,local_exponent_error,blocks_affected")},
    {QStringLiteral("S_t"), QStringLiteral("t,S_t,S_t_error,blocks_affected")},
    {QStringLiteral("D_t"), QStringLiteral("t,D_t,D_t_error,blocks_affected")},
};

class TestExport : public QObject {
  Q_OBJECT
 private:
  MainWindow* window_ = nullptr;
  QTemporaryDir dir_;

 private Q_SLOTS:
  void initTestCase() {
    QVERIFY(dir_.isValid());
    window_ = new MainWindow;
    window_->setConfirmations(false);
    window_->show();
    window_->parameterPanel()->setParameters(archipelago::test::shortRun(), 2);
    QVERIFY(window_->startRun());
    QVERIFY(QTest::qWaitFor([this] { return window_->runStatus() == RunStatus::finished; }, 20000));
  }
  void cleanupTestCase() { delete window_; }

  void exportAllWritesValidFiles() {
    const QString folder = dir_.filePath(QStringLiteral("export"));
    QString error;
    QVERIFY2(window_->exportAllTo(folder, &error), qPrintable(error));
    for (archipelago::ui::StatisticsPlot* plot : window_->statisticsView()->plots()) {
      const QString base = QDir(folder).filePath(plot->fileName());

      QImage png;
      QVERIFY2(png.load(base + QStringLiteral(".png"), "PNG"), qPrintable(base));
      QVERIFY(png.width() > 500 && png.height() > 300);
      // Issue 54, item 6: the run shown is in the PNG's text, each parameter as the CSV files' header gives it.
      QFile header(QDir(folder).filePath(QStringLiteral("summary.csv")));
      QVERIFY(header.open(QIODevice::ReadOnly | QIODevice::Text));
      QHash<QString, QString> recorded;
      for (const QString& line : QString::fromUtf8(header.readAll()).split(QLatin1Char('\n')))
        if (line.startsWith(QStringLiteral("# ")) && line.contains(QStringLiteral(": ")))
          recorded.insert(line.mid(2, line.indexOf(QStringLiteral(": ")) - 2), line.mid(line.indexOf(QStringLiteral(": ")) + 2));
      for (const char* key : {"K", "xmin", "xmax", "Xr", "q", "T", "M", "seed", "blocks_done"})
        QVERIFY2(!recorded.value(QLatin1String(key)).isEmpty() && png.text(QLatin1String(key)) == recorded.value(QLatin1String(key)),
                 qPrintable(base + QStringLiteral(": ") + QLatin1String(key) + QStringLiteral(" = ") +
                            png.text(QLatin1String(key))));
      // Not blank: the data curve's colour is somewhere in the image.
      bool hasCurveColour = false;
      for (int y = 0; y < png.height() && !hasCurveColour; y += 1)
        for (int x = 0; x < png.width() && !hasCurveColour; x += 1) {
          const QColor c = png.pixelColor(x, y);
          hasCurveColour = c.blue() > 120 && c.red() < 80 && c.green() < 120;
        }
      QVERIFY2(hasCurveColour, qPrintable(base));

      QSvgRenderer svg(base + QStringLiteral(".svg"));
      QVERIFY2(svg.isValid(), qPrintable(base));
      QVERIFY(svg.defaultSize().width() > 0);

      QFile pdf(base + QStringLiteral(".pdf"));
      QVERIFY(pdf.open(QIODevice::ReadOnly));
      const QByteArray bytes = pdf.readAll();
      QVERIFY(bytes.startsWith("%PDF-"));
      QVERIFY(bytes.contains("%%EOF"));

      // Numbers: core's CSV writer (the same files as `stats --csv`; tests/gui/test_csv_export.cpp compares them
      // byte for byte): comment lines, then descriptive columns, then 17-digit rows.
      QFile csv(base + QStringLiteral(".csv"));
      QVERIFY2(csv.open(QIODevice::ReadOnly | QIODevice::Text), qPrintable(base));
      QStringList lines = QString::fromUtf8(csv.readAll()).split(QLatin1Char('\n'), Qt::SkipEmptyParts);
      QVERIFY(lines.front().startsWith(QStringLiteral("# program: archipelago ")));
      while (!lines.isEmpty() && lines.front().startsWith(QStringLiteral("# "))) lines.removeFirst();
      QVERIFY(!lines.isEmpty());
      QCOMPARE(lines.front(), kColumns.value(plot->fileName()));
      int dataRows = 0;
      for (int i = 1; i < lines.size(); ++i) {
        const QStringList cells = lines.at(i).split(QLatin1Char(','));
        QCOMPARE(cells.size(), 4);
        // blocks_affected: 1 below 10 q steps (the q-block artefact; docs/design.md, "Blocks of q steps"), else 0.
        QVERIFY(cells.at(3) == QStringLiteral("0") || cells.at(3) == QStringLiteral("1"));
        bool okX = false, okV = false, okE = false;
        const double x = cells.at(0).toDouble(&okX);
        const double v = cells.at(1).toDouble(&okV);
        const double e = cells.at(2).toDouble(&okE);
        QVERIFY(okX && okV && okE);
        // Numbers round-trip exactly (17 digits).
        const auto row = static_cast<std::size_t>(dataRows);
        QCOMPARE(x, plot->data().x.at(row));
        QCOMPARE(v, plot->data().value.at(row));
        QCOMPARE(e, plot->data().error.at(row));
        ++dataRows;
      }
      QCOMPARE(static_cast<std::size_t>(dataRows), plot->data().x.size());
      QVERIFY(dataRows > 0);
    }
    // Beyond the plots: p_t (no plot of its own) and the summary.
    for (const char* name : {"p_t_probability.csv", "summary.csv"})
      QVERIFY2(QFileInfo::exists(QDir(folder).filePath(QLatin1String(name))), name);
    // K = 0.1: no small-K theory (§4), so no theory file.
    QVERIFY(QDir(folder).entryList({QStringLiteral("*.theory.csv")}).isEmpty());
  }

  // Issue 13, finding 13: "Export all" left out the portrait, the segments table and the parameters.
  void exportAllWritesThePortraitTheSegmentsAndTheSpec() {
    const QString folder = dir_.filePath(QStringLiteral("export-extras"));
    QString error;
    QVERIFY2(window_->exportAllTo(folder, &error), qPrintable(error));
    const QDir dir(folder);
    QImage portrait;
    QVERIFY(portrait.load(dir.filePath(QStringLiteral("portrait.png")), "PNG"));
    QVERIFY(portrait.width() > 500);

    // The longest segments, longest first, with the metadata header of every CSV file.
    QFile csv(dir.filePath(QStringLiteral("longest_segments.csv")));
    QVERIFY(csv.open(QIODevice::ReadOnly | QIODevice::Text));
    QStringList lines = QString::fromUtf8(csv.readAll()).split(QLatin1Char('\n'), Qt::SkipEmptyParts);
    QVERIFY(lines.front().startsWith(QStringLiteral("# program: archipelago ")));
    QVERIFY(lines.contains(QStringLiteral("# K: 0.1")));
    while (!lines.isEmpty() && lines.front().startsWith(QStringLiteral("# "))) lines.removeFirst();
    QCOMPARE(lines.front(), QStringLiteral("rank,length_steps,length_blocks,orbit,start_block,start_draws,start_X,"
                                          "start_Y,start_x,start_y"));
    const archipelago::TrappingState& state = window_->latestSnapshot()->state;
    const auto& items = state.longest.items();
    QVERIFY(!items.empty());
    QCOMPARE(lines.size() - 1, static_cast<int>(items.size()));
    const QStringList first = lines.at(1).split(QLatin1Char(','));
    QCOMPARE(first.at(0), QStringLiteral("1"));
    QCOMPARE(first.at(1).toULongLong(), static_cast<qulonglong>(items.front().length * state.params.q));
    QCOMPARE(first.at(3).toULongLong(), static_cast<qulonglong>(items.front().orbit));
    QCOMPARE(first.at(6).toULongLong(), static_cast<qulonglong>(items.front().start.z.X));

    // The parameters through core's spec codec: `archipelago-cli run --spec` reads them back.
    const archipelago::RunSpec spec = archipelago::loadRunSpec(dir.filePath(QStringLiteral("run_spec.json")).toStdString());
    QVERIFY(spec.parameters == state.params);
  }

  // Issue 13, finding 13: file dialogs did not reopen in the last folder.
  void dialogsStartInTheLastFolder() {
    const QString folder = dir_.filePath(QStringLiteral("somewhere"));
    QVERIFY(QDir().mkpath(folder));
    archipelago::ui::SettingsController::rememberFolder(QDir(folder).filePath(QStringLiteral("run.json")));
    QCOMPARE(archipelago::ui::SettingsController::lastFolder(), QFileInfo(folder).absoluteFilePath());
    archipelago::ui::SettingsController::rememberFolder(dir_.path());  // a folder itself
    QCOMPARE(archipelago::ui::SettingsController::lastFolder(), QFileInfo(dir_.path()).absoluteFilePath());
  }

  // Issue 13, finding 13: a run file that failed to open was reported only in the status bar, cut off.
  void aCorruptRunFileShowsTheWholeReason() {
    const QString path = dir_.filePath(QStringLiteral("corrupt.json"));
    QFile file(path);
    QVERIFY(file.open(QIODevice::WriteOnly));
    file.write("{\"format\": \"archipelago-run\", \"version\": 1, \"this is\": \"not a run file\"}");
    file.close();
    MainWindow other;
    other.setConfirmations(false);
    other.show();
    QString error;
    QVERIFY(!other.openRunFile(path, &error));
    QVERIFY(!error.isEmpty());
    auto* box = other.findChild<QMessageBox*>(QStringLiteral("openErrorDialog"));
    QVERIFY(box);
    QCOMPARE(box->informativeText(), error);  // the whole reason, not a status-bar line
    QVERIFY(box->text().contains(QStringLiteral("corrupt.json")));
    box->close();
  }

  void unknownImageFormatIsRefused() {
    QString error;
    QVERIFY(!window_->statisticsView()->plots().front()->exportImage(dir_.filePath(QStringLiteral("x.bmpx")), &error));
    QVERIFY(error.contains(QStringLiteral("format")));
  }

  void runFilesRoundTripThroughTheWindow() {
    const QString path = dir_.filePath(QStringLiteral("run.json"));
    QString error;
    QVERIFY2(window_->saveRunFile(path, &error), qPrintable(error));
    const archipelago::TrappingState saved = window_->latestSnapshot()->state;
    QVERIFY(archipelago::loadRunFile(path.toStdString()).subsets == saved.subsets);

    MainWindow other;
    other.setConfirmations(false);
    QVERIFY2(other.openRunFile(path, &error), qPrintable(error));
    QVERIFY(QTest::qWaitFor([&] { return other.runStatus() == RunStatus::finished; }, 10000));
    QVERIFY(other.latestSnapshot()->state.subsets == saved.subsets);
    QTRY_COMPARE(other.statisticsView()->plots().front()->data().value,
                 window_->statisticsView()->plots().front()->data().value);
    QVERIFY(other.windowTitle().startsWith(QStringLiteral("run.json")));

    QVERIFY(!other.openRunFile(dir_.filePath(QStringLiteral("missing.json")), &error));
    QVERIFY(!error.isEmpty());

    // Saved and opened files are remembered for File ▸ Open Recent.
    const QStringList recent = QSettings().value(QStringLiteral("recentFiles")).toStringList();
    QVERIFY(recent.contains(QFileInfo(path).absoluteFilePath()));
  }

  void droppingARunFileOpensIt() {
    const QString path = dir_.filePath(QStringLiteral("dropped.json"));
    QVERIFY(window_->saveRunFile(path));
    MainWindow target;
    target.setConfirmations(false);
    target.show();
    QMimeData mime;
    mime.setUrls({QUrl::fromLocalFile(path)});
    const QPoint centre = target.rect().center();
    QDragEnterEvent enter(centre, Qt::CopyAction, &mime, Qt::LeftButton, Qt::NoModifier);
    enter.setAccepted(false);
    QApplication::sendEvent(&target, &enter);
    QVERIFY(enter.isAccepted());
    QDropEvent drop(QPointF(centre), Qt::CopyAction, &mime, Qt::LeftButton, Qt::NoModifier);
    QApplication::sendEvent(&target, &drop);
    QVERIFY(QTest::qWaitFor([&] { return target.runStatus() == RunStatus::finished; }, 10000));
    QVERIFY(target.latestSnapshot()->state.subsets == window_->latestSnapshot()->state.subsets);

    // Anything but a .json file is refused.
    QMimeData other;
    other.setUrls({QUrl::fromLocalFile(dir_.filePath(QStringLiteral("picture.png")))});
    QDragEnterEvent refused(centre, Qt::CopyAction, &other, Qt::LeftButton, Qt::NoModifier);
    refused.setAccepted(false);
    QApplication::sendEvent(&target, &refused);
    QVERIFY(!refused.isAccepted());
  }
};

ARCHIPELAGO_GUI_TEST_MAIN(TestExport)
#include "test_export.moc"
