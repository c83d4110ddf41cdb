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
/// Below the tree, the Meiss–Ott Markov tree of the atlas shown (core/markovtree, docs/markov-tree.md, issue 40):
/// "Model P_t…" asks the window for the entry's α and b₂, computeMarkovTree() runs core's computeMarkovTree on a
/// background job, and markovTreeFinished() hands the result on (the window draws its P_t on the P_t plot); the page
/// shows each atlas level's share of the model's survivors at t = 10⁴, 10⁵, 10⁶ (core's markovTreeLevelShares), and,
/// with a tail file, the model against the tail as `archipelago-cli markov-tree --tail` prints it (core's comparison).

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
#include "core/markovtree/MarkovTreeExport.hpp"

class QCheckBox;
class QElapsedTimer;
class QLabel;
class QPushButton;
class QSpinBox;
class QTableWidget;
class QTimer;
class QTreeWidget;
class QTreeWidgetItem;

namespace archipelago::ui {

class BackgroundJobs;
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

  /// The t (steps) at which the page shows each level's share of the model's survivors: 10⁴, 10⁵, 10⁶.
  [[nodiscard]] static std::vector<std::uint64_t> shareTimes();
  /// Computes the Markov tree of the atlas shown and its P_t = w S(t), w = α Φ_centre / b₂ (α the run's mean segment
  /// length, b₂ its stochastic area), on a background job; markovTreeFinished() says how it ended.  False at once,
  /// with the reason (core's for the numbers), when there is no finished atlas or the request is refused.  A second
  /// request replaces the first (latest wins).
  /// With `tailFile` (a tail file of the atlas's map, as `markov-tree --tail`), the model is set against its levels:
  /// core's comparison (model / measured per level, the reach, the level holding the survivors) fills
  /// comparisonTable() and a line of the page (issue 53, missing); a file that cannot be read or is of another map
  /// gives the model alone.
  bool computeMarkovTree(double alpha, double b2, QString* error = nullptr, const QString& tailFile = {});
  [[nodiscard]] bool markovTreePending() const noexcept { return treeRequest_ != 0; }
  /// The α and b₂ of the model shown or being computed (none: no model asked for this atlas): what a tail opened
  /// meanwhile sets the model against again — a model still computing was asked for without it.
  [[nodiscard]] std::optional<std::pair<double, double>> markovTreeInputs() const noexcept { return modelInputs_; }
  /// The model shown (null: none; a new atlas removes it).
  [[nodiscard]] std::shared_ptr<const MarkovTreeResult> markovTree() const noexcept { return model_; }
  /// The shares: one row per atlas level, one column per shareTimes() (Qt::UserRole holds the share as a double).
  [[nodiscard]] QTableWidget* sharesTable() const noexcept { return shares_; }
  /// The model against the tail: one row per level compared (t, measured ± error, model, ratio, level holding).
  [[nodiscard]] QTableWidget* comparisonTable() const noexcept { return comparison_; }
  [[nodiscard]] QPushButton* markovTreeButton() const noexcept { return modelButton_; }
  [[nodiscard]] QPushButton* openButton() const noexcept { return open_; }
  [[nodiscard]] QString markovTreeText() const;

 Q_SIGNALS:
  /// "Model P_t…" was pressed: the window asks α and b₂ and calls computeMarkovTree().
  void markovTreeAsked();
  /// computeMarkovTree()'s end: the model (null on failure) and the failure's reason (empty on success).
  void markovTreeFinished(std::shared_ptr<const archipelago::MarkovTreeResult> model, const QString& error);
  void statusMessage(const QString& text);
  /// The atlas shown changed: a step of the computation, its end, a restore.
  void atlasChanged();
  /// The computation ended (finished or stopped) or failed.
  void computationEnded();

 private:
  /// An export by core's writer (`write`: writeAtlasJson or writeAtlasCsv); false with the reason.
  bool exportWith(void (*write)(const std::filesystem::path&, const Atlas&), const QString& path, QString* error);

  /// The constructor's steps, in the order the widgets are made (the order of the Tab chain): depth, largest
  /// period, Compute, Stop and the progress line; the tree and the selected island's details; Export JSON / CSV
  /// and Open; "Model P_t…" with its text and shares; then the page's layout.
  void createRequestControls();
  void createIslandTree();
  void createFileButtons();
  void createMarkovTreeWidgets();
  void layOut();

  struct Snapshot;
  void show(std::shared_ptr<const Atlas> atlas, int done, const QString& stage);
  void fillTree();
  void updateProgress();
  void updateDetails();
  void updateButtons();
  void fillShares();
  void fillComparison();
  /// The model's refusal (core's reason, whole) below "Model P_t…".
  void showModelRefusal(const QString& why);
  /// Why the atlas shown has no Markov tree (none, computing, or core's markovTreeAtlasError), empty when it can.
  [[nodiscard]] QString markovTreeMissing() const;
  /// "Model P_t…"'s tooltip when it can be pressed.
  [[nodiscard]] static QString modelTip();
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
  QPushButton* modelButton_ = nullptr;
  QLabel* modelText_ = nullptr;
  QTableWidget* shares_ = nullptr;
  QTableWidget* comparison_ = nullptr;
  std::shared_ptr<const MarkovTreeResult> model_;
  quint64 treeRequest_ = 0;
  std::optional<std::pair<double, double>> modelInputs_;  ///< α, b₂ of the model asked for last (this atlas)
  std::unique_ptr<QElapsedTimer> elapsed_;
  std::vector<QTreeWidgetItem*> items_;   // items_[i] shows atlas_->nodes[i]
  std::shared_ptr<const Atlas> atlas_;
  int done_ = -1;                         // islands finished while computing (−1: not computing)
  QString stage_;                         // what core is doing ("island 6 > 138")
  bool restored_ = false;                 // atlas_ came from a session or a file
  bool saved_ = false;                    // atlas_ was exported as JSON or saved in a session
  std::function<bool(const QString&)> confirm_;
  QString source_;                        // … that file's name (openAtlasFile), empty for a session
  bool stopping_ = false;                 // Stop was asked; the island under way ends first
  quint64 request_ = 0;
  std::unique_ptr<BackgroundJobs> jobs_;  // last: stopped and joined first
};

}  // namespace archipelago::ui
