#pragma once
/// \file MarkovTreePanel.hpp
/// \brief The Atlas page's Markov tree (issue 40; issue 51: one owner from the button to the plot): "Model P_t…",
/// the dialog asking α and b₂, the background job running core's computeMarkovTree on the page's atlas, the model's
/// text, each atlas level's share of its survivors at t = 10⁴, 10⁵, 10⁶ (core's markovTreeLevelShares), with a
/// tail file the model against it as `archipelago-cli markov-tree --tail` prints it (core's comparison), and the
/// finished curve P_t = w S(t) handed to the P_t plot by one signal (curveReady).
///
/// It takes the atlas from the Atlas page that holds it (its accessors; atlasChanged() when it changes: a new atlas
/// removes the model of the previous one); what it offers for α and b₂ is core's markovTreeEntryOffer for that atlas
/// and the shown run (Sources: the window's run, parameters and tail file).  Everything numerical is core's
/// (core/markovtree, docs/markov-tree.md).

#include <QString>
#include <QWidget>

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <utility>
#include <vector>

#include "core/markovtree/MarkovTreeExport.hpp"
#include "core/run/TrappingRun.hpp"

class QLabel;
class QPushButton;
class QTableWidget;

namespace archipelago::ui {

class BackgroundJobs;

class MarkovTreePanel : public QWidget {
  Q_OBJECT
 public:
  /// The shown run's state and statistics, read at once (null: no run, or no statistics yet).
  using RunShown = std::pair<const TrappingState*, const TrappingStatistics*>;
  /// What the model's entry and its comparison read from the window: the shown run, the parameters' map (the map
  /// offered for when no atlas is on the page) and the tail file drawn on P_t (empty: none).
  struct Sources {
    std::function<RunShown()> run;
    std::function<std::optional<MapParameters>()> parametersMap;
    std::function<QString()> tailFile;
  };
  /// The entry's numbers offered for P_t = w S(t), each with where it comes from, or 0 (an empty field) with why
  /// there is none: core's markovTreeEntryOffer for the page's atlas (the parameters' map without one) and the shown
  /// run — α the run's mean segment length when its map is the atlas's (of its process of blocks of q steps, named
  /// with q, also after splicing: the q = 1 companion's α is not the tail's), else docs/markov-tree.md's for an atlas
  /// at K = 0.1 in the default box; b₂ docs/markov-tree.md's for that map only.
  struct Entry {
    double alpha = 0, b2 = 0;
    QString alphaSource, b2Source;
  };

  /// A panel of the Atlas page `parent`, whose atlas shown is `atlas()` (null: none) and is being computed while
  /// `computing()`.
  MarkovTreePanel(std::function<std::shared_ptr<const Atlas>()> atlas, std::function<bool()> computing,
                  QWidget* parent);
  ~MarkovTreePanel() override;

  void setSources(Sources sources) { sources_ = std::move(sources); }
  [[nodiscard]] Entry entry() const;
  /// "Model P_t…": a small dialog asking α and b₂, prefilled with entry(), then draw().
  void ask();
  /// Computes the model with the tail file drawn on P_t, saying so in the status bar: true when that started, and
  /// drawn() says how it ended; false at once with the reason (no finished atlas, α or b₂ refused by core).
  bool draw(double alpha, double b2, QString* error = nullptr);
  /// A tail file was drawn on P_t: the model shown, or still computing without it, is set against it now.
  void redrawAgainstTail();
  /// The page's atlas changed: another atlas's model is removed; the button says whether one can be computed.
  void atlasChanged();

  /// The t (steps) at which the page shows each level's share of the model's survivors: 10⁴, 10⁵, 10⁶.
  [[nodiscard]] static std::vector<std::uint64_t> shareTimes();
  /// Why the atlas `atlas` has no Markov tree (none, still computing, or core's markovTreeAtlasError), empty when
  /// it can have one.
  [[nodiscard]] static QString missing(const Atlas* atlas, bool computing);
  /// Computes the Markov tree of the page's atlas and its P_t = w S(t), w = α Φ_centre / b₂ (α the run's mean segment
  /// length, b₂ its stochastic area), on a background job; drawn() says how it ended.  False at once, with the reason
  /// (core's for the numbers), when there is no finished atlas or the request is refused.  A second request replaces
  /// the first (latest wins).
  /// With `tailFile` (a tail file of the atlas's map, as `markov-tree --tail`), the model is set against its levels:
  /// core's comparison (model / measured per level, the reach, the level holding the survivors) fills
  /// comparisonTable() and a line of the page (issue 53, missing); a file that cannot be read or is of another map
  /// gives the model alone.
  bool compute(double alpha, double b2, QString* error = nullptr, const QString& tailFile = {});
  [[nodiscard]] bool pending() const noexcept { return request_ != 0; }
  /// The α and b₂ of the model shown or being computed (none: no model asked for this atlas): what a tail opened
  /// meanwhile sets the model against again — a model still computing was asked for without it.
  [[nodiscard]] std::optional<std::pair<double, double>> inputs() const noexcept { return inputs_; }
  /// The model shown (null: none; a new atlas removes it).
  [[nodiscard]] std::shared_ptr<const MarkovTreeResult> model() const noexcept { return model_; }
  /// The shares: one row per atlas level, one column per shareTimes() (Qt::UserRole holds the share as a double).
  [[nodiscard]] QTableWidget* sharesTable() const noexcept { return shares_; }
  /// The model against the tail: one row per level compared (t, measured ± error, model, ratio, level holding).
  [[nodiscard]] QTableWidget* comparisonTable() const noexcept { return comparison_; }
  [[nodiscard]] QPushButton* button() const noexcept { return button_; }
  [[nodiscard]] QString text() const;

 Q_SIGNALS:
  /// The finished model's P_t and its legend title ("Markov tree (atlas depth N)"), for the P_t plot.
  void curveReady(const archipelago::Series& curve, const QString& title);
  /// compute()'s end: error is empty when the curve was handed on (curveReady), else the reason.
  void drawn(const QString& error);
  /// A line for the window's status bar (kept until the next).
  void statusMessage(const QString& text);
  /// A line for the Atlas page's own messages (AtlasPanel::statusMessage: shown a while with the portrait).
  void pageMessage(const QString& text);

 private:
  void finish(std::shared_ptr<const MarkovTreeResult> model, const QString& failure);
  void updateButton();
  void fillShares();
  void fillComparison();
  /// The model's refusal (core's reason, whole) below "Model P_t…".
  void showRefusal(const QString& why);
  /// "Model P_t…"'s tooltip when it can be pressed.
  [[nodiscard]] static QString tip();

  std::function<std::shared_ptr<const Atlas>()> atlas_;
  std::function<bool()> computing_;
  Sources sources_;
  std::shared_ptr<const Atlas> shownAtlas_;  ///< the page's atlas the model belongs to
  QPushButton* button_ = nullptr;
  QLabel* text_ = nullptr;
  QTableWidget* shares_ = nullptr;
  QTableWidget* comparison_ = nullptr;
  std::shared_ptr<const MarkovTreeResult> model_;
  quint64 request_ = 0;
  std::optional<std::pair<double, double>> inputs_;  ///< α, b₂ of the model asked for last (this atlas)
  std::unique_ptr<BackgroundJobs> jobs_;             // last: stopped and joined first
};

}  // namespace archipelago::ui
