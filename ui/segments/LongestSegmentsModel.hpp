#pragma once
/// \file LongestSegmentsModel.hpp
/// \brief The table of a run's longest trapped segments (Karney 1983, §6), with their island chains.
///
/// Rows are the run's LongestSegments in rank order (longest first).  Columns: rank, length in steps of N⁻¹
/// (q · blocks), orbit, start block, start point (x, y) in physical coordinates, and the period of the island
/// chain the segment sticks to, which background jobs fill in (the model only stores what they return).
/// Chains are cached by segment (orbit, start block) for as long as the run's parameters stay the same, so
/// live updates during a run keep what was identified.

#include <QAbstractTableModel>

#include <compare>
#include <cstdint>
#include <map>
#include <vector>

#include "core/periodic/SegmentAnalysis.hpp"
#include "ui/portrait/SegmentResults.hpp"

namespace archipelago::ui {

/// A segment's identity within a run: (orbit, first block).
struct SegmentKey {
  std::uint64_t orbit = 0;
  std::uint64_t block = 0;
  [[nodiscard]] static SegmentKey of(const SegmentRecord& r) noexcept { return {r.orbit, r.start.block}; }
  friend auto operator<=>(const SegmentKey&, const SegmentKey&) = default;
};

class LongestSegmentsModel : public QAbstractTableModel {
  Q_OBJECT
 public:
  enum Column { Rank, Length, Orbit, StartBlock, StartX, StartY, Chain, ColumnCount };
  enum class ChainStatus { unknown, pending, done };

  explicit LongestSegmentsModel(QObject* parent = nullptr);

  [[nodiscard]] int rowCount(const QModelIndex& parent = {}) const override;
  [[nodiscard]] int columnCount(const QModelIndex& parent = {}) const override;
  [[nodiscard]] QVariant data(const QModelIndex& index, int role) const override;
  [[nodiscard]] QVariant headerData(int section, Qt::Orientation orientation, int role) const override;

  /// Shows these segments of the run with these parameters.  New parameters forget the cached chains.
  /// Returns true when the rows changed (then the model was reset).
  bool setSegments(const TrappingParameters& params, const std::vector<SegmentRecord>& items);
  void clear();

  [[nodiscard]] bool hasRun() const noexcept { return hasRun_; }
  [[nodiscard]] const TrappingParameters& parameters() const noexcept { return params_; }
  [[nodiscard]] const std::vector<SegmentRecord>& segments() const noexcept { return items_; }
  /// The record of `row`, or null.
  [[nodiscard]] const SegmentRecord* record(int row) const noexcept;
  /// The row showing the segment `key`, or −1.
  [[nodiscard]] int rowOf(SegmentKey key) const noexcept;
  /// Increases whenever the parameters change (jobs of an older generation are stale).
  [[nodiscard]] quint64 generation() const noexcept { return generation_; }

  [[nodiscard]] ChainStatus chainStatus(SegmentKey key) const;
  [[nodiscard]] ChainResultPtr chain(SegmentKey key) const;
  void setChainPending(SegmentKey key);
  void setChain(SegmentKey key, ChainResultPtr result);

 private:
  struct ChainEntry {
    ChainStatus status = ChainStatus::unknown;
    ChainResultPtr result;
  };
  [[nodiscard]] QVariant chainText(const SegmentRecord& r, int role) const;
  void chainChanged(SegmentKey key);

  bool hasRun_ = false;
  TrappingParameters params_;
  std::vector<SegmentRecord> items_;
  std::vector<PhysicalPoint> starts_;   // start points, physical, per row
  std::map<SegmentKey, ChainEntry> chains_;
  quint64 generation_ = 0;
};

}  // namespace archipelago::ui
