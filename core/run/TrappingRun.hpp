#pragma once
/// \file TrappingRun.hpp
/// \brief Trapping-statistics runs: M orbits × T blocks of N^−q (Karney 1983, §3, appendix B).
///
/// A run is a value, TrappingState: parameters, the integer map coefficients, every orbit's state, the
/// subset histograms and the longest segments.  runTrapping() advances it chunk by chunk, in parallel over
/// orbits (parallel/ParallelFor.hpp), calling an observer at each chunk boundary and honouring a stop token there.  Each
/// orbit depends only on (seed, orbit index), so the result does not depend on the number of threads, on the
/// chunk sizes, or on being stopped and resumed; any range of orbit indices can run alone and the results be
/// merged (mergeTrapping), which is how checkpoints and (later) MPI ranks share one mechanism.

#include <cstdint>
#include <functional>
#include <optional>
#include <stop_token>
#include <string>
#include <string_view>
#include <vector>

#include "core/kernels/KernelDispatch.hpp"
#include "core/trapping/BlockKernel.hpp"

namespace archipelago {

struct TrappingState {
  TrappingParameters params;
  MapCoefficients coefficients;        ///< the map, exactly; derived from params.map
  std::uint64_t orbitBegin = 0;        ///< this state covers orbits [orbitBegin, orbitEnd)
  std::uint64_t orbitEnd = 0;
  std::uint64_t blocksDone = 0;        ///< every orbit has done this many blocks (≤ params.T)
  std::vector<OrbitState> orbits;      ///< orbitEnd − orbitBegin entries
  std::vector<TrappingHistogram> subsets;  ///< params.subsets histograms; orbit i goes to subset i mod subsets
  LongestSegments longest;
  double elapsedSeconds = 0;           ///< compute time, summed over every session of the run
  std::string kernel;                  ///< the kernel that computed it last
  /// Read from a file whose checksum did not match its content or that had none (format version 1), with
  /// RunFileReadOptions::allowModified: such a state is never written back as a checksummed run file
  /// (runFileText refuses it), so an edit cannot be laundered into a file that looks verified (issue #23).
  bool unverified = false;

  [[nodiscard]] bool finished() const noexcept { return blocksDone >= params.T; }
  /// The sum of the subset histograms.
  [[nodiscard]] TrappingHistogram total() const;
  /// Steps of N⁻¹ done so far: (orbitEnd − orbitBegin) · blocksDone · q.
  [[nodiscard]] double stepsDone() const noexcept;
};

/// orbitEnd of startTrapping(): all M orbits.
inline constexpr std::uint64_t kAllOrbits = UINT64_MAX;

/// The rule of an orbit range [begin, end) of a run of M orbits (issue 35: the one rule, and its one message, for the
/// CLI's --orbits, Python's start_range and the MPI ranks): "orbits [begin, end) must satisfy begin < end ≤ M = …",
/// or nothing.
[[nodiscard]] std::optional<std::string> orbitRangeError(std::uint64_t M, std::uint64_t begin, std::uint64_t end);

/// The rule of a run's M orbits split into `count` parts that each hold an orbit (archipelago-mpi's ranks):
/// "<count> <parts> for M = <M> orbits: use at most M <parts>", or nothing.  `parts` names them ("ranks").
[[nodiscard]] std::optional<std::string> orbitPartsError(std::uint64_t count, std::uint64_t M, std::string_view parts);

/// A fresh run over orbits [orbitBegin, orbitEnd) (kAllOrbits: all M); validates the parameters and the range
/// (orbitRangeError: a range beyond M is refused, never cut silently).
[[nodiscard]] TrappingState startTrapping(const TrappingParameters& params, std::uint64_t orbitBegin = 0,
                                          std::uint64_t orbitEnd = kAllOrbits);

/// Merges two states of the same run (same parameters, same blocksDone) over adjacent orbit ranges.
/// Throws std::invalid_argument when they do not fit together.
[[nodiscard]] TrappingState mergeTrapping(const TrappingState& a, const TrappingState& b);
/// Appends `hi` (the adjacent range above) to `lo` in place: orbits, subset histograms, longest segments,
/// elapsed time.  The same checks as mergeTrapping(); the merge of many ranges (runfile/RunFileMerge.hpp) uses it
/// so that its cost is proportional to bins + segments + orbits.
void appendTrappingRange(TrappingState& lo, const TrappingState& hi);

/// Progress at a chunk boundary.
struct TrappingProgress {
  std::uint64_t blocksDone = 0;
  std::uint64_t blocksTotal = 0;
  double fraction = 0;          ///< blocksDone / blocksTotal
  double stepsPerSecond = 0;    ///< this session's rate of N⁻¹ steps
  double etaSeconds = 0;        ///< at this rate
  double sessionSeconds = 0;    ///< wall time of this session so far
};

/// Called on the computing thread at every chunk boundary (never inside a parallel region).
using TrappingObserver = std::function<void(const TrappingState&, const TrappingProgress&)>;

struct TrappingRunOptions {
  int threads = 0;              ///< 0: OpenMP's default
  double chunkSeconds = 0.25;   ///< target wall time of a chunk (progress and stop granularity)
  std::uint64_t maxChunkBlocks = 0;  ///< 0: no limit; otherwise chunks have at most this many blocks
  /// 0: run to T; otherwise return when blocksDone reaches min(untilBlocks, T) (a chunk never passes it): how
  /// the ranks of a distributed run meet at a common block boundary (app/mpi).
  std::uint64_t untilBlocks = 0;
  /// The instruction-set path, chosen by the caller (selectKernel() at the CLI or GUI edge); its name goes into
  /// TrappingState::kernel.  nullptr: bestKernel(), the fastest this CPU supports.  Every path gives
  /// bit-identical results.
  const KernelInfo* kernel = nullptr;
};

/// The rule of a chunk's target wall time: "chunk_seconds = <s> must lie in (0, 3600]", or nothing.
[[nodiscard]] std::optional<std::string> chunkSecondsError(double chunkSeconds);

/// The rule of a subset's index among a run's `count` subsets: "subset = <i> must lie in [0, count − 1]", or nothing.
[[nodiscard]] std::optional<std::string> subsetIndexError(std::uint64_t index, std::uint64_t count);

/// Advances `state` until it is finished or `stop` is requested (checked at chunk boundaries: a chunk always
/// completes, so that every orbit has done the same number of blocks).  An exception thrown while computing
/// (e.g. std::bad_alloc from a thread's longest-segment list) is rethrown here after the parallel region; the
/// state passed in is then lost.
[[nodiscard]] TrappingState runTrapping(TrappingState state, const TrappingRunOptions& options,
                                        const TrappingObserver& observer = {}, std::stop_token stop = {});

/// Replays a recorded segment bit for bit from its start state, calling visit(step, z) for its first point
/// (step 0) and after every step of N⁻¹ (steps 1 … q·length).  Returns record.length.  A replay never runs
/// past the record: when the segment does not end exactly after record.length blocks (a record of other
/// parameters, or an edited one), it throws std::runtime_error "replay mismatch: …" (at most record.length
/// blocks replayed, never up to T).  A segment cut by the run's last block (start.block + length = T) ends
/// there.
std::uint64_t replaySegment(const TrappingParameters& params, const SegmentRecord& record,
                            const std::function<void(std::uint64_t step, const UnitState& z)>& visit);

/// The general replay: as replaySegment(), but visit returns false to end the replay early (after the current
/// block), and `stop` is checked every 4096 blocks.  Returns the blocks replayed, or nothing when stopped.
/// Throws "replay mismatch" as replaySegment() unless visit ended the replay before the record's end.
[[nodiscard]] std::optional<std::uint64_t> replaySegmentUntil(
    const TrappingParameters& params, const SegmentRecord& record,
    const std::function<bool(std::uint64_t step, const UnitState& z)>& visit, std::stop_token stop = {});

}  // namespace archipelago
