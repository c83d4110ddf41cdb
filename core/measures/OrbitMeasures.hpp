#pragma once
/// \file OrbitMeasures.hpp
/// \brief Measures of single orbits of the exact map N: convergence digits, rotation number, FLI, MEGNO and
/// finite-time Lyapunov exponent — the values every pixel of an indicator map (IndicatorMap.hpp) and every
/// point of a rotation profile (RotationProfile.hpp) holds.
///
/// The orbit points are those of the exact map N (FixedPointMap.hpp), forward (N = Q* on the torus), computed
/// by the chosen instruction-set path; every path gives the same points and the same sums bit for bit
/// (MeasureKernels.hpp), so a measure does not depend on the path or the number of threads.  Kinds, with T the
/// request's `iterations`:
///   - Dig: the weighted Birkhoff average (BirkhoffAverage.hpp) of the physical x over two consecutive blocks
///     of T points (z_1 … z_T, z_{T+1} … z_{2T}); value = digits = −log₁₀ |difference|.  Regular orbits reach
///     ~14 at T = 10⁴, chaotic ones a few.  x is smooth on every orbit that stays away from the seam of the
///     torus, so islands of Q* (those of Q, and the accelerator modes that wrap around the torus) converge and
///     the chaotic sea does not.  Verdict: Chaotic below the threshold, else Regular, or Escaping for an
///     orbit that wrapped (an accelerator-mode island of Q*: regular on the torus, but not an orbit of Q).
///   - Rotation: the rotation number about the elliptic fixed point (−√K, 0) of Q (0 < K < 1), in turns per
///     step, positive in the sense Q turns about it (clockwise in the (x, y) plane; Q moves (−√K + δ, 0) to
///     y = −4√K δ < 0).  The weighted Birkhoff average of the clockwise angle increments about the centre over
///     two blocks of T steps; the value is the mean of the two, the digits of their difference.  Near the
///     centre it tends to α/2π with cos α = 1 − 2√K (the paper's §2: 0.1900993 at K = 0.1); an orbit of an
///     island chain of period n around the central island has p/n (1/6 for the six islands at K = 0.1).
///     No number is given to an orbit that is chaotic (digits below the threshold) or escaping (a step of N
///     wrapped: the orbit left the box, where Q* is no longer Q and "about (−√K, 0)" means nothing) — the
///     verdict says which.
///   - Fli: the fast Lyapunov indicator max_{1≤n≤T} ln |v_n| (Froeschlé, Lega & Gonczi, Celest. Mech. Dyn.
///     Astron. 67 (1997) 41), v_n the tangent vector of DN from v_0 = (1, 0) in physical units; grows like
///     ln T on regular orbits, like λT on chaotic ones.
///   - Megno: the mean exponential growth factor of nearby orbits ⟨Y⟩_T = (1/T) Σ_{n=1}^{T} Y_n,
///     Y_n = (2/n) Σ_{k=1}^{n} k ln(|v_k|/|v_{k−1}|) (Cincotta & Simó, Astron. Astrophys. Suppl. 147 (2000) 205):
///     → 2 on quasi-periodic orbits, → 0 on stable periodic ones, ~ λT/2 on chaotic ones.
///   - Lyapunov: the finite-time maximal Lyapunov exponent ln |v_T| / T (per step).
/// The tangent map is that of Q* on the torus, DN = [[1 + 4x, 1], [4x, 1]] with x the physical abscissa in
/// the box (g'(x) = 4x, eq. qu); the three tangent measures therefore apply to accelerator-mode islands too.

#include <cmath>
#include <cstdint>
#include <optional>
#include <span>
#include <stop_token>
#include <string>
#include <string_view>
#include <vector>

#include "core/kernels/KernelDispatch.hpp"
#include "core/map/FixedPointMap.hpp"
#include "core/measures/BirkhoffAverage.hpp"
#include "core/measures/IndicatorKind.hpp"

namespace archipelago {

/// What became of an orbit.
enum class OrbitVerdict : std::uint8_t {
  NotComputed = 0,  ///< not measured (a progressive raster's pixel not reached yet, or a stop request)
  Measured = 1,     ///< Fli, Megno, Lyapunov: a value, no classification
  Regular = 2,      ///< Dig, Rotation: digits ≥ the threshold, and the orbit stayed in the box
  Chaotic = 3,      ///< Dig, Rotation: digits below the threshold
  Escaping = 4,     ///< the orbit left the box (a step of N wrapped), where Q* is no longer Q: Rotation gives
                    ///< it no number; for Dig, a regular orbit of Q* that is no orbit of Q (an accelerator
                    ///< mode, §2 and appendix B), a chaotic one that wraps is Chaotic
};
/// "not computed", "measured", "regular", "chaotic", "escaping".
[[nodiscard]] std::string_view toString(OrbitVerdict verdict) noexcept;

/// Everything that defines a measurement of orbits, as plain values.
struct MeasureSettings {
  MapParameters map;                                  ///< K, xmin, xmax (default: the paper's K = 0.1 box)
  IndicatorKind kind = IndicatorKind::Rotation;
  std::uint64_t iterations = kDefaultIterations;      ///< T: block length (Dig, Rotation: 2T steps) or steps
  double digitsThreshold = kDefaultDigitsThreshold;   ///< Dig, Rotation: regular when digits ≥ this, [0, 16]
  const KernelInfo* kernel = nullptr;                 ///< the instruction-set path; nullptr: bestKernel()
};

/// The first violated rule, naming the field (the map's rules, iterations in [kMinIterations, kMaxIterations],
/// the threshold in [0, kMaxDigits], 0 < K < 1 for Rotation), or nothing.
[[nodiscard]] std::optional<std::string> validationError(const MeasureSettings& s);

/// Steps of N per orbit: 2T for Dig and Rotation, T for the others.
[[nodiscard]] std::uint64_t stepsPerOrbit(const MeasureSettings& s) noexcept;

/// One orbit's result.
struct OrbitMeasure {
  double value = std::nan("");   ///< Dig: digits; Rotation: turns per step (NaN unless Regular); Fli; Megno;
                                 ///< Lyapunov (per step).  NaN when NotComputed.
  double digits = std::nan("");  ///< Dig, Rotation: the convergence digits (also for chaotic orbits); else NaN
  OrbitVerdict verdict = OrbitVerdict::NotComputed;
};

/// "<name> = (x, y) must lie in the box [xmin, xmax) x [−L/2, L/2)" (or must be finite) when the physical point p
/// is not a point of the box, where an orbit of Q starts as one of Q*; nothing when it is.
[[nodiscard]] std::optional<std::string> boxPointError(const std::string& name, const MapParameters& map,
                                                       PhysicalPoint p);

/// The rotation centre (−√K, 0) in unit coordinates (long double: the centre is not a grid point).
[[nodiscard]] PhysicalPoint rotationCentreUnits(const MapParameters& map) noexcept;

/// Measures orbits: the settings validated and the tables (weights) built once, then any number of orbits.
class OrbitMeasurer {
 public:
  /// Throws std::invalid_argument with validationError(s).
  explicit OrbitMeasurer(const MeasureSettings& s);

  [[nodiscard]] const MeasureSettings& settings() const noexcept { return settings_; }

  /// The orbit from `start` (unit coordinates), on the calling thread.
  [[nodiscard]] OrbitMeasure measure(UnitState start) const;

  /// Every orbit of `starts` into `out` (same size), in parallel on `threads` threads (0: OpenMP's default),
  /// in groups the path keeps in flight.  The stop token is checked between chunks of at most 2^14 steps of a
  /// group; after a stop request the orbits not finished stay NotComputed and the call returns false.  No
  /// exception leaves the parallel region (ParallelFor.hpp).
  bool measure(std::span<const UnitState> starts, std::span<OrbitMeasure> out, std::stop_token stop = {},
               int threads = 0) const;

 private:
  MeasureSettings settings_;
  MapCoefficients coefficients_;
  BirkhoffWeights weights_;
};

}  // namespace archipelago
