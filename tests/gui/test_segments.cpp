// The long-segment table and the periodic-orbit dialog (ui/segments, ui/periodic), on Qt's offscreen platform.

#include <QAction>
#include <QApplication>
#include <QLabel>
#include <QHeaderView>
#include <QPushButton>
#include <QScrollBar>
#include <QToolButton>
#include <QDockWidget>
#include <QSignalSpy>
#include <QTableWidget>
#include <QTableView>
#include <QTemporaryDir>
#include <qwt_plot.h>
#include <QtTest>

#include <cmath>
#include <vector>

#include "GuiTestSupport.hpp"
#include "ui/periodic/PeriodicOrbitDialog.hpp"
#include "ui/portrait/PortraitController.hpp"
#include "ui/portrait/PortraitPanel.hpp"
#include "core/runfile/RunFile.hpp"
#include "core/periodic/PeriodicOrbitFinder.hpp"
#include "ui/portrait/PortraitView.hpp"
#include "ui/segments/LongSegmentsPanel.hpp"
#include "core/run/TrappingRun.hpp"

using namespace archipelago;
using namespace archipelago::ui;

namespace {

/// A finished K = 0.1 run of 16 × 20000 blocks (5·10⁶ steps): its longest segments are 10³–10⁵ steps long.
const TrappingState& shortRun() {
  static const TrappingState state = [] {
    TrappingParameters p;
    p.M = 16;
    p.T = 20000;
    p.longestKept = 12;
    TrappingRunOptions o;
    o.threads = 1;
    return runTrapping(startTrapping(p), o);
  }();
  return state;
}

std::vector<UnitState> replayedByCore(const TrappingParameters& params, const SegmentRecord& record) {
  std::vector<UnitState> states;
  replaySegment(params, record, [&](std::uint64_t, const UnitState& z) { states.push_back(z); });
  return states;
}

}  // namespace

class TestSegments : public QObject {
  Q_OBJECT
 private Q_SLOTS:
  void tableFillsFromAFinishedRun();
  void selectingARowReplaysTheSegmentBitForBit();
  void onlyTheLatestSelectionIsShown();
  void exportsTheReplay();
  void drawsTheSegmentZoomedOnThePortrait();
  void playKeepsTheStepShownInView();
  void columnsFitTheDockAndTheHintHides();
  void periodicDialogFindsTheEllipticPeriodSixOrbit();
  void mainWindowShowsTheSegmentsOfAnOpenedRun();
};

void TestSegments::tableFillsFromAFinishedRun() {
  const TrappingState& state = shortRun();
  const auto& items = state.longest.items();
  QVERIFY(items.size() >= 10);
  LongSegmentsPanel panel;
  panel.setAutoIdentifiedRows(3);
  panel.updateSegments(state.params, state.longest);
  LongestSegmentsModel& model = *panel.model();
  QCOMPARE(model.rowCount(), static_cast<int>(items.size()));
  const QLocale locale;
  for (int row : {0, 5}) {
    const SegmentRecord& r = items[static_cast<std::size_t>(row)];
    QCOMPARE(model.index(row, LongestSegmentsModel::Length).data().toString(),
             locale.toString(static_cast<qulonglong>(r.length * state.params.q)));
    QCOMPARE(model.index(row, LongestSegmentsModel::Orbit).data().toULongLong(), static_cast<qulonglong>(r.orbit));
    QCOMPARE(model.index(row, LongestSegmentsModel::StartBlock).data().toString(),
             locale.toString(static_cast<qulonglong>(r.start.block)));
    const FixedPointMap map(state.params.map);
    QCOMPARE(model.index(row, LongestSegmentsModel::StartX).data().toString().toDouble(),
             std::round(static_cast<double>(map.toPhysical(r.start.z).x) * 1e6) / 1e6);
  }
  // Longest first.
  QVERIFY(items[0].length >= items[1].length);
  // The top rows get their chains in the background; the others are not touched.
  QTRY_VERIFY_WITH_TIMEOUT(panel.idle(), 900000);
  QCoreApplication::processEvents();  // the last job's result is posted just before the thread goes idle
  for (int row = 0; row < 3; ++row) {
    const SegmentKey key = SegmentKey::of(items[static_cast<std::size_t>(row)]);
    QCOMPARE(model.chainStatus(key), LongestSegmentsModel::ChainStatus::done);
    const ChainResultPtr chain = model.chain(key);
    QVERIFY(chain);
    if (chain->chain)
      QCOMPARE(model.index(row, LongestSegmentsModel::Chain).data().toInt(), chain->chain->period);
    else
      QVERIFY(!chain->error.isEmpty());
  }
  QCOMPARE(model.chainStatus(SegmentKey::of(items[5])), LongestSegmentsModel::ChainStatus::unknown);
  // The same segments again (a live update with nothing new) keep the chains; a new run forgets them.
  panel.updateSegments(state.params, state.longest);
  QCOMPARE(model.chainStatus(SegmentKey::of(items[0])), LongestSegmentsModel::ChainStatus::done);
  TrappingParameters other = state.params;
  other.seed = 2;
  panel.setAutoIdentifiedRows(0);
  panel.updateSegments(other, state.longest);
  QCOMPARE(model.chainStatus(SegmentKey::of(items[0])), LongestSegmentsModel::ChainStatus::unknown);
}

void TestSegments::selectingARowReplaysTheSegmentBitForBit() {
  const TrappingState& state = shortRun();
  LongSegmentsPanel panel;
  panel.setAutoIdentifiedRows(0);
  panel.setMaxReplayPoints(10'000'000);  // stride 1: every step
  panel.updateSegments(state.params, state.longest);
  QSignalSpy replays(&panel, &LongSegmentsPanel::replayReady);
  QSignalSpy chains(&panel, &LongSegmentsPanel::chainReady);
  panel.selectRow(1);
  QVERIFY(replays.wait(900000));
  const SegmentReplayPtr replay = panel.currentReplay();
  QVERIFY(replay);
  const SegmentRecord& record = state.longest.items()[1];
  QCOMPARE(replay->trace.record, record);
  QCOMPARE(replay->trace.stride, std::uint64_t{1});
  const std::vector<UnitState> expected = replayedByCore(state.params, record);
  QCOMPARE(replay->trace.states.size(), expected.size());
  QVERIFY(replay->trace.states == expected);  // bit for bit, every step
  QCOMPARE(replay->trace.steps, record.length * state.params.q);
  // The view: where it spent its time holds most of the points.
  QVERIFY(replay->region.fraction >= 0.9);
  QVERIFY(replay->region.width() > 0 && replay->region.height() > 0);
  // Its chain is identified for the selected row even with no automatic rows.
  QTRY_VERIFY_WITH_TIMEOUT(panel.currentChain() != nullptr, 900000);
  QVERIFY(chains.count() >= 1);
  // Stepping moves through the exact states.
  panel.setCurrentIndex(17);
  QCOMPARE(panel.currentIndex(), std::size_t{17});
  panel.setCurrentIndex(expected.size() + 5);
  QCOMPARE(panel.currentIndex(), expected.size() - 1);
}

void TestSegments::onlyTheLatestSelectionIsShown() {
  const TrappingState& state = shortRun();
  LongSegmentsPanel panel;
  panel.setAutoIdentifiedRows(0);
  panel.updateSegments(state.params, state.longest);
  QSignalSpy replays(&panel, &LongSegmentsPanel::replayReady);
  panel.selectRow(0);
  panel.selectRow(3);
  panel.selectRow(2);
  QTRY_VERIFY_WITH_TIMEOUT(panel.idle() && replays.count() >= 1, 900000);
  QCoreApplication::processEvents();
  // Stale replays (rows 0 and 3) were cancelled or dropped: every replay shown is row 2's.
  for (const QList<QVariant>& args : replays) {
    const auto replay = args.at(0).value<SegmentReplayPtr>();
    QCOMPARE(replay->trace.record, state.longest.items()[2]);
  }
  QCOMPARE(panel.currentReplay()->trace.record, state.longest.items()[2]);
  // A live update that moves the segment keeps it selected (by segment, not by row).
  LongestSegments fewer(state.longest.capacity());
  for (std::size_t i = 2; i < state.longest.items().size(); ++i) fewer.insert(state.longest.items()[i]);
  panel.updateSegments(state.params, fewer);
  QCOMPARE(panel.selectedRow(), 0);
  QCOMPARE(replays.count(), 1);  // no second replay of the same segment
}

void TestSegments::exportsTheReplay() {
  const TrappingState& state = shortRun();
  LongSegmentsPanel panel;
  panel.setAutoIdentifiedRows(0);
  panel.setMaxReplayPoints(1000);
  panel.updateSegments(state.params, state.longest);
  QString error;
  QTemporaryDir dir;
  QVERIFY(!panel.exportCsv(dir.filePath(QStringLiteral("none.csv")), &error));
  QVERIFY(!error.isEmpty());
  QSignalSpy replays(&panel, &LongSegmentsPanel::replayReady);
  panel.selectRow(0);
  QVERIFY(replays.wait(900000));
  const SegmentTrace& trace = panel.currentReplay()->trace;
  QVERIFY(trace.stride > 1);
  QVERIFY(trace.states.size() <= 1000);
  const QString csv = dir.filePath(QStringLiteral("segment.csv"));
  QVERIFY2(panel.exportCsv(csv, &error), qPrintable(error));
  QFile file(csv);
  QVERIFY(file.open(QIODevice::ReadOnly));
  const QList<QByteArray> lines = file.readAll().trimmed().split('\n');
  QCOMPARE(lines.size(), static_cast<int>(trace.states.size()) + 1);
  QCOMPARE(lines.front(), QByteArray("step,x,y,X,Y"));
  const QString npy = dir.filePath(QStringLiteral("segment.npy"));
  QVERIFY2(panel.exportNpy(npy, &error), qPrintable(error));
  QFile array(npy);
  QVERIFY(array.open(QIODevice::ReadOnly));
  const QByteArray bytes = array.readAll();
  QVERIFY(bytes.startsWith("\x93NUMPY"));
  QVERIFY(bytes.contains(QByteArray("'shape': (") + QByteArray::number(static_cast<qulonglong>(trace.states.size())) +
                         ", 3)"));
  QVERIFY(!panel.exportCsv(QStringLiteral("/nonexistent-folder/x.csv"), &error));
}

namespace {
/// The island segment of drawsTheSegmentZoomedOnThePortrait(): it starts 0.01 from the centre of one of the
/// six islands around the central one, never reaches the randomizing zone, so lasts until the run's last block.
SegmentRecord islandSegment(const TrappingState& state) {
  const FixedPointMap map(state.params.map);
  SegmentRecord inside;
  inside.orbit = 3;
  inside.length = 2000;
  inside.start = {map.toUnit(0.0609L, 0.0974L), state.params.T - inside.length, 0};
  return inside;
}
}  // namespace

// The segment panel changes the portrait only through its controller: the controller sets the run's map
// (one mapChanged), the segment layer and the zoom; the view shows what the controller holds.
void TestSegments::drawsTheSegmentZoomedOnThePortrait() {
  const TrappingState& state = shortRun();
  PortraitPanel portrait;
  portrait.resize(600, 500);
  PortraitController& controller = *portrait.controller();
  PortraitView& view = *portrait.view();
  controller.setPointBudget(20000);  // the portrait beneath is not what is tested
  MapParameters other;
  other.K = 0.2;
  QVERIFY(controller.setMap(other, 0.02));
  const SegmentRecord inside = islandSegment(state);
  LongestSegments longest = state.longest;
  longest.insert(inside);
  LongSegmentsPanel panel;
  panel.setAutoIdentifiedRows(0);
  panel.setPortraitController(&controller);
  panel.updateSegments(state.params, longest);
  const int row = panel.model()->rowOf(SegmentKey::of(inside));
  QVERIFY(row >= 0);
  QSignalSpy replays(&panel, &LongSegmentsPanel::replayReady);
  QSignalSpy maps(&controller, &PortraitController::mapChanged);
  QSignalSpy views(&controller, &PortraitController::viewportChanged);
  panel.selectRow(row);
  QVERIFY(replays.wait(900000));
  QCOMPARE(panel.currentReplay()->trace.blocks, inside.length);
  // The portrait switched to the run's map and zoomed to where the segment spent its time.
  QCOMPARE(maps.count(), 1);
  QVERIFY(views.count() >= 2);  // the new map's whole box, then the zoom
  QVERIFY(controller.map() == state.params.map);
  QVERIFY(view.parameters() == state.params.map);
  QVERIFY(view.viewport() == controller.viewport());
  const SegmentRegion& region = panel.currentReplay()->region;
  const PhysicalRect shown = controller.viewport().physical(controller.map());
  QVERIFY(shown.x0 <= region.x0 + 1e-12L && shown.x1 >= region.x1 - 1e-12L);
  QVERIFY(shown.y0 <= region.y0 + 1e-12L && shown.y1 >= region.y1 - 1e-12L);
  QVERIFY(shown.x1 - shown.x0 < 0.8L * state.params.map.width());
  QCOMPARE(view.layerItems(PortraitLayer::segment).size(), std::size_t{1});
  QCOMPARE(view.layerItems(PortraitLayer::segmentStep).size(), std::size_t{1});
  // Once the chain is known the view can zoom to one island of it, which lies inside the segment's region.
  QTRY_VERIFY_WITH_TIMEOUT(panel.currentChain() != nullptr, 900000);
  QVERIFY(panel.currentChain()->chain.has_value());
  QCOMPARE(panel.currentChain()->chain->period, 6);
  QCOMPARE(view.layerItems(PortraitLayer::segmentChain).size(), std::size_t{1});
  panel.zoomToIsland();
  const PhysicalRect island = controller.viewport().physical(controller.map());
  QVERIFY(island.x1 - island.x0 < 0.5L * (shown.x1 - shown.x0));
  panel.zoomToSegment();
  QVERIFY(controller.viewport().physical(controller.map()).x0 == shown.x0);
  QVERIFY(view.viewport() == controller.viewport());
  // The same segment again keeps the map (no second mapChanged).
  QCOMPARE(maps.count(), 1);
  // Stepping and an orbit from the dialog draw as layers of the controller.
  panel.setCurrentIndex(panel.currentReplay()->trace.states.size() / 2);
  PeriodicOrbitSearch search;
  search.period = 6;
  search.near = {0.0509L, 0.0974L};
  controller.showPeriodicOrbit(findPeriodicOrbit(0.1L, search));
  QCOMPARE(view.layerItems(PortraitLayer::periodicOrbits).size(), std::size_t{1});
  QImage image = view.grab().toImage();
  QVERIFY(!image.isNull());
  // Clearing the panel clears its layers.
  panel.clear();
  QVERIFY(view.layerItems(PortraitLayer::segment).empty());
  QVERIFY(view.layerItems(PortraitLayer::segmentStep).empty());
}

// Finding 14: during Play the step shown left the zoomed island (the segment hops around its chain of six).
void TestSegments::playKeepsTheStepShownInView() {
  const TrappingState& state = shortRun();
  PortraitPanel portrait;
  portrait.resize(600, 500);
  PortraitController& controller = *portrait.controller();
  controller.setPointBudget(20000);
  const SegmentRecord inside = islandSegment(state);
  LongestSegments longest = state.longest;
  longest.insert(inside);
  LongSegmentsPanel panel;
  panel.setAutoIdentifiedRows(0);
  panel.setPortraitController(&controller);
  panel.updateSegments(state.params, longest);
  QSignalSpy replays(&panel, &LongSegmentsPanel::replayReady);
  panel.selectRow(panel.model()->rowOf(SegmentKey::of(inside)));
  QVERIFY(replays.wait(900000));
  QTRY_VERIFY_WITH_TIMEOUT(panel.currentChain() != nullptr && panel.currentChain()->chain.has_value(), 900000);
  panel.zoomToIsland();
  QToolButton* play = nullptr;
  for (QToolButton* b : panel.findChildren<QToolButton*>())
    if (b->text() == QStringLiteral("Play")) play = b;
  QVERIFY(play);
  int checked = 0, outside = 0;
  const auto& points = panel.currentReplay()->trace.points;
  connect(&panel, &LongSegmentsPanel::currentIndexChanged, &panel, [&](std::size_t index) {
    ++checked;
    if (!controller.shows(points[index].x, points[index].y)) ++outside;
  });
  play->click();
  QTRY_VERIFY_WITH_TIMEOUT(checked >= 12, 900000);
  play->click();  // pause
  QCOMPARE(outside, 0);
  QVERIFY(controller.viewport() == portrait.view()->viewport());
}

// Finding 14: the Start y and Chain period columns needed horizontal scrolling, and the hint stayed.
void TestSegments::columnsFitTheDockAndTheHintHides() {
  // At a desktop's usual 9-point font (Qt 6's offscreen platform has it; Qt 5's has 12 points, at which the panel's
  // width is capped so that the window fits a 1024-pixel screen, and the table scrolls: MainWindow.cpp).
  const QFont font = QApplication::font();
  QFont usual = font;
  usual.setPointSize(9);
  QApplication::setFont(usual);
  const struct Restore {
    QFont f;
    ~Restore() { QApplication::setFont(f); }
  } restore{font};
  const TrappingState& state = shortRun();
  QTemporaryDir dir;
  const QString file = dir.filePath(QStringLiteral("short.json"));
  saveRunFile(file.toStdString(), state);
  MainWindow window;
  window.setConfirmations(false);
  window.resize(1280, 760);  // a laptop screen (the offscreen platform's own screen is 800 × 600)
  window.show();
  QVERIFY(QTest::qWaitForWindowExposed(&window));
  LongSegmentsPanel& panel = *window.longSegments();
  panel.setAutoIdentifiedRows(0);
  auto* dock = qobject_cast<QDockWidget*>(panel.parentWidget());
  QVERIFY(dock);
  dock->raise();
  QLabel* hint = nullptr;
  for (QLabel* label : panel.findChildren<QLabel*>())
    if (label->text().startsWith(QStringLiteral("Run or open a run file"))) hint = label;
  QVERIFY(hint);
  QTRY_VERIFY(panel.isVisible());
  QVERIFY(hint->isVisible());
  QVERIFY(window.openRunFile(file));
  QTRY_VERIFY_WITH_TIMEOUT(panel.model()->rowCount() > 0, 900000);
  QTRY_VERIFY(!hint->isVisible());
  QTableView* table = panel.table();
  QCoreApplication::processEvents();
  QVERIFY2(!table->horizontalScrollBar()->isVisible(),
           qPrintable(QStringLiteral("table %1 wide, columns %2").arg(table->viewport()->width())
                          .arg(table->horizontalHeader()->length())));
  for (int column = 0; column < panel.model()->columnCount(); ++column)
    QVERIFY2(table->columnWidth(column) >= table->horizontalHeader()->sectionSizeHint(column) &&
                 table->columnWidth(column) >= static_cast<QAbstractItemView*>(table)->sizeHintForColumn(column),
             qPrintable(QString::number(column)));  // every column shows its text whole
}

void TestSegments::periodicDialogFindsTheEllipticPeriodSixOrbit() {
  PeriodicOrbitDialog dialog;
  dialog.setK(0.1);
  dialog.setPeriod(6);
  dialog.setNear(0.0509, 0.0974);
  dialog.setStableOnly(true);
  QSignalSpy finished(&dialog, &PeriodicOrbitDialog::searchFinished);
  QSignalSpy overlays(&dialog, &PeriodicOrbitDialog::overlayRequested);
  dialog.find();
  QVERIFY(finished.wait(20000));
  QCOMPARE(finished.front().at(0).toBool(), true);
  QVERIFY(dialog.orbit().has_value());
  const PeriodicOrbit& orbit = *dialog.orbit();
  QCOMPARE(orbit.period, 6);
  QVERIFY(orbit.residue > 0 && orbit.residue < 1);
  QVERIFY(orbit.stable());
  QVERIFY(std::fabs(static_cast<double>(orbit.rotationNumber) - 1.0 / 6) < 1e-12);
  QVERIFY(std::hypot(static_cast<double>(orbit.points[0].x) - 0.0509, static_cast<double>(orbit.points[0].y) - 0.0974) <
          1e-3);
  auto* table = dialog.findChild<QTableWidget*>();
  QVERIFY(table);
  QCOMPARE(table->rowCount(), 6);
  // The summary shows core's words (classifyOrbit, rotationNumberText), the same as archipelago-cli periodic.
  bool summaryShown = false;
  for (QLabel* label : dialog.findChildren<QLabel*>()) {
    const QString text = label->text();
    if (!text.contains(QStringLiteral("residue R"))) continue;
    summaryShown = true;
    QVERIFY2(text.contains(QStringLiteral("stable, elliptic, 0 &lt; R &lt; 1")) ||
                 text.contains(QStringLiteral("stable, elliptic, 0 < R < 1")),
             qPrintable(text));
    QVERIFY2(text.contains(QStringLiteral("= 1/6 = 1/6 (clockwise turns")), qPrintable(text));
    QVERIFY2(!text.contains(QStringLiteral("nan")), qPrintable(text));
  }
  QVERIFY(summaryShown);
  // "Overlay" hands the orbit on.
  for (QPushButton* button : dialog.findChildren<QPushButton*>())
    if (button->text().remove('&') == QStringLiteral("Overlay")) button->click();
  QCOMPARE(overlays.count(), 1);
  // Nothing of period 6 near a point far from the chain, stable only: a clear failure, no orbit.
  dialog.setNear(-0.7, 0.6);
  dialog.setPeriod(7);
  finished.clear();
  dialog.find();
  QVERIFY(finished.wait(20000));
  QCOMPARE(finished.front().at(0).toBool(), false);
  QVERIFY(!dialog.orbit().has_value());
}

void TestSegments::mainWindowShowsTheSegmentsOfAnOpenedRun() {
  const TrappingState& state = shortRun();
  QTemporaryDir dir;
  const QString file = dir.filePath(QStringLiteral("short.json"));
  saveRunFile(file.toStdString(), state);
  MainWindow window;
  window.setConfirmations(false);
  window.show();
  LongSegmentsPanel& panel = *window.longSegments();
  panel.setAutoIdentifiedRows(0);
  QSignalSpy replays(&panel, &LongSegmentsPanel::replayReady);
  window.showLongSegment(1, false);
  QVERIFY(window.openRunFile(file));
  // The table fills from the analysed run file's snapshot; the pending selection replays segment 1.
  QVERIFY(replays.wait(900000));
  QCOMPARE(panel.model()->rowCount(), static_cast<int>(state.longest.items().size()));
  QCOMPARE(panel.currentReplay()->trace.record, state.longest.items()[1]);
  QCOMPARE(window.tabs()->currentWidget(), static_cast<QWidget*>(window.portraitPanel()));
  PortraitController& controller = *window.portraitPanel()->controller();
  QVERIFY(controller.map() == state.params.map);
  QVERIFY(window.portraitPanel()->view()->parameters() == state.params.map);
  const PhysicalRect shown = controller.viewport().physical(controller.map());
  QVERIFY(shown.x0 <= panel.currentReplay()->region.x0 + 1e-12L);
  QVERIFY(shown.y0 <= panel.currentReplay()->region.y0 + 1e-12L);
  const long double L = state.params.map.width();
  QVERIFY((shown.x1 - shown.x0) * (shown.y1 - shown.y0) < 0.8L * L * L);  // zoomed in (not the whole box)
  // Tools ▸ Find Periodic Orbit opens the dialog with K from the parameters.
  QAction* find = nullptr;
  for (QAction* a : window.findChildren<QAction*>())
    if (a->text().remove('&').startsWith(QStringLiteral("Find Periodic Orbit"))) find = a;
  QVERIFY(find);
  find->trigger();
  auto* dialog = window.findChild<PeriodicOrbitDialog*>();
  QVERIFY(dialog && dialog->isVisible());
  QCOMPARE(dialog->K(), state.params.map.K);
  // The dialog's "Overlay" reaches the portrait through its controller: the periodic-orbit layer.
  PeriodicOrbitSearch search;
  search.period = 6;
  search.near = {0.0509L, 0.0974L};
  const PeriodicOrbit orbit = findPeriodicOrbit(0.1L, search);
  const auto views = controller.viewport();
  Q_EMIT dialog->overlayRequested(orbit);
  QCOMPARE(window.portraitPanel()->view()->layerItems(PortraitLayer::periodicOrbits).size(), std::size_t{1});
  QVERIFY(controller.viewport() == views);
  QVERIFY(controller.map() == state.params.map);
  dialog->close();
}

ARCHIPELAGO_GUI_TEST_MAIN(TestSegments)
#include "test_segments.moc"
