#include "core/run/StateValidation.hpp"

#include <map>
#include <string>

namespace archipelago {

namespace {
using u128 = uint128;  // map/FixedPointMap.hpp
std::string str(std::uint64_t v) { return std::to_string(v); }
}  // namespace

std::optional<std::string> consistencyError(const TrappingState& s) {
  const TrappingParameters& p = s.params;
  if (!(s.orbitBegin < s.orbitEnd && s.orbitEnd <= p.M)) return "the orbit range lies outside [0, M)";
  if (s.blocksDone > p.T) return "blocksDone = " + str(s.blocksDone) + " exceeds T = " + str(p.T);
  if (s.orbits.size() != s.orbitEnd - s.orbitBegin) return "expected one state per orbit";
  for (std::size_t i = 0; i < s.orbits.size(); ++i) {
    const OrbitState& o = s.orbits[i];
    const std::string which = "orbit " + str(s.orbitBegin + i);
    if (o.block != s.blocksDone) return which + ": its block count differs from blocksDone";
    if (o.start.block > o.block || o.length != o.block - o.start.block)
      return which + ": its open segment (start block " + str(o.start.block) + ", " + str(o.length) +
             " blocks) does not end at blocksDone";
    if (o.draws > o.block || o.start.draws > o.draws || o.start.draws > o.start.block)
      return which + ": more random draws than blocks";
  }
  if (s.subsets.size() != p.subsets) return "expected one histogram per subset";
  std::vector<u128> orbitsIn(p.subsets, 0);
  for (std::uint64_t i = s.orbitBegin; i < s.orbitEnd; ++i) orbitsIn[i % p.subsets] += 1;
  for (std::size_t k = 0; k < s.subsets.size(); ++k) {
    const TrappingHistogram& h = s.subsets[k];
    u128 lengths = 0;
    for (int bin = 1; bin < TrappingHistogram::kBins; ++bin) {
      const std::uint64_t n = h.count(bin), sum = h.lengthSum(bin);
      if (n == 0 && sum == 0) continue;
      const std::string where = "subset " + str(k) + ", bin " + std::to_string(bin);
      const u128 lower = TrappingHistogram::binLower(bin), upper = TrappingHistogram::binUpper(bin);
      if (n == 0 || sum < n * lower || (bin + 1 < TrappingHistogram::kBins && sum > n * (upper - 1)))
        return where + ": count " + str(n) + " and length sum " + str(sum) + " do not fit the bin";
      if (lower > s.blocksDone) return where + ": segments longer than the " + str(s.blocksDone) + " blocks done";
      lengths += sum;
    }
    if (lengths > orbitsIn[k] * s.blocksDone)
      return "subset " + str(k) + ": its segments add up to more blocks than its orbits have done";
  }
  const auto& items = s.longest.items();
  if (items.size() > p.longestKept) return "more longest segments than longestKept";
  std::map<std::pair<std::size_t, int>, std::uint64_t> inBin;  // longest records per (subset, bin)
  for (std::size_t i = 0; i < items.size(); ++i) {
    const SegmentRecord& r = items[i];
    const std::string which = "longest segment " + str(i);
    if (i > 0 && !LongestSegments::ranksBefore(items[i - 1], r)) return which + ": the list is not ranked";
    if (r.orbit < s.orbitBegin || r.orbit >= s.orbitEnd) return which + ": its orbit is outside the run";
    if (r.length == 0 || r.start.block == 0 || r.length > s.blocksDone || r.start.block > s.blocksDone - r.length)
      return which + ": it does not lie inside the blocks done";
    if (r.start.draws > r.start.block) return which + ": more random draws than blocks";
    const std::size_t subset = r.orbit % p.subsets;
    const int bin = TrappingHistogram::binOf(r.length);
    if (++inBin[{subset, bin}] > s.subsets[subset].count(bin))
      return which + ": its length " + str(r.length) + " is missing from the histogram";
  }
  return std::nullopt;
}

}  // namespace archipelago
