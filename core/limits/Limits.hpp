#pragma once
/// \file Limits.hpp
/// \brief The one table of limits (issue 35, item 2; docs/design.md, "Front ends fill, call and format"): the
/// largest thread count, raster, q, orbit length and seed grid that anything accepts, and the one wording of a
/// value outside its range.  Every request's validation reads its bound here; `--help`, docs/cli.md and the
/// Python module's messages come from the validations, so a limit is written once.  A test
/// (architecture.limits) fails when one of these numbers appears as a bound outside this file.
///
/// Why each bound:
///  - threads: each thread of a run holds its own histograms while a chunk runs; 256 is more than any one node
///    had when this was written, and a larger machine runs ranks (archipelago-mpi).
///  - raster side 16384: a portrait of 16384² pixels holds 2^28 counts (1 GiB), the most the GUI and the PNG
///    writer hold at once; an indicator map measures one orbit per pixel and keeps a verdict and values per pixel:
///    2^24 pixels in all.
///  - q of a run 65536: the histograms count blocks in 32-bit bins per chunk; q of a portrait's or b₂'s blocks
///    4096: a raster pass checks its stop token between blocks, and a block of 4096 steps keeps that under 1 ms.
///  - orbit length 10^8 points: an orbit held in memory (X, Y, x, y and a flag per point: 33 bytes) is 3.3 GB.
///  - Markov tree 2048 states: its survival's eigen-decomposition holds n² long doubles (64 MiB) and takes about
///    10 n³ operations (10¹¹: a minute or two); each state's part at each time is one value, 2^26 of them at most
///    (1 GiB, and the JSON that writes them) — issue 54: an atlas of 20,000 chains asked 6.4 GB per matrix.

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <utility>

namespace archipelago {

namespace limits {
inline constexpr int kThreads = 256;                        ///< threads of any computation (0: one per core)
inline constexpr int kRasterSide = 16384;                   ///< pixels each way of any raster
inline constexpr std::uint64_t kIndicatorPixels = 1ULL << 24;  ///< pixels of an indicator map in all
inline constexpr std::uint64_t kRunQ = 65536;               ///< steps of N⁻¹ per block of a run
inline constexpr std::uint64_t kRasterQ = 4096;             ///< steps per block of a portrait's or b₂'s orbits
inline constexpr std::uint64_t kRasterOrbits = 65536;       ///< orbits in parallel in a portrait or b₂
inline constexpr std::uint64_t kSeedGridSide = 4096;        ///< seeds each way of a portrait's seed grid
inline constexpr std::uint64_t kOrbitLength = 100'000'000;  ///< points of one orbit held in memory
inline constexpr std::uint64_t kPortraitBudgetMin = 1'000'000;      ///< points a portrait accumulates: the least
inline constexpr std::uint64_t kPortraitBudget = 1'000'000'000'000;  ///< … and the most (hours of accumulation)
inline constexpr std::uint64_t kSeeds = 1000;   ///< seeds of one seed ensemble (each a whole run)
inline constexpr int kChainRows = 1000;        ///< rows of the GUI's segment table whose chain is named by itself
inline constexpr double kScriptSeconds = 86400;  ///< the longest a scripted GUI run waits (a day: more is a typo)
inline constexpr int kMarkovTreeStates = 2048;  ///< states of a Markov tree whose survival is computed
inline constexpr std::uint64_t kMarkovTreeValues = 1ULL << 26;  ///< its survival's values: states × times
}  // namespace limits

/// One row of the table, for `--help`, the docs and the tests.
struct LimitInfo {
  std::string_view key;      ///< the name a request and a front end give the value
  std::string_view what;
  long long min = 0, max = 0;
};

/// Every limit above, in the order of the table.
[[nodiscard]] std::span<const LimitInfo> limitsTable() noexcept;

/// The table as Markdown (docs/cli.md holds it between the markers `<!-- limits -->` and `<!-- /limits -->`;
/// `archipelago-cli limits` prints it and ctest cli.limits checks that the two agree).
[[nodiscard]] std::string limitsMarkdown();

/// The one wording of a value outside its range: "<name> = <value> must lie in [<lo>, <hi>]" (and " (<note>)"
/// when a note is given), or nothing when lo ≤ value ≤ hi.
template <class T>
[[nodiscard]] std::optional<std::string> rangeError(std::string_view name, T value, long long lo, long long hi,
                                                    std::string_view note = {}) {
  if (std::cmp_greater_equal(value, lo) && std::cmp_less_equal(value, hi)) return std::nullopt;
  std::string s = std::string(name) + " = " + std::to_string(value) + " must lie in [" + std::to_string(lo) + ", " +
                  std::to_string(hi) + "]";
  if (!note.empty()) s += " (" + std::string(note) + ")";
  return s;
}

/// The same for a whole number with a lower bound only: "<name> = <value> must be at least <lo>" (and " (<note>)"),
/// as realIntervalError words a real without an upper bound, or nothing when lo ≤ value.
template <class T>
[[nodiscard]] std::optional<std::string> lowerBoundError(std::string_view name, T value, long long lo,
                                                         std::string_view note = {}) {
  if (std::cmp_greater_equal(value, lo)) return std::nullopt;
  std::string s = std::string(name) + " = " + std::to_string(value) + " must be at least " + std::to_string(lo);
  if (!note.empty()) s += " (" + std::string(note) + ")";
  return s;
}

/// The same for a whole number a front end holds only as text (a Python int of any size, before it is converted to a
/// 64- or 32-bit integer): "<name> = <text> must lie in <range>".
[[nodiscard]] std::string wholeRangeError(std::string_view name, std::string_view text, std::string_view range);

/// The same for a real value (bounds written shortest): NaN and infinities are outside every range.
[[nodiscard]] std::optional<std::string> realRangeError(std::string_view name, double value, double lo, double hi,
                                                        std::string_view note = {});

/// The same for a real value whose lower bound may be open and whose upper bound may be absent (hi = +∞): "<name> =
/// <value> must lie in (<lo>, <hi>]" (openLow) or "… in [<lo>, <hi>]", and without an upper bound "<name> = <value>
/// must be finite and above <lo>" (openLow) or "… and at least <lo>" (and " (<note>)"), or nothing.  NaN and infinities
/// are outside every range.
[[nodiscard]] std::optional<std::string> realIntervalError(std::string_view name, double value, double lo, bool openLow,
                                                           double hi, std::string_view note = {});

/// The same for an interval open at both ends: "<name> = <value> must lie in (<lo>, <hi>)" (and " (<note>)"), or
/// nothing.  NaN and infinities are outside every range.
[[nodiscard]] std::optional<std::string> realOpenIntervalError(std::string_view name, double value, double lo,
                                                               double hi, std::string_view note = {});

/// The thread count's rule: "threads = <n> must lie in [0, 256] (0: one per core)", or nothing.
[[nodiscard]] std::optional<std::string> threadsError(std::int64_t threads);

/// A raster's size: "raster size = <w>x<h> must lie in [1, 16384] pixels each way", and "… and at most 2^<k> in all"
/// when `maxPixels` (a power of two) is below 16384², or nothing.
[[nodiscard]] std::optional<std::string> rasterSizeError(
    long long width, long long height,
    std::uint64_t maxPixels = static_cast<std::uint64_t>(limits::kRasterSide) * limits::kRasterSide);

}  // namespace archipelago
