// Issue 28, deliverable 5 (the GUI of the manifolds and the flux): the manifolds layer of the hyperbolic fixed point,
// refined in the visible view when zooming, stable and unstable in their colours, the turnstile's lobes shaded with
// their area; the "Manifolds and flux" page's numbers are the CLI's (`archipelago-cli flux --json`); Tools ▸ Find
// Periodic Orbit offers the hyperbolic partner of an elliptic chain and its manifolds.
#include <QAction>
#include <QFile>
#include <QJsonDocument>
#include <QJsonObject>
#include <QProcess>
#include <QSignalSpy>
#include <QTemporaryDir>
#include <QtTest>
#include <QPushButton>
#include <set>
#include "core/manifolds/ManifoldExport.hpp"

#include <cmath>

#include "GuiTestSupport.hpp"
#include "ui/periodic/PeriodicOrbitDialog.hpp"
#include "ui/portrait/ManifoldsPanel.hpp"
#include "ui/portrait/PortraitController.hpp"
#include "ui/portrait/PortraitLayers.hpp"
#include "ui/portrait/PortraitPanel.hpp"
#include "ui/portrait/PortraitView.hpp"

#ifndef ARCHIPELAGO_CLI
#error "ARCHIPELAGO_CLI must name the archipelago-cli executable (tests/gui/CMakeLists.txt)"
#endif

using archipelago::ui::PortraitController;
using archipelago::ui::PortraitLayer;
using archipelago::ui::PortraitPanel;
using archipelago::ui::PointsItem;

namespace {
QJsonObject cliJson(const QStringList& args) {
  QProcess p;
  p.start(QStringLiteral(ARCHIPELAGO_CLI), args);
  if (!p.waitForFinished(120000) || p.exitCode() != 0) return {};
  return QJsonDocument::fromJson(p.readAllStandardOutput()).object();
}

/// The largest distance between consecutive points of the manifolds inside `r`.
double largestStepInside(const archipelago::ui::ManifoldsResult& m, const archipelago::PhysicalRect& r) {
  double largest = 0;
  for (const auto* list : {&m.unstable, &m.stable})
    for (const archipelago::ManifoldCurve& c : *list)
      for (const archipelago::ManifoldPiece& piece : c.pieces)
        for (std::size_t i = 1; i < piece.points.size(); ++i) {
          const auto& a = piece.points[i - 1];
          const auto& b = piece.points[i];
          const auto inside = [&](const archipelago::PhysicalPoint& p) {
            return p.x >= r.x0 && p.x <= r.x1 && p.y >= r.y0 && p.y <= r.y1;
          };
          if (inside(a) && inside(b))
            largest = std::max(largest, static_cast<double>(std::hypot(b.x - a.x, b.y - a.y)));
        }
  return largest;
}
}  // namespace

class TestManifolds : public QObject {
  Q_OBJECT
 private Q_SLOTS:
  // The flux shown is the CLI's: the same lobe area by both methods, the same zone, the same homoclinic points.
  void theGuiAndTheCliGiveTheSameFlux() {
    PortraitPanel panel;
    panel.resize(800, 500);
    panel.show();
    QVERIFY(QTest::qWaitForWindowExposed(&panel));
    PortraitController& c = *panel.controller();
    panel.manifoldsAction()->trigger();
    QVERIFY(c.manifoldsShown());
    QTRY_VERIFY_WITH_TIMEOUT(c.manifoldsSettled() && c.flux() && c.manifolds(), 900000);
    QVERIFY2(c.flux()->flux.has_value(), qPrintable(c.flux()->error));
    const archipelago::TurnstileFlux& f = *c.flux()->flux;
    const QJsonObject json = cliJson({QStringLiteral("flux"), QStringLiteral("--K"), QStringLiteral("0.1"), QStringLiteral("--json")});
    QVERIFY(!json.isEmpty());
    const QJsonObject lobe = json[QStringLiteral("lobe_area")].toObject();
    QCOMPARE(QString::fromStdString(archipelago::quadText(f.lobeAction < 0 ? -f.lobeAction : f.lobeAction)),
             lobe[QStringLiteral("action_text")].toString());
    QCOMPARE(static_cast<double>(std::fabs(f.lobePolygon.area)), lobe[QStringLiteral("polygon")].toDouble());
    // The page shows these numbers, and exports the CLI's JSON (but for the time it took).
    const double shown = panel.manifoldsPanel()->displayedLobeArea();
    QCOMPARE(shown, lobe[QStringLiteral("action")].toDouble());
    QVERIFY(panel.manifoldsPanel()->numbersText().contains(lobe[QStringLiteral("action_text")].toString().left(18)));
    QTemporaryDir dir;
    const QString path = dir.filePath(QStringLiteral("flux.json"));
    QVERIFY(panel.manifoldsPanel()->exportJson(path));
    QFile file(path);
    QVERIFY(file.open(QIODevice::ReadOnly));
    QJsonObject exported = QJsonDocument::fromJson(file.readAll()).object();
    QJsonObject expected = json;
    exported.remove(QStringLiteral("seconds"));
    expected.remove(QStringLiteral("seconds"));
    QCOMPARE(exported, expected);
    // Drawn: curves in two colours (unstable red, stable blue) and the two lobes, one labelled with its area.
    const auto& curves = panel.view()->layerItems(PortraitLayer::manifolds);
    QVERIFY(curves.size() >= 2);
    std::set<QRgb> colours;
    for (const QwtPlotItem* i : curves) colours.insert(static_cast<const PointsItem*>(i)->colour().rgb());
    QCOMPARE(colours.size(), std::size_t{2});
    QCOMPARE(panel.view()->layerItems(PortraitLayer::lobes).size(), std::size_t{2});
  }

  // Zooming refines the manifolds in the visible view: the steps between points inside a small view are a few
  // pixels of it, where the whole-box curves jumped across it.
  void manifoldsAreRefinedInTheVisibleViewWhenZooming() {
    PortraitPanel panel;
    panel.resize(800, 500);
    panel.show();
    QVERIFY(QTest::qWaitForWindowExposed(&panel));
    PortraitController& c = *panel.controller();
    c.setManifoldsShown(true);
    QTRY_VERIFY_WITH_TIMEOUT(c.manifoldsSettled() && c.manifolds(), 900000);
    const auto whole = c.manifolds();
    // A 0.002-wide view at the first homoclinic point, in the tangle.
    const archipelago::PhysicalRect view{-0.682L, -0.680L, -0.3648L, -0.3628L};
    c.setViewport(archipelago::Viewport::fromPhysical(c.map(), view));
    QTRY_VERIFY_WITH_TIMEOUT(c.manifoldsSettled() && c.manifolds() != whole, 900000);
    const double refined = largestStepInside(*c.manifolds(), view);
    QVERIFY(refined > 0);
    QVERIFY2(refined <= 0.002 / 100, qPrintable(QString::number(refined)));
    QVERIFY(largestStepInside(*whole, view) > 2 * refined);
  }

  // Tools ▸ Find Periodic Orbit offers the hyperbolic partner of an elliptic chain, and draws its manifolds.
  void theDialogOffersTheHyperbolicPartnerAndItsManifolds() {
    archipelago::ui::PeriodicOrbitDialog dialog;
    dialog.setK(0.1);
    dialog.setPeriod(6);
    dialog.setNear(0.0509, 0.0974);
    QSignalSpy done(&dialog, &archipelago::ui::PeriodicOrbitDialog::searchFinished);
    dialog.find();
    QVERIFY(done.wait(900000));
    QVERIFY(done.last().first().toBool());
    QVERIFY(dialog.orbit()->classification().stable());
    dialog.findPartner();
    QVERIFY(done.wait(900000));
    QVERIFY(done.last().first().toBool());
    const archipelago::PeriodicOrbit partner = *dialog.orbit();
    QCOMPARE(partner.period, 6);
    QVERIFY(!partner.classification().stable());
    QSignalSpy manifolds(&dialog, &archipelago::ui::PeriodicOrbitDialog::manifoldsRequested);
    PortraitPanel panel;
    connect(&dialog, &archipelago::ui::PeriodicOrbitDialog::manifoldsRequested, panel.controller(),
            &PortraitController::setManifoldOrbit);
    QPushButton* button = nullptr;
    for (QPushButton* b : dialog.findChildren<QPushButton*>())
      if (b->text() == QStringLiteral("&Manifolds")) button = b;
    QVERIFY(button && button->isEnabled());
    button->click();
    QCOMPARE(manifolds.count(), 1);
    QVERIFY(panel.controller()->manifoldsShown());
    QCOMPARE(panel.controller()->manifoldOrbit()->period, 6);
    QTRY_VERIFY_WITH_TIMEOUT(panel.controller()->manifoldsSettled() && panel.controller()->flux(), 900000);
    QVERIFY2(panel.controller()->flux()->flux.has_value(), qPrintable(panel.controller()->flux()->error));
  }
};

ARCHIPELAGO_GUI_TEST_MAIN(TestManifolds)
#include "test_manifolds.moc"
