#include "core/limits/Limits.hpp"

#include <array>
#include <bit>
#include <charconv>
#include <cmath>

namespace archipelago {

namespace {
const std::array<LimitInfo, 14> kTable{{
    {"threads", "worker threads of any computation (0: one per core)", 0, limits::kThreads},
    {"raster side", "pixels each way of a portrait, an indicator map or an export", 1, limits::kRasterSide},
    {"indicator pixels", "pixels of an indicator map in all", 1, static_cast<long long>(limits::kIndicatorPixels)},
    {"q", "steps of N⁻¹ per block of a trapping run or a tail", 1, static_cast<long long>(limits::kRunQ)},
    {"raster q", "steps per block of a portrait's (stickiness) or b₂'s orbits", 1,
     static_cast<long long>(limits::kRasterQ)},
    {"raster orbits", "orbits in parallel of a portrait or of b₂", 1, static_cast<long long>(limits::kRasterOrbits)},
    {"seed grid", "seeds each way of a portrait's seed grid", 1, static_cast<long long>(limits::kSeedGridSide)},
    {"orbit length", "points of one orbit held in memory (orbit, launched orbits, overlays)", 1,
     static_cast<long long>(limits::kOrbitLength)},
    {"portrait budget", "points a portrait accumulates (the GUI's portrait budget)",
     static_cast<long long>(limits::kPortraitBudgetMin), static_cast<long long>(limits::kPortraitBudget)},
    {"seeds", "runs of one seed ensemble (each a whole run)", 1, static_cast<long long>(limits::kSeeds)},
    {"chain rows", "rows of the GUI's segment table whose chain is named by itself", 0, limits::kChainRows},
    {"script seconds", "the longest a scripted GUI run waits (before it acts, or measures)", 0,
     static_cast<long long>(limits::kScriptSeconds)},
    {"markov tree states", "states of a Markov tree whose survival is computed (markov-tree, the Atlas page's model)", 1,
     limits::kMarkovTreeStates},
    {"markov tree survival values", "states x times of a Markov tree's survival (each state's part at each t)", 1,
     static_cast<long long>(limits::kMarkovTreeValues)},
}};

/// The shortest text that reads back as v ("0.5", "86400", "1e+12").
std::string shortest(double v) {
  char buffer[32];
  const auto end = std::to_chars(buffer, buffer + sizeof buffer, v).ptr;
  return std::string(buffer, end);
}
}  // namespace

std::span<const LimitInfo> limitsTable() noexcept { return kTable; }

std::string limitsMarkdown() {
  std::string s = "| limit | what | range |\n|---|---|---|\n";
  for (const LimitInfo& l : kTable)
    s += "| " + std::string(l.key) + " | " + std::string(l.what) + " | " + std::to_string(l.min) + " … " +
         std::to_string(l.max) + " |\n";
  return s;
}

std::optional<std::string> realRangeError(std::string_view name, double value, double lo, double hi,
                                          std::string_view note) {
  if (value >= lo && value <= hi) return std::nullopt;
  std::string s = std::string(name) + " = " + shortest(value) + " must lie in [" + shortest(lo) + ", " + shortest(hi) +
                  "]";
  if (!note.empty()) s += " (" + std::string(note) + ")";
  return s;
}

std::optional<std::string> realIntervalError(std::string_view name, double value, double lo, bool openLow, double hi,
                                             std::string_view note) {
  if (std::isfinite(value) && (openLow ? value > lo : value >= lo) && value <= hi) return std::nullopt;
  std::string s = std::string(name) + " = " + shortest(value);
  if (std::isinf(hi) && hi > 0)
    s += std::string(" must be finite and ") + (openLow ? "above " : "at least ") + shortest(lo);
  else
    s += std::string(" must lie in ") + (openLow ? "(" : "[") + shortest(lo) + ", " + shortest(hi) + "]";
  if (!note.empty()) s += " (" + std::string(note) + ")";
  return s;
}

std::optional<std::string> realOpenIntervalError(std::string_view name, double value, double lo, double hi,
                                                 std::string_view note) {
  if (value > lo && value < hi) return std::nullopt;
  std::string s = std::string(name) + " = " + shortest(value) + " must lie in (" + shortest(lo) + ", " + shortest(hi) +
                  ")";
  if (!note.empty()) s += " (" + std::string(note) + ")";
  return s;
}

std::string wholeRangeError(std::string_view name, std::string_view text, std::string_view range) {
  return std::string(name) + " = " + std::string(text) + " must lie in " + std::string(range);
}

std::optional<std::string> threadsError(std::int64_t threads) {
  return rangeError("threads", threads, 0, limits::kThreads, "0: one per core");
}

std::optional<std::string> rasterSizeError(long long width, long long height, std::uint64_t maxPixels) {
  if (width >= 1 && width <= limits::kRasterSide && height >= 1 && height <= limits::kRasterSide &&
      static_cast<std::uint64_t>(width) * static_cast<std::uint64_t>(height) <= maxPixels)
    return std::nullopt;
  std::string s = "raster size = " + std::to_string(width) + "x" + std::to_string(height) + " must lie in [1, " +
                  std::to_string(limits::kRasterSide) + "] pixels each way";
  if (maxPixels < static_cast<std::uint64_t>(limits::kRasterSide) * limits::kRasterSide)
    s += " and at most 2^" + std::to_string(std::bit_width(maxPixels) - 1) + " in all";
  return s;
}

}  // namespace archipelago
