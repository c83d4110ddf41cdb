#pragma once
/// \file TailSampler.hpp
/// \brief The tail of P_t beyond brute force: fixed-population splitting on the age of a trapped segment
/// (issue #29), for exactly the process of `run` (Karney 1983, §3 and appendix B; docs/design.md, "Trapping
/// statistics" and "Rare-event tail").
///
/// Glossary (lengths in blocks of q steps, as the trapping block counts them; t = q·blocks in steps):
///   - segment, age   — a trapped segment of the run process (BlockKernel.hpp: the randomizing zone, q steps of
///                      N⁻¹, a wrap or the zone ends it).  A walker's age is the blocks its segment has lasted.
///   - level L_k      — an age.  A walker "reaches" L_k when its segment lasts more than L_k blocks, so
///                      P(t_k) = Pr(length > L_k) = P_t of eq. (pdef) at t = q·L_k, exactly.  Levels are
///                      chosen so that L_k + 1 is a lower edge of TrappingHistogram's bins: there a run's
///                      histogram gives the brute-force P_t exactly (BruteForceSurvival.hpp).
///   - entry orbit    — an orbit of the run process itself (its block, its seed, its random numbers): entry orbit
///                      j of stream r is orbit 2^63 + r·2^40 + j (`run` uses orbits below 2^32, so never the same
///                      ones).  Replica r is stream r, the pilot stream 2^23 − 1.  It runs warmupBlocks blocks
///                      (the record's start on X = 0 forgotten), then a window of kEntryWindowBlocks blocks: every
///                      segment that starts in the window (after a block of the window ended the previous one) is
///                      a trial, followed until it ends or reaches L_0 — the one still open when the window closes
///                      too.  A trial that reaches L_0 is a success: its state at age L_0 is kept, and the orbit
///                      goes on through it (the window is fixed in advance, never cut by an outcome).
///   - stage 0        — a brute-force estimate of P(t_0) and the first population.  A pilot (its own stream, entry
///                      orbits until kPilotSuccesses successes) sizes it: every replica then examines the same
///                      number of entry orbits, entryOrbitsPerReplica(), expecting kEntrySuccessTarget·N successes.
///                      P_r(t_0) = successes/trials, the estimator of `run` (each segment counts once); the pilot is
///                      independent of the replicas, so the number of orbits is not an outcome of their data.  The
///                      successes are level 0's survivors, resampled to N like any level's (N of them when there
///                      are more, each its own lineage).
///   - splitting      — the population (N walkers at age L_k) is advanced by the block kernel (any path of
///                      core/kernels: bit-identical) until age L_{k+1}; the s walkers still in their segment
///                      survive, and P(t_{k+1}) = P(t_k)·s/N.  The survivors are resampled to N: each gets ⌊N/s⌋
///                      copies and N mod s of them, chosen at random, one more; a survivor's first copy is
///                      itself, the others are clones.  A clone inherits its parent's ancestor.
///   - clone rule     — perturb (the default, docs/tail.md says why): a clone is its parent moved by (δX, δY), each
///                      uniform in [−ε, ε] lattice units (2^−52 of the box), not both 0.  The map is exact and
///                      one-to-one, so the clone's future is exactly that of its own state.  metropolis: the move is a Metropolis step whose
///                      target is the uniform law on the states of age exactly L_k (what the process puts at
///                      age L_k: the block is doubly stochastic, so the stationary law is uniform on the
///                      lattice of the stochastic region, and age is a function of the state).  The proposal is
///                      accepted when its past, followed back with the exact inverse N (FixedPointMap.hpp's
///                      forwardStep, same wrap rule), has L_k blocks without a wrap or a start in the zone and
///                      a block before them that ended the previous segment; otherwise the clone stays at its
///                      parent's state.  That step preserves the target exactly (Leitão, Lopes & Altmann, PRL
///                      110 (2013) 220601; PRE 90 (2014) 052916, sample initial conditions by Metropolis steps
///                      restricted to trajectories still trapped).  metropolisSteps steps are made per clone.
///                      Measured at K = 0.1, almost every move is rejected (the past of a trapped state holds the
///                      chaotic approach to the trap, so the exact-age states form a dust at the lattice's scale):
///                      the clones stay copies of their parents.
///   - lineages       — the distinct ancestors among a level's survivors, per replica.  A level whose replicas
///                      hold fewer than minAncestors lineages in all is unreliable (TailResult.hpp).
///   - replicas       — R independent populations (their own entry orbits and random choices); the error of
///                      P(t_k) is the standard error of the mean over replicas.
///   - slice          — the replicas [first, first + count) of a request, run on their own (a process of a
///                      distributed run: `tail --slice`, `archipelago-mpi tail`).  Replica r's work depends only on
///                      r and the pilot, which every slice computes alike (it is deterministic and small); the
///                      slice holding replica 0 counts the pilot's steps, the others do not.  So the merge of
///                      slices that tile [0, R) (mergeTailSlices()) is the one-process run, bit for bit, steps
///                      included; only the compute time (the slices' sum) and the kernel's name may differ.
///
/// Random choices (which survivors get an extra copy, the moves) use core/random's counter generator with the
/// run's seed: the key of replica r at level k is orbitKey(seed, 2^62 + r·2^24 + k), the draws of its i-th
/// survivor's rank orbitDraw(key, i + 1), and those of new walker c the draws of orbitKey(key, c).  So a
/// sampler run is a pure function of its request: bit for bit the same on any number of threads, any kernel,
/// and across stops and resumes (chunk sizes depend only on ages, never on time).
///
/// Cost: stage 0 takes about kEntrySuccessTarget·N·α / P(t_0) steps per replica (α the mean segment length, steps),
/// a brute-force run up to t_0 at the block kernel's speed; splitting takes, at each level, the ages its walkers
/// reach within it, which grows like t_k once the survivors sit in deep traps (measured at K = 0.1, N = 800, R = 16:
/// 0.38 N R t_max for the level from 4.7·10⁶ to t_max = 10⁷, 0.68 N R t_max for the whole splitting; docs/tail.md).

#include <cstdint>
#include <functional>
#include <optional>
#include <stdexcept>
#include <stop_token>
#include <string>
#include <utility>
#include <vector>

#include "core/kernels/KernelDispatch.hpp"
#include "core/trapping/BlockKernel.hpp"
#include "core/trapping/TrappingParameters.hpp"

namespace archipelago {

enum class CloneRule { perturb, metropolis };

/// A request the sampler finds out of the map's reach only while it runs (the pilot of stage 0: the first level is
/// too high for this map), naming the setting to change by its role ("first"); runTailJob (TailJob.hpp) names it as
/// the front end does (--first, first=…).  what() ends "(role)".
class TailSettingOutOfReach : public std::invalid_argument {
 public:
  TailSettingOutOfReach(const std::string& text, std::string role)
      : std::invalid_argument(text + " (" + role + ")"), text_(text), role_(std::move(role)) {}
  [[nodiscard]] const std::string& role() const noexcept { return role_; }
  /// The text with the setting named `name`.
  [[nodiscard]] std::string namedAs(const std::string& name) const { return text_ + " (" + name + ")"; }

 private:
  std::string text_, role_;
};

/// "perturb" or "metropolis".
[[nodiscard]] const char* cloneRuleName(CloneRule rule) noexcept;
/// The rule called `name`; nothing for another name.
[[nodiscard]] std::optional<CloneRule> cloneRuleByName(std::string_view name) noexcept;

/// The fewest lineages, summed over the replicas, at a reliable level (docs/tail.md: measured).
inline constexpr std::uint64_t kDefaultMinAncestors = 20;

/// Everything that defines a sampler run.  The defaults are issue #29's acceptance run at K = 0.1.
struct TailRequest {
  /// The process: map, box, Xr, q and seed of a run spec (T, M, subsets and longestKept do not apply).
  TrappingParameters run;
  std::uint32_t population = 200;             ///< N, walkers per replica: 2 … kMaxTailPopulation
  std::uint32_t replicas = 4;                 ///< R: 1 … kMaxTailReplicas (the error needs 2)
  std::uint64_t firstSteps = 1000;            ///< the first level is the lowest one at or above this (steps)
  std::uint64_t maxSteps = 10'000'000;        ///< the last level is the lowest one at or above this (steps)
  std::uint32_t binsPerLevel = 10;            ///< level spacing in histogram bins (30 a decade): 10 = ×2.15
  std::uint64_t epsilon = 1'000'000;          ///< clone moves: each coordinate within ±ε lattice units (docs/tail.md)
  CloneRule clones = CloneRule::perturb;
  std::uint32_t metropolisSteps = 1;          ///< Metropolis steps per clone (clone rule metropolis)
  std::uint64_t warmupBlocks = 64;            ///< blocks an entry orbit runs before its window of trials
  std::uint64_t minAncestors = kDefaultMinAncestors;  ///< lineages a reliable level needs (all replicas)

  friend bool operator==(const TailRequest&, const TailRequest&) = default;
};

/// The documented limits (checked by tailRequestError() before any work).
inline constexpr std::uint32_t kMaxTailPopulation = 1'000'000;
inline constexpr std::uint32_t kMaxTailReplicas = 4096;
inline constexpr std::uint64_t kMaxTailEpsilon = std::uint64_t{1} << 40;
inline constexpr std::uint32_t kMaxMetropolisSteps = 64;
inline constexpr std::uint64_t kMaxWarmupBlocks = std::uint64_t{1} << 20;
/// Stage 0: the window of an entry orbit (blocks), the pilot's successes, its largest number of entry orbits (then
/// the first level is out of reach: an error naming --first), and the successes a replica's entry orbits are sized
/// for, per walker.
inline constexpr std::uint64_t kEntryWindowBlocks = 1024;
inline constexpr std::uint64_t kPilotSuccesses = 32;
inline constexpr std::uint64_t kMaxPilotOrbits = std::uint64_t{1} << 24;
/// The pilot gives up (an error naming --first) when this many segments gave fewer than kPilotSuccesses/8
/// successes: P(t_0) ≲ 2·10⁻⁷, where stage 0 would need more than 10⁷ N segments a replica (at K = 0.1 that is
/// t_0 ≳ 10⁵ steps; a map without sticky islands, K ≤ 0, gives up within seconds).
inline constexpr std::uint64_t kPilotTrials = std::uint64_t{1} << 24;
inline constexpr std::uint64_t kEntrySuccessTarget = 2;
inline constexpr std::size_t kPilotStream = (std::size_t{1} << 23) - 1;
inline constexpr std::uint32_t kMaxBinsPerLevel = 300;   ///< ten decades a level
inline constexpr std::uint64_t kMaxTailSteps = std::uint64_t{1} << 60;  ///< t_max (steps)
inline constexpr std::size_t kMaxTailWalkers = 16'000'000;  ///< N·R: the population held in memory (≈ 1.3 GB)

/// The first violated rule of the request (the run's map, Xr and q by their own rules; N ≥ 2, R ≥ 1 and the
/// limits above; 1 ≤ firstSteps ≤ maxSteps; ε ≥ 1; …), naming the option, or nothing.
[[nodiscard]] std::optional<std::string> tailRequestError(const TailRequest& r);

/// The levels of a request, in blocks: L_k + 1 = e(j_0 + k·binsPerLevel), e(j) = ⌈10^(j/30)⌉ (the lower edge of
/// histogram bin j when j > 50), j_0 the smallest j with q·L ≥ firstSteps, up to and including the first level
/// with q·L ≥ maxSteps.  Throws std::invalid_argument as tailRequestError().
[[nodiscard]] std::vector<std::uint64_t> tailLevels(const TailRequest& r);

/// One replica's count at one level.
struct TailLevelCount {
  std::uint64_t population = 0;  ///< walkers that set out for the level (level 0: the trials examined)
  std::uint64_t survivors = 0;   ///< that reached it
  std::uint64_t ancestors = 0;   ///< distinct lineages among the survivors
  std::uint64_t proposals = 0;   ///< Metropolis moves proposed when the survivors were resampled (0: perturb)
  std::uint64_t accepted = 0;    ///< and accepted
  friend bool operator==(const TailLevelCount&, const TailLevelCount&) = default;
};

/// A walker: a segment of the run process at some age (state.length, blocks), and its lineage.
struct TailWalker {
  OrbitState state;
  std::uint32_t ancestor = 0;
  friend bool operator==(const TailWalker&, const TailWalker&) = default;
};

struct TailReplica {
  std::vector<TailLevelCount> levels;  ///< one per level reached
  std::vector<TailWalker> walkers;     ///< stage 0: the successes so far; then the population (alive or not)
  std::vector<std::uint8_t> alive;     ///< per walker, while a level is under way
  std::uint64_t orbitsDone = 0;        ///< stage 0: entry orbits examined
  std::uint64_t trials = 0;            ///< stage 0: trials examined
  friend bool operator==(const TailReplica&, const TailReplica&) = default;
};

/// A sampler run as a value: the request, its levels, and where every replica stands.  Between calls it is
/// always at a consistent point (a whole stage-0 batch, a whole chunk of blocks, or a level resampled), which is
/// what a tail file stores and resumes (TailFile.hpp).
struct TailState {
  TailRequest request;
  MapCoefficients coefficients;          ///< of request.run.map
  std::vector<std::uint64_t> levels;     ///< blocks (tailLevels())
  /// The level the walkers are heading for: 0 during stage 0; levels.size() when finished.
  std::size_t next = 0;
  /// Blocks the live walkers have lasted: 0 while stage 0 examines entry orbits, levels[0] once it has (level 0 is
  /// then closed next).
  std::uint64_t age = 0;
  std::uint64_t pilotOrbits = 0, pilotTrials = 0, pilotSuccesses = 0;  ///< stage 0's pilot so far
  std::uint64_t entryOrbits = 0;         ///< per replica, once the pilot is done (0 before)
  /// The replicas [firstReplica, firstReplica + replicas.size()): all R from 0, or a slice of them.
  std::uint32_t firstReplica = 0;
  std::vector<TailReplica> replicas;
  std::uint64_t steps = 0;               ///< steps of N⁻¹ and N the sampler computed (exact, thread-independent)
  std::vector<std::uint64_t> stepsAtLevel;  ///< `steps` when each level was reached
  double elapsedSeconds = 0;             ///< compute time over every session
  std::string kernel;                    ///< the kernel that computed it last

  [[nodiscard]] bool finished() const noexcept { return next >= levels.size(); }
  friend bool operator==(const TailState&, const TailState&) = default;
};

/// A fresh sampler run.  Throws std::invalid_argument (tailRequestError()) for a bad request.
[[nodiscard]] TailState startTail(const TailRequest& request);

/// The replicas [⌊R·i/n⌋, ⌊R·(i+1)/n⌋) of R: slice i of n, as the ranks of a distributed run take them.
struct ReplicaRange {
  std::uint32_t first = 0, count = 0;
};
/// Throws std::invalid_argument unless 0 ≤ i < n ≤ R (every slice holds a replica).
[[nodiscard]] ReplicaRange replicaSlice(std::uint32_t replicas, std::uint32_t i, std::uint32_t n);
/// A fresh run of the replicas `range` of the request ("slice" above).  Throws std::invalid_argument for a bad
/// request or a range that is empty or beyond R.
[[nodiscard]] TailState startTailSlice(const TailRequest& request, ReplicaRange range);
/// The one-process state of finished slices that tile the replicas [0, R) (in any order): their replicas in
/// order, their steps summed (the pilot's counted once, by the slice of replica 0), and their compute times
/// summed.  Throws std::invalid_argument naming the first problem (no slices, another request, an unfinished
/// slice, a gap or an overlap, pilots that differ).
[[nodiscard]] TailState mergeTailSlices(std::vector<TailState> slices);

/// Where the sampler stands, at each chunk boundary.
struct TailProgress {
  std::size_t level = 0;          ///< the level under way (TailState::next)
  std::size_t levels = 0;         ///< of
  double t = 0;                   ///< its age so far (steps); stage 0: 0
  double fraction = 0;            ///< of log t_max reached (a rough share of the work)
  double steps = 0;               ///< TailState::steps
  double stepsPerSecond = 0;      ///< this session's rate
  std::uint64_t alive = 0;        ///< walkers still in their segment (stage 0: successes so far)
};

using TailObserver = std::function<void(const TailState&, const TailProgress&)>;

struct TailRunOptions {
  int threads = 0;                  ///< 0: OpenMP's default
  const KernelInfo* kernel = nullptr;  ///< nullptr: bestKernel(); every path gives the same result
  /// When set: return once the walkers head for this level (or beyond); a test's way to stop at a known point.
  std::size_t untilLevel = SIZE_MAX;
  /// A first level out of the map's reach (tailFirstLevelRefusal()): false: TailSettingOutOfReach is thrown; true:
  /// the state is returned as the pilot left it (a scan keeps it in the K's file and goes on to the next K).
  bool returnRefused = false;
};

/// Why the first level of `state` is out of this map's reach, once its pilot has shown it ("stage 0" above: fewer
/// than kPilotSuccesses/8 successes in kPilotTrials segments, P(t_0) ≲ 2·10⁻⁷, or kMaxPilotOrbits entry orbits
/// without kPilotSuccesses), naming the pilot's counts; nothing otherwise (not yet known, or within reach).
[[nodiscard]] std::optional<std::string> tailFirstLevelRefusal(const TailState& state);

/// Advances `state` until finished or `stop` is requested (checked between chunks; a stopped state is at a
/// consistent point and resumes bit for bit).  The observer is called on this thread between chunks.  A first level
/// out of reach throws TailSettingOutOfReach (role "first"), or returns the state (options.returnRefused).
[[nodiscard]] TailState runTail(TailState state, const TailRunOptions& options, const TailObserver& observer = {},
                                std::stop_token stop = {});

/// Checks the consistency of a state read from a file (sizes, ages, ancestors, levels): the first problem, or
/// nothing.  The state's request is checked by tailRequestError() and its levels against tailLevels().
[[nodiscard]] std::optional<std::string> tailStateError(const TailState& state);

/// The index of entry orbit j of stream `replica` (a replica's, or kPilotStream): 2^63 + replica·2^40 + j.
[[nodiscard]] std::uint64_t entryOrbitIndex(std::size_t replica, std::uint64_t j);

/// What one entry orbit gives stage 0: its trials, the states at age `level` of those that reached it (in order),
/// and the blocks it took.
struct EntryOrbitResult {
  std::uint64_t trials = 0;
  std::vector<OrbitState> successes;
  std::uint64_t blocks = 0;
  friend bool operator==(const EntryOrbitResult&, const EntryOrbitResult&) = default;
};
/// The reference definition, one block at a time (advanceOneBlock()): orbit `orbit` of the run process (settings:
/// its map, Xr, q, seed) from (0, 0), warmupBlocks blocks, then its window (see "entry orbit" above).  The sampler
/// computes the same with the block kernel, 32 orbits at a time (a test checks them equal, on every kernel).
/// A stop request (looked at every block) returns at once with what was found so far, which the sampler discards.
[[nodiscard]] EntryOrbitResult entryOrbitTrials(const KernelSettings& settings, std::uint64_t orbit,
                                                std::uint64_t warmupBlocks, std::uint64_t level,
                                                std::stop_token stop = {});
/// The entry orbits each replica examines: ⌈kEntrySuccessTarget·N·pilotOrbits/pilotSuccesses⌉.
[[nodiscard]] std::uint64_t entryOrbitsPerReplica(std::uint32_t population, std::uint64_t pilotOrbits,
                                                  std::uint64_t pilotSuccesses);

/// The age of the state z in the run process: the number of blocks back, at most maxBlocks + 1, to the block
/// that ended the previous segment, followed with the exact inverse N.  Returns the age when it is ≤ maxBlocks
/// and nothing when the past has more than maxBlocks clean blocks.  (The Metropolis rule accepts a move to z
/// when segmentAge(z, L_k) == L_k.)
[[nodiscard]] std::optional<std::uint64_t> segmentAge(const KernelSettings& settings, const UnitState& z,
                                                      std::uint64_t maxBlocks);

}  // namespace archipelago
