// MeasureDriver.inl — core-internal: the loop of the orbit measures shared by every path (MeasureKernels.hpp).
//
// Included by MeasureKernelScalar.cpp, MeasureKernelAvx2.cpp and MeasureKernelAvx512Ifma.cpp inside an
// anonymous namespace (the vector ones inside their target-attribute region), after MeasureMath.inl, so that
// every function here is compiled once per instruction set with internal linkage.  It includes nothing itself.
//
// A policy `Simd` provides:
//   D, kLanes                  a vector of kLanes doubles with MeasureMath.inl's operations;
//   load(const double*) -> D, store(double*, D)   unaligned moves of kLanes doubles;
//   Stepper<V>                 V vectors of orbits of N, advanced in lockstep:
//     Stepper(setup, xs, ys, steps, trackWraps)   the orbits' X, Y (kLanes·V each), the steps to come;
//     next()                   one step of N for every orbit;
//     x(v), y(v) -> D          vector v's current X, Y as doubles (exact: integers below 2^52);
//     store(xs, ys, wraps)     the states back; wraps[l] |= 1 when orbit l wrapped since construction
//                              (only when trackWraps: Dig and Rotation).
// The accumulation below is the definition of every measure (MeasureKernels.hpp's file comment): the same
// operations in the same order for every lane, whatever D is.

// The loops over the V vectors must be unrolled, so that the accumulators stay in registers.
#if defined(__clang__)
#define ARCHIPELAGO_UNROLL_MEASURE _Pragma("clang loop unroll(full)")
#else
#define ARCHIPELAGO_UNROLL_MEASURE _Pragma("GCC unroll 16")
#endif

constexpr double kRescaleAbove = 0x1p200;  // |v|² above this: v ← 2^−100 v
constexpr double kRescaleBy = 0x1p-100;
constexpr double kRescaleBySquared = 0x1p-200;
constexpr double kRescaleLog2 = 100;

/// Runs `steps` steps from step index `first` on the n ≤ V·kLanes orbits at `lanes` (MeasureKernels.hpp).
template <class Simd, IndicatorKind kKind, int V>
void measureGroup(const MeasureSetup& s, MeasureLane* lanes, std::size_t n, std::uint64_t first, std::uint64_t steps) {
  using D = typename Simd::D;
  constexpr std::size_t W = Simd::kLanes;
  constexpr std::size_t L = W * static_cast<std::size_t>(V);
  constexpr bool kBirkhoff = kKind == IndicatorKind::Dig || kKind == IndicatorKind::Rotation;

  // Structure of arrays; padding lanes repeat lane 0 (harmless, never stored back).
  alignas(64) std::uint64_t xs[L], ys[L], wraps[L];
  alignas(64) double hiA[L], loA[L], firstA[L], vxA[L], vyA[L], rescaleA[L], maxA[L], lnA[L], sumLnA[L], sumYA[L];
  for (std::size_t l = 0; l < L; ++l) {
    const MeasureLane& m = lanes[l < n ? l : 0];
    xs[l] = m.X;
    ys[l] = m.Y;
    wraps[l] = m.wrapped;
    hiA[l] = m.hi;
    loA[l] = m.lo;
    firstA[l] = m.firstBlock;
    vxA[l] = m.vx;
    vyA[l] = m.vy;
    rescaleA[l] = m.rescale;
    maxA[l] = m.maxNormSq;
    lnA[l] = m.lnNorm;
    sumLnA[l] = m.sumLn;
    sumYA[l] = m.sumY;
  }
  typename Simd::template Stepper<V> orbit(s, xs, ys, steps, kBirkhoff);

  D hi[V], lo[V], firstBlock[V], vx[V], vy[V], rescale[V], maxNormSq[V], lnNorm[V], sumLn[V], sumY[V];
  D px[V], py[V];  // Rotation: z_n − c;  Fli, Megno, Lyapunov: X_n
  const D cx(s.centreX), cy(s.centreY), fx(s.centreFracX), fy(s.centreFracY);
  ARCHIPELAGO_UNROLL_MEASURE
  for (int v = 0; v < V; ++v) {
    const std::size_t o = static_cast<std::size_t>(v) * W;
    hi[v] = Simd::load(hiA + o);
    lo[v] = Simd::load(loA + o);
    firstBlock[v] = Simd::load(firstA + o);
    vx[v] = Simd::load(vxA + o);
    vy[v] = Simd::load(vyA + o);
    rescale[v] = Simd::load(rescaleA + o);
    maxNormSq[v] = Simd::load(maxA + o);
    lnNorm[v] = Simd::load(lnA + o);
    sumLn[v] = Simd::load(sumLnA + o);
    sumY[v] = Simd::load(sumYA + o);
    if constexpr (kKind == IndicatorKind::Rotation) {
      px[v] = (orbit.x(v) - cx) - fx;
      py[v] = (orbit.y(v) - cy) - fy;
    } else {
      px[v] = orbit.x(v);
    }
  }

  const D xmin(s.xmin), unit(s.unit);
  for (std::uint64_t j = 0; j < steps; ++j) {
    const std::uint64_t step = first + j;
    orbit.next();
    if constexpr (kBirkhoff) {
      const D w(s.weights[step < s.T ? step : step - s.T]);
      ARCHIPELAGO_UNROLL_MEASURE
      for (int v = 0; v < V; ++v) {
        if constexpr (kKind == IndicatorKind::Dig) {
          twoSumAdd(hi[v], lo[v], w * orbit.x(v));
        } else {
          const D dx = (orbit.x(v) - cx) - fx;
          const D dy = (orbit.y(v) - cy) - fy;
          twoSumAdd(hi[v], lo[v], w * clockwiseAngle(px[v], py[v], dx, dy));
          px[v] = dx;
          py[v] = dy;
        }
      }
      if (step + 1 == s.T) {
        ARCHIPELAGO_UNROLL_MEASURE
        for (int v = 0; v < V; ++v) {
          firstBlock[v] = hi[v] + lo[v];
          hi[v] = D(0.0);
          lo[v] = D(0.0);
        }
      }
    } else {
      const D inverse(1.0 / static_cast<double>(step + 1));  // Megno: 1/(n + 1)
      ARCHIPELAGO_UNROLL_MEASURE
      for (int v = 0; v < V; ++v) {
        const D slope = (xmin + unit * px[v]) * 4.0;  // g'(x) = 4x at z_n
        px[v] = orbit.x(v);
        vy[v] = vy[v] + slope * vx[v];
        vx[v] = vx[v] + vy[v];
        D normSq = vx[v] * vx[v] + vy[v] * vy[v];
        const auto big = normSq > D(kRescaleAbove);
        vx[v] = select(big, vx[v] * kRescaleBy, vx[v]);
        vy[v] = select(big, vy[v] * kRescaleBy, vy[v]);
        normSq = select(big, normSq * kRescaleBySquared, normSq);
        rescale[v] = select(big, rescale[v] + kRescaleLog2, rescale[v]);
        if constexpr (kKind == IndicatorKind::Fli) {
          maxNormSq[v] = maxValue(select(big, maxNormSq[v] * kRescaleBySquared, maxNormSq[v]), normSq);
        } else if constexpr (kKind == IndicatorKind::Megno) {
          const D a = rescale[v] * kLn2Hi +
                      (rescale[v] * kLn2Lo + lnPositive(normSq) * 0.5);
          sumLn[v] = sumLn[v] + lnNorm[v];
          lnNorm[v] = a;
          sumY[v] = sumY[v] + (a - sumLn[v] * inverse) * 2.0;
        }
      }
    }
  }

  ARCHIPELAGO_UNROLL_MEASURE
  for (int v = 0; v < V; ++v) {
    const std::size_t o = static_cast<std::size_t>(v) * W;
    Simd::store(hiA + o, hi[v]);
    Simd::store(loA + o, lo[v]);
    Simd::store(firstA + o, firstBlock[v]);
    Simd::store(vxA + o, vx[v]);
    Simd::store(vyA + o, vy[v]);
    Simd::store(rescaleA + o, rescale[v]);
    Simd::store(maxA + o, maxNormSq[v]);
    Simd::store(lnA + o, lnNorm[v]);
    Simd::store(sumLnA + o, sumLn[v]);
    Simd::store(sumYA + o, sumY[v]);
  }
  orbit.store(xs, ys, wraps);
  for (std::size_t l = 0; l < n; ++l) {
    MeasureLane& m = lanes[l];
    m.X = xs[l];
    m.Y = ys[l];
    m.wrapped = wraps[l];
    m.hi = hiA[l];
    m.lo = loA[l];
    m.firstBlock = firstA[l];
    m.vx = vxA[l];
    m.vy = vyA[l];
    m.rescale = rescaleA[l];
    m.maxNormSq = maxA[l];
    m.lnNorm = lnA[l];
    m.sumLn = sumLnA[l];
    m.sumY = sumYA[l];
  }
}

/// Chooses the number of vectors (1 … V) that holds n orbits, so that a small group computes no empty vectors.
template <class Simd, IndicatorKind kKind, int V>
void measureGroupOfSize(std::size_t vectors, const MeasureSetup& s, MeasureLane* lanes, std::size_t n,
                        std::uint64_t first, std::uint64_t steps) {
  if constexpr (V > 1) {
    if (vectors < static_cast<std::size_t>(V)) {
      measureGroupOfSize<Simd, kKind, V - 1>(vectors, s, lanes, n, first, steps);
      return;
    }
  }
  measureGroup<Simd, kKind, V>(s, lanes, n, first, steps);
}

template <class Simd, IndicatorKind kKind, int V>
void measureWithKind(const MeasureSetup& s, std::span<MeasureLane> lanes, std::uint64_t first, std::uint64_t steps) {
  constexpr std::size_t group = Simd::kLanes * static_cast<std::size_t>(V);
  for (std::size_t begin = 0; begin < lanes.size(); begin += group) {
    const std::size_t n = std::min(group, lanes.size() - begin);
    measureGroupOfSize<Simd, kKind, V>((n + Simd::kLanes - 1) / Simd::kLanes, s, lanes.data() + begin, n, first,
                                       steps);
  }
}

/// The kernel of MeasureKernels.hpp for the policy `Simd` with V vectors per group (VRotation for the rotation
/// measure, whose long per-step atan2 may want fewer vectors in flight than the map's latency alone).
template <class Simd, int V, int VRotation = V>
void measureWith(const MeasureSetup& s, std::span<MeasureLane> lanes, std::uint64_t first, std::uint64_t steps) {
  switch (s.kind) {
    case IndicatorKind::Dig: measureWithKind<Simd, IndicatorKind::Dig, V>(s, lanes, first, steps); break;
    case IndicatorKind::Rotation:
      measureWithKind<Simd, IndicatorKind::Rotation, VRotation>(s, lanes, first, steps);
      break;
    case IndicatorKind::Fli: measureWithKind<Simd, IndicatorKind::Fli, V>(s, lanes, first, steps); break;
    case IndicatorKind::Megno: measureWithKind<Simd, IndicatorKind::Megno, V>(s, lanes, first, steps); break;
    case IndicatorKind::Lyapunov: measureWithKind<Simd, IndicatorKind::Lyapunov, V>(s, lanes, first, steps); break;
  }
}
