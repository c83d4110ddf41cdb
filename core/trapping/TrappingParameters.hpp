#pragma once
/// \file TrappingParameters.hpp
/// \brief Settings of a trapping-statistics run (Karney 1983, §3 and appendix B, steps 1–9).

#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "core/limits/Limits.hpp"
#include "core/map/FixedPointMap.hpp"

namespace archipelago {

/// Everything that defines a trapping run, as plain values.  Defaults: the paper's K = 0.1 case (§5).
struct TrappingParameters {
  MapParameters map;              ///< K, xmin, xmax of Q*
  double Xr = 0.02;               ///< randomizing zone 0 ≤ X ≤ Xr, in unit coordinates (appendix B, 6.1)
  std::uint32_t q = 16;           ///< power of N⁻¹ per block: statistics are gathered for N^−q
  std::uint64_t T = 1'000'000;    ///< blocks per orbit (the orbit is qT steps long)
  std::uint64_t M = 64;           ///< number of orbits
  std::uint64_t seed = 1;         ///< seed of the counter-based random numbers (random/CounterRng.hpp)
  std::uint32_t subsets = 16;     ///< orbits are split by index mod subsets, for error estimates
  std::uint32_t longestKept = 100;  ///< how many of the longest segments keep their start state

  friend bool operator==(const TrappingParameters&, const TrappingParameters&) = default;
};

/// The documented limits of the integer parameters (docs/design.md, "no silent wrong answer": every input has a
/// range checked before work starts).  Each bounds the time or memory one value can ask for: q a block's
/// length (a chunk is at least one block, so q bounds the latency of a stop), T so that lengths in steps
/// (blocks × q) fit 63 bits, M the orbit states held, subsets the histograms and the statistics' work,
/// longestKept the records kept and written.
inline constexpr std::uint64_t kMaxQ = limits::kRunQ;  // the one table of limits (core/limits)
inline constexpr std::uint64_t kMaxT = std::uint64_t{1} << 62;
inline constexpr std::uint64_t kMaxStepsPerOrbit = std::uint64_t{1} << 62;  ///< q·T
inline constexpr std::uint64_t kMaxM = std::uint64_t{1} << 32;
inline constexpr std::uint64_t kMaxSubsets = 1024;
inline constexpr std::uint64_t kMaxLongestKept = 100'000;

/// One parameter of TrappingParameters as files, the CLI and the GUI name it: the one table of keys,
/// meanings and ranges.  The JSON codec (runspec/RunSpec.hpp), the CLI's options (--key) and help texts, and
/// validationError() read it.
struct ParameterRule {
  std::string_view key;      ///< JSON key and CLI option --key
  std::string_view meaning;  ///< one line for help texts
  bool integer = false;      ///< a whole number; else a finite real
  std::uint64_t min = 0;     ///< integers: the valid range [min, max]
  std::uint64_t max = 0;
  std::string_view range;    ///< the valid values in words, for help texts and messages
};
[[nodiscard]] std::span<const ParameterRule> parameterRules() noexcept;
/// The rule of `key`, or nullptr.
[[nodiscard]] const ParameterRule* findParameterRule(std::string_view key) noexcept;

/// A parameter's value: a double for the reals (K, xmin, xmax, Xr), a std::uint64_t for the integers.
using ParameterValue = std::variant<double, std::uint64_t>;
/// The value of parameter `key` (one of parameterRules()).  Throws std::invalid_argument for another key.
[[nodiscard]] ParameterValue parameterValue(const TrappingParameters& p, std::string_view key);
/// Sets parameter `key`.  Throws std::invalid_argument naming the key for an unknown key, a value of the
/// other kind, or an integer the member cannot hold (so that no value is ever narrowed silently); the
/// other rules are validationError()'s.
void setParameterValue(TrappingParameters& p, std::string_view key, const ParameterValue& value);

/// Every violated rule (map rules first, then Xr, each integer's range from parameterRules(), q·T, subsets ≤ M),
/// each naming the parameters it is about, so that a form marks every wrong field at once.
[[nodiscard]] std::vector<ParameterError> validationErrors(const TrappingParameters& p);
/// The first of validationErrors(p), or nothing when valid.
[[nodiscard]] std::optional<std::string> validationError(const TrappingParameters& p);
void validate(const TrappingParameters& p);

/// The rule for the randomizing zone's width: Xr finite and in [0, 1).  The message names Xr, or nothing.
[[nodiscard]] std::optional<std::string> randomizingZoneError(double Xr);

/// The largest run file read (a run of 10⁶ orbits takes about 125 MB): a bound checked before reading, so that a
/// wrong path (a disk image, /dev/zero) fails at once instead of exhausting memory; and a bound on M, so that
/// no run writes a file it could not read back (memoryError()).
inline constexpr std::uintmax_t kMaxRunFileBytes = std::uintmax_t{2} << 30;
/// The most bytes one orbit's state takes in a run file (nine 52-bit integers, one per line, indented).
inline constexpr double kRunFileBytesPerOrbit = 200;
/// The most bytes of memory one orbit's state takes while its run file is written (measured ~730).
inline constexpr double kSaveBytesPerOrbit = 800;

/// The memory a run of these parameters needs on `threads` threads (0: one per core), in bytes: the orbit
/// states, the histograms (one set per thread while a chunk runs), the longest segments and the run file's
/// text when it is written.  An estimate within a factor of about two.
[[nodiscard]] std::uint64_t estimatedMemoryBytes(const TrappingParameters& p, int threads) noexcept;

/// An error when estimatedMemoryBytes() exceeds the memory this process may still take (io::availableMemoryBytes:
/// MemAvailable and what RLIMIT_AS leaves), naming both, or when the run's
/// file would exceed kMaxRunFileBytes; checked before a run starts.
[[nodiscard]] std::optional<std::string> memoryError(const TrappingParameters& p, int threads);

/// The q = 1 companion of a run of q > 1 (issue #26; docs/design.md, "Blocks of q steps"): the short-time statistics
/// of the paper's q = 1 process, spliced with the run's at a crossover ≥ 10 q (computeSplicedStatistics).  The same
/// map, Xr, M, subsets and longestKept; q = 1; T = max(1, round(fraction · q · T)) blocks of one step, so that it
/// costs `fraction` of the run's steps; the seed mix64(seed ⊕ kCompanionSeedSalt), another member of the seed's
/// family, so that its random numbers are independent of the run's yet reproducible from the run's spec.
/// Throws std::invalid_argument for q = 1 (no companion is needed) or a fraction outside (0, 1].
[[nodiscard]] TrappingParameters companionParameters(const TrappingParameters& p, double fraction);
inline constexpr std::uint64_t kCompanionSeedSalt = 0x436f6d70616e696fULL;  // "Companio"

/// ⌊Xr·2^52⌋, the largest X inside the randomizing zone, for a valid Xr (randomizingZoneError); defined for every
/// double (NaN and Xr ≤ 0: 0; Xr ≥ 1: 2^52), never the undefined conversion of an out-of-range value.
[[nodiscard]] std::uint64_t randomizingThreshold(double Xr) noexcept;

/// The state of one orbit at the start of a trapped segment: enough to replay the segment bit for bit.
struct SegmentStart {
  UnitState z;               ///< state before the segment's first block
  std::uint64_t block = 0;   ///< index of the segment's first block (0-based) in its orbit
  std::uint64_t draws = 0;   ///< random draws the orbit had used before that block
  friend bool operator==(const SegmentStart&, const SegmentStart&) = default;
};

/// One orbit's complete state between blocks (what a checkpoint stores).
struct OrbitState {
  UnitState z;               ///< current state
  std::uint64_t block = 0;   ///< blocks done so far
  std::uint64_t draws = 0;   ///< random draws used so far
  std::uint64_t length = 0;  ///< blocks in the current, still open segment
  SegmentStart start;        ///< where the open segment started
  friend bool operator==(const OrbitState&, const OrbitState&) = default;
};

/// An orbit's state as one row of 9 numbers: X, Y, block, draws, length, start X, start Y, start block, start draws.
/// The one order of the run file's "orbits", the tail file's walkers and the Python module's orbit_states().
inline constexpr std::size_t kOrbitStateRowSize = 9;
using OrbitStateRow = std::array<std::uint64_t, kOrbitStateRowSize>;
[[nodiscard]] OrbitStateRow orbitStateRow(const OrbitState& o) noexcept;
/// The state of a row (X, Y and start X, Y < 2^52: the reader's to check, orbitStateRowMax).
[[nodiscard]] OrbitState orbitStateOfRow(const OrbitStateRow& row) noexcept;
/// The largest value of each column of a row: 2^52 − 1 for the four coordinates, 2^64 − 1 for the counts.
[[nodiscard]] std::uint64_t orbitStateRowMax(std::size_t column) noexcept;

/// A finished segment with its start state.
struct SegmentRecord {
  std::uint64_t orbit = 0;
  std::uint64_t length = 0;  ///< in blocks
  SegmentStart start;
  friend bool operator==(const SegmentRecord&, const SegmentRecord&) = default;
};

}  // namespace archipelago
