// Issue 27, deliverable 3 (the GUI of the phase-space instruments): a clicked orbit's rotation number, digits and
// chain — "The CLI, GUI and Python give the same numbers for the same orbit": the GUI's numbers are compared with
// `archipelago-cli rotation --json` (the Python module's are compared with the CLI's in tests/python); each
// indicator mode renders progressively with a titled colour bar and core's own numbers, and exports .npy with
// its sidecar; the rotation-profile tool gives the CLI's profile.
#include <map>
#include <vector>

#include <QAction>
#include <QDir>
#include <QFile>
#include <QFileInfo>
#include <QJsonArray>
#include <QJsonDocument>
#include <QJsonObject>
#include <QProcess>
#include <QSignalSpy>
#include <QTemporaryDir>
#include <QVBoxLayout>
#include <QtTest>
#include <qwt_plot.h>
#include <qwt_scale_widget.h>

#include <cmath>

#include "GuiTestSupport.hpp"
#include "core/io/Png.hpp"
#include "core/measures/IndicatorMap.hpp"
#include "ui/portrait/LaunchedOrbits.hpp"
#include "ui/portrait/OrbitListPanel.hpp"
#include "ui/portrait/PortraitController.hpp"
#include "ui/portrait/PortraitPanel.hpp"
#include "ui/portrait/PortraitView.hpp"
#include "ui/portrait/PortraitWorker.hpp"
#include "ui/portrait/RotationProfilePanel.hpp"

#ifndef ARCHIPELAGO_CLI
#error "ARCHIPELAGO_CLI must name the archipelago-cli executable (tests/gui/CMakeLists.txt)"
#endif

using archipelago::IndicatorKind;
using archipelago::ui::PortraitController;
using archipelago::ui::PortraitPanel;
using archipelago::ui::PortraitView;
using archipelago::ui::RenderState;

namespace {
QByteArray cli(const QStringList& args) {
  QProcess p;
  p.start(QStringLiteral(ARCHIPELAGO_CLI), args);
  if (!p.waitForFinished(120000) || p.exitCode() != 0) {
    qWarning("%s", p.readAllStandardError().constData());
    return {};
  }
  return p.readAllStandardOutput();
}

QString exact(double v) { return QString::number(v, 'g', 17); }
}  // namespace

class TestInstruments : public QObject {
  Q_OBJECT
 private Q_SLOTS:
  // The same numbers for the same orbit: an orbit of the six islands' chain and one on an invariant curve.
  void theGuiAndTheCliGiveTheSameNumbersForTheSameOrbit() {
    PortraitPanel panel;
    panel.resize(700, 500);
    panel.show();
    QVERIFY(QTest::qWaitForWindowExposed(&panel));
    PortraitController& c = *panel.controller();
    const double starts[][2] = {{0.06, 0.0974}, {-0.2, 0.0}};
    for (const auto& s : starts) QVERIFY(c.launchOrbit(s[0], s[1]) != 0);
    QTRY_VERIFY_WITH_TIMEOUT(c.orbitsSettled(), 900000);
    for (std::size_t i = 0; i < 2; ++i) {
      const auto& orbit = c.launchedOrbits()[i];
      QVERIFY(orbit.measures && orbit.measures->error.isEmpty());
      const archipelago::ChainIdentification& chain = orbit.measures->chain;
      const QByteArray out = cli({QStringLiteral("rotation"), QStringLiteral("--K"), QStringLiteral("0.1"),
                                  QStringLiteral("--x=") + exact(starts[i][0]), QStringLiteral("--y=") + exact(starts[i][1]),
                                  QStringLiteral("--json")});
      const QJsonObject json = QJsonDocument::fromJson(out).object();
      QVERIFY2(!json.isEmpty(), out.constData());
      QCOMPARE(chain.levels.front().rotation.rotation, json[QStringLiteral("rotation")].toDouble());
      QCOMPARE(chain.levels.front().rotation.digits, json[QStringLiteral("digits")].toDouble());
      const QJsonObject jc = json[QStringLiteral("chain")].toObject();
      QCOMPARE(static_cast<qint64>(chain.period), static_cast<qint64>(jc[QStringLiteral("period")].toDouble()));
      QCOMPARE(QString::fromStdString(chain.summary), jc[QStringLiteral("summary")].toString());
      QCOMPARE(static_cast<int>(chain.levels.size()), jc[QStringLiteral("levels")].toArray().size());
      // What the list shows is those numbers.
      const QString shown = archipelago::ui::rotationText(*orbit.measures);
      QVERIFY2(shown.contains(QString::number(json[QStringLiteral("rotation")].toDouble(), 'g', 10)), qPrintable(shown));
    }
    // The first orbit is in the six islands' chain: 1/6 about the centre, and its chain's elliptic orbit is drawn
    // when it is highlighted.
    QCOMPARE(c.launchedOrbits()[0].measures->chain.period, std::uint64_t{6});
    c.highlightOrbit(c.launchedOrbits()[0].id);
    QCOMPARE(panel.view()->layerItems(archipelago::ui::PortraitLayer::orbitChain).size(), std::size_t{1});
    QTRY_VERIFY(panel.orbitList()->detailsText().contains(QStringLiteral("period 6")));
  }

  // Each indicator: a coarse picture first, then finer; a titled colour bar; core's numbers; .npy + sidecar.
  void indicatorModesAreProgressiveWithTitledColourBars() {
    PortraitPanel panel;
    panel.resize(360, 300);
    panel.show();
    QVERIFY(QTest::qWaitForWindowExposed(&panel));
    PortraitController& c = *panel.controller();
    // A small view in the six islands' region keeps the maps quick (2·10⁴ steps per pixel).
    c.setViewport(archipelago::Viewport::fromPhysical(c.map(), {0.0L, 0.1L, 0.05L, 0.15L}));
    QTemporaryDir dir;
    for (IndicatorKind kind : {IndicatorKind::Dig, IndicatorKind::Rotation, IndicatorKind::Fli, IndicatorKind::Megno,
                               IndicatorKind::Lyapunov}) {
      std::vector<std::uint32_t> passes;
      auto connection = connect(panel.view(), &PortraitView::frameShown, this,
                                [&] { passes.push_back(panel.view()->currentFrame()->passesDone); });
      QSignalSpy finished(panel.view(), &PortraitView::renderFinished);
      panel.setDisplay({archipelago::PortraitMode::Orbits, kind});
      QVERIFY(finished.wait(900000));
      disconnect(connection);
      QVERIFY2(passes.size() >= 2 && passes.front() == 1, qPrintable(QString::number(passes.size())));
      const auto* frame = panel.view()->currentFrame();
      QVERIFY(frame->indicator && frame->final);
      // The colour bar has a title naming the quantity.
      const QwtPlot* plot = panel.view()->findChild<QwtPlot*>();
      QVERIFY(plot->axisEnabled(QwtPlot::yRight));
      QVERIFY(!plot->axisTitle(QwtPlot::yRight).text().isEmpty());
      // The raster shown is core's for the same request, pixel for pixel.
      archipelago::IndicatorRequest request = *frame->indicatorRequest;
      request.measure.kernel = nullptr;
      const archipelago::IndicatorResult direct = archipelago::computeIndicatorMap(request);
      QCOMPARE(direct.raster.values.size(), frame->indicator->values.size());
      for (std::size_t i = 0; i < direct.raster.values.size(); i += 7) {
        const double a = direct.raster.values[i], b = frame->indicator->values[i];
        QVERIFY2((std::isnan(a) && std::isnan(b)) || a == b, qPrintable(QString::number(i)));
      }
      const QString npy = dir.filePath(QStringLiteral("%1.npy").arg(QString::fromLatin1(toString(kind).data())));
      QVERIFY(panel.view()->exportNpy(npy));
      QVERIFY(QFileInfo(npy).size() > 128);
      QVERIFY(QFileInfo::exists(npy.left(npy.size() - 4) + QStringLiteral(".json")));
    }
  }

  // The rotation-profile tool: a line dragged on the portrait, the profile of the CLI's `rotation --line`.
  void rotationProfileToolGivesTheClisProfile() {
    PortraitPanel panel;
    panel.resize(800, 500);
    panel.show();
    QVERIFY(QTest::qWaitForWindowExposed(&panel));
    archipelago::ui::RotationProfilePanel& profile = *panel.profilePanel();
    panel.profileToolAction()->trigger();
    QVERIFY(profile.toolActive());
    QVERIFY(panel.view()->lineTool());
    // A drag on the canvas draws the line (not a zoom) and starts the profile.
    QWidget* canvas = panel.view()->canvas();
    QSignalSpy ready(&profile, &archipelago::ui::RotationProfilePanel::profileReady);
    const QPoint a = canvas->rect().center() - QPoint(canvas->width() / 4, 0), b = canvas->rect().center();
    QTest::mousePress(canvas, Qt::LeftButton, Qt::NoModifier, a);
    QTest::mouseMove(canvas, b);
    QTest::mouseRelease(canvas, Qt::LeftButton, Qt::NoModifier, b);
    QVERIFY(panel.controller()->viewport() == archipelago::Viewport());
    QVERIFY(ready.wait(900000));
    QVERIFY(profile.currentProfile() != nullptr);
    // The same line at 40 points through both front ends: the same table.
    const archipelago::PhysicalPoint from{-0.45L, 0.0L}, to{-0.1L, 0.0L};
    profile.profile(from, to, 40);
    QVERIFY(ready.wait(900000));
    QTemporaryDir dir;
    const QString gui = dir.filePath(QStringLiteral("gui.csv")), cliCsv = dir.filePath(QStringLiteral("cli.csv"));
    QVERIFY(profile.exportCsv(gui));
    QVERIFY(!cli({QStringLiteral("rotation"), QStringLiteral("--K"), QStringLiteral("0.1"), QStringLiteral("--line=-0.45,0:-0.1,0"),
                  QStringLiteral("--points"), QStringLiteral("40"), QStringLiteral("--csv"), cliCsv, QStringLiteral("--quiet")})
                 .isNull());
    const auto rows = [](const QString& path) {
      QFile f(path);
      f.open(QIODevice::ReadOnly);
      QStringList lines;
      for (const QByteArray& l : f.readAll().split('\n'))
        if (!l.startsWith('#') && !l.isEmpty()) lines << QString::fromUtf8(l);
      return lines;
    };
    const QStringList g = rows(gui), c = rows(cliCsv);
    QCOMPARE(g.size(), 41);
    QCOMPARE(g, c);
    QVERIFY(profile.exportPng(dir.filePath(QStringLiteral("profile.png"))));
    // Issue 54: the PNG carries what it shows, the map and the line measured (it carried only the version and commit).
    QFile png(dir.filePath(QStringLiteral("profile.png")));
    QVERIFY(png.open(QIODevice::ReadOnly));
    const QByteArray bytes = png.readAll();
    std::map<std::string, std::string> text;
    for (const auto& [k, v] : archipelago::io::readPngText(std::vector<std::uint8_t>(bytes.begin(), bytes.end()))) text[k] = v;
    QCOMPARE(QString::fromStdString(text["K"]), QStringLiteral("0.1"));
    QCOMPARE(QString::fromStdString(text["From"]), QStringLiteral("-0.45,0"));
    QCOMPARE(QString::fromStdString(text["To"]), QStringLiteral("-0.1,0"));
    QCOMPARE(QString::fromStdString(text["Points"]), QStringLiteral("40"));
  }
};

ARCHIPELAGO_GUI_TEST_MAIN(TestInstruments)
#include "test_instruments.moc"
