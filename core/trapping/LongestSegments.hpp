#pragma once
/// \file LongestSegments.hpp
/// \brief The N longest trapped segments, each with the exact state at its start (docs/design.md, "Trapping statistics").
///
/// Order: longer first; ties by orbit, then by start block.  This is a total order on segments, so the
/// kept set does not depend on the order of insertion or merging (threads, ranks, checkpoints).

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/trapping/TrappingParameters.hpp"

namespace archipelago {

class LongestSegments {
 public:
  explicit LongestSegments(std::size_t capacity = 100) : capacity_(capacity) {}

  /// True when `a` ranks before `b`.
  [[nodiscard]] static bool ranksBefore(const SegmentRecord& a, const SegmentRecord& b) noexcept {
    if (a.length != b.length) return a.length > b.length;
    if (a.orbit != b.orbit) return a.orbit < b.orbit;
    return a.start.block < b.start.block;
  }
  /// Would a segment of this length be kept now?  (Cheap pre-test for kernels.)
  [[nodiscard]] bool mightKeep(std::uint64_t length) const noexcept {
    return capacity_ > 0 && (items_.size() < capacity_ || length >= items_.back().length);
  }
  void insert(const SegmentRecord& s);
  void merge(const LongestSegments& other);

  [[nodiscard]] const std::vector<SegmentRecord>& items() const noexcept { return items_; }  ///< ranked
  [[nodiscard]] std::size_t capacity() const noexcept { return capacity_; }

  friend bool operator==(const LongestSegments&, const LongestSegments&) = default;

 private:
  std::size_t capacity_;
  std::vector<SegmentRecord> items_;
};

/// The rule of a rank among a run's longest segments (0 is the longest), for `replay --segment`, Python's
/// Run.replay(rank) and the GUI's --segment: "<name> = <rank> must lie in [0, kept − 1] (...)", or nothing.  `kept`:
/// the segments the run keeps, or, before its file is read, the most any run keeps (kMaxLongestKept).
[[nodiscard]] std::optional<std::string> longestRankError(std::string_view name, std::uint64_t rank,
                                                          std::uint64_t kept = kMaxLongestKept);

}  // namespace archipelago
