#include "core/trapping/LongestSegments.hpp"

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

}  // namespace archipelago
