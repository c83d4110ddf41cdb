#include "core/tail/TailSampler.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <numeric>
#include <stdexcept>
#include <string>

#include "core/kernels/ScalarLanes.hpp"
#include "core/limits/Limits.hpp"
#include "core/parallel/ParallelFor.hpp"
#include "core/random/CounterRng.hpp"
#include "core/trapping/BlockKernel.hpp"
#include "core/trapping/TrappingHistogram.hpp"

namespace archipelago {

namespace {

// Where the sampler's random numbers come from (TailSampler.hpp): orbit indices no `run` uses (M ≤ 2^32).
constexpr std::uint64_t kEntryOrbitBase = std::uint64_t{1} << 63;   // + r·2^40 + j: entry orbit j of replica r
constexpr int kEntryReplicaShift = 40;
constexpr std::uint64_t kLevelStreamBase = std::uint64_t{1} << 62;  // + r·2^24 + k: choices at level k
constexpr int kLevelReplicaShift = 24;

// Stage 0 (TailSampler.hpp): entry orbits per unit of work (between stop checks) per replica, and for the pilot.
constexpr std::uint64_t kEntryOrbitsPerUnit = 64;
constexpr std::uint64_t kPilotUnitsAtOnce = 16;              // the pilot's units computed in one parallel loop
constexpr std::uint64_t kEntryOrbitsPerReplicaUnit = 512;    // a replica's entry orbits in one unit of stage 0
constexpr std::size_t kEntryGroup = 32;  // orbits the block kernel advances together
constexpr std::uint64_t kEntryGroupMinLevel = 8;  // below, entry orbits are followed one block at a time
// Steps a group of entry orbits computes between two looks at the stop token (~10 ms on the scalar path).
constexpr std::uint64_t kStopCheckSteps = std::uint64_t{1} << 22;
// A chunk of splitting lasts at most age/16 blocks (a walker that dies in it is iterated at most 1/16 of its age
// in vain) and at most 2^20 steps per walker (a stop is honoured within a second or two at N·R = 800).
constexpr std::uint64_t kChunkAgeDivisor = 16;
constexpr std::uint64_t kMaxChunkStepsPerWalker = std::uint64_t{1} << 20;

// e(j) = ⌈10^(j/30)⌉: the lower edge of histogram bin j when j > 50 (TrappingHistogram's own table), else the
// same formula (every length up to 50 is an edge of its own exact bin).
std::uint64_t ceilPow10Thirtieth(int j) {
  if (j > TrappingHistogram::kExactMax) return TrappingHistogram::binLower(j);
  if (j % TrappingHistogram::kBinsPerDecade == 0) {
    std::uint64_t p = 1;
    for (int k = 0; k < j / TrappingHistogram::kBinsPerDecade; ++k) p *= 10;
    return p;
  }
  return static_cast<std::uint64_t>(
      std::ceil(std::pow(10.0L, static_cast<long double>(j) / TrappingHistogram::kBinsPerDecade)));
}

std::uint64_t levelKey(std::uint64_t seed, std::size_t replica, std::size_t level) {
  return orbitKey(seed, kLevelStreamBase + (static_cast<std::uint64_t>(replica) << kLevelReplicaShift) + level);
}

}  // namespace

std::uint64_t entryOrbitIndex(std::size_t replica, std::uint64_t j) {
  return kEntryOrbitBase + (static_cast<std::uint64_t>(replica) << kEntryReplicaShift) + j;
}

namespace {

// A uniform integer of [−ε, ε] from a 52-bit draw: ⌊u (2ε + 1)/2^52⌋ − ε (exact in 128 bits; the 2^52 draws
// fall on the 2ε + 1 values within one part in 2^52/(2ε + 1) ≥ 2^11 of uniform).
std::int64_t offsetOf(std::uint64_t u, std::uint64_t epsilon) {
  const auto v = static_cast<std::uint64_t>((uint128{u} * (2 * epsilon + 1)) >> fixedpoint::kBits);
  return static_cast<std::int64_t>(v) - static_cast<std::int64_t>(epsilon);
}

// The state moved by the next (δX, δY) of stream `key` (draws counter + 1, …), not both 0.
UnitState moved(const UnitState& z, std::uint64_t key, std::uint64_t& counter, std::uint64_t epsilon) {
  for (;;) {
    const std::int64_t dx = offsetOf(orbitDraw(key, ++counter), epsilon);
    const std::int64_t dy = offsetOf(orbitDraw(key, ++counter), epsilon);
    if (dx == 0 && dy == 0) continue;
    return {(z.X + static_cast<std::uint64_t>(dx)) & fixedpoint::kMask,
            (z.Y + static_cast<std::uint64_t>(dy)) & fixedpoint::kMask};
  }
}

}  // namespace

EntryOrbitResult entryOrbitTrials(const KernelSettings& k, std::uint64_t orbit, std::uint64_t warmupBlocks,
                                  std::uint64_t level, std::stop_token stop) {
  EntryOrbitResult out;
  OrbitState s;  // (0, 0): appendix B, step 2
  const std::uint64_t end = warmupBlocks + kEntryWindowBlocks;
  for (std::uint64_t b = 0; b < end; ++b) {
    if (stop.stop_requested()) return out;  // a block is at most 65536 steps: the caller discards the part
    const bool ended = advanceOneBlock(k, orbit, s, nullptr);
    if (ended && b >= warmupBlocks) ++out.trials;  // the next segment starts at block b + 1, inside the window
    if (!ended && s.start.block > warmupBlocks && s.length == level) out.successes.push_back(s);
  }
  out.blocks = end;
  // The trial still open when the window closes is followed until it ends or reaches the level.
  if (s.start.block > warmupBlocks && s.length < level) {
    for (;;) {
      if (stop.stop_requested()) return out;
      const bool ended = advanceOneBlock(k, orbit, s, nullptr);
      ++out.blocks;
      if (ended) break;
      if (s.length == level) {
        out.successes.push_back(s);
        break;
      }
    }
  }
  return out;
}

std::optional<std::string> tailFirstLevelRefusal(const TailState& s) {
  if (s.entryOrbits != 0 || s.pilotSuccesses >= kPilotSuccesses) return std::nullopt;
  const std::string t = std::to_string(s.levels.empty() ? 0 : s.levels[0] * s.request.run.q);
  if (s.pilotTrials >= kPilotTrials && s.pilotSuccesses < kPilotSuccesses / 8)
    // P(t_0) below ~2·10^-7: stage 0 would need more than 10^7 N segments a replica (a map without sticky islands,
    // K ≤ 0, or a first level too high).  Said after a second or two, rather than after hours.
    return "only " + std::to_string(s.pilotSuccesses) + " of the pilot's " + std::to_string(s.pilotTrials) +
           " segments lasted longer than the first level t = " + t + " steps: give a lower first level";
  if (s.pilotOrbits >= kMaxPilotOrbits)
    return "the pilot's " + std::to_string(s.pilotTrials) + " segments of " + std::to_string(s.pilotOrbits) +
           " entry orbits gave " + std::to_string(s.pilotSuccesses) + " longer than the first level t = " + t +
           " steps: give a lower first level";
  return std::nullopt;
}

const char* cloneRuleName(CloneRule rule) noexcept { return rule == CloneRule::perturb ? "perturb" : "metropolis"; }

std::optional<CloneRule> cloneRuleByName(std::string_view name) noexcept {
  if (name == "perturb") return CloneRule::perturb;
  if (name == "metropolis") return CloneRule::metropolis;
  return std::nullopt;
}

std::uint64_t entryOrbitsPerReplica(std::uint32_t population, std::uint64_t pilotOrbits, std::uint64_t pilotSuccesses) {
  if (pilotSuccesses == 0) throw std::invalid_argument("the pilot found no success");
  const uint128 wanted = uint128{kEntrySuccessTarget} * population * pilotOrbits;
  return static_cast<std::uint64_t>((wanted + pilotSuccesses - 1) / pilotSuccesses);
}

std::optional<std::string> tailRequestError(const TailRequest& r) {
  if (auto e = validationError(r.run)) return e;
  // Every bound lies below 2^63 (t-max's is 2^60, the walkers' below kMaxTailWalkers): within rangeError's long long.
  if (auto e = rangeError("population", r.population, 2, kMaxTailPopulation)) return e;
  if (auto e = rangeError("replicas", r.replicas, 1, kMaxTailReplicas)) return e;
  if (std::uint64_t{r.population} * r.replicas > kMaxTailWalkers)
    return "population x replicas = " + std::to_string(std::uint64_t{r.population} * r.replicas) +
           " walkers exceeds the limit of " + std::to_string(kMaxTailWalkers);
  if (auto e = rangeError("t-max", r.maxSteps, 1, kMaxTailSteps)) return e;
  if (auto e = rangeError("first", r.firstSteps, 1, r.maxSteps)) return e;
  if (auto e = rangeError("level-bins", r.binsPerLevel, 1, kMaxBinsPerLevel)) return e;
  if (auto e = rangeError("epsilon", r.epsilon, 1, kMaxTailEpsilon)) return e;
  if (auto e = rangeError("metropolis-steps", r.metropolisSteps, 1, kMaxMetropolisSteps)) return e;
  if (auto e = rangeError("warmup", r.warmupBlocks, 1, kMaxWarmupBlocks)) return e;
  if (auto e = rangeError("min-ancestors", r.minAncestors, 1, std::uint64_t{r.population} * r.replicas)) return e;
  return std::nullopt;
}

std::vector<std::uint64_t> tailLevels(const TailRequest& r) {
  if (auto e = tailRequestError(r)) throw std::invalid_argument(*e);
  const std::uint64_t q = r.run.q;
  // Level L = e(j) − 1 blocks is t = q·L steps; the bins stop at 2^63 > q·L for every t ≤ kMaxTailSteps.
  const auto stepsOf = [&](int j) { return (ceilPow10Thirtieth(j) - 1) * q; };
  int j = 1;  // e(0) − 1 = 0 is no level
  while (stepsOf(j) < r.firstSteps) ++j;
  std::vector<std::uint64_t> levels;
  for (;; j += static_cast<int>(r.binsPerLevel)) {
    if (j >= TrappingHistogram::kBins) throw std::invalid_argument("t-max is beyond the histogram's bins");
    const std::uint64_t L = ceilPow10Thirtieth(j) - 1;
    if (levels.empty() || L > levels.back()) levels.push_back(L);
    if (L * q >= r.maxSteps) break;
  }
  return levels;
}

TailState startTail(const TailRequest& request) { return startTailSlice(request, {0, request.replicas}); }

ReplicaRange replicaSlice(std::uint32_t replicas, std::uint32_t i, std::uint32_t n) {
  if (auto e = lowerBoundError("slices", n, 1)) throw std::invalid_argument(*e);
  const std::string which = "one of the " + std::to_string(n) + " slices, counted from 0";
  if (auto e = rangeError("slice", i, 0, std::int64_t{n} - 1, which)) throw std::invalid_argument(*e);
  if (n > replicas)
    throw std::invalid_argument(std::to_string(n) + " slices of " + std::to_string(replicas) +
                                " replicas: every slice needs a replica (at most " + std::to_string(replicas) + " slices)");
  const auto edge = [&](std::uint64_t k) { return static_cast<std::uint32_t>(std::uint64_t{replicas} * k / n); };
  return {edge(i), edge(i + 1) - edge(i)};
}

TailState startTailSlice(const TailRequest& request, ReplicaRange range) {
  TailState s;
  s.request = request;
  s.levels = tailLevels(request);  // validates
  if (range.count == 0 || std::uint64_t{range.first} + range.count > request.replicas)
    throw std::invalid_argument("replicas [" + std::to_string(range.first) + ", " +
                                std::to_string(std::uint64_t{range.first} + range.count) + ") are not a slice of the " +
                                std::to_string(request.replicas) + " replicas");
  s.coefficients = computeCoefficients(request.run.map);
  s.firstReplica = range.first;
  s.replicas.resize(range.count);
  return s;
}

TailState mergeTailSlices(std::vector<TailState> slices) {
  if (slices.empty()) throw std::invalid_argument("no slices to merge");
  std::sort(slices.begin(), slices.end(),
            [](const TailState& a, const TailState& b) { return a.firstReplica < b.firstReplica; });
  TailState m = slices.front();
  const auto where = [](const TailState& s) {
    return "the slice of replicas [" + std::to_string(s.firstReplica) + ", " +
           std::to_string(s.firstReplica + s.replicas.size()) + ")";
  };
  if (m.firstReplica != 0) throw std::invalid_argument("no slice holds replica 0");
  for (std::size_t i = 0; i < slices.size(); ++i) {
    const TailState& s = slices[i];
    if (auto e = tailStateError(s)) throw std::invalid_argument(where(s) + ": " + *e);
    if (!s.finished()) throw std::invalid_argument(where(s) + " is not finished (resume it first)");
    if (!(s.request == m.request)) throw std::invalid_argument(where(s) + " is of another sampler run (its settings differ)");
    if (s.pilotOrbits != m.pilotOrbits || s.pilotTrials != m.pilotTrials || s.pilotSuccesses != m.pilotSuccesses ||
        s.entryOrbits != m.entryOrbits || s.age != m.age)
      throw std::invalid_argument(where(s) + " has another pilot");
    if (i == 0) continue;
    const TailState& before = slices[i - 1];
    const std::uint64_t expected = before.firstReplica + before.replicas.size();
    if (s.firstReplica != expected)
      throw std::invalid_argument(s.firstReplica < expected ? where(s) + " overlaps " + where(before)
                                                            : "replicas [" + std::to_string(expected) + ", " +
                                                                  std::to_string(s.firstReplica) + ") are in no slice");
    m.replicas.insert(m.replicas.end(), s.replicas.begin(), s.replicas.end());
    m.steps += s.steps;
    for (std::size_t k = 0; k < m.stepsAtLevel.size(); ++k) m.stepsAtLevel[k] += s.stepsAtLevel[k];
    m.elapsedSeconds += s.elapsedSeconds;
    if (s.kernel != m.kernel && m.kernel.find(s.kernel) == std::string::npos) m.kernel += ", " + s.kernel;
  }
  if (m.replicas.size() != m.request.replicas)
    throw std::invalid_argument("replicas [" + std::to_string(m.replicas.size()) + ", " +
                                std::to_string(m.request.replicas) + ") are in no slice");
  if (auto e = tailStateError(m)) throw std::invalid_argument("the merged slices: " + *e);
  return m;
}

std::optional<std::string> tailStateError(const TailState& s) {
  const TailRequest& r = s.request;
  if (auto e = tailRequestError(r)) return e;
  if (s.levels != tailLevels(r)) return std::string("the levels differ from those of the sampler's settings");
  if (s.replicas.empty() || std::uint64_t{s.firstReplica} + s.replicas.size() > r.replicas)
    return std::string("expected one entry per replica of the run or of its slice");
  if (s.next > s.levels.size()) return std::string("the level under way is beyond the last level");
  if (s.stepsAtLevel.size() != s.next) return std::string("expected the steps of every level reached");
  for (std::size_t k = 1; k < s.stepsAtLevel.size(); ++k)
    if (s.stepsAtLevel[k] < s.stepsAtLevel[k - 1]) return std::string("the steps per level must not decrease");
  if (!s.stepsAtLevel.empty() && s.stepsAtLevel.back() > s.steps) return std::string("a level's steps exceed the total");
  if (s.next == 0 && s.age != 0 && s.age != s.levels[0]) return std::string("stage 0's age is 0 or the first level");
  if (s.pilotSuccesses > s.pilotTrials || s.pilotOrbits % kEntryOrbitsPerUnit != 0 || s.pilotOrbits > kMaxPilotOrbits)
    return std::string("the pilot's counts are inconsistent");
  if ((s.entryOrbits != 0) != (s.pilotSuccesses >= kPilotSuccesses) ||
      (s.entryOrbits != 0 && s.entryOrbits != entryOrbitsPerReplica(r.population, s.pilotOrbits, s.pilotSuccesses)))
    return std::string("the entry orbits per replica are not the pilot's");
  if (s.entryOrbits == 0 && (s.next != 0 || s.age != 0)) return std::string("stage 0 went on without its pilot");
  if (s.next > 0) {
    const std::uint64_t lo = s.levels[s.next - 1], hi = s.finished() ? lo : s.levels[s.next];
    if (s.age < lo || s.age > hi) return std::string("the walkers' age lies outside the level under way");
  }
  const std::uint64_t N = r.population;
  for (std::size_t rep = 0; rep < s.replicas.size(); ++rep) {
    const TailReplica& x = s.replicas[rep];
    const std::string who = "replica " + std::to_string(rep) + ": ";
    if (x.levels.size() != s.next) return who + "expected one count per level reached";
    for (std::size_t k = 0; k < x.levels.size(); ++k) {
      const TailLevelCount& c = x.levels[k];
      if (c.survivors > c.population || c.ancestors > c.survivors || (c.survivors > 0 && c.ancestors == 0) ||
          c.accepted > c.proposals)
        return who + "a level's counts are inconsistent";
      if (k == 0 && (c.population != x.trials || c.ancestors != c.survivors))
        return who + "stage 0's counts are inconsistent";
      if (k > 0 && c.population != (x.levels[k - 1].survivors > 0 ? N : 0)) return who + "a level's population is not N";
      if (k == 1 && c.ancestors > N) return who + "lineages cannot grow";
      if (k > 0 && c.ancestors > x.levels[k - 1].ancestors) return who + "lineages cannot grow";
    }
    if (s.next == 0) {
      const bool examined = s.age == s.levels[0];
      if (x.orbitsDone > s.entryOrbits || (examined && x.orbitsDone != s.entryOrbits) || x.trials < x.walkers.size() ||
          x.alive.size() != (examined ? x.walkers.size() : 0) || x.walkers.size() > std::uint64_t{UINT32_MAX})
        return who + "stage 0's walkers are inconsistent";
      for (std::size_t w = 0; w < x.walkers.size(); ++w)
        if (x.walkers[w].ancestor != w || x.walkers[w].state.length != s.levels[0] ||
            (examined && x.alive[w] != 1))
          return who + "a stage-0 walker is inconsistent";
      continue;
    }
    // What closeLevel() and propagateChunk() leave (issue 36: a re-signed file whose replica had 28 survivors and
    // no walkers was resumed, and its P beyond that level was wrong).  Under way to level `next`: the walkers are
    // the resampled survivors of level next − 1 (N of them, or none when none survived), each alive exactly when
    // it has the walkers' age (a walker whose segment ended keeps its state at an earlier chunk's start).  Finished:
    // the walkers that set out for the last level are kept, with its counts.
    if (x.orbitsDone != s.entryOrbits) return who + "stage 0's entry orbits are not all examined";
    if (x.alive.size() != x.walkers.size()) return who + "expected one alive flag per walker";
    const TailLevelCount& last = x.levels.back();
    const bool onlyStageZero = s.finished() && s.next == 1;  // level 0 was the last: its successes are the walkers
    const std::uint64_t expectedWalkers = !s.finished() ? (last.survivors > 0 ? N : 0)
                                          : onlyStageZero ? last.survivors
                                                          : last.population;
    if (x.walkers.size() != expectedWalkers)
      return who + "holds " + std::to_string(x.walkers.size()) + " walkers where its counts give " +
             std::to_string(expectedWalkers);
    const std::uint64_t lowest = s.levels[s.finished() && s.next > 1 ? s.next - 2 : s.next - 1];
    std::vector<std::uint32_t> lineages;
    std::uint64_t alive = 0;
    for (std::size_t w = 0; w < x.walkers.size(); ++w) {
      const TailWalker& walker = x.walkers[w];
      if (x.alive[w] > 1) return who + "an alive flag is neither 0 nor 1";
      if (walker.ancestor >= x.levels[0].survivors) return who + "a walker's lineage is not one of stage 0's successes";
      if (x.alive[w] != (walker.state.length == s.age ? 1 : 0) || walker.state.length < lowest ||
          walker.state.length > s.age)
        return who + "a walker's age does not match its alive flag and the level";
      alive += x.alive[w];
      if (!s.finished() || x.alive[w] != 0) lineages.push_back(walker.ancestor);
    }
    std::sort(lineages.begin(), lineages.end());
    const auto distinct = static_cast<std::uint64_t>(std::unique(lineages.begin(), lineages.end()) - lineages.begin());
    // Resampling keeps every lineage of the survivors, but stage 0 may have had more than N (then N of them, once).
    if (s.finished() ? (alive != last.survivors || distinct != last.ancestors) : distinct != std::min(last.ancestors, N))
      return who + "the walkers' lineages or survivors differ from the level's counts";
  }
  return std::nullopt;
}

std::optional<std::uint64_t> segmentAge(const KernelSettings& k, const UnitState& z, std::uint64_t maxBlocks) {
  UnitState lane = z;
  const ScalarStep c(k.coefficients);
  for (std::uint64_t age = 0; age <= maxBlocks; ++age) {
    std::uint8_t wrapped = 0;
    stepLanes<1>(c, MapDirection::forward, &lane, k.q, &wrapped, [](std::uint64_t, const std::uint64_t*,
                                                                     const std::uint64_t*) {});
    if (wrapped || lane.X <= k.randomizingX) return age;  // that block ended the previous segment
  }
  return std::nullopt;
}

namespace {

// The ages of many states at once: kScalarLanes in lockstep (ScalarLanes.hpp), each lane's answer
// decided at its first ended block or after maxBlocks + 1 clean ones.  Returns the steps computed.
std::uint64_t segmentAgesAreExactly(const KernelSettings& k, std::span<UnitState> z, std::uint64_t level,
                                    std::uint8_t* exact) {
  const ScalarStep c(k.coefficients);
  std::uint64_t steps = 0;
  const auto group = [&]<std::size_t Lanes>(UnitState* lanes, std::uint8_t* out) {
    std::uint8_t decided[Lanes] = {};
    std::size_t open = Lanes;
    for (std::uint64_t age = 0; age <= level && open > 0; ++age) {
      std::uint8_t wrapped[Lanes] = {};
      // Each clone's own steps, up to its decision (not the lanes a group carries on past it): so the count is
      // a function of each replica alone, and a distributed run's slices add up to the one-process run's.
      steps += open * k.q;
      stepLanes<Lanes>(c, MapDirection::forward, lanes, k.q, wrapped,
                       [](std::uint64_t, const std::uint64_t*, const std::uint64_t*) {});
      for (std::size_t l = 0; l < Lanes; ++l) {
        if (decided[l] || !(wrapped[l] || lanes[l].X <= k.randomizingX)) continue;
        decided[l] = 1;
        --open;
        out[l] = age == level ? 1 : 0;  // the block before the segment's first ended it: age exactly `level`
      }
    }
    for (std::size_t l = 0; l < Lanes; ++l)
      if (!decided[l]) out[l] = 0;  // older than `level`
  };
  std::size_t i = 0;
  for (; i + kScalarLanes <= z.size(); i += kScalarLanes) group.template operator()<kScalarLanes>(z.data() + i, exact + i);
  for (; i < z.size(); ++i) group.template operator()<1>(z.data() + i, exact + i);
  return steps;
}

// entryOrbitTrials() for n consecutive entry orbits at once, advanced by the block kernel (any path: the orbit
// states are bit-identical), with the same results.  Trials are counted from each lane's histogram (every segment
// that ends in a block of the window starts a trial); a success needs the state at the moment a trial segment
// reaches the level, which the kernel does not stop at: chunks are at most the level long, so only a segment
// already open at a chunk's start can reach the level within it, and such a lane ("candidate": a trial of age a
// with a + chunk ≥ level) is followed again from the chunk's start with advanceOneBlock() for at most level − a
// blocks, which says whether it reaches the level and gives the state there.
std::vector<EntryOrbitResult> entryGroupTrials(const KernelSettings& k, const KernelInfo& kernel,
                                               std::uint64_t firstOrbit, std::size_t n, std::uint64_t warmupBlocks,
                                               std::uint64_t level, std::stop_token stop) {
  std::vector<EntryOrbitResult> out(n);
  std::vector<OrbitState> lanes(n);  // (0, 0): appendix B, step 2
  SegmentSink sink(static_cast<std::uint32_t>(n), 0);  // one histogram per lane: lane i is subset (firstOrbit + i) % n
  const auto segmentsOf = [&](std::size_t i) { return sink.subsets()[(firstOrbit + i) % n].segments(); };
  // The lanes advanced by `blocks`, in calls of at most kStopCheckSteps steps with a look at the stop token
  // between them (the lanes carry the orbits' whole state, so the calls add up to one: the results are the same).
  // False when stopped: the caller discards the group (issue 36: at q = 65536 a group's 1088 blocks ran 68 s
  // between checks).
  const std::uint64_t perCall = std::max<std::uint64_t>(1, kStopCheckSteps / (n * k.q));
  const auto advance = [&](std::uint64_t blocks) {
    for (std::uint64_t done = 0; done < blocks;) {
      if (stop.stop_requested()) return false;
      const std::uint64_t b = std::min(perCall, blocks - done);
      kernel.blocks(k, lanes, firstOrbit, b, sink);
      done += b;
    }
    return true;
  };
  if (!advance(warmupBlocks)) return out;
  std::vector<std::uint64_t> before(n);
  for (std::size_t i = 0; i < n; ++i) before[i] = segmentsOf(i);
  const std::uint64_t chunk = std::max<std::uint64_t>(1, std::min<std::uint64_t>(level / 4, 64));
  std::vector<OrbitState> saved(n);
  std::vector<std::uint8_t> candidate(n);
  for (std::uint64_t done = 0; done < kEntryWindowBlocks;) {
    const std::uint64_t c = std::min(chunk, kEntryWindowBlocks - done);
    for (std::size_t i = 0; i < n; ++i) {
      const OrbitState& s = lanes[i];
      candidate[i] = s.start.block > warmupBlocks && s.length < level && s.length + c >= level ? 1 : 0;
      if (candidate[i]) saved[i] = s;
    }
    if (!advance(c)) return out;
    done += c;
    for (std::size_t i = 0; i < n; ++i) {
      if (!candidate[i]) continue;
      OrbitState s = saved[i];
      while (!advanceOneBlock(k, firstOrbit + i, s, nullptr))
        if (s.length == level) {
          out[i].successes.push_back(s);
          break;
        }
    }
  }
  for (std::size_t i = 0; i < n; ++i) {
    out[i].trials = segmentsOf(i) - before[i];
    out[i].blocks = warmupBlocks + kEntryWindowBlocks;
    OrbitState s = lanes[i];
    if (!(s.start.block > warmupBlocks && s.length < level)) continue;
    for (;;) {  // the trial still open when the window closes
      if (stop.stop_requested()) return out;
      const bool ended = advanceOneBlock(k, firstOrbit + i, s, nullptr);
      ++out[i].blocks;
      if (ended) break;
      if (s.length == level) {
        out[i].successes.push_back(s);
        break;
      }
    }
  }
  return out;
}

using Clock = std::chrono::steady_clock;

class Sampler {
 public:
  Sampler(TailState& s, const TailRunOptions& o, std::stop_token stop)
      : s_(s), stop_(std::move(stop)), threads_(parallelThreads(o.threads)), kernel_(kernelOrBest(o.kernel)),
        k_(blockSettings(s.coefficients, s.request.run.Xr, s.request.run.q, s.request.run.seed)) {
    s_.kernel = std::string(kernel_.name);
  }

  // One unit of work: a stage-0 batch, a chunk of blocks, or a level closed.  False when stopped inside it
  // (the state is then unchanged).
  bool step() {
    if (s_.next == 0 && s_.age == 0) return stageZeroUnit();
    if (s_.age < s_.levels[s_.next]) return propagateChunk();
    return closeLevel();
  }

 private:
  // Consecutive entry orbits [first, first + count) of one stream (a replica's, or the pilot's).
  struct EntryRange {
    std::size_t stream = 0;
    std::uint64_t first = 0, count = 0;
  };

  // The entry orbits of every range, by groups of kEntryGroup, all in one parallel loop (a loop per range of 64
  // orbits spent 87 % of stage 0 in OpenMP's barrier on two loaded cores: 2·10⁷ steps/s at K = 0.35, perf).
  // Per range, the results in orbit order; nothing when stopped (a group may have returned a part).
  std::optional<std::vector<std::vector<EntryOrbitResult>>> entryOrbits(const std::vector<EntryRange>& ranges) {
    std::vector<std::vector<EntryOrbitResult>> results(ranges.size());
    std::vector<std::pair<std::size_t, std::uint64_t>> groups;  // (range, offset of its first orbit)
    for (std::size_t i = 0; i < ranges.size(); ++i) {
      results[i].resize(ranges[i].count);
      for (std::uint64_t j = 0; j < ranges[i].count; j += kEntryGroup) groups.emplace_back(i, j);
    }
    const bool complete = parallelFor(
        groups.size(),
        [&](std::size_t g, int) {
          const auto [i, j] = groups[g];
          const EntryRange& range = ranges[i];
          const std::size_t n = std::min<std::uint64_t>(kEntryGroup, range.count - j);
          const std::uint64_t orbit = entryOrbitIndex(range.stream, range.first + j);
          if (s_.levels[0] < kEntryGroupMinLevel) {
            // A first level of a few blocks makes every open trial a candidate in every chunk of one block: the
            // block-at-a-time reference is then the faster way to the same results.
            for (std::size_t o = 0; o < n; ++o)
              results[i][j + o] = entryOrbitTrials(k_, orbit + o, s_.request.warmupBlocks, s_.levels[0], stop_);
            return;
          }
          std::vector<EntryOrbitResult> r =
              entryGroupTrials(k_, kernel_, orbit, n, s_.request.warmupBlocks, s_.levels[0], stop_);
          std::move(r.begin(), r.end(), results[i].begin() + static_cast<std::ptrdiff_t>(j));
        },
        stop_, threads_);
    if (!complete || stop_.stop_requested()) return std::nullopt;
    return results;
  }

  std::uint64_t stepsOf(const std::vector<EntryOrbitResult>& results) const {
    std::uint64_t blocks = 0;
    for (const EntryOrbitResult& r : results) blocks += r.blocks;
    return blocks * s_.request.run.q;
  }

  // The pilot (TailSampler.hpp, "stage 0"): entry orbits of its own stream until kPilotSuccesses trials reached
  // the first level; then the number of entry orbits per replica.  Its rule is applied after every
  // kEntryOrbitsPerUnit orbits (so pilotOrbits, and every replica's entry orbits, are those of one unit at a time);
  // kPilotUnitsAtOnce units are computed in one loop, and those after the rule has decided are discarded.
  bool pilotUnit() {
    const std::uint64_t units =
        std::max<std::uint64_t>(1, std::min(kPilotUnitsAtOnce, (kMaxPilotOrbits - s_.pilotOrbits) / kEntryOrbitsPerUnit));
    std::vector<EntryRange> ranges;
    for (std::uint64_t u = 0; u < units; ++u)
      ranges.push_back({kPilotStream, s_.pilotOrbits + u * kEntryOrbitsPerUnit, kEntryOrbitsPerUnit});
    const auto r = entryOrbits(ranges);
    if (!r) return false;
    for (const std::vector<EntryOrbitResult>& unit : *r) {
      // Every slice computes the pilot; the slice of replica 0 counts it.
      if (s_.firstReplica == 0) s_.steps += stepsOf(unit);
      if (pilotRule(unit)) break;
    }
    return true;
  }

  // One unit of the pilot's orbits counted; true when the rule has decided: the entry orbits per replica are set,
  // or the first level is out of reach (tailFirstLevelRefusal()).
  bool pilotRule(const std::vector<EntryOrbitResult>& unit) {
    for (const EntryOrbitResult& o : unit) {
      s_.pilotTrials += o.trials;
      s_.pilotSuccesses += o.successes.size();
    }
    s_.pilotOrbits += kEntryOrbitsPerUnit;
    if (s_.pilotSuccesses >= kPilotSuccesses)
      s_.entryOrbits = entryOrbitsPerReplica(s_.request.population, s_.pilotOrbits, s_.pilotSuccesses);
    return s_.entryOrbits != 0 || tailFirstLevelRefusal(s_);
  }

  // Stage 0's next entry orbits of every replica (up to kEntryOrbitsPerReplicaUnit each), in one loop; a stop
  // is honoured between units, and inside one (its work is then discarded).  The walkers and trials of each
  // replica are appended in orbit order, so the units' size does not change the run.
  bool stageZeroUnit() {
    if (s_.entryOrbits == 0) return pilotUnit();
    std::vector<EntryRange> ranges;
    std::vector<std::size_t> replicaOf;
    for (std::size_t rep = 0; rep < s_.replicas.size(); ++rep) {
      const TailReplica& x = s_.replicas[rep];
      if (x.orbitsDone >= s_.entryOrbits) continue;
      ranges.push_back({s_.firstReplica + rep, x.orbitsDone,
                        std::min(kEntryOrbitsPerReplicaUnit, s_.entryOrbits - x.orbitsDone)});
      replicaOf.push_back(rep);
    }
    if (ranges.empty()) {
      // Every replica examined its entry orbits: its successes are level 0's survivors, closed like any level's.
      for (TailReplica& x : s_.replicas) x.alive.assign(x.walkers.size(), 1);
      s_.age = s_.levels[0];
      return true;
    }
    const auto results = entryOrbits(ranges);
    if (!results) return false;
    for (std::size_t i = 0; i < ranges.size(); ++i) {
      TailReplica& x = s_.replicas[replicaOf[i]];
      for (const EntryOrbitResult& o : (*results)[i]) {
        x.trials += o.trials;
        for (const OrbitState& w : o.successes) x.walkers.push_back({w, static_cast<std::uint32_t>(x.walkers.size())});
      }
      x.orbitsDone += ranges[i].count;
      s_.steps += stepsOf((*results)[i]);
    }
    return true;
  }

  bool propagateChunk() {
    const std::uint64_t target = s_.levels[s_.next];
    const std::uint64_t chunk = std::min({target - s_.age, std::max<std::uint64_t>(1, s_.age / kChunkAgeDivisor),
                                          std::max<std::uint64_t>(1, kMaxChunkStepsPerWalker / s_.request.run.q)});
    std::vector<OrbitState> live;
    std::vector<std::pair<std::size_t, std::size_t>> where;
    for (std::size_t rep = 0; rep < s_.replicas.size(); ++rep) {
      const TailReplica& x = s_.replicas[rep];
      for (std::size_t w = 0; w < x.walkers.size(); ++w)
        if (x.alive[w]) {
          live.push_back(x.walkers[w].state);
          where.emplace_back(rep, w);
        }
    }
    const std::size_t per = orbitsPerTask(kernel_, live.size(), threads_);
    std::vector<SegmentSink> sinks(static_cast<std::size_t>(threads_), SegmentSink(1, 0));
    // No stop token: a chunk completes, so that every live walker has the same age.
    parallelFor(
        (live.size() + per - 1) / per,
        [&](std::size_t g, int thread) {
          const std::size_t first = g * per;
          const std::size_t n = std::min(per, live.size() - first);
          // The orbit index only selects random draws, and a draw ends the segment: a dead walker's draws
          // are never looked at.
          kernel_.blocks(k_, std::span<OrbitState>(live.data() + first, n), 0, chunk,
                         sinks[static_cast<std::size_t>(thread)]);
        },
        {}, threads_);
    s_.steps += static_cast<std::uint64_t>(live.size()) * chunk * s_.request.run.q;
    s_.age += chunk;
    for (std::size_t i = 0; i < live.size(); ++i) {
      auto [rep, w] = where[i];
      TailReplica& x = s_.replicas[rep];
      // A walker whose segment ended within the chunk keeps its state at the chunk's start (its last age on a
      // chunk boundary): past the end, the kernel's draws depend on its lane, i.e. on the other walkers and the
      // threads, and would make the state (never used again) differ between runs that agree on every result.
      if (live[i].length == s_.age) x.walkers[w].state = live[i];
      else x.alive[w] = 0;
    }
    return true;
  }

  // The live walkers reached levels[next]: count them, and (below the last level) resample them to N.
  bool closeLevel() {
    const TailRequest& r = s_.request;
    const std::size_t level = s_.next;
    const bool last = level + 1 >= s_.levels.size();
    std::vector<TailLevelCount> counts(s_.replicas.size());
    std::vector<std::vector<TailWalker>> next(s_.replicas.size());
    std::vector<std::vector<std::uint8_t>> isClone(s_.replicas.size());
    for (std::size_t rep = 0; rep < s_.replicas.size(); ++rep) {
      const TailReplica& x = s_.replicas[rep];
      std::vector<std::size_t> survivors;
      for (std::size_t w = 0; w < x.walkers.size(); ++w)
        if (x.alive[w]) survivors.push_back(w);
      std::vector<std::uint32_t> lineages;
      for (std::size_t w : survivors) lineages.push_back(x.walkers[w].ancestor);
      std::sort(lineages.begin(), lineages.end());
      counts[rep].population = level == 0 ? x.trials : x.walkers.size();
      counts[rep].survivors = survivors.size();
      counts[rep].ancestors = static_cast<std::uint64_t>(std::unique(lineages.begin(), lineages.end()) - lineages.begin());
      if (last || survivors.empty()) continue;
      // ⌊N/s⌋ copies each; N mod s survivors, those of the smallest random ranks, one more (when s > N, which only
      // stage 0 can give: the N of the smallest ranks, once each).
      const std::size_t n = r.population, sCount = survivors.size();
      const std::uint64_t key = levelKey(r.run.seed, s_.firstReplica + rep, level);
      std::vector<std::size_t> order(sCount);
      std::iota(order.begin(), order.end(), std::size_t{0});
      std::vector<std::uint64_t> rank(sCount);
      for (std::size_t i = 0; i < sCount; ++i) rank[i] = orbitDraw(key, i + 1);
      std::sort(order.begin(), order.end(),
                [&](std::size_t a, std::size_t b) { return rank[a] != rank[b] ? rank[a] < rank[b] : a < b; });
      std::vector<std::size_t> copies(sCount, n / sCount);
      for (std::size_t e = 0; e < n % sCount; ++e) copies[order[e]] += 1;
      for (std::size_t i = 0; i < sCount; ++i)
        for (std::size_t c = 0; c < copies[i]; ++c) {
          next[rep].push_back(x.walkers[survivors[i]]);
          isClone[rep].push_back(c > 0 ? 1 : 0);
        }
    }
    if (!last && !moveClones(next, isClone, counts, level)) return false;
    for (std::size_t rep = 0; rep < s_.replicas.size(); ++rep) {
      TailReplica& x = s_.replicas[rep];
      x.levels.push_back(counts[rep]);
      if (!last) {
        x.walkers = std::move(next[rep]);
        x.alive.assign(x.walkers.size(), 1);
      }
    }
    s_.stepsAtLevel.push_back(s_.steps);
    s_.next = level + 1;
    return true;
  }

  // Moves every clone: a perturbation, or metropolisSteps Metropolis steps (TailSampler.hpp).
  bool moveClones(std::vector<std::vector<TailWalker>>& next, const std::vector<std::vector<std::uint8_t>>& isClone,
                  std::vector<TailLevelCount>& counts, std::size_t level) {
    const TailRequest& r = s_.request;
    struct Clone {
      std::size_t replica, index;
      std::uint64_t key, counter;
    };
    std::vector<Clone> clones;
    for (std::size_t rep = 0; rep < next.size(); ++rep) {
      const std::uint64_t key = levelKey(r.run.seed, s_.firstReplica + rep, level);
      for (std::size_t c = 0; c < next[rep].size(); ++c)
        if (isClone[rep][c]) clones.push_back({rep, c, orbitKey(key, c), 0});
    }
    if (r.clones == CloneRule::perturb) {
      for (Clone& c : clones) {
        UnitState& z = next[c.replica][c.index].state.z;
        z = moved(z, c.key, c.counter, r.epsilon);
      }
      return true;
    }
    const std::uint64_t age = s_.levels[level];
    std::vector<UnitState> proposal(clones.size()), stepped(clones.size());
    std::vector<std::uint8_t> accept(clones.size());
    std::uint64_t steps = 0;
    for (std::uint32_t m = 0; m < r.metropolisSteps; ++m) {
      for (std::size_t i = 0; i < clones.size(); ++i)
        proposal[i] = moved(next[clones[i].replica][clones[i].index].state.z, clones[i].key, clones[i].counter,
                            r.epsilon);
      stepped = proposal;  // followed back in place
      const std::size_t per = 8 * kScalarLanes;
      std::vector<std::uint64_t> taskSteps((clones.size() + per - 1) / per, 0);
      const bool complete = parallelFor(
          taskSteps.size(),
          [&](std::size_t g, int) {
            const std::size_t first = g * per;
            const std::size_t n = std::min(per, clones.size() - first);
            taskSteps[g] = segmentAgesAreExactly(k_, std::span<UnitState>(stepped.data() + first, n), age,
                                                 accept.data() + first);
          },
          stop_, threads_);
      if (!complete) return false;  // the level is closed again on resume, from the same survivors
      for (std::uint64_t t : taskSteps) steps += t;
      for (std::size_t i = 0; i < clones.size(); ++i) {
        const Clone& c = clones[i];
        counts[c.replica].proposals += 1;
        if (!accept[i]) continue;  // the Metropolis step stays where it was
        next[c.replica][c.index].state.z = proposal[i];
        counts[c.replica].accepted += 1;
      }
    }
    s_.steps += steps;
    return true;
  }

  TailState& s_;
  std::stop_token stop_;
  int threads_;
  const KernelInfo& kernel_;
  KernelSettings k_;
};

}  // namespace

TailState runTail(TailState state, const TailRunOptions& options, const TailObserver& observer, std::stop_token stop) {
  Sampler sampler(state, options, stop);
  const auto sessionStart = Clock::now();
  const std::uint64_t stepsAtStart = state.steps;
  while (!state.finished() && state.next < options.untilLevel && !stop.stop_requested() &&
         !tailFirstLevelRefusal(state)) {
    const auto t0 = Clock::now();
    const bool done = sampler.step();
    const auto now = Clock::now();
    state.elapsedSeconds += std::chrono::duration<double>(now - t0).count();
    if (!done) break;
    if (observer) {
      TailProgress p;
      p.level = state.next;
      p.levels = state.levels.size();
      p.t = static_cast<double>(state.age) * state.request.run.q;
      const double top = std::log(static_cast<double>(state.levels.back()) * state.request.run.q);
      p.fraction = state.finished() ? 1.0 : (p.t > 1 && top > 0 ? std::log(p.t) / top : 0.0);
      p.steps = static_cast<double>(state.steps);
      const double seconds = std::chrono::duration<double>(now - sessionStart).count();
      p.stepsPerSecond = seconds > 0 ? static_cast<double>(state.steps - stepsAtStart) / seconds : 0;
      for (const TailReplica& x : state.replicas)
        p.alive += state.next == 0 ? x.walkers.size()
                                   : static_cast<std::uint64_t>(std::count(x.alive.begin(), x.alive.end(), 1));
      observer(state, p);
    }
  }
  // The request cannot go on (its first level is out of this map's reach): invalid_argument, Python's ValueError
  // (issue 54: it was a RuntimeError), named by its role, not a flag.
  if (const std::optional<std::string> why = tailFirstLevelRefusal(state); why && !options.returnRefused)
    throw TailSettingOutOfReach(*why, "first");
  return state;
}

}  // namespace archipelago
