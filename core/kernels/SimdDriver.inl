// SimdDriver.inl — the loops shared by the vector paths (KernelAvx2.cpp, KernelAvx512Ifma.cpp).
//
// Each of those files includes this one inside an anonymous namespace and inside its target-attribute region,
// so every function here is compiled once per instruction set with internal linkage (no ODR merging of an
// AVX-512 copy into the AVX2 path or into generic code).  It includes nothing itself.
//
// A SIMD policy `Simd` provides:
//   Vec, kLanes                       the vector type of 64-bit integer lanes and its number of lanes;
//   State                             the type that holds X or Y of kLanes orbits while they are iterated
//                                     (Vec itself, or another encoding of the same integers);
//   Constants(coefficients, Xr)       broadcast map coefficients, masks and the randomizing threshold;
//   load/store/zero                   unaligned 64-bit lane moves;
//   loadState/storeState              unit coordinates (uint64 arrays) to State and back;
//   storeStateMasked(p, lanes, S)     storeState for the lanes in `lanes` only;
//   noWraps() -> State                an empty wrap accumulator;
//   backward(c, X, Y, wraps)          one N⁻¹ step; records in the accumulator `wraps` whether a lane wrapped;
//   forward(c, X, Y)                  one N step;
//   atMost(c, X) -> unsigned          bit l set when lane l has X ≤ Xr (the randomizing zone);
//   wrapped(c, wraps) -> unsigned     bit l set when lane l wrapped;
//   refreshDraws(c, lanes, key, D, U) for the lanes in `lanes`: U ← orbitDraw(key, D + 1) (key, U: arrays);
//   select(lanes, a, b)               a in the lanes in `lanes`, b elsewhere;
//   addModMasked(c, Y, lanes, U)      Y + U in the lanes in `lanes`, Y elsewhere (Y a State, U a Vec); the sum
//                                     may be left unreduced (< 2^53): the block's first step reduces it and
//                                     the lane's segment ends in this block whatever its wrap flag says;
//   set1, add, sub                    64-bit lane arithmetic;
//   atLeast(lanes, a, b) -> unsigned  bit l set when l is in `lanes` and a ≥ b in lane l (values < 2^63);
//   below(lanes, a, b) -> unsigned    bit l set when l is in `lanes` and a < b in lane l (values < 2^63);
//   storeMasked(p, lanes, v)          stores the lanes in `lanes` only;
//   compressStore(p, lanes, v)        stores the lanes in `lanes`, packed, at p (may write kLanes words).

// Loops over the V vectors must be unrolled, so that X[v], Y[v] stay in registers (GCC does not unroll them
// at -O2 by itself).
#if defined(__clang__)
#define ARCHIPELAGO_UNROLL_VECTORS _Pragma("clang loop unroll(full)")
#else
#define ARCHIPELAGO_UNROLL_VECTORS _Pragma("GCC unroll 16")
#endif

/// The lowest event tag (length << 6 | lane) whose length LongestSegments::mightKeep() accepts now;
/// INT64_MAX when none (tags stay below 2^63).
inline std::uint64_t keepTag(const LongestSegments& longest) {
  constexpr auto kNone = static_cast<std::uint64_t>(INT64_MAX);
  if (longest.capacity() == 0) return kNone;
  if (longest.items().size() < longest.capacity()) return 0;
  const std::uint64_t length = longest.items().back().length;
  return length >= (std::uint64_t{1} << 56) ? kNone : length << 6;
}

/// Runs `blocks` trapping blocks on n ≤ V·kLanes orbits held in V vectors (appendix B, steps 5–9), with the
/// same effect as advanceOneBlock() on each.
///
/// Only X, Y and a wrap accumulator per vector live in registers.  Everything else is per-lane arrays touched
/// when a lane's segment ends, which in the chaotic sea is often (at q = 1 about a third of the blocks, at
/// q = 16 most), so that path is vectorised too:
///   - the open segment's length is (blocks done) − (block where it began), so nothing is counted per block;
///   - the next segment's start X, Y is written with masked stores (its block and draws follow from the tag
///     base and the draw counter);
///   - segments of one block are counted per lane in vectors; longer ones go, compressed, into an event
///     buffer as (length << 6) | lane, binned in a tight loop later: lengths ≤ kExactMax into per-lane counts
///     (merged into the sink's subset histograms at the end), longer ones straight into the histogram;
///   - only a segment long enough for the longest-segments list (rare once the list is full) takes the scalar
///     path, at once, while its start state is still at hand; its length is compared with the list's
///     threshold only in lanes found, every 64 blocks, to be able to reach it (`candidates`);
///   - a lane's draw counter is brought up to date when its next draw is computed, not in the zone step.
/// The histograms and the longest list do not depend on the order of insertion, so this equals the scalar
/// kernel's sink bit for bit.
template <class Simd, int V>
void advanceGroup(const typename Simd::Constants& c, const KernelSettings& k, OrbitState* orbits, std::size_t n,
                  std::uint64_t firstOrbit, std::uint64_t blocks, SegmentSink& sink) {
  using Vec = typename Simd::Vec;
  constexpr std::size_t W = Simd::kLanes;
  constexpr std::size_t L = W * V;
  static_assert(L <= 64, "an event tag holds the lane in 6 bits");
  constexpr std::uint64_t kExact = TrappingHistogram::kExactMax;
  // Segments that are not recorded — an orbit's first one (it began at block 0) and every one of a padding
  // lane — carry kUnrecorded in their tag; such tags are dropped when binned or kept.
  constexpr std::uint64_t kUnrecorded = std::uint64_t{1} << 62;
  alignas(64) std::uint64_t xs[L], ys[L], draws[L], keys[L], laneTags[L];
  // The open segment's start.  X and Y are stored (masked) whenever a segment ends; the block and the draws
  // need no stores: a segment that began in this call began at local block segmentBegin ≥ 1 (from tagBase),
  // and its draws are the lane's current draws, since entering the zone (the only place draws change) ends
  // the segment.  startBlockLocal (relative to firstBlock, modulo 2^64) and startDraws keep the values of the
  // segment open on entry (segmentBegin ≤ 0).
  alignas(64) std::uint64_t startX[L], startY[L], startBlockLocal[L], startDraws[L];
  // tagBase = segmentBegin·64 − laneTag, segmentBegin being the local block where the open segment began, so
  // that the event tag (length << 6) | lane (+ kUnrecorded) of a segment ending after local block a is
  // a·64 − tagBase (all modulo 2^64; lane < 64 and lengths < 2^56).
  alignas(64) std::uint64_t tagBase[L], firstBlock[L];
  for (std::size_t l = 0; l < L; ++l) {
    const OrbitState s = l < n ? orbits[l] : OrbitState{};  // padding lanes: computed, never recorded or stored
    xs[l] = s.z.X;
    ys[l] = s.z.Y;
    draws[l] = s.draws;
    keys[l] = l < n ? orbitKey(k.seed, firstOrbit + l) : 0;
    laneTags[l] = l < n ? l : l + kUnrecorded;
    startX[l] = s.start.z.X;
    startY[l] = s.start.z.Y;
    startBlockLocal[l] = s.start.block - s.block;
    startDraws[l] = s.start.draws;
    // segmentBegin = −length; an orbit's first segment is not recorded (SegmentSink::record).
    tagBase[l] = ((std::uint64_t{0} - s.length) << 6) - laneTags[l] - (l < n && !isRecorded(s.start) ? kUnrecorded : 0);
    firstBlock[l] = s.block;
  }
  // The local block where lane l's open segment began, from its tagBase (negative: before this call).
  const auto segmentBegin = [&](std::uint64_t base, std::size_t l) {
    return static_cast<std::int64_t>(base + l) >> 6;  // l < n: laneTags[l] = l
  };
  // Per-lane values read every block stay in registers: a load of words just written by a masked store
  // cannot take them from the store buffer and would stall.
  // The draws stay in memory (draws[]) and lag: a lane in `stale` has used one more draw than draws[] says,
  // and the increment is made when its next draw is computed (refreshDraws), so the zone costs no store.
  typename Simd::State X[V], Y[V];
  Vec base[V];  // base: tagBase
  unsigned active[V];
  ARCHIPELAGO_UNROLL_VECTORS
  for (std::size_t v = 0; v < V; ++v) {
    X[v] = Simd::loadState(xs + v * W);
    Y[v] = Simd::loadState(ys + v * W);
    base[v] = Simd::load(tagBase + v * W);
    const std::size_t begin = v * W;
    active[v] = (1u << (n > begin ? std::min(W, n - begin) : 0)) - 1u;
  }

  alignas(64) std::uint64_t nextDraw[L];  // orbitDraw(key, draws + 1): the draw each lane uses next
  for (std::size_t l = 0; l < L; ++l) nextDraw[l] = orbitDraw(keys[l], draws[l] + 1);
  unsigned stale[V] = {};  // lanes whose nextDraw was used: draws[] is one short, nextDraw must be recomputed
  const Vec one = Simd::set1(1);
  constexpr std::uint64_t kRefreshBlocks = 8;
  const auto refreshDraws = [&] {
    ARCHIPELAGO_UNROLL_VECTORS
    for (std::size_t v = 0; v < V; ++v) {
      if (stale[v] == 0) continue;  // common at q ≥ 16 between zone visits
      const Vec D = Simd::load(draws + v * W);
      const Vec used = Simd::select(stale[v], Simd::add(D, one), D);
      Simd::store(draws + v * W, used);
      Simd::refreshDraws(c, stale[v], keys + v * W, used, nextDraw + v * W);
      stale[v] = 0;
    }
  };

  LongestSegments& longest = sink.longest();
  Vec keepFrom = Simd::set1(keepTag(longest));
  // Lanes whose open segment may become long enough for the longest list before the next recomputation
  // (every kCandidateBlocks blocks); only an ended segment of theirs is compared with keepFrom, so the
  // comparison leaves the per-block path once the list is full.  A superset is harmless: keepFrom only grows.
  constexpr std::uint64_t kCandidateBlocks = 64;
  unsigned candidates[V] = {};
  const auto findCandidates = [&](std::uint64_t b) {
    // A segment that begins at or after block b ends by block b + kCandidateBlocks with a tag below
    // kCandidateBlocks·64; below that threshold every lane is a candidate.
    const bool everyLane = keepTag(longest) < (kCandidateBlocks << 6);
    const Vec horizon = Simd::set1((b + kCandidateBlocks) << 6);  // the largest tag of an older segment
    ARCHIPELAGO_UNROLL_VECTORS
    for (std::size_t v = 0; v < V; ++v)
      candidates[v] = everyLane ? active[v] : Simd::atLeast(active[v], Simd::sub(horizon, base[v]), keepFrom);
  };
  constexpr std::size_t kEventCapacity = 2048;
  alignas(64) std::uint64_t events[kEventCapacity + 1];
  std::size_t eventCount = 0;
  // [length·64 + lane], lengths 1 … kExactMax, in two copies: even and odd events count into different
  // copies, which halves the chains of increments of one counter (each waits for the previous store).
  constexpr std::size_t kExactTags = (kExact + 1) * 64;
  std::uint64_t exactCounts[2 * kExactTags] = {};
  // Segments of one block, about two thirds of all at q = 1 (f_1 ≈ 0.22 of f ≈ 0.32 per block at K = 0.1),
  // are counted per lane in vectors and never become events.
  Vec singles[V];
  const Vec twoBlocks = Simd::set1(2 << 6);  // tags of one-block segments are below this
  ARCHIPELAGO_UNROLL_VECTORS
  for (std::size_t v = 0; v < V; ++v) singles[v] = Simd::zero();
  const auto binLong = [&](std::uint64_t tag) {
    if (tag >= kUnrecorded) return;
    const std::uint64_t orbit = firstOrbit + (tag & 63);
    sink.subsets()[orbit % sink.subsets().size()].add(tag >> 6);
  };
  const auto binEvents = [&] {
    events[eventCount] = 0;  // an even count: the padding tag 0 (length 0) is counted and ignored
    for (std::size_t i = 0; i < eventCount; i += 2) {
      const std::uint64_t even = events[i], odd = events[i + 1];
      if (even < kExactTags) [[likely]] exactCounts[even] += 1; else binLong(even);
      if (odd < kExactTags) [[likely]] exactCounts[kExactTags + odd] += 1; else binLong(odd);
    }
    eventCount = 0;
  };

  const std::uint32_t q = k.q;
  for (std::uint64_t b = 0; b < blocks; ++b) {
    if (b % kCandidateBlocks == 0) findCandidates(b);
    // Appendix B, 6.1–6.2: in the zone, Y ← Y + U (the orbit's next draw) and the segment ends.  The draw
    // was computed ahead (nextDraw), so the zone costs a few branch-free masked operations here; the
    // 64-bit multiplies of the next draws are batched every kRefreshBlocks blocks, or done at once in the
    // rare case that a lane enters the zone again before its draw was refreshed.
    unsigned zone[V];
    unsigned reusedStale = 0;
    ARCHIPELAGO_UNROLL_VECTORS
    for (std::size_t v = 0; v < V; ++v) {
      zone[v] = Simd::atMost(c, X[v]);  // padding lanes too: harmless, never recorded nor stored
      reusedStale |= zone[v] & stale[v];
    }
    if (reusedStale) [[unlikely]] refreshDraws();
    ARCHIPELAGO_UNROLL_VECTORS
    for (std::size_t v = 0; v < V; ++v) {
      const std::size_t o = v * W;
      Y[v] = Simd::addModMasked(c, Y[v], zone[v], Simd::load(nextDraw + o));
      stale[v] |= zone[v];
    }
    if (b % kRefreshBlocks == kRefreshBlocks - 1) refreshDraws();
    typename Simd::State wrapBits[V];
    ARCHIPELAGO_UNROLL_VECTORS
    for (std::size_t v = 0; v < V; ++v) wrapBits[v] = Simd::noWraps();
    for (std::uint32_t j = 0; j < q; ++j) {
      ARCHIPELAGO_UNROLL_VECTORS
      for (std::size_t v = 0; v < V; ++v) Simd::backward(c, X[v], Y[v], wrapBits[v]);
    }
    unsigned ended[V];
    unsigned anyEnded = 0;
    ARCHIPELAGO_UNROLL_VECTORS
    for (std::size_t v = 0; v < V; ++v) {
      ended[v] = Simd::wrapped(c, wrapBits[v]) | zone[v];
      anyEnded |= ended[v];
    }
    if (!anyEnded) continue;
    const std::uint64_t after = b + 1;  // local blocks done after this one
    const Vec afterTag = Simd::set1(after << 6);
    ARCHIPELAGO_UNROLL_VECTORS
    for (std::size_t v = 0; v < V; ++v) {
      const unsigned e = ended[v];  // usually nonzero at small q; with e = 0 the masked work below is void
      const std::size_t o = v * W;
      const Vec tag = Simd::sub(afterTag, base[v]);
      const unsigned single = Simd::below(e, tag, twoBlocks);  // unrecorded tags (≥ kUnrecorded) are not
      singles[v] = Simd::select(single, Simd::add(singles[v], one), singles[v]);
      Simd::compressStore(events + eventCount, e & ~single, tag);
      eventCount += static_cast<std::size_t>(__builtin_popcount(e & ~single));
      const unsigned keep = (e & candidates[v]) ? Simd::atLeast(e, tag, keepFrom) : 0u;
      if (keep) [[unlikely]] {
        alignas(64) std::uint64_t tags[W], bases[W], drawsNow[W];
        Simd::store(tags, tag);
        Simd::store(bases, base[v]);
        Simd::store(drawsNow, Simd::select(stale[v], Simd::add(Simd::load(draws + o), one), Simd::load(draws + o)));
        for (unsigned bits = keep; bits; bits &= bits - 1) {
          const std::size_t lane = static_cast<std::size_t>(__builtin_ctz(bits));
          const std::size_t l = o + lane;
          if (tags[lane] >= kUnrecorded) continue;
          // Its block from tagBase (before this block's update); its draws before this block's zone step.
          const std::int64_t begin = segmentBegin(bases[lane], l);
          const bool begunHere = begin > 0;
          const std::uint64_t began = begunHere ? static_cast<std::uint64_t>(begin) : startBlockLocal[l];
          const std::uint64_t startDrawsNow = begunHere ? drawsNow[lane] - ((zone[v] >> lane) & 1u) : startDraws[l];
          longest.insert({firstOrbit + l, tags[lane] >> 6, {{startX[l], startY[l]}, firstBlock[l] + began, startDrawsNow}});
        }
        keepFrom = Simd::set1(keepTag(longest));
      }
      Simd::storeStateMasked(startX + o, e, X[v]);
      Simd::storeStateMasked(startY + o, e, Y[v]);
      base[v] = Simd::select(e, Simd::sub(afterTag, Simd::load(laneTags + o)), base[v]);
    }
    if (eventCount > kEventCapacity - L) binEvents();
  }
  binEvents();
  refreshDraws();  // brings draws[] up to date

  alignas(64) std::uint64_t singleCounts[L];
  ARCHIPELAGO_UNROLL_VECTORS
  for (std::size_t v = 0; v < V; ++v) {
    Simd::storeState(xs + v * W, X[v]);
    Simd::storeState(ys + v * W, Y[v]);
    Simd::store(tagBase + v * W, base[v]);
    Simd::store(singleCounts + v * W, singles[v]);
  }
  for (std::size_t l = 0; l < n; ++l) {
    OrbitState& s = orbits[l];
    s.z = {xs[l], ys[l]};
    s.draws = draws[l];
    s.block = firstBlock[l] + blocks;
    s.length = (((blocks << 6) - tagBase[l]) & (kUnrecorded - 1)) >> 6;
    const std::int64_t begin = segmentBegin(tagBase[l], l);
    const bool begunHere = begin > 0;
    const std::uint64_t began = begunHere ? static_cast<std::uint64_t>(begin) : startBlockLocal[l];
    s.start = {{startX[l], startY[l]}, firstBlock[l] + began, begunHere ? draws[l] : startDraws[l]};
    TrappingHistogram& h = sink.subsets()[(firstOrbit + l) % sink.subsets().size()];
    for (std::uint64_t t = 1; t <= kExact; ++t) {
      const std::uint64_t count =
          exactCounts[t * 64 + l] + exactCounts[kExactTags + t * 64 + l] + (t == 1 ? singleCounts[l] : 0);
      const int bin = static_cast<int>(t);  // TrappingHistogram::binOf(t) = t for t ≤ kExactMax
      if (count) h.setBin(bin, h.count(bin) + count, h.lengthSum(bin) + count * t);
    }
  }
}

/// Chooses the number of vectors (1 … V) that holds n orbits, so a small group computes no empty vectors.
template <class Simd, int V>
void advanceGroupOfSize(std::size_t vectors, const typename Simd::Constants& c, const KernelSettings& k,
                        OrbitState* orbits, std::size_t n, std::uint64_t firstOrbit, std::uint64_t blocks,
                        SegmentSink& sink) {
  if constexpr (V > 1) {
    if (vectors < static_cast<std::size_t>(V)) {
      advanceGroupOfSize<Simd, V - 1>(vectors, c, k, orbits, n, firstOrbit, blocks, sink);
      return;
    }
  }
  advanceGroup<Simd, V>(c, k, orbits, n, firstOrbit, blocks, sink);
}

template <class Simd, int V>
void advanceBlocksWith(const KernelSettings& k, std::span<OrbitState> orbits, std::uint64_t firstOrbit,
                       std::uint64_t blocks, SegmentSink& sink) {
  const typename Simd::Constants c(k.coefficients, k.randomizingX);
  constexpr std::size_t group = Simd::kLanes * V;
  for (std::size_t first = 0; first < orbits.size(); first += group) {
    const std::size_t n = std::min(group, orbits.size() - first);
    advanceGroupOfSize<Simd, V>((n + Simd::kLanes - 1) / Simd::kLanes, c, k, orbits.data() + first, n,
                                firstOrbit + first, blocks, sink);
  }
}

/// Plain iteration of n ≤ V·kLanes orbits; trace as in OrbitKernel, with row length `stride`.
template <class Simd, int V>
void iterateGroup(const typename Simd::Constants& c, MapDirection direction, UnitState* orbits, std::size_t n,
                  std::uint64_t steps, UnitState* trace, std::size_t stride) {
  constexpr std::size_t W = Simd::kLanes;
  constexpr std::size_t L = W * V;
  alignas(64) std::uint64_t xs[L], ys[L];
  for (std::size_t l = 0; l < L; ++l) {
    xs[l] = l < n ? orbits[l].X : 0;
    ys[l] = l < n ? orbits[l].Y : 0;
  }
  typename Simd::State X[V], Y[V];
  ARCHIPELAGO_UNROLL_VECTORS
  for (int v = 0; v < V; ++v) {
    X[v] = Simd::loadState(xs + v * W);
    Y[v] = Simd::loadState(ys + v * W);
  }
  const auto record = [&](std::uint64_t j) {
    ARCHIPELAGO_UNROLL_VECTORS
    for (int v = 0; v < V; ++v) {
      Simd::storeState(xs + v * W, X[v]);
      Simd::storeState(ys + v * W, Y[v]);
    }
    UnitState* row = trace + j * stride;
    for (std::size_t l = 0; l < n; ++l) row[l] = {xs[l], ys[l]};
  };
  if (direction == MapDirection::backward) {
    typename Simd::State unused[V];
    ARCHIPELAGO_UNROLL_VECTORS
    for (int v = 0; v < V; ++v) unused[v] = Simd::noWraps();
    for (std::uint64_t j = 0; j < steps; ++j) {
      ARCHIPELAGO_UNROLL_VECTORS
      for (int v = 0; v < V; ++v) Simd::backward(c, X[v], Y[v], unused[v]);
      if (trace) record(j);
    }
  } else {
    for (std::uint64_t j = 0; j < steps; ++j) {
      ARCHIPELAGO_UNROLL_VECTORS
      for (int v = 0; v < V; ++v) Simd::forward(c, X[v], Y[v]);
      if (trace) record(j);
    }
  }
  ARCHIPELAGO_UNROLL_VECTORS
  for (int v = 0; v < V; ++v) {
    Simd::storeState(xs + v * W, X[v]);
    Simd::storeState(ys + v * W, Y[v]);
  }
  for (std::size_t l = 0; l < n; ++l) orbits[l] = {xs[l], ys[l]};
}

template <class Simd, int V>
void iterateGroupOfSize(std::size_t vectors, const typename Simd::Constants& c, MapDirection direction,
                        UnitState* orbits, std::size_t n, std::uint64_t steps, UnitState* trace, std::size_t stride) {
  if constexpr (V > 1) {
    if (vectors < static_cast<std::size_t>(V)) {
      iterateGroupOfSize<Simd, V - 1>(vectors, c, direction, orbits, n, steps, trace, stride);
      return;
    }
  }
  iterateGroup<Simd, V>(c, direction, orbits, n, steps, trace, stride);
}

template <class Simd, int V>
void iterateOrbitsWith(const MapCoefficients& coefficients, MapDirection direction, std::span<UnitState> orbits,
                       std::uint64_t steps, UnitState* trace) {
  const typename Simd::Constants c(coefficients, 0);
  constexpr std::size_t group = Simd::kLanes * V;
  for (std::size_t first = 0; first < orbits.size(); first += group) {
    const std::size_t n = std::min(group, orbits.size() - first);
    iterateGroupOfSize<Simd, V>((n + Simd::kLanes - 1) / Simd::kLanes, c, direction, orbits.data() + first, n,
                                steps, trace ? trace + first : nullptr, orbits.size());
  }
}

/// Density binning of n ≤ V·kLanes orbits (DensityKernel in VectorKernels.hpp).  Simd::pixels(g, X, Y, out)
/// writes the pixel indices of the lanes to out and returns the mask of the lanes inside the grid.
template <class Simd, int V>
std::uint64_t densityGroup(const typename Simd::Constants& c, const typename Simd::Grid& g, UnitState* orbits,
                           std::size_t n, std::uint64_t steps, std::uint8_t* counts,
                           std::vector<std::uint32_t>& carries) {
  constexpr std::size_t W = Simd::kLanes;
  constexpr std::size_t L = W * V;
  alignas(64) std::uint64_t xs[L], ys[L], pixels[L];
  for (std::size_t l = 0; l < L; ++l) {
    xs[l] = l < n ? orbits[l].X : 0;
    ys[l] = l < n ? orbits[l].Y : 0;
  }
  typename Simd::State X[V], Y[V];
  unsigned active[V];
  ARCHIPELAGO_UNROLL_VECTORS
  for (int v = 0; v < V; ++v) {
    X[v] = Simd::loadState(xs + v * W);
    Y[v] = Simd::loadState(ys + v * W);
    const std::size_t begin = static_cast<std::size_t>(v) * W;
    active[v] = (1u << (n > begin ? std::min(W, n - begin) : 0)) - 1u;
  }
  std::uint64_t binned = 0;
  for (std::uint64_t j = 0; j < steps; ++j) {
    unsigned inside[V];
    ARCHIPELAGO_UNROLL_VECTORS
    for (int v = 0; v < V; ++v) {
      Simd::forward(c, X[v], Y[v]);
      inside[v] = Simd::pixels(g, X[v], Y[v], pixels + v * W) & active[v];
    }
    ARCHIPELAGO_UNROLL_VECTORS
    for (int v = 0; v < V; ++v) {
      binned += static_cast<std::uint64_t>(__builtin_popcount(inside[v]));
      for (unsigned bits = inside[v]; bits; bits &= bits - 1) {
        const std::uint64_t p = pixels[static_cast<std::size_t>(v) * W + static_cast<std::size_t>(__builtin_ctz(bits))];
        if (++counts[p] == 0) [[unlikely]] carries.push_back(static_cast<std::uint32_t>(p));
      }
    }
  }
  ARCHIPELAGO_UNROLL_VECTORS
  for (int v = 0; v < V; ++v) {
    Simd::storeState(xs + v * W, X[v]);
    Simd::storeState(ys + v * W, Y[v]);
  }
  for (std::size_t l = 0; l < n; ++l) orbits[l] = {xs[l], ys[l]};
  return binned;
}

template <class Simd, int V>
std::uint64_t densityGroupOfSize(std::size_t vectors, const typename Simd::Constants& c, const typename Simd::Grid& g,
                                 UnitState* orbits, std::size_t n, std::uint64_t steps, std::uint8_t* counts,
                                 std::vector<std::uint32_t>& carries) {
  if constexpr (V > 1) {
    if (vectors < static_cast<std::size_t>(V))
      return densityGroupOfSize<Simd, V - 1>(vectors, c, g, orbits, n, steps, counts, carries);
  }
  return densityGroup<Simd, V>(c, g, orbits, n, steps, counts, carries);
}

template <class Simd, int V>
std::uint64_t binDensityWith(const MapCoefficients& coefficients, std::span<UnitState> orbits, std::uint64_t steps,
                             const RasterGrid& grid, std::uint8_t* counts, std::vector<std::uint32_t>& carries) {
  const typename Simd::Constants c(coefficients, 0);
  const typename Simd::Grid g(grid);
  constexpr std::size_t group = Simd::kLanes * V;
  std::uint64_t binned = 0;
  for (std::size_t first = 0; first < orbits.size(); first += group) {
    const std::size_t n = std::min(group, orbits.size() - first);
    binned += densityGroupOfSize<Simd, V>((n + Simd::kLanes - 1) / Simd::kLanes, c, g, orbits.data() + first, n,
                                          steps, counts, carries);
  }
  return binned;
}
