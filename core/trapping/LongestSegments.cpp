#include "core/trapping/LongestSegments.hpp"

#include "core/limits/Limits.hpp"

#include <algorithm>

namespace archipelago {

void LongestSegments::insert(const SegmentRecord& s) {
  if (capacity_ == 0) return;
  if (items_.size() == capacity_ && !ranksBefore(s, items_.back())) return;
  items_.insert(std::upper_bound(items_.begin(), items_.end(), s, ranksBefore), s);
  if (items_.size() > capacity_) items_.pop_back();
}

void LongestSegments::merge(const LongestSegments& other) {
  for (const auto& s : other.items_) insert(s);
}

std::optional<std::string> longestRankError(std::string_view name, std::uint64_t rank, std::uint64_t kept) {
  if (rank < kept) return std::nullopt;
  if (kept == 0) return std::string(name) + " = " + std::to_string(rank) + ": the run keeps no longest segment";
  return rangeError(name, rank, 0, static_cast<long long>(kept - 1),
                    kept == kMaxLongestKept ? "a rank among the longest segments a run keeps; 0 is the longest"
                                            : "a rank among the " + std::to_string(kept) +
                                                  " longest segments the run keeps; 0 is the longest");
}

}  // namespace archipelago
