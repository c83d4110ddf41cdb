#pragma once
/// \file TrappingHistogram.hpp
/// \brief Counts of trapped-segment lengths: exact for short segments, logarithmic bins above.
///
/// Karney (1983), appendix B, bins b(t): t itself for t ≤ 50, then ⌊30 log10 t⌋; docs/design.md, "Trapping statistics", drops the paper's
/// overflow bin at 10^5, so the logarithmic bins (30 per decade) go on to 2^63.  Lengths are in blocks (one
/// block = q steps of N⁻¹).  Each bin keeps the integer count of segments and the integer sum of their
/// lengths, so that merging threads, ranks and checkpoints is exact and independent of order.
///
/// Bin i ≤ 50 holds exactly t = i.  Bin i ≥ 51 holds edge(i) ≤ t < edge(i+1), edge(i) = ⌈10^(i/30)⌉
/// (edge(51) = 51, so the bins are contiguous).  The last bin, kBins − 1, is open above.

#include <array>
#include <cstdint>

namespace archipelago {

class TrappingHistogram {
 public:
  static constexpr int kExactMax = 50;         ///< lengths 1..kExactMax have a bin each (bin 0 is unused)
  static constexpr int kBinsPerDecade = 30;
  static constexpr int kBins = 568;            ///< edge(567) = ⌈10^18.9⌉ < 2^63; bin 567 is open above

  /// The bin that holds a segment of length t ≥ 1 blocks.
  [[nodiscard]] static int binOf(std::uint64_t t) noexcept;
  /// Smallest length in bin i (1 ≤ i < kBins).
  [[nodiscard]] static std::uint64_t binLower(int i) noexcept;
  /// One past the largest length in bin i; UINT64_MAX for the last bin.
  [[nodiscard]] static std::uint64_t binUpper(int i) noexcept;

  /// Records one segment of length t ≥ 1.
  void add(std::uint64_t t) noexcept {
    const int i = binOf(t);
    counts_[i] += 1;
    sums_[i] += t;
  }
  /// Adds the counts of another histogram (exact, commutative, associative).
  void merge(const TrappingHistogram& other) noexcept;

  [[nodiscard]] std::uint64_t count(int i) const noexcept { return counts_[i]; }
  [[nodiscard]] std::uint64_t lengthSum(int i) const noexcept { return sums_[i]; }
  /// Sets bin i directly (run-file reading, synthetic histograms in tests).
  void setBin(int i, std::uint64_t count, std::uint64_t lengthSum) noexcept {
    counts_[i] = count;
    sums_[i] = lengthSum;
  }
  [[nodiscard]] std::uint64_t segments() const noexcept;     ///< Σ counts
  [[nodiscard]] std::uint64_t totalLength() const noexcept;  ///< Σ lengths, in blocks
  /// Highest non-empty bin, or 0 when empty.
  [[nodiscard]] int lastUsedBin() const noexcept;

  friend bool operator==(const TrappingHistogram&, const TrappingHistogram&) = default;

 private:
  std::array<std::uint64_t, kBins> counts_{};
  std::array<std::uint64_t, kBins> sums_{};
};

}  // namespace archipelago
