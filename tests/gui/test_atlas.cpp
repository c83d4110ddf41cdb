// Issue 38, deliverable 3: the Atlas page beside the portrait.  The atlas of K = 0.1 is computed in the background and
// the tree fills as core measures each island (the centre, then the chains about it: the paper's chain of six, 1/6
// about the centre, with core's numbers); a click on an island zooms the portrait to it and draws its boundary circle,
// its chain and its partner's manifolds; Stop keeps what is finished; the exports are core's text; a session keeps
// the atlas and gives back the same tree.
#include <algorithm>
#include <QCheckBox>
#include <QFile>
#include <QJsonArray>
#include <QJsonDocument>
#include <QJsonObject>
#include <QPushButton>
#include <QSignalSpy>
#include <QSpinBox>
#include <QTabWidget>
#include <QTemporaryDir>
#include <QTreeWidget>
#include <QTreeWidgetItemIterator>
#include <QtTest>

#include <cmath>
#include <memory>

#include "GuiTestSupport.hpp"
#include "core/atlas/AtlasExport.hpp"
#include "core/portrait/MapOverlays.hpp"
#include "core/session/SessionFile.hpp"
#include "ui/portrait/AtlasPanel.hpp"
#include "ui/portrait/PortraitController.hpp"
#include "ui/portrait/PortraitLayers.hpp"
#include "ui/portrait/PortraitPanel.hpp"
#include "ui/portrait/PortraitView.hpp"
#include "ui/window/MainWindow.hpp"
#include "ui/window/SessionController.hpp"

using archipelago::Atlas;
using archipelago::AtlasNode;
using archipelago::AtlasRequest;
using archipelago::ui::AtlasPanel;
using archipelago::ui::MainWindow;
using archipelago::ui::PortraitLayer;

namespace {

/// The hang bound of every wait, not a speed claim: a depth-1 atlas takes about a minute on two quiet cores in a release
/// build, and 435 s beside two other test runs (load ~5) once a thin island's circles were sought on its frame's rays
/// too, which crossed the 300 s this bound was.
constexpr int kWait = 1800000;

/// The request of the core test (tests/core/atlas/test_atlas.cpp): K = 0.1, depth 1, periods ≤ 200, 1000 points a side.
AtlasRequest depthOne(const AtlasPanel& panel) {
  AtlasRequest r = panel.request();
  r.depth = 1;
  r.maxPeriod = 200;
  r.scanSteps = 0;
  return r;
}

/// The index of the chain p/q about `parent`, or −1.
int chainOf(const Atlas& a, int parent, std::int64_t p, std::int64_t q) {
  for (std::size_t i = 0; i < a.nodes.size(); ++i) {
    const AtlasNode& n = a.nodes[i];
    if (n.parent == parent && n.aboutParent && n.aboutParent->p == p && n.aboutParent->q == q) return static_cast<int>(i);
  }
  return -1;
}

int rows(const QTreeWidget& tree) {
  int n = 0;
  for (QTreeWidgetItemIterator it(const_cast<QTreeWidget*>(&tree)); *it; ++it) ++n;
  return n;
}

/// Every row's texts, in the tree's order.
QStringList treeTexts(const QTreeWidget& tree) {
  QStringList out;
  for (QTreeWidgetItemIterator it(const_cast<QTreeWidget*>(&tree)); *it; ++it) {
    QStringList row;
    for (int c = 0; c < tree.columnCount(); ++c) row << (*it)->text(c);
    out << row.join(QStringLiteral(" | "));
  }
  return out;
}

QByteArray fileBytes(const QString& path) {
  QFile f(path);
  return f.open(QIODevice::ReadOnly) ? f.readAll() : QByteArray();
}

void clickRow(AtlasPanel& panel, int index) {
  QTreeWidgetItem* item = panel.item(index);
  QVERIFY(item);
  panel.tree()->scrollToItem(item);
  const QRect rect = panel.tree()->visualItemRect(item);
  QVERIFY(!rect.isEmpty());
  // Within the viewport: the row's columns may reach beyond it (the tree scrolls sideways in the side column).
  const QPoint at(std::min(rect.center().x(), panel.tree()->viewport()->width() - 8), rect.center().y());
  QTest::mouseClick(panel.tree()->viewport(), Qt::LeftButton, {}, at);
}

bool inside(const archipelago::PhysicalRect& r, double x, double y) { return x >= r.x0 && x <= r.x1 && y >= r.y0 && y <= r.y1; }

}  // namespace

class TestAtlas : public QObject {
  Q_OBJECT
 private:
  std::unique_ptr<MainWindow> w_;
  AtlasPanel* panel_ = nullptr;
  QTemporaryDir dir_;

 private Q_SLOTS:
  void initTestCase() {
    w_ = std::make_unique<MainWindow>();
    w_->setConfirmations(false);
    w_->resize(1280, 770);
    w_->show();
    QVERIFY(QTest::qWaitForWindowExposed(w_.get()));
    w_->tabs()->setCurrentWidget(w_->portraitPanel());
    panel_ = w_->portraitPanel()->atlasPanel();
    QVERIFY(panel_);
    w_->portraitPanel()->sidePages()->setCurrentWidget(panel_);
    QCOMPARE(w_->portraitPanel()->sidePages()->tabText(w_->portraitPanel()->sidePages()->currentIndex()),
             QStringLiteral("Atlas"));
  }

  // The page fits the window at 1280×800 (its minimum neither widens nor heightens the window).
  void thePageFitsTheWindow() {
    QVERIFY2(w_->minimumSizeHint().width() <= 1024, qPrintable(QString::number(w_->minimumSizeHint().width())));
    QVERIFY2(w_->minimumSizeHint().height() <= 700, qPrintable(QString::number(w_->minimumSizeHint().height())));
    QVERIFY(panel_->computeButton()->isEnabled());
    QVERIFY(!panel_->stopButton()->isEnabled());
    QVERIFY(panel_->depthBox()->maximum() <= archipelago::kMaxAtlasDepth);
  }

  // Issue 50: the page asks for the cantori as the CLI's --cantori does (core's default, off: a few seconds each).
  void theCantoriAreAskedForByTheirBox() {
    QVERIFY(panel_->cantoriBox() != nullptr);
    QCOMPARE(panel_->cantoriBox()->isChecked(), archipelago::AtlasRequest{}.cantori);
    panel_->cantoriBox()->setChecked(true);
    QVERIFY(panel_->request().cantori);
    panel_->cantoriBox()->setChecked(false);
    QVERIFY(!panel_->request().cantori);
  }

  // The tree fills as core measures the islands (the centre first, its chains listed before they are measured), and
  // shows core's numbers: the centre, and the chain of six at 1/6 about it.
  void computeFillsTheTreeWithCoresNumbers() {
    int partialRows = 0;
    const auto connection = connect(panel_, &AtlasPanel::atlasChanged, this, [&] {
      if (panel_->busy()) partialRows = std::max(partialRows, rows(*panel_->tree()));
    });
    QVERIFY(panel_->compute(depthOne(*panel_)));
    QVERIFY(panel_->busy());
    QVERIFY(!panel_->computeButton()->isEnabled());
    QVERIFY(panel_->stopButton()->isEnabled());
    QTRY_VERIFY_WITH_TIMEOUT(!panel_->busy(), kWait);
    disconnect(connection);
    const std::shared_ptr<const Atlas> atlas = panel_->atlas();
    QVERIFY(atlas);
    QVERIFY(!atlas->cancelled);
    QVERIFY2(partialRows > 1, "the tree listed the centre's chains while the computation went on");
    QVERIFY(panel_->progressText().contains(QStringLiteral("islands in")));

    QCOMPARE(rows(*panel_->tree()), static_cast<int>(atlas->nodes.size()));
    QCOMPARE(panel_->tree()->topLevelItemCount(), 1);
    QCOMPARE(panel_->item(0)->text(AtlasPanel::island), QStringLiteral("centre"));
    QCOMPARE(panel_->item(0)->childCount(), static_cast<int>(atlas->nodes[0].children.size()));
    const int six = chainOf(*atlas, 0, 1, 6);
    QVERIFY2(six > 0, "the chain of six about the centre");

    // The numbers of the rows are those of core's JSON of the same atlas.
    const QJsonObject json = QJsonDocument::fromJson(QByteArray::fromStdString(archipelago::atlasJson(*atlas))).object();
    const QJsonArray nodes = json[QStringLiteral("nodes")].toArray();
    QCOMPARE(static_cast<std::size_t>(nodes.size()), atlas->nodes.size());
    for (const int i : {0, six}) {
      const QJsonObject n = nodes[i].toObject();
      const QTreeWidgetItem* row = panel_->item(i);
      QCOMPARE(row->text(AtlasPanel::island), n[QStringLiteral("path")].toString());
      QCOMPARE(row->text(AtlasPanel::period), QString::number(static_cast<qint64>(n[QStringLiteral("period")].toDouble())));
      QVERIFY(n[QStringLiteral("boundary")].toObject()[QStringLiteral("found")].toBool());
      QCOMPARE(row->text(AtlasPanel::area),
               QStringLiteral("%1 ± %2")
                   .arg(QString::number(n[QStringLiteral("area")].toDouble(), 'g', 4),
                        QString::number(n[QStringLiteral("area_error")].toDouble(), 'g', 1)));
      const QJsonObject flux = n[QStringLiteral("flux")].toObject();
      if (flux[QStringLiteral("found")].toBool()) {
        QCOMPARE(row->text(AtlasPanel::flux), QString::number(flux[QStringLiteral("flux_per_step")].toDouble(), 'g', 4));
        QCOMPARE(row->text(AtlasPanel::layer), QString::number(flux[QStringLiteral("layer_area")].toDouble(), 'g', 4));
        const double residence = flux[QStringLiteral("residence")].toDouble();
        QCOMPARE(row->text(AtlasPanel::residence), QString::number(residence, 'f', std::fabs(residence) < 100 ? 1 : 0));
      }
    }
    QCOMPARE(panel_->item(six)->text(AtlasPanel::island), QStringLiteral("6"));
    QCOMPARE(panel_->item(six)->text(AtlasPanel::period), QStringLiteral("6"));
    QCOMPARE(panel_->item(six)->text(AtlasPanel::rotation), QStringLiteral("1/6"));
    QCOMPARE(nodes[six].toObject()[QStringLiteral("about_parent")].toString(), QStringLiteral("1/6"));
    // The central island's area is the paper's (docs/atlas.md: 0.2392 with 1000 points a side).
    QVERIFY(std::fabs(static_cast<double>(atlas->nodes[0].area) - 0.2392) < 2e-3);
  }

  // A click on the six's row zooms the portrait to that island (its centre inside a view smaller than the box) and
  // draws its boundary circle, its chain of six and its partner's manifolds; the centre's row shows the whole
  // central island (every point of its boundary circle in the view).
  void aClickZoomsToTheIslandAndDrawsIt() {
    const std::shared_ptr<const Atlas> atlas = panel_->atlas();
    QVERIFY(atlas);
    auto* c = w_->portraitPanel()->controller();
    const double box = c->map().width();
    const int six = chainOf(*atlas, 0, 1, 6);
    QVERIFY(six > 0);
    const AtlasNode& node = atlas->nodes[static_cast<std::size_t>(six)];
    const archipelago::Viewport before = c->viewport();
    clickRow(*panel_, six);
    QVERIFY(panel_->detailsText().contains(QStringLiteral("Island 6")));
    QTRY_VERIFY_WITH_TIMEOUT(c->atlasIslandSettled() && c->atlasIsland(), kWait);
    QVERIFY2(c->atlasIsland()->error.isEmpty(), qPrintable(c->atlasIsland()->error));
    QVERIFY(!(c->viewport() == before));
    const archipelago::PhysicalRect view = c->viewport().physical(c->map());
    QVERIFY(inside(view, static_cast<double>(node.centre.x), static_cast<double>(node.centre.y)));
    QVERIFY(static_cast<double>(view.x1 - view.x0) < box / 4);
    QVERIFY(static_cast<double>(view.y1 - view.y0) < box / 4);
    QCOMPARE(w_->portraitPanel()->view()->layerItems(PortraitLayer::atlasIsland).size(), std::size_t{1});
    QVERIFY(c->atlasIsland()->boundary.size() >= 6 * 2000);
    QCOMPARE(w_->portraitPanel()->view()->layerItems(PortraitLayer::periodicOrbits).size(), std::size_t{1});
    QCOMPARE(c->sessionState().periodic.front().points.size(), std::size_t{6});
    // The island shown whole: its part of the boundary orbit (the points nearer its centre than any other island's).
    int own = 0;
    for (const QPointF& p : c->atlasIsland()->boundary) {
      const auto nearest = c->atlasIsland()->chain->nearestIndex({p.x(), p.y()});
      const auto& z = c->atlasIsland()->chain->points[nearest];
      if (std::hypot(static_cast<double>(z.x - node.centre.x), static_cast<double>(z.y - node.centre.y)) > 1e-9) continue;
      ++own;
      QVERIFY2(inside(view, p.x(), p.y()), qPrintable(QStringLiteral("(%1, %2)").arg(p.x()).arg(p.y())));
    }
    QVERIFY(own > 1000);
    if (node.flux.partner) {
      QVERIFY(c->manifoldsShown());
      QVERIFY(c->manifoldOrbit().has_value());
      QCOMPARE(c->manifoldOrbit()->period, 6);
    }

    clickRow(*panel_, 0);
    QTRY_VERIFY_WITH_TIMEOUT(c->atlasIslandSettled() && c->atlasIsland() && c->atlasIsland()->chain &&
                                 c->atlasIsland()->chain->period == 1,
                             kWait);
    const archipelago::PhysicalRect centreView = c->viewport().physical(c->map());
    QVERIFY(static_cast<double>(centreView.x1 - centreView.x0) < box);
    QVERIFY(!c->atlasIsland()->boundary.empty());
    for (const QPointF& p : c->atlasIsland()->boundary)
      QVERIFY2(inside(centreView, p.x(), p.y()), qPrintable(QStringLiteral("(%1, %2)").arg(p.x()).arg(p.y())));
    QVERIFY(c->manifoldsShown());
    QVERIFY(!c->manifoldOrbit().has_value());  // the fixed point (√K, 0)'s loop
  }

  // The boundary point core keeps may lie on another island of the chain than the node's centre (6 > 138's at K = 0.1,
  // depth 2): the view is still of the island about the centre, whole.
  void theViewIsOfTheIslandAboutTheCentre() {
    const std::shared_ptr<const Atlas> computed = panel_->atlas();
    QVERIFY(computed);
    Atlas moved = *computed;
    const int six = chainOf(moved, 0, 1, 6);
    AtlasNode& node = moved.nodes[static_cast<std::size_t>(six)];
    auto* c = w_->portraitPanel()->controller();
    node.boundaryPoint = archipelago::traceOrbit(c->map(), node.boundaryPoint.x, node.boundaryPoint.y, 2, false).at(1);
    QVERIFY(std::hypot(static_cast<double>(node.boundaryPoint.x - node.centre.x),
                       static_cast<double>(node.boundaryPoint.y - node.centre.y)) > 0.1);  // on the next island
    panel_->restoreAtlas(moved);
    QVERIFY(panel_->showIsland(six));
    QTRY_VERIFY_WITH_TIMEOUT(c->atlasIslandSettled() && c->atlasIsland() && c->atlasIsland()->island, kWait);
    const archipelago::PhysicalRect view = c->viewport().physical(c->map());
    QVERIFY(inside(view, static_cast<double>(node.centre.x), static_cast<double>(node.centre.y)));
    QVERIFY(!inside(view, static_cast<double>(node.boundaryPoint.x), static_cast<double>(node.boundaryPoint.y)));
    QVERIFY(static_cast<double>(view.x1 - view.x0) < c->map().width() / 4);
    panel_->restoreAtlas(*computed);
  }

  // The exports are core's text of the atlas shown (writeAtlasJson, writeAtlasCsv).
  void theExportsAreCoresText() {
    const std::shared_ptr<const Atlas> atlas = panel_->atlas();
    QVERIFY(atlas);
    const QString json = dir_.filePath(QStringLiteral("atlas.json"));
    const QString csv = dir_.filePath(QStringLiteral("atlas.csv"));
    QString error;
    QVERIFY2(panel_->exportJson(json, &error), qPrintable(error));
    QVERIFY2(panel_->exportCsv(csv, &error), qPrintable(error));
    QCOMPARE(fileBytes(json), QByteArray::fromStdString(archipelago::atlasJson(*atlas)));
    QCOMPARE(fileBytes(csv), QByteArray::fromStdString(archipelago::atlasCsv(*atlas)));
    QVERIFY(!panel_->exportJson(dir_.filePath(QStringLiteral("no/such/folder/atlas.json")), &error));
    QVERIFY(!error.isEmpty());
  }

  // A session keeps the atlas (core's JSON, read back, not recomputed) and gives back the same tree; opening a
  // session without one clears the page.
  void aSessionGivesBackTheSameTree() {
    const QString path = dir_.filePath(QStringLiteral("atlas.archipelago"));
    QString error;
    QVERIFY2(w_->saveSession(path, &error), qPrintable(error));
    const archipelago::Session saved = archipelago::loadSession(path.toStdString());
    QVERIFY(saved.atlas.has_value());
    QCOMPARE(saved.atlas->nodes.size(), panel_->atlas()->nodes.size());
    const QStringList tree = treeTexts(*panel_->tree());

    MainWindow w;
    w.setConfirmations(false);
    w.resize(1280, 770);
    w.show();
    QSignalSpy restored(w.sessions(), &archipelago::ui::SessionController::restored);
    QVERIFY2(w.openSession(path, &error), qPrintable(error));
    QVERIFY(restored.count() > 0 || restored.wait(kWait));
    AtlasPanel* back = w.portraitPanel()->atlasPanel();
    QVERIFY(back->atlas());
    QVERIFY(!back->busy());
    QCOMPARE(treeTexts(*back->tree()), tree);
    QCOMPARE(archipelago::atlasJson(*back->atlas()), archipelago::atlasJson(*saved.atlas));
    QVERIFY(back->progressText().startsWith(QStringLiteral("From the session")));
    // Its islands are drawn as those of a computed atlas (the orbits found again from the points the JSON keeps).
    const int six = chainOf(*back->atlas(), 0, 1, 6);
    QVERIFY(back->showIsland(six));
    auto* c = w.portraitPanel()->controller();
    QTRY_VERIFY_WITH_TIMEOUT(c->atlasIslandSettled() && c->atlasIsland(), kWait);
    QVERIFY2(c->atlasIsland()->error.isEmpty(), qPrintable(c->atlasIsland()->error));
    QVERIFY(c->atlasIsland()->chain.has_value());
    QCOMPARE(c->atlasIsland()->chain->points.size(), std::size_t{6});

    // A session without an atlas clears the page.
    archipelago::Session none = saved;
    none.atlas.reset();
    const QString nonePath = dir_.filePath(QStringLiteral("none.archipelago"));
    archipelago::saveSession(nonePath.toStdString(), none);
    QVERIFY2(w.openSession(nonePath, &error), qPrintable(error));
    QVERIFY(!back->atlas());
    QCOMPARE(back->tree()->topLevelItemCount(), 0);
  }

  // An atlas of another map stays listed when K changes (no work lost), says whose it is, and draws nothing.
  void anAtlasOfAnotherMapIsKeptButNotDrawn() {
    auto* c = w_->portraitPanel()->controller();
    const archipelago::MapParameters k01 = c->map();
    archipelago::MapParameters other = k01;
    other.K = 0.11;
    QVERIFY(c->setMap(other, c->Xr()));
    QVERIFY(panel_->atlas());
    // Both K as they were typed (not 0.10000000000000001 and 0.11000000000000000).
    QVERIFY2(panel_->progressText().contains(QStringLiteral("This atlas is of K = 0.1; the portrait shows K = 0.11:")),
             qPrintable(panel_->progressText()));
    QVERIFY(!panel_->showIsland(0));
    QVERIFY(c->setMap(k01, c->Xr()));
    QVERIFY(!panel_->progressText().contains(QStringLiteral("This atlas is of")));
    QVERIFY(panel_->showIsland(0));
  }

  // Issue 50: a box that does not hold the central island is refused before anything is cleared (core's
  // atlasRequestError: at K = 0.22 the default box cuts the island's circle), and the atlas shown stays.
  void aBoxThatCutsTheIslandIsRefusedAndTheAtlasShownStays() {
    QVERIFY(panel_->atlas());
    const std::size_t shown = panel_->atlas()->nodes.size();
    const int listed = rows(*panel_->tree());
    AtlasRequest r = depthOne(*panel_);
    r.map.K = 0.22;
    QSignalSpy said(panel_, &AtlasPanel::statusMessage);
    QVERIFY(!panel_->compute(r));
    QVERIFY(!panel_->busy());
    QCOMPARE(said.count(), 1);
    const QString message = said.at(0).at(0).toString();
    QVERIFY2(message.startsWith(QStringLiteral("Atlas: the box does not hold the central island at K = 0.22")) &&
                 message.contains(QStringLiteral("The K scan's box")),
             qPrintable(message));
    QVERIFY(panel_->atlas() && panel_->atlas()->nodes.size() == shown);
    QCOMPARE(rows(*panel_->tree()), listed);
    // The whole reason on the page (the status line cuts it short at 1280 wide), above what the page said before,
    // until the map changes.
    QVERIFY2(panel_->progressText().startsWith(QStringLiteral("Not computed: ") + message.mid(7)) &&
                 panel_->progressText().contains(QStringLiteral("islands in")),
             qPrintable(panel_->progressText()));
    auto* c = w_->portraitPanel()->controller();
    const archipelago::MapParameters k01 = c->map();
    archipelago::MapParameters other = k01;
    other.K = 0.11;
    QVERIFY(c->setMap(other, c->Xr()));
    QVERIFY(c->setMap(k01, c->Xr()));
    QVERIFY2(!panel_->progressText().contains(QStringLiteral("Not computed")), qPrintable(panel_->progressText()));
  }

  // Stop during the computation keeps the islands finished: a partial tree, marked stopped.
  void aStopKeepsAPartialTree() {
    AtlasRequest r = depthOne(*panel_);
    r.depth = 2;
    r.maxPeriod = 1000;  // minutes: the stop surely comes first
    QVERIFY(panel_->compute(r));
    QCOMPARE(panel_->tree()->topLevelItemCount(), 0);  // the previous atlas is replaced
    QTRY_VERIFY_WITH_TIMEOUT(panel_->atlas() && panel_->atlas()->nodes.size() > 1, kWait);
    QVERIFY(panel_->busy());
    panel_->stopButton()->click();
    QTRY_VERIFY_WITH_TIMEOUT(!panel_->busy(), kWait);
    const std::shared_ptr<const Atlas> atlas = panel_->atlas();
    QVERIFY(atlas);
    QVERIFY(atlas->cancelled);
    QCOMPARE(rows(*panel_->tree()), static_cast<int>(atlas->nodes.size()));
    QVERIFY(atlas->nodes[0].boundaryFound);
    QVERIFY(panel_->item(0)->text(AtlasPanel::note) != QStringLiteral("not measured (stopped)"));
    bool unmeasured = false;
    for (int i = 1; i < static_cast<int>(atlas->nodes.size()); ++i)
      unmeasured = unmeasured || panel_->item(i)->text(AtlasPanel::note) == QStringLiteral("not measured (stopped)");
    QVERIFY(unmeasured);
    QVERIFY(panel_->progressText().startsWith(QStringLiteral("Stopped")));
    // What a session keeps of it reads back the same.
    const auto kept = panel_->sessionAtlas();
    QVERIFY(kept && kept->cancelled);
    const std::string text = archipelago::atlasJson(archipelago::atlasFromJson(archipelago::atlasJson(*kept)));
    QCOMPARE(archipelago::atlasJson(archipelago::atlasFromJson(text)), text);
  }

  void cleanupTestCase() { w_.reset(); }
};

ARCHIPELAGO_GUI_TEST_MAIN(TestAtlas)
#include "test_atlas.moc"
