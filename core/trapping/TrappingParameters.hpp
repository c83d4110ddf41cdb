#pragma once
/// \file TrappingParameters.hpp
/// \brief Settings of a trapping-statistics run (Karney 1983, §3 and appendix B, steps 1–9).

#include <cstdint>
#include <optional>
#include <string>

#include "map/FixedPointMap.hpp"

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

/// The first violated rule, naming the parameter (map rules included), or nothing when valid.
[[nodiscard]] std::optional<std::string> validationError(const TrappingParameters& p);
void validate(const TrappingParameters& p);

/// The rule for the randomizing zone's width: Xr finite and in [0, 1).  The message names Xr, or nothing.
[[nodiscard]] std::optional<std::string> randomizingZoneError(double Xr);

/// ⌊Xr·2^52⌋, the largest X inside the randomizing zone.
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

/// A finished segment with its start state.
struct SegmentRecord {
  std::uint64_t orbit = 0;
  std::uint64_t length = 0;  ///< in blocks
  SegmentStart start;
  friend bool operator==(const SegmentRecord&, const SegmentRecord&) = default;
};

}  // namespace archipelago
