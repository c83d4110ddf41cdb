#include "core/trapping/TrappingHistogram.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace archipelago {

namespace {
// edge(i) = ⌈10^(i/30)⌉ for i > kExactMax, computed once.  10^(i/30) is an integer only when 30 | i (a power
// of ten, set exactly); otherwise it is irrational and long double's 64-bit mantissa places the ceiling
// correctly for every edge below 2^63.
struct EdgeTable {
  std::array<std::uint64_t, TrappingHistogram::kBins + 1> lower{};
  EdgeTable() {
    for (int i = 0; i <= TrappingHistogram::kExactMax; ++i) lower[i] = static_cast<std::uint64_t>(i);
    for (int i = TrappingHistogram::kExactMax + 1; i < TrappingHistogram::kBins; ++i) {
      if (i % TrappingHistogram::kBinsPerDecade == 0) {
        std::uint64_t p = 1;
        for (int k = 0; k < i / TrappingHistogram::kBinsPerDecade; ++k) p *= 10;
        lower[i] = p;
      } else {
        lower[i] = static_cast<std::uint64_t>(
            std::ceil(std::pow(10.0L, static_cast<long double>(i) / TrappingHistogram::kBinsPerDecade)));
      }
    }
    lower[TrappingHistogram::kBins] = std::numeric_limits<std::uint64_t>::max();
  }
};
const EdgeTable& edges() {
  static const EdgeTable table;
  return table;
}
}  // namespace

int TrappingHistogram::binOf(std::uint64_t t) noexcept {
  if (t <= static_cast<std::uint64_t>(kExactMax)) return static_cast<int>(t);
  const auto& lower = edges().lower;
  // The last bin whose lower edge is ≤ t.
  const auto it = std::upper_bound(lower.begin() + kExactMax + 1, lower.begin() + kBins, t);
  return static_cast<int>(it - lower.begin()) - 1;
}

std::uint64_t TrappingHistogram::binLower(int i) noexcept { return edges().lower[i]; }
std::uint64_t TrappingHistogram::binUpper(int i) noexcept { return edges().lower[i + 1]; }

void TrappingHistogram::merge(const TrappingHistogram& other) noexcept {
  for (int i = 0; i < kBins; ++i) {
    counts_[i] += other.counts_[i];
    sums_[i] += other.sums_[i];
  }
}

std::uint64_t TrappingHistogram::segments() const noexcept {
  std::uint64_t n = 0;
  for (const auto c : counts_) n += c;
  return n;
}

std::uint64_t TrappingHistogram::totalLength() const noexcept {
  std::uint64_t n = 0;
  for (const auto s : sums_) n += s;
  return n;
}

int TrappingHistogram::lastUsedBin() const noexcept {
  for (int i = kBins - 1; i > 0; --i)
    if (counts_[i] != 0) return i;
  return 0;
}

}  // namespace archipelago
