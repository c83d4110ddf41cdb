#pragma once
/// \file AtlasPanel.hpp
/// \brief The "Atlas" page beside the portrait (issue 38, deliverable 3): the hierarchy of islands around islands of
/// the portrait's map as an expandable tree — each island's path, period, p/q about its parent, area (± error), the
/// flux through its chain's barrier, the layer and the mean residence time there — computed in the background,
/// the first levels first, the tree filling as each island is measured.
///
/// Everything is core's (core/atlas: computeAtlas with its progress and stop token, atlasPath, atlasJson/atlasCsv,
/// writeAtlasJson/writeAtlasCsv; docs/atlas.md): this page fills the request (depth, largest period; the rest is
/// core's default), runs it on a background job (ui/jobs: each island's progress posts a copy of the atlas so far;
/// Stop keeps what is finished, as `archipelago-cli atlas` does on Ctrl-C), and formats.  A click on an island asks
/// the PortraitController to zoom to it (its boundary circle with a margin) and draw its boundary circle, its chain
/// (the periodic-orbit overlay) and its partner's manifolds (the Manifolds page's mechanism).  The atlas is kept in sessions (core/session: its JSON, read back, not
/// recomputed).  An atlas of another map than the portrait's stays listed (a change of K loses nothing) but its
/// islands are not drawn until that map is shown again.
///
/// An atlas file (`archipelago-cli atlas --json`, Export JSON) can be opened instead of computed (openAtlasFile).
/// Below the tree, the Meiss–Ott Markov tree of the atlas shown (core/markovtree, docs/markov-tree.md, issue 40): a
/// MarkovTreePanel, which owns it from its button to the curve it hands to the P_t plot.

#include <QString>
#include <QWidget>

#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <utility>
#include <string>
#include <vector>

#include "core/atlas/Atlas.hpp"

class QCheckBox;
class QElapsedTimer;
class QLabel;
class QPushButton;
class QSpinBox;
class QTimer;
class QTreeWidget;
class QTreeWidgetItem;

namespace archipelago::ui {

class BackgroundJobs;
class MarkovTreePanel;
class PortraitController;

class AtlasPanel : public QWidget {
  Q_OBJECT
 public:
  /// The tree's columns.
  enum Column { island, period, rotation, area, flux, layer, residence, note, columns };

  AtlasPanel(PortraitController* controller, QWidget* parent = nullptr);
  ~AtlasPanel() override;

  /// No wider than the other side pages ask: the tree's eight columns would otherwise widen the side column and
  /// narrow the portrait (the tree scrolls sideways instead; gui.issue25's equal aspect ratio).
  [[nodiscard]] QSize sizeHint() const override;

  [[nodiscard]] QSpinBox* depthBox() const noexcept { return depth_; }
  [[nodiscard]] QSpinBox* maxPeriodBox() const noexcept { return maxPeriod_; }
  [[nodiscard]] QCheckBox* cantoriBox() const noexcept { return cantori_; }
  [[nodiscard]] QPushButton* computeButton() const noexcept { return compute_; }
  [[nodiscard]] QPushButton* stopButton() const noexcept { return stop_; }
  [[nodiscard]] QTreeWidget* tree() const noexcept { return tree_; }
  /// The tree's row of island `index` (null when it is not listed).
  [[nodiscard]] QTreeWidgetItem* item(int index) const;
  /// The progress line and the selected island's details, as shown.
  [[nodiscard]] QString progressText() const;
  [[nodiscard]] QString detailsText() const;

  /// The request the controls describe, for the portrait's map (core's defaults for the rest).
  [[nodiscard]] AtlasRequest request() const;
  /// Computes the atlas of `request` in the background (its map should be the portrait's), replacing the one shown;
  /// false, with core's reason in the status bar, when core refuses the request.
  bool compute(const AtlasRequest& request);
  /// Stops the computation: the islands finished stay (the atlas is marked cancelled).
  void stop();
  /// True while an atlas is being computed.
  [[nodiscard]] bool busy() const noexcept { return request_ != 0; }
  /// The atlas shown (null: none): while computing, the atlas so far.
  [[nodiscard]] std::shared_ptr<const Atlas> atlas() const noexcept { return atlas_; }
  /// What a session keeps: the atlas shown, or while computing a copy of the atlas so far marked cancelled (it is
  /// incomplete); nothing without one.
  [[nodiscard]] std::optional<Atlas> sessionAtlas() const;
  /// Shows `atlas` (a session's; nothing clears the page), stopping any computation.
  void restoreAtlas(const std::optional<Atlas>& atlas);
  /// Zooms the portrait to island `index` and draws its boundary, chain and partner's manifolds (a click on its row;
  /// the zoom comes with the traced boundary, PortraitController::showAtlasIsland); false, with the reason in the
  /// status bar, when there is no such island or the atlas is of another map.
  bool showIsland(int index);
  /// Core's JSON / CSV of the atlas shown (writeAtlasJson / writeAtlasCsv, atomic).  False with the reason.
  bool exportJson(const QString& path, QString* error = nullptr);
  bool exportCsv(const QString& path, QString* error = nullptr);
  /// Reads an atlas file (`archipelago-cli atlas --json`, Export JSON: core's atlasFromJson) and shows it as a
  /// session's atlas is shown, stopping any computation; false with core's reason (also in the status bar).
  bool openAtlasFile(const QString& path, QString* error = nullptr);

  /// True when the atlas shown was computed here (finished, stopped or under way) and is in no file: neither
  /// exported as JSON nor held by a saved session.  Replacing it or quitting loses the work.
  [[nodiscard]] bool unsavedWork() const;
  /// The atlas shown is in a file now (Export JSON, a saved session); one under way stays unsaved.
  void markSaved();
  /// Who is asked before an unsaved atlas goes (the window: Save, Discard or Cancel): true to go on, false to keep
  /// it.  `action` says what would replace it ("opening another atlas").  Without one nothing is asked.
  void setConfirmDiscard(std::function<bool(const QString& action)> confirm) { confirm_ = std::move(confirm); }
  /// True when the atlas shown may go for `action`: nothing unsaved, or the one asked said so.
  bool confirmDiscard(const QString& action);
  /// Export JSON… / CSV…'s file dialog and export; true when the file was written.
  bool exportWithDialog(bool json);

  /// The Markov tree of the atlas shown, below the tree ("Model P_t…", its shares and comparison).
  [[nodiscard]] MarkovTreePanel* markovTreePanel() const noexcept { return markovTree_; }
  [[nodiscard]] QPushButton* openButton() const noexcept { return open_; }

 Q_SIGNALS:
  void statusMessage(const QString& text);
  /// The atlas shown changed: a computation's start, a step of it, its end, a restore.
  void atlasChanged();
  /// The computation ended (finished or stopped) or failed.
  void computationEnded();

 private:
  /// An export by core's writer (`write`: writeAtlasJson or writeAtlasCsv); false with the reason.
  bool exportWith(void (*write)(const std::filesystem::path&, const Atlas&), const QString& path, QString* error);

  /// The constructor's steps, in the order the widgets are made (the order of the Tab chain): depth, largest
  /// period, Compute, Stop and the progress line; the tree and the selected island's details; Export JSON / CSV
  /// and Open; the Markov tree's panel; then the page's layout.
  void createRequestControls();
  void createIslandTree();
  void createFileButtons();
  void layOut();

  struct Snapshot;
  void show(std::shared_ptr<const Atlas> atlas, int done, const QString& stage);
  void fillTree();
  void updateProgress();
  void updateDetails();
  void updateButtons();
  [[nodiscard]] bool ofPortraitMap() const;

  PortraitController* controller_;
  QSpinBox* depth_ = nullptr;
  QSpinBox* maxPeriod_ = nullptr;
  QCheckBox* cantori_ = nullptr;
  QPushButton* compute_ = nullptr;
  QPushButton* stop_ = nullptr;
  QLabel* progress_ = nullptr;
  QTreeWidget* tree_ = nullptr;
  QLabel* details_ = nullptr;
  QPushButton* json_ = nullptr;
  QPushButton* csv_ = nullptr;
  QTimer* clock_ = nullptr;
  QPushButton* open_ = nullptr;
  MarkovTreePanel* markovTree_ = nullptr;
  std::unique_ptr<QElapsedTimer> elapsed_;
  std::vector<QTreeWidgetItem*> items_;   // items_[i] shows atlas_->nodes[i]
  std::shared_ptr<const Atlas> atlas_;
  int done_ = -1;                         // islands finished while computing (−1: not computing)
  QString stage_;                         // what core is doing ("island 6 > 138")
  bool restored_ = false;                 // atlas_ came from a session or a file
  QString refusal_;                       // why the last Compute was refused (core's words), until the map changes
  bool saved_ = false;                    // atlas_ was exported as JSON or saved in a session
  std::function<bool(const QString&)> confirm_;
  QString source_;                        // … that file's name (openAtlasFile), empty for a session
  bool stopping_ = false;                 // Stop was asked; the island under way ends first
  quint64 request_ = 0;
  std::unique_ptr<BackgroundJobs> jobs_;  // last: stopped and joined first
};

}  // namespace archipelago::ui
