#include "ui/segments/LongestSegmentsModel.hpp"

#include <QLocale>

#include "core/map/FixedPointMap.hpp"

namespace archipelago::ui {

LongestSegmentsModel::LongestSegmentsModel(QObject* parent) : QAbstractTableModel(parent) {}

int LongestSegmentsModel::rowCount(const QModelIndex& parent) const {
  return parent.isValid() ? 0 : static_cast<int>(items_.size());
}

int LongestSegmentsModel::columnCount(const QModelIndex& parent) const { return parent.isValid() ? 0 : ColumnCount; }

QVariant LongestSegmentsModel::headerData(int section, Qt::Orientation orientation, int role) const {
  if (orientation != Qt::Horizontal) return {};
  if (role == Qt::DisplayRole) {
    switch (section) {
      case Rank: return tr("#");
      case Length: return tr("Steps");
      case Orbit: return tr("Orbit");
      case StartBlock: return tr("Block");
      case StartX: return tr("x\u2080");
      case StartY: return tr("y\u2080");
      case Chain: return tr("Chain");
      default: return {};
    }
  }
  if (role == Qt::ToolTipRole) {
    switch (section) {
      case Length: return tr("Steps of N\u207B\u00B9 the orbit stayed trapped: q \u00D7 blocks");
      case StartBlock: return tr("Block of its orbit where the segment started");
      case StartX:
      case StartY: return tr("Physical coordinates of the exact start state (6 decimals; the tooltip of a cell "
                             "has the exact unit coordinates)");
      case Chain:
        return tr("Chain period: the period of the island chain the segment sticks to (identified in the "
                  "background)");
      default: return {};
    }
  }
  return {};
}

QVariant LongestSegmentsModel::data(const QModelIndex& index, int role) const {
  const SegmentRecord* r = record(index.row());
  if (r == nullptr) return {};
  const auto row = static_cast<std::size_t>(index.row());
  if (index.column() == Chain) return chainText(*r, role);
  if (role == Qt::TextAlignmentRole) return QVariant(Qt::AlignRight | Qt::AlignVCenter);
  const QLocale locale;
  if (role == Qt::DisplayRole) {
    switch (index.column()) {
      case Rank: return index.row() + 1;
      case Length: return locale.toString(static_cast<qulonglong>(r->length * params_.q));
      case Orbit: return static_cast<qulonglong>(r->orbit);
      case StartBlock: return locale.toString(static_cast<qulonglong>(r->start.block));
      case StartX: return QString::number(static_cast<double>(starts_[row].x), 'f', 6);
      case StartY: return QString::number(static_cast<double>(starts_[row].y), 'f', 6);
      default: return {};
    }
  }
  if (role == Qt::UserRole) {  // sortable raw values
    switch (index.column()) {
      case Length: return static_cast<qulonglong>(r->length * params_.q);
      case StartBlock: return static_cast<qulonglong>(r->start.block);
      default: return {};
    }
  }
  if (role == Qt::ToolTipRole && (index.column() == StartX || index.column() == StartY))
    return tr("X = %1, Y = %2 (units of 2\u207B\u2075\u00B2), %3 random draws before")
        .arg(r->start.z.X)
        .arg(r->start.z.Y)
        .arg(r->start.draws);
  return {};
}

QVariant LongestSegmentsModel::chainText(const SegmentRecord& r, int role) const {
  const auto it = chains_.find(SegmentKey::of(r));
  const ChainStatus status = it == chains_.end() ? ChainStatus::unknown : it->second.status;
  if (role == Qt::TextAlignmentRole) return QVariant(Qt::AlignRight | Qt::AlignVCenter);
  if (status == ChainStatus::unknown) return role == Qt::DisplayRole ? QVariant(QString()) : QVariant();
  if (status == ChainStatus::pending) return role == Qt::DisplayRole ? QVariant(tr("\u2026")) : QVariant();
  const ChainResult& result = *it->second.result;
  if (!result.chain) {
    if (role == Qt::DisplayRole) return tr("\u2014");
    if (role == Qt::ToolTipRole) return result.error;
    return {};
  }
  const IslandChain& chain = *result.chain;
  if (role == Qt::DisplayRole) return chain.period;
  if (role == Qt::ToolTipRole) {
    QStringList levels;
    for (int level : chain.hierarchy) levels << QString::number(level);
    QString tip = tr("Hierarchy %1; member near (%2, %3)")
                      .arg(levels.join(QStringLiteral(" \u2192 ")))
                      .arg(static_cast<double>(chain.member.x), 0, 'f', 6)
                      .arg(static_cast<double>(chain.member.y), 0, 'f', 6);
    if (chain.centre)
      tip += tr("; centre orbit R = %1 (%2)")
                 .arg(static_cast<double>(chain.centre->residue), 0, 'g', 6)
                 .arg(QString::fromLatin1(chain.centre->classification().description()));
    return tip;
  }
  return {};
}

bool LongestSegmentsModel::setSegments(const TrappingParameters& params, const std::vector<SegmentRecord>& items) {
  const bool sameRun = hasRun_ && params == params_;
  if (sameRun && items == items_) return false;
  beginResetModel();
  if (!sameRun) {
    chains_.clear();
    ++generation_;
  }
  hasRun_ = true;
  params_ = params;
  items_ = items;
  starts_.clear();
  const FixedPointMap map(params.map);
  for (const SegmentRecord& r : items_) starts_.push_back(map.toPhysical(r.start.z));
  endResetModel();
  return true;
}

void LongestSegmentsModel::clear() {
  beginResetModel();
  hasRun_ = false;
  items_.clear();
  starts_.clear();
  chains_.clear();
  ++generation_;
  endResetModel();
}

const SegmentRecord* LongestSegmentsModel::record(int row) const noexcept {
  if (row < 0 || static_cast<std::size_t>(row) >= items_.size()) return nullptr;
  return &items_[static_cast<std::size_t>(row)];
}

int LongestSegmentsModel::rowOf(SegmentKey key) const noexcept {
  for (std::size_t i = 0; i < items_.size(); ++i)
    if (SegmentKey::of(items_[i]) == key) return static_cast<int>(i);
  return -1;
}

LongestSegmentsModel::ChainStatus LongestSegmentsModel::chainStatus(SegmentKey key) const {
  const auto it = chains_.find(key);
  return it == chains_.end() ? ChainStatus::unknown : it->second.status;
}

ChainResultPtr LongestSegmentsModel::chain(SegmentKey key) const {
  const auto it = chains_.find(key);
  return it == chains_.end() ? nullptr : it->second.result;
}

void LongestSegmentsModel::setChainPending(SegmentKey key) {
  chains_[key] = {ChainStatus::pending, nullptr};
  chainChanged(key);
}

void LongestSegmentsModel::setChain(SegmentKey key, ChainResultPtr result) {
  chains_[key] = {ChainStatus::done, std::move(result)};
  chainChanged(key);
}

void LongestSegmentsModel::chainChanged(SegmentKey key) {
  const int row = rowOf(key);
  if (row >= 0) Q_EMIT dataChanged(index(row, Chain), index(row, Chain));
}

}  // namespace archipelago::ui
