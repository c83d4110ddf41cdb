#pragma once
/// \file MeasureKernels.hpp
/// \brief Core-internal: the fused kernels of the orbit measures (iterate the exact map N and accumulate), one per
/// instruction-set path, and the state they carry between calls.
///
/// Contract of every MeasureKernel: identical to measureKernelScalar() bit for bit — the orbit states (X, Y, the
/// wrap flag) and every accumulator of MeasureLane.  The orbit points are those of N (FixedPointMap.hpp); the
/// accumulations are MeasureMath.hpp's operations in one fixed order per orbit (the steps in sequence, one lane
/// per orbit), so vector lanes reproduce the scalar sums exactly.  Paths:
///   - scalar     : ScalarStep (the reference; 8 orbits interleaved);
///   - avx2       : the AVX2 orbit kernel (iterateOrbitsAvx2, unchanged) fills a trace of a chunk of steps,
///                  which 256-bit double arithmetic then accumulates (the AVX2 step runs in round-down mode, the
///                  accumulation in round-to-nearest, so they cannot share a loop);
///   - avx512f    : the avx2 accumulation, on the trace of the AVX-512F orbit kernel (MeasureSetup::trace);
///   - avx512ifma : fused: the IFMA step (KernelAvx512Ifma.cpp's arithmetic) and 512-bit accumulation in one
///                  loop, the orbits' X, Y never leaving registers.
/// Steps, with n = 0, 1, … the step index of the orbit (all orbits of a call are at the same n) and
/// z_{n+1} = N(z_n):
///   - Dig       : f_n = X_{n+1} (unit coordinates; the physical x is xmin + unit·X), weight g(n mod T / T);
///   - Rotation  : f_n = clockwiseAngle(z_n − c, z_{n+1} − c) (grid units), weight g(n mod T / T);
///   - Dig and Rotation: a step that wraps (FixedPointMap.hpp) marks the orbit;
///   - Dig and Rotation: the terms n < T form the first block (its sum is kept in firstBlock when n = T − 1
///                 ends it), the terms T ≤ n < 2T the second;
///   - Fli, Megno, Lyapunov: the tangent vector v_{n+1} = DN(z_n) v_n, DN = [[1 + 4x, 1], [4x, 1]] with
///                 x = xmin + unit·X_n the physical abscissa (δy ← δy + 4x δx, δx ← δx + δy, as the map itself),
///                 v_0 = (1, 0); whenever |v|² exceeds 2^200 it is multiplied by 2^−100 (exactly) and rescale
///                 grows by 100, so that |v_n| = 2^rescale |v| never overflows;
///     Fli: maxNormSq = max over 1 ≤ k ≤ n + 1 of |v_k|² (in the current scale);
///     Megno: a_k = ln|v_k| = rescale·ln 2 + ½ lnPositive(|v|²); S ← S + a_n; Y_{n+1} = 2 (a_{n+1} − S/(n + 1));
///     sumY ← sumY + Y_{n+1} (Cincotta & Simó 2000: ⟨Y⟩_T = sumY/T).

#include <cstddef>
#include <cstdint>
#include <span>

#include "core/kernels/KernelDispatch.hpp"
#include "core/kernels/VectorKernels.hpp"
#include "core/map/FixedPointMap.hpp"
#include "core/measures/IndicatorKind.hpp"

namespace archipelago::measures {

/// What every orbit of a call shares: the map, the measure and its tables.
struct MeasureSetup {
  IndicatorKind kind = IndicatorKind::Dig;
  MapCoefficients coefficients;
  std::uint64_t T = 0;              ///< block length (Dig, Rotation) or steps (Fli, Megno, Lyapunov)
  const double* weights = nullptr;  ///< g(n/T), n = 0 … T − 1 (Dig, Rotation)
  double xmin = 0;                  ///< physical x = xmin + unit·X
  double unit = 0;                  ///< L/2^52
  double K = 0;                     ///< the map parameter (wrap detection from points, avx2)
  /// The rotation centre in grid units, split into an integer (exact as a double) and a fraction in [0, 1):
  /// z − c = ((X − centreX) − centreFracX, (Y − centreY) − centreFracY), the first difference exact.
  double centreX = 0, centreY = 0, centreFracX = 0, centreFracY = 0;
  /// The orbit kernel whose trace the avx2 accumulation reads (the path's KernelInfo::orbits: iterateOrbitsAvx2,
  /// or iterateOrbitsAvx512F on the avx512f path); null: iterateOrbitsAvx2.
  OrbitKernel trace = nullptr;
};

/// One orbit's state between calls (see the file comment for the fields' meaning).
struct MeasureLane {
  std::uint64_t X = 0, Y = 0;
  std::uint64_t wrapped = 0;     ///< 1 once a step wrapped (Dig, Rotation; 0 for the other kinds)
  double hi = 0, lo = 0;         ///< Σ g f of the open block (TwoSum pair)
  double firstBlock = 0;         ///< Σ g f of the first block, once it ended
  double vx = 1, vy = 0;         ///< tangent vector / 2^rescale
  double rescale = 0;
  double maxNormSq = 1;          ///< Fli
  double lnNorm = 0;             ///< Megno: a_n
  double sumLn = 0;              ///< Megno: S_n = a_0 + … + a_{n−1}
  double sumY = 0;               ///< Megno: Y_1 + … + Y_n
};

/// Advances every lane by `steps` steps from step index `first` (all lanes at the same index), accumulating.
using MeasureKernel = void (*)(const MeasureSetup& setup, std::span<MeasureLane> lanes, std::uint64_t first,
                               std::uint64_t steps);

void measureKernelScalar(const MeasureSetup& setup, std::span<MeasureLane> lanes, std::uint64_t first,
                         std::uint64_t steps);
/// Requires AVX2 and FMA (KernelDispatch.hpp decides).
void measureKernelAvx2(const MeasureSetup& setup, std::span<MeasureLane> lanes, std::uint64_t first,
                       std::uint64_t steps);
/// Requires AVX-512 F, VL, DQ and IFMA.
void measureKernelAvx512Ifma(const MeasureSetup& setup, std::span<MeasureLane> lanes, std::uint64_t first,
                             std::uint64_t steps);

/// The kernel of a path, and the orbits it keeps in flight (give it multiples of that).
struct MeasurePath {
  MeasureKernel kernel;
  std::size_t groupOrbits;
};
[[nodiscard]] MeasurePath measurePath(KernelKind kind) noexcept;

/// The steps a whole measurement takes: 2T for Dig and Rotation, T for the others.
[[nodiscard]] std::uint64_t totalSteps(IndicatorKind kind, std::uint64_t T) noexcept;

}  // namespace archipelago::measures
